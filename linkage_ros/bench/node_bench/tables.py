# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""What linkage-bench node prints: progress on stderr, CSV tables on stdout."""

import sys

import numpy as np

from ...outputs import write_table


def progress(text):
    print(f'linkage-bench node: {text}', file=sys.stderr, flush=True)


def table(header, rows):
    """
    Print a CSV table with the table writer (doc/tables.md), the section its first cell.

    Measured floats are printed to 4 significant digits: a timing's run-to-run spread is
    percents, so the writer's shortest round-trip digits would only print noise.
    """
    write_table(None, header, [[float(f'{cell:.4g}') if isinstance(cell, float) else cell
                                for cell in row] for row in rows])
    print()


def us(values, q=50):
    return float(np.percentile(values, q) * 1e6) if len(values) else float('nan')
