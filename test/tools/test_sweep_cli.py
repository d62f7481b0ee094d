# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-sweep: CSV columns, units, defaults from the scene, clear errors."""

import csv
import io
from pathlib import Path
import subprocess
import sys

from linkage_ros.tools.sweep import COLUMNS, main
import numpy as np
import pytest

LEADING = ('travel_mm,camber_deg,toe_deg,wheel_center_x_mm,wheel_center_y_mm,'
           'wheel_center_z_mm,qx,qy,qz,qw,residual_mm,iterations')


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, list(csv.DictReader(io.StringIO(out))), out, err


def test_columns_are_exactly_the_documented_ones():
    assert ','.join(COLUMNS) == LEADING


def test_defaults_come_from_the_scene_travel_block(capsys):
    code, rows, out, _ = run(capsys, 'five_link')
    assert code == 0 and out.splitlines()[0] == LEADING
    assert len(rows) == 161
    assert float(rows[0]['travel_mm']) == -80.0 and float(rows[-1]['travel_mm']) == 80.0


def test_table_is_in_mm_and_degrees(capsys):
    # Reference: ../shared/refdata/five_link_test.yaml, camber -2.9175 deg at +80 mm.
    _, rows, _, _ = run(capsys, 'five_link', '--travel', '80:80:1')
    assert float(rows[0]['camber_deg']) == pytest.approx(-2.9175, abs=1e-4)
    assert float(rows[0]['wheel_center_z_mm']) == pytest.approx(380.0)
    assert float(rows[0]['residual_mm']) <= 1e-9


def test_metre_scene_is_tabulated_in_mm(capsys):
    _, rows, _, _ = run(capsys, 'macpherson', '--travel', '0:10:10')
    assert float(rows[0]['wheel_center_y_mm']) == pytest.approx(1099.99965)
    assert float(rows[1]['wheel_center_z_mm']) - float(rows[0]['wheel_center_z_mm']) \
        == pytest.approx(10.0)


def test_output_option_writes_the_file_and_paper_method_matches(tmp_path, capsys):
    path = tmp_path / 'out.csv'
    assert main(['double_wishbone', '--travel', '-80:80:40', '--method', 'paper', '-o',
                 str(path)]) == 0
    paper = np.loadtxt(path, delimiter=',', skiprows=1)
    _, rows, _, _ = run(capsys, 'double_wishbone', '--travel', '-80:80:40')
    fast = np.array([[float(r[c]) for c in COLUMNS] for r in rows])
    assert paper[:, 3:6] == pytest.approx(fast[:, 3:6], abs=1e-9)


def test_bad_scene_exits_2_with_the_loader_message(tmp_path, capsys):
    path = tmp_path / 'bad.yaml'
    path.write_text('units: furlong\n')
    code, _, _, err = run(capsys, str(path))
    assert code == 2 and 'units' in err and 'furlong' in err and 'Traceback' not in err


def test_unreachable_range_exits_1_after_writing_the_rows_it_solved(capsys):
    code, rows, _, err = run(capsys, 'five_link', '--travel', '0:1000:100')
    assert code == 1 and 'out of reach' in err and len(rows) >= 2


@pytest.mark.parametrize('span, limit', [(('400', '400'), 'bump limit 387.469 mm'),
                                         (('-300', '0'), 'rebound limit -274.673 mm')])
def test_a_first_travel_out_of_reach_is_one_line_and_status_1(capsys, span, limit):
    # Issue 18 defect 4: a traceback (cannot reshape array of size 0) where the first
    # travel asked for is already beyond a limit.
    code, rows, out, err = run(capsys, 'five_link', '--travel', f'{span[0]}:{span[1]}:1')
    assert code == 1 and rows == [] and out == LEADING + '\n'
    assert 'Traceback' not in err and len(err.splitlines()) == 2   # the header line, the why
    assert 'out of reach' in err and limit in err and '(0 positions written)' in err


def test_console_script_runs_as_a_module():
    out = subprocess.run([sys.executable, '-m', 'linkage_ros.tools.sweep', 'five_link',
                          '--travel', '-80:80:80'], capture_output=True, text=True, check=True)
    assert out.stdout.splitlines()[0] == LEADING and len(out.stdout.splitlines()) == 4


