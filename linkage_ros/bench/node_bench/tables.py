# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""What linkage-node-bench prints: progress on stderr, CSV tables on stdout."""

import sys

import numpy as np


def progress(text):
    print(f'linkage-node-bench: {text}', file=sys.stderr, flush=True)


def table(header, rows):
    """Print a CSV table: header (first cell: the section) and rows, floats to 4 digits."""
    print(','.join(header))
    for row in rows:
        print(','.join(f'{v:.4g}' if isinstance(v, float) else str(v) for v in row))
    print()


def us(values, q=50):
    return float(np.percentile(values, q) * 1e6) if len(values) else float('nan')
