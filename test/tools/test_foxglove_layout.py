# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The Foxglove layout of a scene or a vehicle (linkage-foxglove, tools/foxglove_layout.py).

Topics are checked against what suspension_node publishes for the scene or vehicle (its own
list, ros/corner.corner_outputs, and the bundled bag); the grid against the contact-patch
plane computed from the scene files' numbers by hand.
"""

import json
from pathlib import Path
import subprocess
import sys

from linkage_ros.core.model import load_scene, load_vehicle
from linkage_ros.ros.corner import corner_outputs
from linkage_ros.ros.parameters import PARAMETERS
from linkage_ros.ros.testing import read_mcap_ros2
from linkage_ros.tools.foxglove_layout import foxglove_layout
import pytest

ROOT = Path(__file__).resolve().parents[2]
BUNDLED = ROOT / 'config' / 'foxglove_layout.json'


def named_topics(layout):
    """Return every topic a layout reads: its plots' and its URDF layer's."""
    panels = layout['configById']
    topics = {p['value'].split('.')[0] for k, v in panels.items() if k.startswith('Plot!')
              for p in v['paths']}
    three_d = next(v for k, v in panels.items() if k.startswith('3D!'))
    return topics | {v['topic'] for v in three_d['layers'].values()
                     if v['layerId'] == 'foxglove.Urdf'}


def grid_z(layout):
    three_d = next(v for k, v in layout['configById'].items() if k.startswith('3D!'))
    (grid,) = [v for v in three_d['layers'].values() if v['layerId'] == 'foxglove.Grid']
    return grid['position'][2]


def published(scenes):
    """Return the topics the node publishes for {prefix: Scene}, with its defaults."""
    params = {name: spec[0] for name, spec in PARAMETERS.items()}
    topics = {'/robot_description', '/tf', '/tf_static', '/diagnostics'}
    for prefix, scene in scenes.items():
        topics |= {'/' + name for name, kind in corner_outputs(scene, params, prefix).items()
                   if kind == 'publisher'}
    return topics


def test_a_vehicle_layout_plots_every_corner_on_topics_the_node_publishes_for_it():
    vehicle = load_vehicle('demo_vehicle')
    scenes = {f'{name}/': scene for name, scene in vehicle.corners.items()}
    layout = foxglove_layout(scenes)
    topics = named_topics(layout)
    assert topics <= published(scenes)
    for corner in vehicle.corners:
        assert {f'/{corner}/wheel_carrier_pose', f'/{corner}/camber',
                f'/{corner}/toe'} <= topics


def test_the_bundled_layout_is_five_links_and_names_only_topics_of_the_bundled_bag():
    layout = json.loads(BUNDLED.read_text())
    assert layout == foxglove_layout({'': load_scene('five_link')})
    bag = set(read_mcap_ros2(ROOT / 'bags' / 'five_link_sweep.mcap'))
    assert named_topics(layout) <= bag


@pytest.mark.parametrize('scene,ground_m', [
    ('five_link', (300.0 - 330.0) / 1000.0),         # five_link.yaml: centre z, radius (mm)
    ('macpherson', -0.02602507 - 0.33),              # macpherson.yaml, in m
])
def test_the_grid_lies_in_the_contact_patch_plane(scene, ground_m):
    assert grid_z(foxglove_layout({'': load_scene(scene)})) == pytest.approx(ground_m,
                                                                             abs=1e-9)


def test_the_bundled_layouts_grid_lies_in_five_links_contact_patch_plane():
    assert grid_z(json.loads(BUNDLED.read_text())) == pytest.approx(-0.030, abs=1e-9)


def test_linkage_foxglove_writes_the_layout_of_a_vehicle(tmp_path):
    out = tmp_path / 'layout.json'
    done = subprocess.run([str(Path(sys.executable).parent / 'linkage-foxglove'),
                           'demo_vehicle', '-o', str(out)], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert 'demo_vehicle: 4 corners, ground at z = -0.0300 m' in done.stderr
    vehicle = load_vehicle('demo_vehicle')
    assert json.loads(out.read_text()) == foxglove_layout(
        {f'{name}/': scene for name, scene in vehicle.corners.items()})
