# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node and a scene or vehicle with a number outside its range (issue 36, item 2).

A scene of `axial: 1e308` passed the loader: at start the node exited 2 with neither file nor
field named; switched in at run time, its SetParameters request was never answered and the
node died. The loader now refuses it (doc/scenes.md#ranges): at start in one line, status 2;
at run time as the request's answer, unsuccessful with that line, and the node goes on.
"""

from pathlib import Path

from linkage_ros.core.model import load_scene
from linkage_ros.ros.testing import ParameterClient
import pytest
from test_node_manners import run_node
from test_params_runtime import assert_answers
import yaml

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def bad_scene(tmp_path):
    """Return a bushed scene whose first arm's axial rate is 1e308 N/mm, and its line."""
    data = yaml.safe_load(Path(load_scene('double_wishbone_bushings').source).read_text())
    arm = data['constraints'][0]
    arm['bushing']['axial'] = 1e308
    path = tmp_path / 'huge_axial.yaml'
    path.write_text(yaml.safe_dump(data))
    return str(path), (f'{path}: constraints[0] ({arm["name"]}).bushing.axial: 1e+308 N/mm is '
                       'outside 0.001 to 1e+11 N/mm (doc/scenes.md#ranges)')


def test_a_node_started_on_it_says_the_file_and_field_in_one_line_and_ends_2(bad_scene):
    path, line = bad_scene
    status, out, err = run_node('--ros-args', '-p', f'scene:={path}')
    assert (status, out) == (2, '')
    assert err == f'suspension_node: {line}\n'


def test_a_node_started_on_a_vehicle_of_1e308_kg_says_so_and_ends_2(tmp_path):
    car = yaml.safe_load((ROOT / 'config' / 'vehicles' / 'demo_vehicle.yaml').read_text())
    car['mass']['sprung'] = 1e308
    path = tmp_path / 'heavy.yaml'
    path.write_text(yaml.safe_dump(car))
    status, out, err = run_node('--ros-args', '-p', f'vehicle:={path}')
    assert (status, out) == (2, '')
    assert err == (f'suspension_node: {path}: mass.sprung: 1e+308 kg is outside 0.001 to 1e+07 '
                   'kg (doc/scenes.md#ranges)\n')


def test_switched_in_at_run_time_it_is_refused_as_the_answer_and_the_node_goes_on(
        suspension_node, probe, bad_scene):
    path, line = bad_scene
    node = suspension_node(diagnostic_period=3600.0)
    assert_answers(probe, 'five_link', [0.01])
    client = ParameterClient(probe)
    assert client.set(scene=path) == [(False, line)]
    assert node.get_parameter('scene').value == 'five_link'
    assert_answers(probe, 'five_link', [0.02, -0.01])          # the node goes on
    assert client.set(scene='double_wishbone') == [(True, '')]   # and takes the next request
    assert_answers(probe, 'double_wishbone', [0.015])
