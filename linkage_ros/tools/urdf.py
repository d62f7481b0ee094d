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

from .target import check_text_output, write_text
from .. import cli
from ..core.base import LinkageError
from ..core.model import load_target

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


@cli.program(PROG)
def _main(argv):
    parser = cli.Parser(PROG, cli.summary(__doc__), EPILOG)
    parser.add_argument('target', metavar='SCENE_OR_VEHICLE',
                        help='bundled scene or vehicle name, or the path of either file')
    parser.add_argument('-o', '--output', metavar='FILE', required=True,
                        help="the URDF file to write ('-': stdout)")
    parser.add_argument('--frame-id', default='base_link',
                        help="the root link: the node's frame_id (default: base_link)")
    args = parser.parse_args(argv)
    try:
        target = load_target(args.target)
        cli.warn(PROG, target.warnings)
        check_text_output(args.output, target)
        from ..answer.robot_description import robot_description
        text = robot_description(target.prefixed, args.frame_id, target.name)
        write_text(args.output, text)
    except (cli.Mistake, LinkageError) as exc:
        return cli.fail(PROG, exc)
    if args.output != '-':
        print(f'{PROG}: {target.name}: {text.count("<link ")} links -> {args.output}',
              file=sys.stderr)
    return cli.DONE


if __name__ == '__main__':
    sys.exit(main())
