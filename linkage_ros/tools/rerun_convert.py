"""
linkage-rerun: convert a recorded run (MCAP) into a Rerun .rrd for offline viewing.

for example:
    linkage-rerun run.mcap                 writes ./run.rrd
    linkage-rerun run.mcap -o view.rrd --scene double_wishbone
    rerun run.rrd                          opens the viewer: 3D view of the corner beside
                                           travel, camber and toe

BAG is an MCAP file with the ROS 2 profile or a rosbag2 bag folder holding one. Reads
wheel_travel, wheel_carrier_pose, camber and toe (by their last name, any namespace) and logs
them as columns (see rerun_view). The scene is --scene, else the one the bag names in its
metadata (custom_data 'scene', written by linkage-replay), else five_link. A bag cut short
or damaged gives a warning naming what was found, and its readable messages are converted.
Progress goes to stderr.
"""

import importlib
import math
import sys

from .. import cli
from ..core.errors import LinkageError
from ..core.scene import load_scene

PROG = 'linkage-rerun'
DEFAULT_SCENE = 'five_link'
ROLES = 'wheel_travel, wheel_carrier_pose, camber or toe'


def convert(bag, scene, output, recording_id=None):
    """
    Log the drawable messages of a Bag (from read_bag) into output (.rrd).

    Returns {role: samples logged}.
    """
    from ..record.rerun_view import RerunRecorder, topic_role
    counts = {}
    with RerunRecorder(output, scene, recording_id=recording_id, batch_rows=math.inf,
                       batch_delay=math.inf) as viewer:
        for m in bag.messages:
            role = topic_role(m.topic)
            if role is None:
                continue
            viewer.record(m.topic, m.type_name, m.data, m.log_time, m.publish_time)
            counts[role] = counts.get(role, 0) + 1
    return counts


def parse_args(argv):
    summary, text = __doc__.strip().split('\n', 1)
    parser = cli.Parser(prog=PROG, description=summary,
                        epilog=text + '\n' + cli.EXIT_STATUSES)
    parser.add_argument('bag', metavar='BAG',
                        help='recorded run: an .mcap file, or a rosbag2 bag folder holding one')
    parser.add_argument('-o', '--output', metavar='OUT',
                        help=".rrd file to write; its folder must exist (default: BAG's name "
                        'with .rrd, in the current folder)')
    parser.add_argument('--scene', help='bundled scene name or scene YAML path (default: the '
                        f'scene named in the bag metadata, else {DEFAULT_SCENE})')
    return parser.parse_args(argv)


@cli.program(PROG)
def main(argv=None):
    """Run linkage-rerun; returns the exit status (0, 1 or 2)."""
    args = parse_args(argv)
    try:
        return run(args)
    except (cli.Mistake, LinkageError) as exc:   # SceneError, RecordingError
        return cli.fail(PROG, exc)


def run(args):
    """Carry out parsed arguments; raises Mistake or LinkageError for a user mistake."""
    for feature, module in (('reading bags', 'linkage_ros.record.mcap_reader'),
                            ('writing .rrd files', 'linkage_ros.record.rerun_view')):
        try:
            importlib.import_module(module)
        except ImportError as exc:
            raise cli.Mistake(cli.missing_package(exc, feature)) from None
    from ..record.mcap_reader import read_bag
    cli.check_input(args.bag)
    output = args.output or cli.default_output(args.bag, '.rrd')
    cli.check_output(output, '-o' if args.output else 'output', inputs=[args.bag])
    bag = read_bag(args.bag)
    named = bag.custom_data.get('scene')
    try:
        scene = load_scene(args.scene or named or DEFAULT_SCENE)
    except LinkageError as exc:
        if args.scene or not named:
            raise
        raise cli.Mistake(f'{exc} (the scene the bag names; choose one with --scene)') \
            from None
    damaged = f' ({bag.describe()})' if bag.truncated else ''
    if not any(_drawable(topic) for topic in bag.topics) or not bag.messages:
        raise cli.Mistake(f'{args.bag}: no {ROLES} messages to convert (topics: '
                          f'{", ".join(bag.topics) or "none"}){damaged}')
    if bag.truncated:
        print(f'{PROG}: warning: {args.bag}: {bag.describe()}; converting those',
              file=sys.stderr)
    print(f'{PROG}: {scene.name}: converting {len(bag.messages)} messages of {args.bag}',
          file=sys.stderr)
    counts = convert(bag, scene, output)
    summary = ', '.join(f'{n} {role}' for role, n in counts.items()) or 'nothing'
    print(f'{PROG}: wrote {output}: {summary}', file=sys.stderr)
    return cli.DAMAGED if bag.truncated else cli.DONE


def _drawable(topic):
    from ..record.rerun_view import topic_role
    return topic_role(topic) is not None


if __name__ == '__main__':
    sys.exit(main())
