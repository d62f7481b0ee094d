# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node and a scene whose constraint name is no ROS name token (issue 36, item 3).

Before: a bushed scene with a constraint named lower-arm (or unterer_Querlenker_ü, 9arm) made
pickup/<name> topics rclpy refuses: at start a 26-line traceback, and switched in at run time
the node died. Now the name is refused at load: at start one line and status 2, no
traceback; at run time the SetParameters request is answered unsuccessfully with that line,
and the node goes on answering with the scene it has.
"""

import copy
from pathlib import Path

from linkage_ros.core.model import SceneError
from linkage_ros.ros.testing import ParameterClient
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
BAD = ['lower-arm', 'unterer_Querlenker_ü', '9arm']


def bad_scene(tmp_path, name):
    """Write double_wishbone_bushings with its lower arm renamed name; return its path."""
    data = yaml.safe_load((ROOT / 'config' / 'scenes' / 'double_wishbone_bushings.yaml')
                          .read_text())
    data = copy.deepcopy(data)
    data['constraints'][1]['name'] = name
    for element in data['elements']:
        element['arm'] = name
    path = tmp_path / 'bad_names.yaml'
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding='utf-8')
    return path


def said_of(path, name):
    return (f'{path}: constraints[1].name: {name!r} is not a ROS name token: a letter, then '
            'letters, digits and _, without __ or a trailing _, at most 64 characters')


@pytest.mark.parametrize('name', BAD)
def test_a_node_started_on_it_exits_2_with_one_line(node_process, tmp_path, name):
    node = node_process('-p', f'scene:={bad_scene(tmp_path, name)}')
    status, out, err = node.finish(60.0)
    assert status == 2
    assert err.startswith(f'suspension_node: {said_of(bad_scene(tmp_path, name), name)}')
    assert len(err.splitlines()) == 1 and 'Traceback' not in err


def test_the_in_process_node_refuses_it_with_the_scene_error(suspension_node, tmp_path):
    path = bad_scene(tmp_path, 'lower-arm')
    with pytest.raises(SceneError) as raised:
        suspension_node(scene=str(path))
    assert str(raised.value).startswith(said_of(path, 'lower-arm'))


@pytest.mark.parametrize('name', BAD)
def test_switched_in_at_run_time_it_is_refused_and_the_node_answers_on(
        suspension_node, probe, tmp_path, name):
    node = suspension_node(scene='double_wishbone', diagnostic_period=3600.0)
    path = bad_scene(tmp_path, name)
    (result,) = ParameterClient(probe).set(scene=str(path))
    assert result[0] is False and result[1].startswith(said_of(path, name)), result
    assert node.corners[''].scene.name == 'double_wishbone'
    assert probe.ask(0.01).pose is not None
