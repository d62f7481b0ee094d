"""linkage-rerun: convert a recorded run (MCAP) into a Rerun .rrd for offline viewing.

    linkage-rerun run.mcap -o run.rrd [--scene five_link]
    rerun run.rrd          # opens the viewer: 3D view of the corner beside travel, camber, toe

Reads wheel_travel, wheel_carrier_pose, camber and toe (by their last name, any namespace)
and logs them as columns (see rerun_view). The scene is --scene, else the one the bag names in
its metadata (custom_data 'scene', written by linkage-replay), else five_link. A truncated bag
gives a warning and its readable messages are converted. Progress goes to stderr.
"""

import argparse
import math
from pathlib import Path
import sys

from ..record.bag import read_bag, RecordingError
from ..record.rerun_view import RerunRecorder, topic_role
from ..core.scene import load_scene, SceneError

PROG = 'linkage-rerun'
DEFAULT_SCENE = 'five_link'


def convert(bag, scene, output, recording_id=None):
    """Log the drawable messages of a Bag (from read_bag) into output (.rrd).

    Returns {role: samples logged}.
    """
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
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__.split('\n')[0])
    parser.add_argument('bag', help='recorded run (.mcap)')
    parser.add_argument('-o', '--output', help='.rrd to write (default: BAG with .rrd)')
    parser.add_argument('--scene', help='bundled scene name or YAML path (default: the scene '
                        f'named in the bag metadata, else {DEFAULT_SCENE})')
    return parser.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    output = args.output or str(Path(args.bag).with_suffix('.rrd'))
    try:
        bag = read_bag(args.bag)
        scene = load_scene(args.scene or bag.custom_data.get('scene') or DEFAULT_SCENE)
    except (RecordingError, SceneError) as exc:
        print(f'{PROG}: {exc}', file=sys.stderr)
        return 2
    if bag.truncated:
        print(f'{PROG}: warning: {args.bag}: bag truncated after {len(bag.messages)} messages '
              f'({bag.problem}); converting those', file=sys.stderr)
    print(f'{PROG}: {scene.name}: converting {len(bag.messages)} messages of {args.bag}',
          file=sys.stderr)
    counts = convert(bag, scene, output)
    if not counts:
        print(f'{PROG}: warning: no wheel_travel, wheel_carrier_pose, camber or toe topic in '
              f'{args.bag} (topics: {", ".join(bag.topics) or "none"})', file=sys.stderr)
    summary = ', '.join(f'{n} {role}' for role, n in counts.items()) or 'nothing'
    print(f'{PROG}: wrote {output}: {summary}', file=sys.stderr)
    return 1 if bag.truncated else 0


if __name__ == '__main__':
    sys.exit(main())
