# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""doc/maps.md: its Python runs as written, and its table of mid-cell errors is what it prints."""

import contextlib
import io
import os
from pathlib import Path
import re
import sys

from linkage_ros.tools.kinematic_map import main
import pytest

DOC = (Path(__file__).resolve().parents[2] / 'doc' / 'maps.md').read_text()
BLOCKS = re.findall(r'```python\n(.*?)```', DOC, re.S)
NUMBER = re.compile(r'-?\d+\.\d+e[-+]\d+')     # as the table prints them: 1.92e-03
PRINTED = re.search(r'It prints the largest error.*?```\n(.*?)```', DOC, re.S).group(1)


@pytest.fixture(scope='module')
def maps_folder(tmp_path_factory):
    """Make the two default maps the doc's programs read, in maps/ of a fresh folder."""
    folder = tmp_path_factory.mktemp('doc')
    for name in ('double_wishbone', 'five_link'):
        assert main([name, '-o', str(folder / 'maps')]) == 0
    return folder


def run(code, folder):
    out, here = io.StringIO(), os.getcwd()
    os.chdir(folder)
    try:
        with contextlib.redirect_stdout(out):
            exec(compile(code, 'doc/maps.md', 'exec'), {'__name__': '__main__'})
    finally:
        os.chdir(here)
    return out.getvalue()


def test_the_loading_example_interpolates_the_map(maps_folder):
    printed = run(BLOCKS[0], maps_folder)
    assert re.fullmatch(r'\[ *-?\d+\.\d+(e-?\d+)? +-?\d+\.\d+(e-?\d+)?\]\n', printed)


def test_the_mid_cell_error_table_is_what_the_program_prints(maps_folder):
    (code,) = [b for b in BLOCKS if 'mid_cell_errors.py' in b]
    # The same words, and each number to one unit of its last printed digit (3 significant):
    # the errors are differences of computed values, whose round-off (another processor's
    # BLAS kernel) may turn a last digit that the text rounds.
    printed = [line.split() for line in run(code, maps_folder).splitlines()]
    expected = [line.split() for line in PRINTED.splitlines()]
    assert [[w for w in line if not NUMBER.fullmatch(w)] for line in printed] == [
        [w for w in line if not NUMBER.fullmatch(w)] for line in expected]
    for got, want in zip(printed, expected):
        for a, b in zip(got, want):
            if NUMBER.fullmatch(b):
                assert float(a) == pytest.approx(float(b), rel=0, abs=last_digit(b)), (got, want)


def test_the_parquet_example_reads_with_pyarrow_alone_no_pandas(maps_folder, monkeypatch):
    # issue 27 item 24: the doc read Parquet with .to_pandas(), and no extra installs pandas
    folder = str(maps_folder / 'maps')
    assert main(['double_wishbone', '-o', folder, '--format', 'parquet']) == 0
    (code,) = [b for b in BLOCKS if 'parquet' in b]
    monkeypatch.setitem(sys.modules, 'pandas', None)   # import pandas raises ImportError
    printed = run(code, maps_folder).split()
    assert printed[:3] == ['2737', '-80.0', '80.0']    # 161 travels x 17 racks, mm
    assert -10.0 < float(printed[3]) < float(printed[4]) < 10.0   # camber, deg


def last_digit(text):
    """Return the value of one unit in the last digit of a number written as 1.23e-04."""
    mantissa, exponent = text.split('e')
    return 10.0 ** (int(exponent) - len(mantissa.split('.')[1]))
