# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
One command-line vocabulary: --travel/--rack FROM[:TO:STEP], -o/--output, linkage-bench.

Every program reads a range with one parser (cli.span); a bad range is one line naming the
option, status 2. The spellings kept for a release before 0.1.0 (which never was) are gone:
each is now an unknown option, one line, status 2 (CHANGELOG.rst, 0.2.0).
"""

import argparse
import csv
import io
from pathlib import Path
import subprocess
import sys

from linkage_ros import cli
from linkage_ros.bench import cli as bench_cli
from linkage_ros.study import cli as study_cli
from linkage_ros.tools import axle, kinematic_map, plot, replay, sweep
from mcap.reader import make_reader
import numpy as np
import pytest

PROGRAMS = {'linkage-sweep': sweep.main, 'linkage-axle': axle.main,
            'linkage-map': kinematic_map.main, 'linkage-study': study_cli.main,
            'linkage-replay': replay.main}
BAG = 'bags/five_link_sweep.mcap'


def outcome(main, argv, capsys):
    """Run a program's main in this process: (status, stdout, stderr)."""
    try:
        status = main(argv)
    except SystemExit as exited:
        status = exited.code
    out, err = capsys.readouterr()
    return status, out, err


def rows_of(text):
    return list(csv.DictReader(io.StringIO(text)))


@pytest.mark.parametrize('text, span', [
    ('-80:80:1', (-80.0, 80.0, 1.0)), ('5', (5.0, 5.0, 1.0)), ('-2.5e1', (-25.0, -25.0, 1.0)),
    ('20:-20:10', (20.0, -20.0, 10.0)), (' 1 : 2 : 0.5 ', (1.0, 2.0, 0.5))])
def test_span_reads_one_value_or_from_to_step(text, span):
    assert cli.span(text) == span


@pytest.mark.parametrize('text', ['', '1:2', '1:2:3:4', '0:1:0', '0:1:-1', 'nan', '0:inf:1',
                                  'a:b:c', '1e400'])
def test_span_refuses_what_is_not_finite_from_to_step_above_zero(text):
    with pytest.raises(argparse.ArgumentTypeError, match='expected FROM'):
        cli.span(text)


def test_span_says_to_leave_the_unit_out():
    with pytest.raises(argparse.ArgumentTypeError, match='without a unit'):
        cli.span('-80mm:80mm:1')


def test_sweep_takes_travel_and_rack_ranges_and_writes_to_output(tmp_path, capsys):
    path = tmp_path / 'grid.csv'
    status, out, _ = outcome(sweep.main, ['double_wishbone', '--travel', '-40:40:40', '--rack',
                                          '-10:10:10', '--output', str(path)], capsys)
    assert (status, out) == (0, '')
    rows = rows_of(path.read_text())
    assert [(float(r['travel_mm']), float(r['rack_mm'])) for r in rows] == [
        (t, r) for r in (-10.0, 0.0, 10.0) for t in (-40.0, 0.0, 40.0)]


def test_axle_takes_a_rack_range_and_writes_to_output(tmp_path, capsys):
    path = tmp_path / 'axle.csv'
    status, _, _ = outcome(axle.main, ['demo_vehicle', '--heave', '0', '--rack', '-20:20:20',
                                       '-o', str(path)], capsys)
    rows = rows_of(path.read_text())
    assert status == 0 and [float(r['rack_mm']) for r in rows] == [-20.0, 0.0, 20.0]


def test_map_takes_one_travel_and_one_rack_and_writes_into_output(tmp_path, capsys):
    status, _, _ = outcome(kinematic_map.main, ['double_wishbone', '--travel', '10', '--rack',
                                                '-5', '-o', str(tmp_path)], capsys)
    grid = np.load(tmp_path / 'double_wishbone.npz')
    assert status == 0
    assert grid['travel_mm'].tolist() == [10.0] and grid['rack_mm'].tolist() == [-5.0]