def test_a_reader_that_stops_early_ends_the_table_quietly_as_cat_does():
    # linkage-sweep five_link | head -1: once a BrokenPipeError traceback
    sweep_cli = subprocess.Popen([sys.executable, '-m', 'linkage_ros.tools.sweep', 'five_link',
                                  '--travel', '-80:80:0.01'], stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True)
    assert sweep_cli.stdout.readline() == LEADING + '\n'
    sweep_cli.stdout.close()                      # what head does after its line
    err = sweep_cli.stderr.read()
    assert sweep_cli.wait(timeout=60) == 128 + 13  # SIGPIPE's status, as cat's
    assert err == 'linkage-sweep: five_link: 16001 positions from -80 to 80 mm, method fast\n'


@pytest.mark.skipif(not Path('/dev/full').exists(), reason='needs /dev/full')
def test_a_device_that_refuses_writes_is_one_line_and_status_2_before_the_sweep(capsys):
    code, _, _, err = run(capsys, 'five_link', '-o', '/dev/full')
    assert code == 2   # refused before any work: /dev/full refuses even a write of no byte
    assert err == 'linkage-sweep: -o: /dev/full: cannot write (No space left on device)\n'


def test_rack_option_adds_the_rack_column_and_steers(capsys):
    _, rows, out, _ = run(capsys, 'double_wishbone', '--travel', '0:0:1',
                          '--rack', '10')
    assert out.splitlines()[0] == LEADING + ',rack_mm'
    assert float(rows[0]['rack_mm']) == 10.0 and float(rows[0]['toe_deg']) > 3.0


def test_a_rack_range_solves_every_travel_at_every_rack(capsys):
    code, rows, _, _ = run(capsys, 'double_wishbone', '--travel', '-80:80:80',
                           '--rack=-10:10:10')
    assert code == 0 and len(rows) == 9
    assert sorted({float(r['rack_mm']) for r in rows}) == [-10.0, 0.0, 10.0]


def test_rack_on_a_scene_without_steer_link_is_refused(capsys):
    code, _, _, err = run(capsys, 'five_link', '--rack', '5')
    assert code == 2 and 'steer: rack' in err


@pytest.mark.parametrize('option, said', [
    (['--rack', '1e400'], "expected FROM[:TO:STEP], finite numbers with STEP > 0, got '1e400'"),
    (['--rack=1:2'], "expected FROM[:TO:STEP], finite numbers with STEP > 0, got '1:2'"),
    (['--rack=-5:5:0'], "expected FROM[:TO:STEP], finite numbers with STEP > 0, got '-5:5:0'"),
    (['--rack', '5mm'], "'5mm': give FROM[:TO:STEP] as plain numbers, without a unit")])
def test_a_bad_rack_is_one_line_naming_the_option_and_nothing_is_solved(capsys, option, said):
    with pytest.raises(SystemExit) as exited:
        main(['double_wishbone', *option])
    out, err = capsys.readouterr()
    assert (exited.value.code, out) == (2, '')
    assert err == f'linkage-sweep: error: argument --rack: {said} (see linkage-sweep --help)\n'


def test_a_rack_on_a_scene_without_a_steer_link_is_one_line(capsys):
    code, _, out, err = run(capsys, 'five_link', '--rack', '5')
    assert (code, out, err) == (2, '', 'linkage-sweep: five_link: no constraint is marked '
                                'steer: rack, so a rack input moves nothing\n')


def test_alignment_option_adds_its_columns(capsys):
    _, rows, _, _ = run(capsys, 'double_wishbone', '--travel', '-80:80:80', '--alignment')
    assert float(rows[1]['kingpin_inclination_deg']) == pytest.approx(10.66, abs=0.05)
    assert float(rows[1]['scrub_radius_mm']) > 0


def test_a_negative_rack_range_after_a_space_is_read_as_the_range(capsys):
    # argparse took -20:20:10 for an option: "expected one argument"
    code, rows, _, _ = run(capsys, 'double_wishbone', '--travel', '-80:80:80', '--rack',
                           '-20:20:10')
    assert code == 0
    assert sorted({float(r['rack_mm']) for r in rows}) == [-20.0, -10.0, 0.0, 10.0, 20.0]


def test_negative_travels_in_any_float_spelling_are_read(capsys):
    code, rows, _, _ = run(capsys, 'five_link', '--travel', '-4e1:-.5e1:35')
    assert code == 0 and [float(r['travel_mm']) for r in rows] == [-40.0, -5.0]


