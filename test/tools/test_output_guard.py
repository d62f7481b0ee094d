# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
No program output replaces an input or a device (linkage_ros/outputs/guard.py).

Every program with a file output is given, as that output, an input it reads named every way
a path can name it (hypothesis draws the way and the names of the links): the same path, a
'./' path, a path through '..', a symbolic link (or a chain of them), a hard link, a scene the
vehicle file names. Each refusal is one line naming the option, status 2, before any work,
and leaves every file as it was (bytes and inode) with nothing new beside it.
"""

import os
from pathlib import Path
import shutil

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros.core.model import scene_dir, vehicle_dir
from linkage_ros.study import cli as study_cli
from linkage_ros.tools import (axle, chrono, foxglove_layout, kc, kinematic_map, plot,
                               replay, rerun_convert, sweep, urdf, vehicle)
import pytest

ROOT = Path(__file__).resolve().parents[2]
BAG = ROOT / 'bags' / 'five_link_sweep.mcap'
CHRONO = ROOT / 'config' / 'chrono'
SETTINGS = settings(max_examples=12, deadline=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture])
# Names of links: unicode, dashes, digits first, long; no '/' and no NUL (a file name's own)
NAMES = st.text(st.characters(blacklist_categories=('Cs', 'Cc'), blacklist_characters='/\0'),
                min_size=1, max_size=40).filter(lambda n: n not in ('.', '..') and
                                                len(n.encode()) < 200)
WAYS = ('same', 'dot', 'dotdot', 'absolute', 'symlink', 'chain', 'hardlink')


def workspace(folder):
    """Make the inputs of every case in folder: scenes, a vehicle naming them, a bag, Chrono."""
    for name, bundled in (('dw.yaml', 'double_wishbone'), ('fl.yaml', 'five_link'),
                          ('dwb.yaml', 'double_wishbone_bushings')):
        shutil.copy(scene_dir() / f'{bundled}.yaml', folder / name)
    text = (vehicle_dir() / 'demo_vehicle.yaml').read_text()
    (folder / 'car.yaml').write_text(text.replace('scene: double_wishbone', 'scene: dw.yaml')
                                     .replace('scene: five_link', 'scene: fl.yaml'))
    shutil.copy(BAG, folder / 'run.mcap')
    shutil.copytree(CHRONO / 'hmmwv', folder / 'data' / 'hmmwv')
    (folder / 'targets.yaml').write_text(
        'scene: dw.yaml\nfree:\n  tie_rod.base: [-5, 5]\n'
        'targets:\n  - {quantity: toe_deg, travel: [-20, 20, 20], value: 0.0}\n')
    return folder


FRONT = 'data/hmmwv/suspension/HMMWV_DoubleWishboneFront.json'
VEHICLE_JSON = 'data/hmmwv/vehicle/HMMWV_Vehicle.json'
# (program, its main, argv with OUT for the output, the input named as OUT, the option)
CASES = [
    ('linkage-sweep', sweep.main, ['fl.yaml', '-o', 'OUT'], 'fl.yaml', '-o'),
    ('linkage-axle', axle.main, ['car.yaml', '--axle', 'front', '-o', 'OUT'], 'dw.yaml', '-o'),
    ('linkage-kc', kc.main, ['dwb.yaml', '--travel', '0', '-o', 'OUT'], 'dwb.yaml', '-o'),
    ('linkage-kc', kc.main, ['dwb.yaml', '--travel', '0', '--matrix', 'OUT'], 'dwb.yaml',
     '--matrix'),
    ('linkage-kc', kc.main, ['dwb.yaml', '--travel', '0', '--plot', 'OUT'], 'dwb.yaml', '--plot'),
    ('linkage-vehicle', vehicle.main, ['car.yaml', '--csv', 'OUT'], 'car.yaml', '-o'),
    ('linkage-vehicle', vehicle.main, ['car.yaml', '--csv', 'OUT'], 'fl.yaml', '-o'),
    ('linkage-vehicle', vehicle.main, ['car.yaml', '--plot', 'OUT'], 'dw.yaml', '--plot'),
    ('linkage-urdf', urdf.main, ['car.yaml', '-o', 'OUT'], 'fl.yaml', '-o'),
    ('linkage-foxglove', foxglove_layout.main, ['car.yaml', '-o', 'OUT'], 'car.yaml', '-o'),
    ('linkage-chrono', chrono.main, ['import', VEHICLE_JSON, '-o', 'OUT'], FRONT, '-o'),
    ('linkage-chrono', chrono.main, ['export', 'dw.yaml', '-o', 'OUT'], 'dw.yaml', '-o'),
    ('linkage-study', study_cli.main, ['sensitivity', 'dw.yaml', '--travel', '0', '-o', 'OUT'],
     'dw.yaml', '-o'),
    ('linkage-study', study_cli.main, ['tolerance', 'dw.yaml', '--travel', '0', '--sigma', '0.1',
                                       '--samples', '4', '--plot', 'OUT'], 'dw.yaml', '--plot'),
    ('linkage-study', study_cli.main, ['fit', 'targets.yaml', '-o', 'OUT'], 'dw.yaml', '-o'),
    ('linkage-replay', replay.main, ['solve', 'run.mcap', '-o', 'OUT'], 'run.mcap', '-o'),
    ('linkage-replay', replay.main, ['sweep', '--scene', 'fl.yaml', '-o', 'OUT'], 'fl.yaml',
     '-o'),
    ('linkage-rerun', rerun_convert.main, ['run.mcap', '--scene', 'fl.yaml', '-o', 'OUT'],
     'fl.yaml', '-o'),
    ('linkage-plot', plot.main, ['camber-toe', '-o', 'OUT', 'fl.yaml'], 'fl.yaml', ''),
]


def alias(folder, target, way, name, depth=1):
    """Return a path that names target (a file or folder in folder) the way asked, as text."""
    if way == 'same':
        return target
    if way == 'dot':
        return f'./{target}'
    if way == 'dotdot':
        return f'../{folder.name}/{target}'
    if way == 'absolute':
        return str(folder / target)
    link = folder / 'links' / name
    link.parent.mkdir(exist_ok=True)
    if way == 'hardlink':
        os.link(folder / target, link)
        return str(link)
    previous = folder / target
    for k in range(depth):
        step = link if k == depth - 1 else folder / 'links' / f'{k}{name}'
        step.symlink_to(previous)
        previous = step
    return str(link)


def snapshot(folder):
    """Return {path: (bytes or None, inode)} of everything under folder (links as links)."""
    seen = {}
    for path in sorted(folder.rglob('*')):
        info = path.lstat()
        content = path.read_bytes() if path.is_file() and not path.is_symlink() else None
        seen[str(path)] = (content, info.st_ino)
    return seen


def refused(main, argv, capsys):
    """Run main(argv): (status, the one line on stderr); asserts nothing on stdout."""
    try:
        status = main(argv)
    except SystemExit as exited:
        status = exited.code
    out, err = capsys.readouterr()
    assert out == '', out
    return status, err


@pytest.mark.parametrize('prog, main, argv, source, option', CASES,
                         ids=[f'{c[0]}{c[4]}-{c[3]}' for c in CASES])
@SETTINGS
@given(way=st.sampled_from(WAYS), name=NAMES, depth=st.integers(1, 3))
def test_an_output_that_names_an_input_is_refused_before_any_work(
        prog, main, argv, source, option, way, name, depth, tmp_path_factory, capsys,
        monkeypatch):
    folder = workspace(tmp_path_factory.mktemp('ws'))
    monkeypatch.chdir(folder)
    path = alias(folder, source, way, name, depth)
    before = snapshot(folder)
    status, err = refused(main, [path if a == 'OUT' else a for a in argv], capsys)
    assert status == 2, err
    assert err.count('\n') == 1 and err.startswith(f'{prog}: ') and 'Traceback' not in err
    assert f'{option}: ' in err and ' is ' in err and 'input' in err, err
    assert snapshot(folder) == before   # nothing written, replaced or left beside


def test_a_vehicle_is_refused_as_the_csv_of_its_own_sheet(tmp_path, capsys, monkeypatch):
    # the trial: linkage-vehicle VEH --csv VEH replaced the vehicle file with the sheet
    folder = workspace(tmp_path)
    monkeypatch.chdir(folder)
    status, err = refused(vehicle.main, ['car.yaml', '--csv', 'car.yaml'], capsys)
    assert (status, err) == (2, 'linkage-vehicle: -o: car.yaml is the input car.yaml; give '
                                'another file name\n')
    assert (folder / 'car.yaml').read_text().startswith('# A four-corner vehicle')


def test_a_chrono_export_onto_its_scene_is_refused(tmp_path, capsys, monkeypatch):
    folder = workspace(tmp_path)
    monkeypatch.chdir(folder)
    before = (folder / 'dw.yaml').read_bytes()
    status, err = refused(chrono.main, ['export', 'dw.yaml', '-o', 'dw.yaml'], capsys)
    assert (status, err) == (2, 'linkage-chrono: -o: dw.yaml is the input dw.yaml; give '
                                'another file name\n')
    assert (folder / 'dw.yaml').read_bytes() == before


def test_a_chrono_vehicle_import_is_refused_onto_a_suspension_file_it_reads(
        tmp_path, capsys, monkeypatch):
    folder = workspace(tmp_path)
    monkeypatch.chdir(folder)
    before = (folder / FRONT).read_bytes()
    status, err = refused(chrono.main, ['import', VEHICLE_JSON, '-o', FRONT], capsys)
    assert status == 2 and err == (f'linkage-chrono: -o: {FRONT} is the input '
                                   f'{folder / FRONT}; give another file name\n')
    assert (folder / FRONT).read_bytes() == before


@SETTINGS
@given(way=st.sampled_from(('same', 'absolute', 'symlink', 'hardlink')), name=NAMES)
def test_a_tables_folder_that_holds_an_input_named_like_a_table_is_refused(
        way, name, tmp_path_factory, capsys, monkeypatch):
    # the trial: --tables DIR replaced a scene of the vehicle named front_heave.csv
    folder = workspace(tmp_path_factory.mktemp('ws'))
    monkeypatch.chdir(folder)
    (folder / 'dw.yaml').rename(folder / 'front_heave.csv')
    car = (folder / 'car.yaml').read_text().replace('scene: dw.yaml', 'scene: front_heave.csv')
    (folder / 'car.yaml').write_text(car)
    tables = '.'
    if way in ('symlink', 'hardlink'):   # another folder, the file in it a link to the input
        tables = str(folder / 'links' / name)
        Path(tables).mkdir(parents=True)
        (os.link if way == 'hardlink' else os.symlink)(folder / 'front_heave.csv',
                                                       Path(tables) / 'front_heave.csv')
    elif way == 'absolute':
        tables = str(folder)
    before = snapshot(folder)
    status, err = refused(vehicle.main, ['car.yaml', '--tables', tables], capsys)
    assert status == 2 and err.startswith('linkage-vehicle: --tables: ') and \
        err.endswith('front_heave.csv; give another folder\n'), err
    assert snapshot(folder) == before


@pytest.mark.parametrize('main, argv, prog', [
    (vehicle.main, ['demo_vehicle', '--tables', '/proc'], 'linkage-vehicle: --tables'),
    (kinematic_map.main, ['double_wishbone', '-o', '/proc'], 'linkage-map: -o')])
def test_a_folder_that_cannot_hold_files_is_one_line(main, argv, prog, capsys):
    status, err = refused(main, argv, capsys)   # once a traceback after the sheet was solved
    assert status == 2 and err.startswith(f'{prog}: cannot write into the folder /proc (')
    assert err.count('\n') == 1


@pytest.mark.parametrize('prog, main, argv', [
    ('linkage-sweep', sweep.main, ['five_link', '-o', 'OUT']),
    ('linkage-kc', kc.main, ['five_link_bushings', '--travel', '0', '-o', 'OUT']),
    ('linkage-study', study_cli.main, ['sensitivity', 'five_link', '--travel', '0', '-o', 'OUT']),
    ('linkage-chrono', chrono.main, ['export', 'five_link', '-o', 'OUT']),
    ('linkage-urdf', urdf.main, ['demo_vehicle', '-o', 'OUT']),
    ('linkage-replay', replay.main, ['sweep', '--scene', 'five_link', '-o', 'OUT'])])
def test_a_bundled_file_named_by_its_bare_name_is_refused_as_an_output(
        prog, main, argv, tmp_path, capsys, monkeypatch):
    # linkage-study once compared -o with the name 'five_link', not with the file it names
    config = tmp_path / 'config'   # a copy: a program that failed here would write the copy
    shutil.copytree(ROOT / 'config' / 'scenes', config / 'scenes')
    shutil.copytree(ROOT / 'config' / 'vehicles', config / 'vehicles')
    monkeypatch.setattr('linkage_ros.core.model.bundled.SOURCE_CONFIG', config)
    bundled = config / 'scenes' / ('five_link_bushings.yaml' if prog == 'linkage-kc' else
                                   'five_link.yaml')
    before = snapshot(config)
    status, err = refused(main, [str(bundled) if a == 'OUT' else a for a in argv], capsys)
    assert status == 2 and err == (f'{prog}: -o: {bundled} is the input {bundled}; give '
                                   'another file name\n')
    assert snapshot(config) == before
