# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-foxglove: write the Foxglove layout of a scene or a vehicle.

    foxglove_layout({'': scene}, 'base_link')                      -> layout (dict)
    foxglove_layout({'front_left/': scene, ...}, 'base_link')      a vehicle's corners

The layout is config/foxglove_layout.json (a 3D panel with the URDF of robot_description placed
by TF, over a ground grid, beside plots of the wheel centre's z (the travel, as answered),
camber and toe) made for the topics that suspension_node publishes for that scene or
vehicle: each plot names every corner's topic (front_left/camber, ...), and the grid lies in
the contact-patch plane, the design wheel centre's z less the wheel radius (m, in frame_id;
the mean over the corners; z = 0 where no scene gives a wheel_radius).
"""

import copy
import json
import sys

from .target import TextProgram
from .. import cli
from ..core.base import M_PER_MM

PROG = 'linkage-foxglove'
TEMPLATE = 'foxglove_layout.json'     # in the package's config folder (core.model.bundled)
# plot panel: (topic's last name, the message path after it) of what it draws. Travel is
# drawn as the wheel centre's z of the answers: a vehicle commanded by joint_states has no
# wheel_travel messages, and every answer has a pose.
PLOTS = {'Plot!travel': ('wheel_carrier_pose', '.pose.position.z'),
         'Plot!camber': ('camber', '.data.@degrees'), 'Plot!toe': ('toe', '.data.@degrees')}
LABELS = {'Plot!travel': 'wheel centre z', 'Plot!camber': 'camber', 'Plot!toe': 'toe'}
EPILOG = """The layout's topics are those the node has for the scene or vehicle (relative names
under the root namespace: run the node in another namespace and they are not found); the
grid is the contact-patch plane of the design position.

example:
  linkage-foxglove demo_vehicle -o demo_vehicle_layout.json
  (Foxglove: open the vehicle's .mcap, then Layout > Import from file)

exit status:
  0  written
""" + '  ' + cli.EXIT_STATUS


def template() -> dict:
    """Return the layout every generated one starts from (config/foxglove_layout.json)."""
    from ..core.model import config_dir
    return json.loads((config_dir() / TEMPLATE).read_text(encoding='utf-8'))


def ground_z(scenes: dict) -> float:
    """
    Return the z (m, frame_id) of the contact-patch plane of scenes ({prefix: Scene}).

    The mean over the scenes that have a wheel_radius of their design wheel centre's z less
    that radius; 0.0 if none has one.
    """
    patches = [s.wheel_center[2] - s.wheel_radius for s in scenes.values() if s.wheel_radius > 0]
    return float(sum(patches) / len(patches)) * M_PER_MM if patches else 0.0


def foxglove_layout(scenes: dict, frame_id: str = 'base_link') -> dict:
    """
    Return the Foxglove layout of scenes ({topic prefix: Scene}; '' for one scene).

    Plots of every corner's wheel centre z (m), camber and toe (deg), each path labelled
    with its corner; the 3D panel follows frame_id, with its grid at ground_z.
    """
    layout = copy.deepcopy(template())
    panels = layout['configById']
    three_d = next(v for k, v in panels.items() if k.startswith('3D!'))
    three_d['followTf'] = frame_id
    grid = next(v for v in three_d['layers'].values() if v['layerId'] == 'foxglove.Grid')
    grid['frameId'] = frame_id
    grid['position'] = [0.0, 0.0, round(ground_z(scenes), 9)]
    for panel, (name, path) in PLOTS.items():
        paths = []
        for prefix in scenes:
            label = f'{prefix.rstrip("/")} {LABELS[panel]}'.strip()
            paths.append({'value': f'/{prefix}{name}{path}', 'enabled': True,
                          'timestampMethod': 'receiveTime', 'label': label})
        panels[panel]['paths'] = paths
    return layout


def layout_text(layout: dict) -> str:
    """Return a layout as the JSON text written (2-space indent, a newline at the end)."""
    return json.dumps(layout, indent=2) + '\n'


def main(argv=None):
    """Run linkage-foxglove; returns the exit status."""
    return _main(argv)


def _said(target, text):
    scenes = target.prefixed
    return (f'{len(scenes)} corner{"s" if len(scenes) > 1 else ""}, ground at z = '
            f'{ground_z(scenes):.4f} m')


PROGRAM = TextProgram(
    PROG, __doc__, EPILOG, "the layout (.json) to write ('-': stdout)",
    "the node's frame_id, which the 3D view follows (default: base_link)",
    lambda target, frame_id: layout_text(foxglove_layout(target.prefixed, frame_id)), _said)


@cli.program(PROG)
def _main(argv):
    return PROGRAM.run(argv)


if __name__ == '__main__':
    sys.exit(main())
