# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-urdf: write the robot description (URDF) of a scene or a vehicle.

The same text suspension_node publishes on robot_description
(linkage_ros.answer.robot_description): a link per body (carrier, wheel, each link, arm and
strut of every corner) named as its TF frame, every one hung from the root frame by a floating
joint (the wheel fixed to its carrier), so that RViz, Foxglove or Rerun place each body by the
node's /tf.
"""

import sys

from .target import TextProgram
from .. import cli

PROG = 'linkage-urdf'
EPILOG = """frames and links: <corner>/wheel_carrier, <corner>/wheel, <corner>/<constraint
name> for a vehicle's corners; wheel_carrier, wheel, <constraint name> for a scene.

example:
  linkage-urdf five_link -o five_link.urdf
  linkage-urdf demo_vehicle -o demo_vehicle.urdf --frame-id base_link

exit status:
  0  written
""" + '  ' + cli.EXIT_STATUS


def main(argv=None):
    """Run linkage-urdf; returns the exit status."""
    return _main(argv)


def _text(target, frame_id):
    from ..answer.robot_description import robot_description
    return robot_description(target.prefixed, frame_id, target.name)


PROGRAM = TextProgram(PROG, __doc__, EPILOG, "the URDF file to write ('-': stdout)",
                      "the root link: the node's frame_id (default: base_link)", _text,
                      lambda target, text: f'{text.count("<link ")} links')


@cli.program(PROG)
def _main(argv):
    return PROGRAM.run(argv)


if __name__ == '__main__':
    sys.exit(main())