def test_study_takes_travels_and_ranges_mixed_and_writes_to_output(tmp_path, capsys):
    path = tmp_path / 's.csv'
    status, _, _ = outcome(study_cli.main, ['sensitivity', 'five_link', '--travel', '-20:0:10',
                                            '30', '--quantity', 'camber_deg', '-o', str(path)],
                           capsys)
    travels = sorted({float(r['travel_mm']) for r in rows_of(path.read_text())})
    assert status == 0 and travels == [-20.0, -10.0, 0.0, 30.0]


def test_replay_sweep_takes_a_travel_range(tmp_path, capsys):
    path = tmp_path / 'sweep.mcap'
    status, _, _ = outcome(replay.main, ['sweep', '--travel', '-3:3:3', '-o', str(path)],
                           capsys)
    with open(path, 'rb') as stream:
        travels = [m.data for _, c, m in make_reader(stream).iter_messages()
                   if c.topic == '/wheel_travel']
    assert status == 0 and len(travels) == 3


@pytest.mark.parametrize('prog, argv, option', [
    ('linkage-sweep', ['five_link', '--travel', '0:10'], '--travel'),
    ('linkage-sweep', ['double_wishbone', '--rack', '1:2:0'], '--rack'),
    ('linkage-axle', ['demo_vehicle', '--rack', '0:x:1'], '--rack'),
    ('linkage-axle', ['demo_vehicle', '--heave', '0:10:-1'], '--heave'),
    ('linkage-map', ['double_wishbone', '--travel', '0:10', '-o', 'maps'], '--travel'),
    ('linkage-map', ['double_wishbone', '--rack', 'inf', '-o', 'maps'], '--rack'),
    ('linkage-study', ['sensitivity', 'five_link', '--travel', '0', '1:2'], '--travel'),
    ('linkage-replay', ['sweep', '--travel', '0:1:0'], '--travel')])
