# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The one table writer (outputs/table.py): what it writes reads back to what was given.

The rule (doc/tables.md): a number as the shortest decimal that reads back to the same
float64, without a trailing .0; NaN as nan; a result not finite where a number belongs (an
infinity always) as nan, never as a number, and told; None as an empty cell; text as text.
Read back here by independent readers: Python's csv module and float(), and pyarrow for
Parquet.
"""

import csv
import io
import math
import struct

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros import cli
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import sweep, travel_range
from linkage_ros.outputs import write_table
from linkage_ros.tools import sweep as sweep_tool
from linkage_ros.tools.sweep import COLUMNS
import numpy as np
import pyarrow.parquet as pq
import pytest

# every float64: huge (up to 1.7e308), tiny, subnormal, zero of both signs, NaN, infinities
FLOATS = st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True)
TEXT = st.text(st.characters(blacklist_categories=('Cs',)), max_size=30)
SETTINGS = settings(max_examples=60, deadline=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture])


def bits(value):
    """Return a float's 64 bits as the writer keeps them: -0 as 0, every NaN and inf alike."""
    value = float(value)
    return 'nan' if not math.isfinite(value) else struct.pack('<d', value + 0.0)


def read_csv(text):
    """Return (header, rows) of CSV text, read with Python's csv module."""
    rows = list(csv.reader(io.StringIO(text, newline='')))
    return rows[0], rows[1:]


@SETTINGS
@given(rows=st.integers(0, 6).flatmap(lambda n: st.lists(
    st.lists(FLOATS, min_size=3, max_size=3), min_size=n, max_size=n)))
def test_every_finite_float64_reads_back_bit_for_bit_from_an_array_and_from_rows(rows):
    header = ['a_mm', 'b_deg', 'c']
    texts = []
    for given_rows in (np.array(rows, float).reshape(-1, 3), rows):   # fast path, row path
        stream = io.StringIO()
        write_table(None, header, given_rows, stream)
        texts.append(stream.getvalue())
    assert texts[0] == texts[1]
    read_header, read_rows = read_csv(texts[0])
    assert read_header == header
    assert [[bits(v) for v in row] for row in read_rows] == [[bits(v) for v in row]
                                                             for row in rows]
    assert not any(cell.endswith('.0') or cell == '-0' for row in read_rows for cell in row)


@SETTINGS
@given(rows=st.lists(st.tuples(TEXT, st.one_of(st.none(), FLOATS), st.integers(-2**62, 2**62)),
                     max_size=6))
def test_text_none_and_integers_read_back_as_given(rows):
    stream = io.StringIO()
    write_table(None, ['name', 'value_mm', 'count'], rows, stream)
    _, read_rows = read_csv(stream.getvalue())
    assert [r[0] for r in read_rows] == [r[0] for r in rows]   # quoted where CSV needs it
    assert [r[1] == '' for r in read_rows] == [r[1] is None for r in rows]   # '' only for None
    assert [bits(r[1]) for r in read_rows if r[1] != ''] == [bits(r[1]) for r in rows
                                                             if r[1] is not None]
    assert [int(r[2]) for r in read_rows] == [r[2] for r in rows]


@SETTINGS
@given(values=st.lists(FLOATS, min_size=1, max_size=8))
def test_parquet_keeps_every_finite_float64_and_the_names(values, tmp_path_factory):
    path = tmp_path_factory.mktemp('pq') / 'table.PARQUET'   # the suffix in any case
    written = write_table(str(path), ['x_mm', 'y_deg'], np.column_stack([values, values]))
    table = pq.read_table(path)
    assert table.column_names == ['x_mm', 'y_deg'] and written.rows == len(values)
    assert [bits(v) for v in table.column('x_mm').to_pylist()] == [bits(v) for v in values]


def test_an_infinity_is_lost_written_nan_and_the_status_says_so(capsys):
    # the writers' rule (doc/tables.md): a result that is not finite is never written as a
    # number; an infinity is always an overflow, a NaN is lost where the program says so
    stream = io.StringIO()
    rows = [[1.0, math.inf, 0.0], [math.nan, 2.0, -math.inf], ['inf', None, 3],
            [True, np.False_, 0]]
    written = write_table(None, ['a', 'b', 'c'], rows, stream,
                          lost={'a': np.array([False, True, False, False])})
    assert written.rows == 4   # 'inf' as text is text
    assert {name: mask.tolist() for name, mask in written.lost.items()} == {
        'a': [False, True, False, False], 'b': [True, False, False, False],
        'c': [False, True, False, False]}
    assert stream.getvalue() == 'a,b,c\n1,nan,0\nnan,2,nan\ninf,,3\nTrue,False,0\n'
    assert cli.table_status('linkage-x', written, 'position') == cli.DAMAGED
    assert capsys.readouterr().err == (
        'linkage-x: not finite, so not written as numbers: a at 1 of 4 positions, b at 1 of 4 '
        'positions, c at 1 of 4 positions (an overflow, or a quantity that does not exist '
        'there); the rest of the table is whole\n')
    assert cli.table_status('linkage-x', write_table(None, ['a'], [[math.nan]], stream)) == \
        cli.DONE   # a NaN the program does not call lost is a quantity undefined there


@SETTINGS
@given(values=st.lists(FLOATS, min_size=1, max_size=20))
def test_an_array_and_rows_lose_the_same_cells(values):
    array = np.array(values).reshape(-1, 1)
    got = [write_table(None, ['x'], given, io.StringIO())
           for given in (array, [[v] for v in values])]
    assert got[0].rows == got[1].rows == len(values)
    assert {k: m.tolist() for k, m in got[0].lost.items()} == {
        k: m.tolist() for k, m in got[1].lost.items()} == (
        {'x': [math.isinf(v) for v in values]} if any(map(math.isinf, values)) else {})


def test_a_sweep_table_reads_back_bit_for_bit_as_the_sweep_solved_it(tmp_path, capsys):
    # before, linkage-sweep wrote 10 significant digits: 1e-10 relative lost on every value
    out = tmp_path / 'sweep.csv'
    assert sweep_tool.main(['five_link', '--travel', '-40:40:0.5', '-o', str(out)]) == 0
    expected = sweep(load_scene('five_link'), travel_range(-40, 40, 0.5))
    header, rows = read_csv(out.read_text())
    assert header == COLUMNS
    got = np.array(rows, float)
    assert np.array_equal(got[:, 0], expected.travel)
    assert np.array_equal(got[:, 1], np.degrees(expected.camber))
    assert np.array_equal(got[:, 3:6], expected.wheel_center)


@pytest.mark.parametrize('value, text', [(-80.0, '-80'), (0.1, '0.1'), (-0.0, '0'),
                                         (1e-13, '1e-13'), (2.0 ** 60, '1.152921504606847e+18'),
                                         (5e-324, '5e-324'), (1.7e308, '1.7e+308'),
                                         (math.nan, 'nan'), (-math.inf, 'nan')])
def test_numbers_are_written_with_the_fewest_digits(value, text):
    stream = io.StringIO()
    write_table(None, ['x'], np.array([[value]]), stream)
    assert stream.getvalue() == f'x\n{text}\n'
