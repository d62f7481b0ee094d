# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-rerun: convert a recorded run (MCAP) into a Rerun .rrd for offline viewing.

for example:
    linkage-rerun run.mcap                 writes ./run.rrd
    linkage-rerun run.mcap -o view.rrd --scene double_wishbone
    rerun run.rrd                          opens the viewer: 3D view of the corner beside
                                           travel, camber and toe (and the steering rack)

BAG is an MCAP file with the ROS 2 profile or a rosbag2 bag folder holding one. Reads
wheel_travel, steering_rack, wheel_carrier_pose, camber and toe (by their last name, any
namespace; std_msgs/msg/Float64 and geometry_msgs/msg/PoseStamped in CDR) and logs them as
columns (see record.rerun_draw); with statics, contact_wrench and pickup/<name>
(geometry_msgs/msg/WrenchStamped) as force arrows of 0.1 mm per N (1 kN: 100 mm): the
contact force at the contact patch, each pickup's force on the body at its pickup. A topic
of such a name but of another type is skipped, with a line. The scene is --scene, else the
one the recording stores (the scene or vehicle file's content, in its 'linkage_ros'
metadata), else the one it names (custom data 'vehicle' or 'scene'), else five_link. A bag
cut short or damaged gives a warning naming what was found, and its readable messages are
converted; a message whose bytes do not decode is left out and named. Either ends with
status 1, even when nothing could be drawn (the .rrd then holds the scene alone). Progress
goes to stderr.

