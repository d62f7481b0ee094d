# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
One loader for a scene or a vehicle (core/model/target.py).

As programs, the node and a recording name them: the kind from the name or the file, the
corners, every file read.
"""

import shutil

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros.core.model import (load_scene, load_target, load_vehicle, scene_dir, SceneError,
                                    vehicle_dir)
from linkage_ros.record.stored import load_stored
import numpy as np
import pytest

# file names: unicode, dashes, digits first, long; no '/' or NUL, and a YAML suffix
NAMES = st.text(st.characters(blacklist_categories=('Cs', 'Cc'), blacklist_characters='/\0'),
                min_size=1, max_size=60).filter(lambda n: len(n.encode()) < 200 and
                                                n not in ('.', '..'))


def same_scene(a, b):
    """Tell whether two loaded scenes are alike: name, file, points, constraints (arrays)."""
    return (a.name, a.source, a.side, len(a.constraints)) == (
        b.name, b.source, b.side, len(b.constraints)) and all(
        np.array_equal(getattr(a, k), getattr(b, k))
        for k in ('wheel_center', 'spin_axis_point', 'third_point'))


def same_corners(a, b):
    """Tell whether two {corner: Scene} are alike, corner by corner, in order."""
    return list(a) == list(b) and all(same_scene(a[k], b[k]) for k in a)


def vehicle_beside(folder, name):
    """Write demo_vehicle as folder/name, its corners naming dw.yaml and fl.yaml beside it."""
    shutil.copy(scene_dir() / 'double_wishbone.yaml', folder / 'dw.yaml')
    shutil.copy(scene_dir() / 'five_link.yaml', folder / 'fl.yaml')
    text = (vehicle_dir() / 'demo_vehicle.yaml').read_text()
    path = folder / name
    path.write_text(text.replace('scene: double_wishbone', 'scene: dw.yaml')
                    .replace('scene: five_link', 'scene: fl.yaml'))
    return path


@settings(max_examples=25, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=NAMES, suffix=st.sampled_from(['.yaml', '.yml', '.YAML', '.txt']))
def test_a_vehicle_file_by_any_name_loads_as_the_vehicle_with_every_file_it_read(
        name, suffix, tmp_path_factory):
    folder = tmp_path_factory.mktemp('car')
    path = vehicle_beside(folder, name + suffix)
    target = load_target(str(path))
    expected = load_vehicle(str(path))
    assert target.vehicle.source == expected.source and target.scene is None
    assert same_corners(target.corners, expected.corners) and target.name == 'demo_vehicle'
    assert target.files == (str(path), str(folder / 'dw.yaml'), str(folder / 'fl.yaml'))
    assert list(target.prefixed) == [f'{c}/' for c in expected.corners]


@settings(max_examples=25, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=NAMES, suffix=st.sampled_from(['.yaml', '.yml']))
def test_a_scene_file_by_any_name_loads_as_its_one_corner(name, suffix, tmp_path_factory):
    path = tmp_path_factory.mktemp('scene') / (name + suffix)
    shutil.copy(scene_dir() / 'five_link.yaml', path)
    target = load_target(str(path))
    assert target.vehicle is None and same_scene(target.scene, load_scene(str(path)))
    assert list(target.corners) == [''] and target.prefixed == {'': target.scene}
    assert target.files == (str(path),) and target.name == 'five_link'


@pytest.mark.parametrize('name, kind', [('demo_vehicle', 'vehicle'), ('five_link', 'scene'),
                                        ('double_wishbone_bushings', 'scene')])
def test_a_bare_name_is_the_bundled_vehicle_if_there_is_one_else_the_bundled_scene(name, kind):
    target = load_target(name)
    assert (target.vehicle is not None) == (kind == 'vehicle')
    folder = vehicle_dir() if kind == 'vehicle' else scene_dir()
    assert target.files[0] == str(folder / f'{name}.yaml')


def test_a_kind_given_loads_that_kind_only(tmp_path):
    path = vehicle_beside(tmp_path, 'car.yaml')
    with pytest.raises(SceneError, match='car.yaml'):
        load_target(str(path), 'scene')   # the node's scene parameter naming a vehicle file
    with pytest.raises(SceneError, match='five_link'):
        load_target('five_link', 'vehicle')
    with pytest.raises(ValueError, match="kind must be None, scene or vehicle, not 'corner'"):
        load_target('five_link', 'corner')


def test_a_recordings_stored_vehicle_and_scene_load_as_the_files_do(tmp_path):
    path = vehicle_beside(tmp_path, 'car.yaml')
    stored = {'linkage_ros': {'vehicle_yaml': path.read_text(),
                              'scene_yaml/front_left': (tmp_path / 'dw.yaml').read_text(),
                              'scene_yaml/front_right': (tmp_path / 'dw.yaml').read_text(),
                              'scene_yaml/rear_left': (tmp_path / 'fl.yaml').read_text(),
                              'scene_yaml/rear_right': (tmp_path / 'fl.yaml').read_text()}}
    vehicle = load_stored(stored, 'run.mcap')
    from_file = load_target(str(path)).corners
    assert list(vehicle.corners) == list(from_file) and all(
        np.array_equal(vehicle.corners[k].wheel_center, from_file[k].wheel_center)
        for k in from_file)
    assert vehicle.files == ()   # read from the recording, not from files
    scene = load_stored({'linkage_ros': {'scene_yaml': (tmp_path / 'fl.yaml').read_text()}},
                        'run.mcap')
    assert scene.vehicle is None and scene.scene.source == 'run.mcap (its scene_yaml)'
    assert np.array_equal(scene.scene.wheel_center,
                          load_scene(str(tmp_path / 'fl.yaml')).wheel_center)


def test_a_bare_name_is_the_bundled_vehicle_whatever_lies_in_the_current_folder(
        tmp_path, monkeypatch, capsys):
    # linkage-map, urdf and foxglove once took a file named demo_vehicle here for a scene
    # file, and refused it, where every loader takes a bare name for a bundled file
    from linkage_ros.tools import urdf
    (tmp_path / 'demo_vehicle').write_text('not a scene\n')
    monkeypatch.chdir(tmp_path)
    assert load_target('demo_vehicle').files[0] == str(vehicle_dir() / 'demo_vehicle.yaml')
    assert urdf.main(['demo_vehicle', '-o', '-']) == 0
    assert '<link name="front_left/wheel_carrier"' in capsys.readouterr().out