def test_a_bad_range_is_one_line_naming_the_option_with_status_2(
        prog, argv, option, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, out, err = outcome(PROGRAMS[prog], argv, capsys)
    assert (status, out) == (2, '') and err.count('\n') == 1, err
    assert err.startswith(f'{prog}') and option in err and 'FROM[:TO:STEP]' in err, err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize('prog, argv, says', [
    ('linkage-sweep', ['five_link', '--from', '-10', '--to', '10', '--step', '10'],
     'unrecognized arguments: --from -10 --to 10 --step 10'),
    ('linkage-sweep', ['double_wishbone', '--travel', '0', '--grid=-10:10:10'],
     'unrecognized arguments: --grid=-10:10:10'),
    ('linkage-sweep', ['five_link', '--csv', 'x.csv'], 'unrecognized arguments: --csv '),
    ('linkage-sweep', ['five_link', '--benchmark', '1'], 'unrecognized arguments: --benchmark 1'),
    ('linkage-axle', ['demo_vehicle', '--heave', '0', '--rack-grid=-20:20:20'],
     'unrecognized arguments: --rack-grid=-20:20:20'),
    ('linkage-axle', ['demo_vehicle', '--csv', 'x.csv'], 'unrecognized arguments: --csv '),
    ('linkage-axle', ['demo_vehicle', '--benchmark', '1'], 'unrecognized arguments: --benchmark'),
    ('linkage-map', ['double_wishbone', '-o', 'maps', '--benchmark', '1'],
     'unrecognized arguments: --benchmark 1'),
    ('linkage-replay', ['sweep', '--from', '0', '--step', '2', '-o', 'x.mcap'],
     'unrecognized arguments: --from 0 --step 2'),
    ('linkage-replay', ['--sweep'], 'unrecognized arguments: --sweep'),
    ('linkage-replay', [BAG, '--copy', '-o', 'x.mcap'], f"invalid choice: '{BAG}'"),
    ('linkage-replay', [BAG, '-o', 'x.mcap'], f"invalid choice: '{BAG}'"),
    # its timing is linkage-bench replay's (bench/ owns all timing)
    ('linkage-replay', ['bench', BAG], "invalid choice: 'bench'"),
])
def test_an_old_spelling_is_now_an_unknown_option_in_one_line_with_status_2(
        prog, argv, says, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(Path(__file__).resolve().parents[2])   # BAG, relative as a user gives it
    status, out, err = outcome(PROGRAMS[prog], [str(tmp_path / a) if a in (
        'x.csv', 'maps', 'x.mcap') else a for a in argv], capsys)
    assert (status, out) == (2, '') and err.count('\n') == 1, err
    assert err.startswith(f'{prog}: error: ') and says in err, err
    assert list(tmp_path.iterdir()) == []


def test_linkage_bench_sweep_times_the_sweep_of_linkage_sweep(capsys):
    status, out, err = outcome(bench_cli.main, ['sweep', 'five_link', '--travel', '0:10:10',
                                                '--rounds', '1'], capsys)
    assert status == 0
    assert out.startswith('five_link: 2 positions from 0 to 10 mm')
    assert [line.split()[0] for line in out.splitlines()[2:]] == ['paper', 'fast', 'fast,']


@pytest.mark.parametrize('argv, says', [
    (['sweep', 'five_link', '--rounds', '0'], 'argument --rounds: expected a whole number of '
     "rounds >= 1, got '0'"),
    (['axle', '--rounds'], "argument --rounds: expected a whole number of rounds >= 1, got ''"),
    (['magic'], "unknown benchmark 'magic': choose one of accuracy, node, soak, sweep, axle, "
     'map, vehicle, study, replay, kc'),
    # without a subcommand it ran accuracy, for one release that never was
    ([], 'error: choose a benchmark: accuracy, node, soak, sweep, axle, map'),
    (['--quick'], 'error: unrecognized arguments: --quick: the benchmark comes first')])
def test_a_linkage_bench_mistake_is_one_line_with_status_2(argv, says, capsys):
    status, out, err = outcome(bench_cli.main, argv, capsys)
    assert (status, out) == (2, '') and err.count('\n') == 1 and says in err, err


def test_linkage_bench_help_names_every_subcommand(capsys):
    status, out, _ = outcome(bench_cli.main, ['--help'], capsys)
    assert status == 0
    for command in bench_cli.COMMANDS:
        assert f'linkage-bench {command} ' in out, command


def test_plot_writes_to_output_with_scenes_on_either_side(tmp_path, capsys):
    status, _, err = outcome(plot.main, ['camber-toe', 'five_link', '-o', str(tmp_path / 'a.png'),
                                         'double_wishbone'], capsys)
    assert status == 0 and (tmp_path / 'a.png').stat().st_size > 0
    assert err == f'linkage-plot: wrote {tmp_path / "a.png"}\n'


def test_plot_without_an_output_is_one_line_naming_o(capsys):
    status, out, err = outcome(plot.main, ['alignment'], capsys)
    assert (status, out) == (2, '')
    assert err == ('linkage-plot: error: -o/--output OUT.png is required (see linkage-plot '
                   '--help)\n')


def test_plot_output_as_a_path_is_refused_naming_o(tmp_path, capsys):
    # the spelling of a release before 0.1.0: OUT.png as the first PATH
    status, out, err = outcome(plot.main, ['camber-toe', str(tmp_path / 'b.png'), 'five_link'],
                               capsys)
    assert (status, out, list(tmp_path.iterdir())) == (2, '', [])
    assert err == ('linkage-plot: error: -o/--output OUT.png is required (see linkage-plot '
                   '--help)\n')


def test_the_old_benchmark_programs_are_no_console_scripts():
    from importlib.metadata import distribution
    scripts = {e.name for e in distribution('linkage_ros').entry_points}
    assert scripts & {'linkage-node-bench', 'linkage-soak'} == set()
    assert 'linkage-bench' in scripts


def test_linkage_bench_help_into_a_closed_pipe_ends_quietly_as_cat_does():
    # linkage-bench --help | head -1 printed a BrokenPipeError traceback (.ci/readme_commands.sh)
    bench = subprocess.Popen([sys.executable, '-m', 'linkage_ros.bench.cli', '--help'],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    bench.stdout.close()          # the reader is gone before the help is written
    err = bench.stderr.read()
    assert (bench.wait(timeout=60), err) == (128 + 13, '')   # SIGPIPE's status, as cat's