A vehicle commanded by joint_states (sensor_msgs/msg/JointState; the vehicle file names each
corner's travel_joint and rack_joint) has each corner's travel and rack plotted from it. A
run whose scene the node changed while it ran (recorded on /parameter_events) is drawn in
parts, each with its own scene under its name (five_link, then double_wishbone), a part's
carrier and links hidden once the next part starts (its base points stay); a change
whose scene does not load here is named, what follows is drawn with the scene before, and
the status is 1 (tools/rerun_inputs.py).

--tf draws instead what any ROS viewer draws, from the bag alone: the URDF of
/robot_description through Rerun's URDF loader, placed by /tf and /tf_static
(record.rerun_tf), beside travel, camber and toe; no scene file is read. A run whose scene
changed holds a URDF per scene: each is drawn only while its part of the run lasts.
"""

import importlib
import math
import sys

from .. import cli
from ..core.base import LinkageError
from ..core.model import load_scene, load_vehicle, resolve_scene_path
from ..core.warmup import compile_if_cold
from ..outputs import check_output
from ..record.stored import load_stored

PROG = 'linkage-rerun'
DEFAULT_SCENE = 'five_link'
ROLES = ('wheel_travel, steering_rack, wheel_carrier_pose, camber, toe, contact_wrench or '
         'pickup/<name>')


def drawable(bag):
    """
    Return the messages of a Bag that can be drawn, and what was skipped.

    (messages, {topic: type found}): messages of a drawn role (rerun_view.topic_role) and
    its type (ROLE_TYPES) whose bytes decode; a topic of another type is in the dict, and a
    message that does not decode is counted in bag.undecoded (bag.losses()).
    """
    from ..record.rerun_view import role_reader, ROLE_TYPES, topic_role
    messages, foreign = [], {}
    for m in bag.messages:
        role = topic_role(m.topic)
        if role is None:
            continue
        if not m.carries(ROLE_TYPES[role]):
            foreign.setdefault(m.topic, f'{m.type_name or "no schema"} in {m.encoding}')
        elif bag.decode(m, role_reader(role)) is not None:
            messages.append(m)
    return messages, foreign


def convert(messages, output, scene=None, corners=None, recording_id=None, ends=()):
    """
    Log messages (BagMessages that decode, from drawable) into output (.rrd).

    scene: the one Scene drawn, or corners: {corner name: Scene} of a vehicle or of the parts
    of a run. ends: [(ns, root)] in time order, where a part of a run under root ended: its
    carrier and links are hidden from there on (RerunRecorder.hide). Returns {role: samples
    logged}.
    """
    from ..record.rerun_view import RerunRecorder, topic_role
    counts = {}
    ends = list(ends)
    rack = any(topic_role(m.topic) == 'rack' for m in messages)
    with RerunRecorder(output, scene, recording_id=recording_id, batch_rows=math.inf,
                       batch_delay=math.inf, corners=corners, rack=rack) as viewer:
        for m in messages:
            while ends and ends[0][0] <= m.log_time:
                viewer.hide(ends.pop(0)[1], m.log_time)
            viewer.record(m.topic, m.type_name, m.data, m.log_time, m.publish_time)
            role = topic_role(m.topic)
            counts[role] = counts.get(role, 0) + 1
    return counts


def parse_args(argv):
    summary, text = __doc__.strip().split('\n', 1)
    parser = cli.Parser(prog=PROG, description=summary,
                        epilog=text + '\n' + cli.EXIT_STATUSES)
    parser.add_argument('bag', metavar='BAG',
                        help='recorded run: an .mcap file, or a rosbag2 bag folder holding one')
    parser.add_argument('-o', '--output', metavar='OUT',
                        help='.rrd file to write; its folder must exist; never BAG or a file '
                        "in BAG's folder (default: BAG's name with .rrd, in the current "
                        'folder)')
    parser.add_argument('--scene', help='bundled scene name or scene YAML path (default: the '
                        'scene or vehicle the recording stores or names, else '
                        f'{DEFAULT_SCENE})')
    parser.add_argument('--tf', action='store_true',
                        help="draw the recording's URDF (/robot_description) placed by its "
                        '/tf and /tf_static, as a ROS viewer does, instead of the scene')
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
    check_output(output, '-o' if args.output else 'output',
                 [args.bag] + ([resolve_scene_path(args.scene)] if args.scene else []))
    bag = read_bag(args.bag)
    if args.tf:
        return _run_tf(args, bag, output)
    scene, corners, joints = drawing(args, bag)
    cli.warn(PROG, [w for s in ([scene] if scene else corners.values()) for w in s.warnings])
    messages, foreign = drawable(bag)
    if joints:       # a vehicle commanded by joint_states: each corner's travel and rack
        from .rerun_inputs import joint_commands
        messages = sorted(messages + joint_commands(bag, joints), key=lambda m: m.log_time)
    if bag.complete and not messages:
        wrong = ''.join(f'; {topic} is {kind}' for topic, kind in foreign.items())
        raise cli.Mistake(f'{args.bag}: no {ROLES} messages to convert (topics: '
                          f'{", ".join(bag.topics) or "none"}{wrong})')
    for topic, kind in foreign.items():
        print(f'{PROG}: {args.bag}: {topic} skipped: it carries {kind}, not what is drawn '
              'from it', file=sys.stderr)
    if bag.truncated:
        print(f'{PROG}: warning: {args.bag}: {bag.describe()}; converting those',
              file=sys.stderr)
    for line in bag.losses():
        print(f'{PROG}: warning: {args.bag}: {line}', file=sys.stderr)
    status = cli.DONE if bag.complete else cli.DAMAGED
    name, ends = (scene.name if scene is not None else 'vehicle'), []
    if scene is not None:   # a scene changed while the node ran: each part with its own
        from .rerun_inputs import run_parts, split_parts
        parts, problem = run_parts(bag, scene)
        if problem:
            print(f'{PROG}: warning: {args.bag}: {problem}', file=sys.stderr)
            status = cli.DAMAGED
        if len(parts) > 1:
            corners, messages = split_parts(parts, messages)
            ends = list(zip([p.start for p in parts[1:]], corners))
            print(f'{PROG}: {len(parts)} parts, each drawn with its scene under its name: '
                  f'{", ".join(corners)}', file=sys.stderr)
            scene, name = None, ' then '.join(corners)
    compile_if_cold(PROG)   # the plots are framed on a sweep of each scene
    print(f'{PROG}: {name}: converting {len(messages)} messages of {args.bag}',
          file=sys.stderr)
    counts = convert(messages, output, scene, corners, ends=ends)
    summary = ', '.join(f'{n} {role}' for role, n in counts.items()) or 'nothing but the scene'
    print(f'{PROG}: wrote {output}: {summary}', file=sys.stderr)
    return status


def _run_tf(args, bag, output):
    """Write the view of the bag's URDF and TF (record.rerun_tf); return the exit status."""
    from ..record.rerun_tf import convert_tf
    if bag.truncated:
        print(f'{PROG}: warning: {args.bag}: {bag.describe()}; converting those',
              file=sys.stderr)
    counts = convert_tf(bag, output)
    summary = ', '.join(f'{n} {what}' for what, n in counts.items())
    print(f'{PROG}: wrote {output} (URDF and TF): {summary}', file=sys.stderr)
    return cli.DONE if bag.complete else cli.DAMAGED


def drawing(args, bag):
    """
    Return (scene, corners, joints) to draw a Bag with.

    One Scene, or corners {corner: Scene} of a vehicle with joints {corner: (travel joint,
    rack joint)} of its joint_states. --scene; else the content stored in the recording's
    'linkage_ros' metadata (vehicle_yaml, scene_yaml); else the vehicle or scene named in
    its custom data; else DEFAULT_SCENE.
    """
    if args.scene:
        return load_scene(args.scene), None, {}
    try:
        loaded = load_stored(bag.metadata, str(args.bag))
    except LinkageError as exc:
        raise cli.Mistake(f'{exc} (choose a scene with --scene)') from None
    if loaded is not None and loaded.vehicle is None:
        return loaded.scene, None, {}
    if loaded is not None:
        return None, loaded.corners, loaded.vehicle.joints
    vehicle, named = bag.custom_data.get('vehicle'), bag.custom_data.get('scene')
    try:
        if vehicle:
            loaded = load_vehicle(vehicle)
            return None, loaded.corners, loaded.joints
        return load_scene(named or DEFAULT_SCENE), None, {}
    except LinkageError as exc:
        if not (vehicle or named):
            raise
        named = 'vehicle the bag names; choose a scene' if vehicle else 'scene the bag names; ' \
            'choose one'
        raise cli.Mistake(f'{exc} (the {named} with --scene)') from None


if __name__ == '__main__':
    sys.exit(main())
