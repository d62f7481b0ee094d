# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The one table writer of the programs: CSV or Parquet by the output's suffix, stdout or a file.

    written = write_table(output, header, rows)   # output None or '-': CSV on stdout

header: the column names (units in the names); rows: a 2-D numeric array, or rows of numbers,
text and None. The rule (doc/tables.md), which loses nothing:
- a number is written as the shortest decimal that reads back to the same float64 (Python's
  repr), without a trailing '.0': -80, 12.5, 0.1, 1e-13, 1.2345678901234567; -0 as 0
- NaN (a quantity not defined at that row, as each column's doc says) as nan, +-infinity as
  inf and -inf
- None (no value: a column that is not the row's) as an empty cell
- integers as integers, booleans as True and False; text as text, quoted where CSV needs it
A name ending in .parquet (any case) is written as Parquet (pyarrow): a column per name,
float64 (NaN and infinity kept as such), int64, text, null for None. A file is written whole
(whole.py); a device or FIFO in place. Written tells the rows written and the columns that
hold an infinite value: an overflow, never a result (the program's status says so).
"""

from __future__ import annotations

from pathlib import Path
import re
import sys
from typing import IO, Iterable, NamedTuple, Sequence

import numpy as np

from .whole import whole_file

PARQUET = '.parquet'
ROWS_AT_ONCE = 4096   # rows formatted into one string before it is written
TRAILING_ZERO = re.compile(r'\.0(?=[,\n])')   # 80.0 -> 80: only in rows of numbers
QUOTED = re.compile(r'[,"\r\n]')             # a CSV cell with these is quoted
INFINITE = ('inf', '-inf')


class Written(NamedTuple):
    """What write_table wrote: the rows, and the columns that hold +-infinity."""

    rows: int
    infinite: tuple[str, ...] = ()


def is_parquet(path) -> bool:
    """Tell whether an output path asks for Parquet (its suffix is .parquet, any case)."""
    return bool(path) and str(path) != '-' and Path(path).suffix.lower() == PARQUET


def write_table(output, header: Sequence[str], rows, stdout: IO[str] | None = None) -> Written:
    """
    Write a table to output (CSV, or Parquet by its suffix), or as CSV to stdout.

    output: a path, or None or '-' for stdout (sys.stdout unless given; flushed). A file is
    written whole: an error leaves it as it was and raises OSError naming it.
    """
    header = [str(name) for name in header]
    if output is None or str(output) == '-':
        stream = stdout or sys.stdout
        written = write_csv(stream, header, rows)
        stream.flush()
        return written
    if is_parquet(output):
        return _write_parquet(output, header, rows)
    with whole_file(output) as stream:
        return write_csv(stream, header, rows)


def write_csv(stream: IO[str], header: Sequence[str], rows) -> Written:
    """Write the header line and the rows to an open text stream as CSV (the module's rule)."""
    stream.write(_line(header))
    array = _numeric(rows, len(header))
    if array is None:
        return _write_mixed(stream, header, rows)
    line = ','.join(['%r'] * len(header)) + '\n'
    for start in range(0, len(array), ROWS_AT_ONCE):
        block = array[start:start + ROWS_AT_ONCE] + 0.0   # + 0.0: -0 as 0
        stream.write(TRAILING_ZERO.sub('', ''.join(line % tuple(r) for r in block.tolist())))
    infinite = np.isinf(array).any(axis=0) if len(array) else np.zeros(len(header), bool)
    return Written(len(array), tuple(n for n, inf in zip(header, infinite) if inf))


def cell(value) -> str:
    """Return one value as the module's rule writes it in CSV (text unquoted)."""
    if value is None:
        return ''
    if isinstance(value, str):
        return value
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    text = repr(float(value) + 0.0)
    return text[:-2] if text.endswith('.0') else text


def _write_mixed(stream, header, rows) -> Written:
    """Write rows of numbers, text and None, one by one."""
    count, infinite = 0, set()
    for row in rows:
        cells = [cell(v) for v in row]
        if 'inf' in cells or '-inf' in cells:   # a number, not text that reads so
            infinite.update(i for i, (c, v) in enumerate(zip(cells, row))
                            if c in INFINITE and not isinstance(v, str))
        stream.write(_line(cells))
        count += 1
    return Written(count, tuple(header[i] for i in sorted(infinite) if i < len(header)))


def _line(cells: Sequence[str]) -> str:
    """
    Return one CSV line of text cells, ended by a line feed.

    A cell with a comma, a quote or a line break (a carriage return too, which Python's csv
    writer leaves bare when lines end in a line feed) is quoted, its quotes doubled; a line
    of one empty cell is written "" so that it is no blank line.
    """
    if len(cells) == 1 and cells[0] == '':
        return '""\n'
    return ','.join('"' + c.replace('"', '""') + '"' if QUOTED.search(c) else c
                    for c in cells) + '\n'


def _numeric(rows, width: int):
    """Return rows as an (n, width) float array if they are a numeric array, else None."""
    if isinstance(rows, np.ndarray) and rows.dtype.kind in 'fiu':
        return np.asarray(rows, float).reshape(-1, width)
    return None


def _write_parquet(output, header, rows) -> Written:
    """Write the table as Parquet, whole (pyarrow: checked for before any work)."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    array = _numeric(rows, len(header))
    if array is not None:
        columns = {name: array[:, i] for i, name in enumerate(header)}
        count = len(array)
    else:
        data = [list(column) for column in zip(*rows)] or [[] for _ in header]
        columns = dict(zip(header, data))
        count = len(data[0]) if data else 0
    table = pa.table(columns)
    infinite = tuple(name for name in header if _any_infinite(columns[name]))
    with whole_file(output, 'wb') as stream:
        pq.write_table(table, stream)
    return Written(count, infinite)


def _any_infinite(values: Iterable) -> bool:
    """Tell whether a column holds +-infinity (numbers only; text and None are not)."""
    if isinstance(values, np.ndarray):
        return bool(np.isinf(values).any())
    return any(isinstance(v, (float, np.floating)) and np.isinf(v) for v in values)
