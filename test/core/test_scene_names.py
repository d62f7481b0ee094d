# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Names and paths of scene and vehicle files that could break the node (issue 27, items 2, 3, 6).

A name becomes TF frame names, URDF (XML) names and diagnostic names: one holding a control
or unassigned character, or starting with '/', is refused at load with one line naming the
file and the field. A path the file system refuses (too long) or that is not a regular file
(a FIFO, which would block the reader for good) is refused the same way.
"""

import copy
import os
import subprocess
import sys
import threading

from linkage_ros.core.model import load_scene, load_vehicle, SceneError
import pytest
from test_scene import VALID
import yaml

BAD_NAMES = [
    ('probe\x01', 'U+0001'),
    ('probe\ufffe', 'U+FFFE'),
    ('pro\x00be', 'U+0000'),
    ('/probe', 'starts with /, which tf2 refuses in a frame name'),
]


def written(tmp_path, data, name='scene.yaml'):
    path = tmp_path / name
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding='utf-8')
    return path


@pytest.mark.parametrize('name,said', BAD_NAMES)
def test_a_scene_name_no_frame_may_have_is_refused_naming_the_field(tmp_path, name, said):
    path = written(tmp_path, {**VALID, 'name': name})
    with pytest.raises(SceneError) as raised:
        load_scene(path)
    assert str(raised.value).startswith(f'{path}: name: {name!r} ')
    assert said in str(raised.value) and '\n' not in str(raised.value)


@pytest.mark.parametrize('name,said', BAD_NAMES)
def test_a_constraint_name_no_frame_may_have_is_refused_naming_the_field(tmp_path, name, said):
    # a constraint's name is stricter still: a ROS name token (test_names_as_tokens.py)
    data = copy.deepcopy(VALID)
    data['constraints'][2]['name'] = name
    path = written(tmp_path, data)
    with pytest.raises(SceneError) as raised:
        load_scene(path)
    assert str(raised.value).startswith(f'{path}: constraints[2].name: {name!r} ')
    assert 'is not a ROS name token' in str(raised.value)


@pytest.mark.parametrize('name,said', BAD_NAMES)
def test_a_vehicle_name_no_frame_may_have_is_refused_naming_the_field(tmp_path, name, said):
    path = written(tmp_path, {'name': name, 'corners': {'front_left': {'scene': 'macpherson'}}},
                   'vehicle.yaml')
    with pytest.raises(SceneError) as raised:
        load_vehicle(path)
    assert str(raised.value).startswith(f'{path}: name: {name!r} ') and said in str(raised.value)


def test_a_name_of_letters_of_any_script_is_kept(tmp_path):
    assert load_scene(written(tmp_path, {**VALID, 'name': 'Vorderachse_é_ß'})).name == \
        'Vorderachse_é_ß'


def test_linkage_urdf_refuses_a_scene_with_a_control_character_in_one_line(tmp_path):
    data = copy.deepcopy(VALID)
    data['constraints'][0]['name'] = 'upper\x01front'
    path = written(tmp_path, data)
    run = subprocess.run([sys.executable, '-c', 'from linkage_ros.tools.urdf import main; '
                          'raise SystemExit(main())', str(path), '-o', str(tmp_path / 'x.urdf')],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 2 and run.stdout == '' and not (tmp_path / 'x.urdf').exists()
    assert len(run.stderr.splitlines()) == 1 and 'U+0001' in run.stderr


def test_a_path_too_long_for_the_file_system_is_refused_in_one_line():
    with pytest.raises(SceneError) as raised:
        load_scene('x' * 5000 + '.yaml')
    assert 'cannot be looked up (File name too long)' in str(raised.value)
    assert len(str(raised.value)) < 400


def test_a_fifo_is_refused_as_not_a_regular_file_without_blocking(tmp_path):
    fifo = tmp_path / 'scene.yaml'
    os.mkfifo(fifo)              # nobody writes to it: opened plainly, it blocks for good
    said = []

    def load():
        with pytest.raises(SceneError) as raised:
            load_scene(fifo)
        said.append(str(raised.value))

    # a daemon thread, so that a loader that blocks fails this test instead of hanging the run
    worker = threading.Thread(target=load, daemon=True)
    worker.start()
    worker.join(60.0)
    assert said == [f'{fifo}: file: not a regular file (a FIFO): give a YAML file']