@pytest.mark.parametrize('value, said', [
    ('-80mm', "'-80mm': give FROM[:TO:STEP] as plain numbers, without a unit"),
    ('-80:80mm:1', "'-80:80mm:1': give FROM[:TO:STEP] as plain numbers, without a unit"),
    ('eighty', "expected FROM[:TO:STEP], finite numbers with STEP > 0, got 'eighty'"),
    ('0:10', "expected FROM[:TO:STEP], finite numbers with STEP > 0, got '0:10'"),
    ('0:10:-1', "expected FROM[:TO:STEP], finite numbers with STEP > 0, got '0:10:-1'"),
    ('0:inf:1', "expected FROM[:TO:STEP], finite numbers with STEP > 0, got '0:inf:1'")])
def test_a_bad_travel_is_one_line_naming_the_option_and_status_2(capsys, value, said):
    with pytest.raises(SystemExit) as exited:
        main(['five_link', f'--travel={value}'])
    err = capsys.readouterr().err
    assert exited.value.code == 2
    assert err == f'linkage-sweep: error: argument --travel: {said} (see linkage-sweep --help)\n'


def test_one_travel_value_is_one_position(capsys):
    code, rows, _, _ = run(capsys, 'five_link', '--travel', '-25')
    assert code == 0 and [float(r['travel_mm']) for r in rows] == [-25.0]


def test_a_travel_range_runs_down_when_to_is_below_from(capsys):
    code, rows, _, _ = run(capsys, 'five_link', '--travel', '20:-20:20')
    assert code == 0 and [float(r['travel_mm']) for r in rows] == [20.0, 0.0, -20.0]


def test_one_position_is_said_in_the_singular(capsys):
    code, rows, _, err = run(capsys, 'five_link', '--travel', '10:10:1')
    assert code == 0 and len(rows) == 1
    assert err.splitlines()[0] == 'linkage-sweep: five_link: 1 position from 10 to 10 mm, ' \
        'method fast'


@pytest.mark.parametrize('option, said', [
    (['--travel=-80:80:1e-300'], '--travel: 1.6e+302 positions (from -80 to 80 mm at '
     'steps of 1e-300 mm) would need about 1.49e+296 GiB'),
    (['--travel', '0:100:1e-9'], '--travel: 1e+11 positions '
     '(from 0 to 100 mm at steps of 1e-09 mm) would need about 9.31e+04 GiB'),
    (['--travel=-80:80:5e-324'], '--travel: more than 1e308 positions (from -80 to 80 '
     'mm at steps of 4.94066e-324 mm) would need more memory than there is'),
    (['--travel', '-80:80:80', '--rack=-20:20:1e-4'], '--rack: 1.2e+06 positions (3 travels '
     'x 400001 racks) would need about 1.12 GiB'),
    (['--travel', '-80:80:80', '--rack=0:1:1e-300'], '--rack: 1e+300 positions (from 0 to 1 mm '
     'at steps of 1e-300 mm) would need about 9.31e+293 GiB')])
def test_a_request_beyond_a_million_positions_is_one_line_saying_what_it_needs(
        capsys, option, said):
    # each was a traceback (a MemoryError or numpy's "Maximum allowed size exceeded")
    code, _, out, err = run(capsys, 'double_wishbone', *option)
    assert (code, out) == (2, '')
    assert err == f'linkage-sweep: {said}; the limit is 1,000,000 positions (a larger step, ' \
        'or a shorter range)\n'


def test_a_scene_whose_travel_step_no_sweep_could_hold_is_one_line(tmp_path, capsys):
    scene = (Path(__file__).parents[2] / 'config' / 'scenes' / 'five_link.yaml').read_text()
    path = tmp_path / 'fine.yaml'
    path.write_text(scene.replace('step: 1}', 'step: 1e-300}'))
    code, _, out, err = run(capsys, str(path))
    assert (code, out) == (2, '')
    assert err.startswith(f'linkage-sweep: {path}: travel.step: 1.6e+302 positions ')
    assert err.count('\n') == 1


def test_a_scene_s_warnings_are_printed_once_before_it_is_solved(capsys):
    stress = Path(__file__).parents[2] / 'config' / 'stress' / 'five_link_kilometres.yaml'
    code, rows, _, err = run(capsys, str(stress), '--travel', '0:0:1')
    assert code == 0 and len(rows) == 1
    assert err.splitlines()[0] == (
        f'linkage-sweep: warning: {stress}: wheel_radius 3.3e+06 mm and half-track 7.6e+06 mm '
        '(|y| of the wheel centre) are outside 50-3000 mm, implausible for a road vehicle: a '
        'file written in mm but labelled units: m? (solved as given)')
    assert err.count('warning') == 1
