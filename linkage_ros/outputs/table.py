# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The one table writer of the programs: CSV or Parquet by the output's suffix, stdout or a file.

    written = write_table(output, header, rows)   # output None or '-': CSV on stdout

header: the column names (units in the names); rows: a 2-D numeric array, or rows of numbers,
text and None. The rule (doc/tables.md), which loses nothing:
- a number is written as the shortest decimal that reads back to the same float64 (Python's
  repr), without a trailing '.0': -80, 12.5, 0.1, 1e-13, 1.2345678901234567; -0 as 0
- NaN (a quantity not defined at that row, as each column's doc says) as nan
- a result that is not finite where a number belongs (the writers' rule, base.lost_cells): as
  nan, never as a number, and told in Written.lost: an infinity always (an overflow), a NaN
  where the caller says (lost=, the program knowing which NaN its quantities may have)
- None (no value: a column that is not the row's) as an empty cell
- integers as integers, booleans as True and False; text as text, quoted where CSV needs it
A name ending in .parquet (any case) is written as Parquet (pyarrow): a column per name,
float64 (NaN kept, a lost cell NaN too), int64, text, null for None. A file is written whole
(whole.py); a device or FIFO in place. The program says what was lost and ends 1
(cli.table_status).
"""

from __future__ import annotations

import itertools
import math
import operator
from pathlib import Path
import re
import sys
from typing import IO, Mapping, NamedTuple, Sequence

import numpy as np

from .whole import whole_file

PARQUET = '.parquet'
ROWS_AT_ONCE = 4096   # rows formatted into one string before it is written
TRAILING_ZERO = re.compile(r'\.0(?=[,\n])')   # 80.0 -> 80: only in rows of numbers
QUOTED = re.compile(r'[,"\r\n]')             # a CSV cell with these is quoted
INFINITE = ('inf', '-inf')


class Written(NamedTuple):
    """What write_table wrote: the rows, and the cells lost, {column: mask (rows,)}."""

    rows: int
    lost: dict = {}


def is_parquet(path) -> bool:
    """Tell whether an output path asks for Parquet (its suffix is .parquet, any case)."""
    return bool(path) and str(path) != '-' and Path(path).suffix.lower() == PARQUET


def write_table(output, header: Sequence[str], rows, stdout: IO[str] | None = None, *,
                lost: Mapping[str, np.ndarray] | None = None) -> Written:
    """
    Write a table to output (CSV, or Parquet by its suffix), or as CSV to stdout.

    output: a path, or None or '-' for stdout (sys.stdout unless given; flushed). A file is
    written whole: an error leaves it as it was and raises OSError naming it. lost: {column:
    mask over the rows} of cells not to be written as numbers (base.lost_cells); every
    infinity is lost too.
    """
    header = [str(name) for name in header]
    if output is None or str(output) == '-':
        stream = stdout or sys.stdout
        written = write_csv(stream, header, rows, lost)
        stream.flush()
        return written
    if is_parquet(output):
        return _write_parquet(output, header, rows, lost)
    with whole_file(output) as stream:
        return write_csv(stream, header, rows, lost)


def write_csv(stream: IO[str], header: Sequence[str], rows,
              lost: Mapping[str, np.ndarray] | None = None) -> Written:
    """Write the header line and the rows to an open text stream as CSV (the module's rule)."""
    stream.write(','.join(_quoted(str(name)) for name in header) + '\n')
    array = _numeric(rows, len(header))
    if array is None:
        return _write_mixed(stream, header, rows, lost or {})
    array, masks = _without_lost(array, header, lost or {})
    line = ','.join(['%r'] * len(header)) + '\n'
    for start in range(0, len(array), ROWS_AT_ONCE):
        block = array[start:start + ROWS_AT_ONCE] + 0.0   # + 0.0: -0 as 0
        stream.write(TRAILING_ZERO.sub('', ''.join(line % tuple(r) for r in block.tolist())))
    return Written(len(array), masks)


def _without_lost(array, header, lost):
    """Return (a copy of array with its lost cells NaN, the masks of the columns losing any)."""
    masks = {}
    for k, name in enumerate(header):
        mask = np.isinf(array[:, k])
        if name in lost:
            mask |= np.asarray(lost[name], bool).reshape(-1)[:len(array)]
        if mask.any():
            masks[name] = mask
    if masks:
        array = array.copy()
        for name, mask in masks.items():
            array[mask, header.index(name)] = np.nan
    return array, masks


def cell(value) -> str:
    """Return one value as the module's rule writes it in CSV (text unquoted)."""
    return _CELLS.get(type(value), _other)(value)


def _number(value) -> str:
    """Return a float (or numpy float) as its shortest round-trip decimal, no trailing .0."""
    text = float.__repr__(float(value) + 0.0)   # + 0.0: -0 as 0
    return text[:-2] if text.endswith('.0') else text


def _other(value) -> str:
    """Return a value of a type _CELLS does not list (a numpy scalar, a subclass)."""
    if value is None:
        return ''
    if isinstance(value, str):
        return str(value)
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return _number(value)


_CELLS = {float: _number, np.float64: _number, int: int.__repr__, str: str,
          bool: str, type(None): lambda value: ''}


def _write_mixed(stream, header, rows, lost) -> Written:
    """Write rows of numbers, text and None: a block of rows at a time, column by column."""
    count, masks = 0, {name: [] for name in header}
    rows = iter(rows)
    while True:
        block = list(itertools.islice(rows, ROWS_AT_ONCE))
        if not block:
            break
        if set(map(len, block)) != {len(header)}:
            raise ValueError(f'every row of a table has {len(header)} values, as its header')
        columns = []
        for k, name in enumerate(header):
            texts, mask = _column(list(map(operator.itemgetter(k), block)))
            if name in lost:
                mask = mask | np.asarray(lost[name], bool)[count:count + len(block)]
            if mask.any():
                texts = ['nan' if m else t for t, m in zip(texts, mask)]
            columns.append(texts)
            masks[name].append(mask)
        if len(header) == 1:   # a line of one empty cell is written "", so that it is no blank
            columns = [['""' if t == '' else t for t in columns[0]]]
        stream.write('\n'.join(map(','.join, zip(*columns))) + '\n')
        count += len(block)
    masks = {name: np.concatenate(parts) for name, parts in masks.items() if parts}
    return Written(count, {name: mask for name, mask in masks.items() if mask.any()})


def _column(values) -> tuple[list[str], np.ndarray]:
    """
    Return a column's cells as CSV text (the module's rule) and where it holds +-infinity.

    A text with a comma, a quote or a line break (a carriage return too, which Python's csv
    writer leaves bare when lines end in a line feed) is quoted, its quotes doubled.
    """
    none = np.zeros(len(values), bool)
    types = set(map(type, values))
    if types == {float}:   # the common cases, at C speed
        infinite = np.isinf(values) if math.inf in values or -math.inf in values else none
        unique = dict.fromkeys(values)
        if 2 * len(unique) < len(values):   # an axis repeated on every line: each once
            text = dict(zip(unique, _floats(list(unique))))
            return [text[v] for v in values], infinite
        return _floats(values), infinite
    if types == {str}:
        return ([_quoted(t) for t in values] if QUOTED.search(''.join(values)) else
                list(values)), none
    texts = [cell(v) for v in values]
    if QUOTED.search(''.join(t for t, v in zip(texts, values) if isinstance(v, str))):
        texts = [_quoted(t) if isinstance(v, str) else t for t, v in zip(texts, values)]
    return texts, np.array([t in INFINITE and not isinstance(v, str)
                            for t, v in zip(texts, values)], bool)


def _floats(values) -> list[str]:
    """Return Python floats as the module's rule writes them, at C speed."""
    text = '\n'.join(map(float.__repr__, [v + 0.0 for v in values])) + '\n'
    return TRAILING_ZERO.sub('', text).split('\n')[:-1]


def _quoted(text: str) -> str:
    """Return a CSV cell's text, quoted (its quotes doubled) where CSV needs it."""
    return '"' + text.replace('"', '""') + '"' if QUOTED.search(text) else text


def _numeric(rows, width: int):
    """Return rows as an (n, width) float array if they are a numeric array, else None."""
    if isinstance(rows, np.ndarray) and rows.dtype.kind in 'fiu':
        return np.asarray(rows, float).reshape(-1, width)
    return None


def _write_parquet(output, header, rows, lost) -> Written:
    """Write the table as Parquet, whole (pyarrow: checked for before any work)."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    array = _numeric(rows, len(header))
    if array is not None:
        array, masks = _without_lost(array, header, lost or {})
        columns = {name: array[:, i] for i, name in enumerate(header)}
        count = len(array)
    else:
        data = [list(column) for column in zip(*rows)] or [[] for _ in header]
        count = len(data[0]) if data else 0
        columns, masks = {}, {}
        for name, values in zip(header, data):
            mask = np.array([not isinstance(v, str) and v is not None and np.isinf(v)
                             for v in values], bool).reshape(-1)
            if lost and name in lost:
                mask |= np.asarray(lost[name], bool)
            if mask.any():
                masks[name] = mask
                values = [math.nan if m else v for v, m in zip(values, mask)]
            columns[name] = values
    with whole_file(output, 'wb') as stream:
        pq.write_table(pa.table(columns), stream)
    return Written(count, masks)
