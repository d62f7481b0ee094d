# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A picture's name whose suffix matplotlib cannot write is refused before any work (cli.py).

The trial: linkage-kc ... --plot rates.txt and linkage-vehicle ... --plot sheet.yaml wrote the
table, then ended in matplotlib's traceback. Every program with a picture checks the suffix
in one place (cli.plot_problem), with the other checks of its outputs.
"""

import os

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros import cli
from linkage_ros.bench.node_bench import cli as node_bench
from linkage_ros.study import cli as study_cli
from linkage_ros.tools import kc, plot, vehicle
from matplotlib.backend_bases import FigureCanvasBase
import pytest

FORMATS = FigureCanvasBase.get_supported_filetypes()   # what savefig writes (png, pdf, svg...)
# suffixes of no picture: a table's, a file format's, and any text (unicode, digits first)
SUFFIXES = st.one_of(st.sampled_from(['txt', 'yaml', 'csv', 'json', 'mcap', 'PNG~']),
                     st.text(st.characters(whitelist_categories=('L', 'N')), min_size=1,
                             max_size=12)).filter(lambda s: s.lower() not in FORMATS)
PROGRAMS = [
    ('linkage-kc', kc.main, ['double_wishbone_bushings', '--travel', '0', '--plot', 'PIC'],
     '--plot'),
    ('linkage-vehicle', vehicle.main, ['demo_vehicle', '--plot', 'PIC'], '--plot'),
    ('linkage-study', study_cli.main, ['tolerance', 'five_link', '--travel', '0', '--sigma',
                                       '0.1', '--samples', '4', '--plot', 'PIC'], '--plot'),
    ('linkage-study', study_cli.main, ['fit', 'config/study/bump_steer_targets.yaml', '-o',
                                       'fitted.yaml', '--plot', 'PIC'], '--plot'),
    ('linkage-plot', plot.main, ['camber-toe', '-o', 'PIC', 'five_link'], ''),
    ('linkage-plot', plot.main, ['roll-centre', '-o', 'PIC'], ''),
    ('linkage-bench node', node_bench.main, ['--plot', 'PIC'], 'error: --plot'),
]


@pytest.mark.parametrize('prog, main, argv, option', PROGRAMS,
                         ids=[f'{p[0]}-{p[2][0]}' for p in PROGRAMS])
@settings(max_examples=8, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(stem=st.sampled_from(['rates', 'sheet', '9-ü']), suffix=SUFFIXES)
def test_a_picture_suffix_matplotlib_cannot_write_is_one_line_before_any_work(
        prog, main, argv, option, stem, suffix, tmp_path_factory, capsys, monkeypatch):
    folder = tmp_path_factory.mktemp('plot')
    config = os.path.join(os.path.dirname(__file__), '..', '..', 'config')
    os.symlink(os.path.abspath(config), folder / 'config')
    monkeypatch.chdir(folder)
    name = f'{stem}.{suffix}'
    try:
        status = main([name if a == 'PIC' else a for a in argv])
    except SystemExit as exited:
        status = exited.code
    out, err = capsys.readouterr()
    assert (status, out) == (2, '')   # no table written before the refusal
    assert err.count('\n') == 1 and 'Traceback' not in err, err
    assert err.startswith(f'{prog}: {option + ": " if option else ""}{name}: matplotlib '
                          f'writes no .{suffix.lower()} files (formats: '), err
    assert sorted(os.listdir(folder)) == ['config']


@pytest.mark.parametrize('suffix', sorted(FORMATS) + ['PNG', 'Svg', ''])
def test_every_suffix_matplotlib_writes_is_taken_and_none_is_png(suffix, tmp_path):
    name = tmp_path / f'picture.{suffix}' if suffix else tmp_path / 'picture'
    assert cli.plot_problem(str(name)) == ''
