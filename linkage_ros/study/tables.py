# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The tables of the studies, written as CSV (exact decimal) or Parquet (by the file's suffix).

A table is a list of column names and a list of rows. CSV numbers are written with 17
significant digits, which read back to the same float64 (the tolerance study's results are
compared bit for bit). Parquet needs pyarrow (pip install -e '.[study]').
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import IO, Iterable, Sequence

SENSITIVITY_COLUMNS = ('travel_mm', 'quantity', 'point', 'axis', 'derivative')
TOLERANCE_COLUMNS = ('travel_mm', 'quantity', 'nominal', 'mean', 'std', 'rss_std', 'p01', 'p99',
                     'out_of_reach')


def is_parquet(path: str | None) -> bool:
    """Tell whether an output path asks for Parquet (its suffix is .parquet)."""
    return bool(path) and Path(path).suffix.lower() == '.parquet'


def _cell(value):
    if isinstance(value, str):
        return value
    if isinstance(value, int):
        return str(value)
    return '%.17g' % (float(value) + 0.0)   # + 0.0: no '-0'


def write_csv(stream: IO[str], columns: Sequence[str], rows: Iterable[Sequence]) -> None:
    """Write a header line and the rows, numbers exact."""
    writer = csv.writer(stream, lineterminator='\n')
    writer.writerow(columns)
    writer.writerows([_cell(v) for v in row] for row in rows)


def write_parquet(path: str, columns: Sequence[str], rows: Iterable[Sequence]) -> None:
    """Write the table as Parquet, a column per name (text columns as strings)."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    data = list(zip(*rows)) or [()] * len(columns)
    pq.write_table(pa.table({name: list(values) for name, values in zip(columns, data)}), path)


def write_table(path: str | None, columns: Sequence[str], rows: Iterable[Sequence],
                stdout: IO[str]) -> None:
    """Write the table to path (CSV, or Parquet by its suffix) or to stdout (CSV)."""
    if is_parquet(path):
        write_parquet(path, columns, rows)
    elif path:
        with open(path, 'w', newline='') as stream:
            write_csv(stream, columns, rows)
    else:
        write_csv(stdout, columns, rows)
        stdout.flush()
