# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-replay: solve the wheel-travel commands of a recorded run, or republish them on ROS.

    linkage-replay solve BAG -o OUT.mcap         solve the commands, write commands + outputs
    linkage-replay sweep -o OUT.mcap             the same for the commands of a travel sweep
    linkage-replay copy BAG -o OUT.mcap          copy every readable message into a complete file
    linkage-replay publish BAG --rate 2 --clock  republish the commands on ROS 2 (and /clock)

(Timing them, with and without recording: linkage-bench replay, which reads its commands
with request().)

BAG is an MCAP file with the ROS 2 profile (ours, rosbag2's, Foxglove's) or a rosbag2 bag
folder holding one. The commands are std_msgs/msg/Float64 wheel travel in m on --topic
(default /wheel_travel) and steering rack in m on steering_rack beside it, in the order
received; solve also applies the node's run-time parameter changes recorded on
/parameter_events (scene, method, max_step_mm, condition_warn, diagnostic_period) as the node
applied them, and a scene change that cannot be replayed (its scene does not load here) ends
the replay there, with status 1 (joint_states commands are not replayed: named, status 1).
Outputs are what suspension_node publishes, answered by the node's
own protocol (linkage_ros.answer.protocol), in the command topic's namespace: wheel_carrier_pose
(geometry_msgs/PoseStamped, m), camber and toe (std_msgs/Float64, rad), /tf
(tf2_msgs/TFMessage: the frames of the carrier, links and arms) and, for a scene with
elements, elements (sensor_msgs/JointState: each spring's, damper's and length's length in m
and motion ratio; doc/elements.md) for a solved command, stamped with its receive time,
/tf_static and /robot_description (std_msgs/String: the URDF) once, and /diagnostics
(diagnostic_msgs/DiagnosticArray) as the node sends it: a report every second of recorded
time, at once for a command that cannot be solved (ERROR, with the reason) or a change of
level, and one after the last command. The new bag keeps the recorded timeline. A bag cut
short (hard kill) or damaged gives a warning naming what was found (where the file is cut,
which chunk fails its CRC, ...) and every readable message is used; copy writes those into
a complete file. Progress goes to stderr.
"""

from pathlib import Path
import sys
import time

from .replay_args import parse_args, PROG
from .replay_commands import (load_changed_scenes, METADATA, parameter_changes,
                              read_commands, seconds, stored_scene, stored_text, SWEEP_HZ)
from .. import cli
from ..cli import counted
from ..core.base import LinkageError
from ..core.warmup import compile_if_cold, wants_statics
from ..outputs import check_output

PROGRESS_PERIOD = 1.0   # s between progress lines


class Progress:
    """Print 'linkage-replay: 120/161 commands (75%)' on stderr, every period s and at the end."""

    def __init__(self, total, what, stream=None, period=PROGRESS_PERIOD):
        self.total, self.what, self.period = total, what, period
        self.stream = stream or sys.stderr
        self._last = time.monotonic()

    def update(self, done):
        now = time.monotonic()
        if done == self.total or now - self._last >= self.period:
            self._last = now
            percent = 100.0 * done / self.total if self.total else 100.0
            print(f'{PROG}: {done}/{self.total} {self.what} ({percent:.0f}%)', file=self.stream,
                  flush=True)


def copy_messages(bag, recorder, progress=None):
    """
    Copy every message read from bag (CDR bytes, times) into recorder.

    recorder is made with the bag's QoS and definitions; each topic's schema is copied as it
    is stored ('ros2idl' too). Returns how many messages were left out (no ROS 2 type, or not
    CDR).
    """
    skipped = 0
    for i, m in enumerate(bag.messages):
        if m.type_name and bag.encodings.get(m.topic) == 'cdr':
            recorder.record(m.topic, m.type_name, m.data, m.log_time, m.publish_time,
                            schema=m.schema)
        else:
            skipped += 1
        if progress:
            progress.update(i + 1)
    return skipped


# --- running -------------------------------------------------------------------------------

BAGS = ('reading and writing bags', 'linkage_ros.record.mcap_writer')
SOLVING = ('solving commands', 'linkage_ros.ros.messages')
PUBLISHING = ('publishing on ROS 2', 'rclpy')
VERBS = {'solve': 'solving', 'sweep': 'solving', 'publish': 'publishing'}


def check_imports(*needs):
    """Import each (feature, module) needed; a missing optional package: a Mistake naming it."""
    import importlib
    for feature, module in needs:
        try:
            importlib.import_module(module)
        except ImportError as exc:
            raise cli.Mistake(cli.missing_package(exc, feature)) from None


@cli.program(PROG)
def main(argv=None):
    """Run linkage-replay; returns the exit status (0, 1 or 2; 130 if interrupted)."""
    args = parse_args(argv, __doc__)
    try:
        return run(args)
    except (cli.Mistake, LinkageError) as exc:   # SceneError, RecordingError, ReplayError
        return cli.fail(PROG, exc)


def run(args):
    """Carry out parsed arguments; raises Mistake or LinkageError for a user mistake."""
    check_imports(*{'copy': [BAGS], 'publish': [BAGS, SOLVING, PUBLISHING]}.get(
        args.command, [BAGS, SOLVING]))
    bag_path = getattr(args, 'bag', None)
    if bag_path:
        cli.check_input(bag_path)
    scene = None if args.command == 'copy' else given_scene(args)
    output = None
    if args.command in ('solve', 'sweep', 'copy'):
        suffix = {'solve': '_solved.mcap', 'copy': '_copy.mcap'}.get(args.command)
        output = args.output or (cli.default_output(bag_path, suffix) if bag_path else
                                 str(Path.cwd() / f'{scene.file_stem}_sweep.mcap'))
        check_output(output, '-o' if args.output else 'output', _inputs(bag_path, scene))
    if args.command == 'copy':
        return _copy(args, output)
    commands, scene, status, read = request(args, scene, VERBS[args.command],
                                            scene_needed=args.command != 'publish')
    stored = read.bag.metadata.get(METADATA) if read else None
    changes, scenes = [], {}
    if bag_path and args.command == 'solve':
        changes, scenes, commands, replayable = _changes(bag_path, read.bag, commands)
        status = max(status, replayable, _joint_states(bag_path, read.bag))
    source = bag_path or 'sweep'
    if args.command == 'publish':   # the Float64 commands: travel and rack
        from .replay_commands import WRENCH
        return _publish(args, [c for c in commands if c.kind != WRENCH], source, status)
    # a corner of a scene with bushings answers loaded poses (warmup.wants_statics)
    compile_if_cold(PROG, statics=any(wants_statics(s) for s in (scene, *scenes.values())))
    return _solve(args, commands, scene, source, output, stored, status, (changes, scenes))


def given_scene(args):
    """Return the Scene --scene names; without it five_link for a sweep, None for a BAG."""
    if args.scene or not getattr(args, 'bag', None):
        from ..core.model import load_scene
        return load_scene(args.scene or 'five_link')
    return None


def request(args, scene, verb, prog=PROG, scene_needed=True):
    """
    Return the commands parsed arguments name: (commands, scene, status, read).

    BAG's commands (read: its Commands; what a damaged bag or undecodable commands lost is
    said on stderr, status 1) or, without BAG, a sweep's over --travel at --hz (read None,
    status 0). scene: given_scene(args); for a BAG without --scene, the scene the recording
    stores, else five_link (left None unless scene_needed). Its warnings are said; verb (as
    'solving') is what is done with the commands, prog the program that says it. Raises
    LinkageError (RecordingError, ReplayError) for a bag or a sweep that cannot be had.
    """
    if not getattr(args, 'bag', None):
        cli.warn(prog, scene.warnings)
        from .replay_commands import sweep_commands
        return sweep_commands(scene, args.start, args.stop, args.step,
                              SWEEP_HZ if args.hz is None else args.hz), scene, cli.DONE, None
    read = read_commands(args.bag, args.topic)
    status = _warn(read, verb, prog)
    if scene is None and scene_needed:
        scene = stored_scene(read.bag, read.topic)
        if scene is not None:
            print(f'{prog}: the scene stored in {args.bag}: {scene.name}', file=sys.stderr)
        else:
            from ..core.model import load_scene
            scene = load_scene('five_link')
    if scene is not None:
        cli.warn(prog, scene.warnings)
    return read.commands, scene, status, read


def _changes(bag_path, bag, commands):
    """
    Return what can be replayed of the node's run-time parameter changes, and the status.

    (changes, {scene value: Scene}, commands, status). A scene change whose scene does not
    load here (a file of the recording's machine, say) cannot be replayed: it is named on
    stderr, neither it nor the commands from its time on are solved, and the status is 1.
    """
    changes = parameter_changes(bag)
    scenes, failed = load_changed_scenes(changes)
    if failed is not None:
        change, exc = failed
        kept = [c for c in commands if c.log_time < change.log_time]
        print(f'{PROG}: warning: {bag_path}: the node changed its scene to '
              f'{change.values["scene"]!r} at {seconds(change.log_time)} s, which does not '
              f'load here ({exc}); the {counted(len(commands) - len(kept), "command")} from '
              'then on are not replayed', file=sys.stderr)
        return changes[:changes.index(change)], scenes, kept, cli.DAMAGED
    return changes, scenes, commands, cli.DONE


def _joint_states(bag_path, bag):
    """
    Say that the node's joint_states commands in a bag are not replayed; return the status.

    The node takes travel (and rack) from sensor_msgs/JointState too (its travel_joint, a
    vehicle's joints); a replay solves the Float64 commands only, so such a run is replayed
    in part: status 1.
    """
    count = sum(1 for m in bag.messages if m.topic.rsplit('/', 1)[-1] == 'joint_states'
                and m.carries('sensor_msgs/msg/JointState'))
    if not count:
        return cli.DONE
    print(f'{PROG}: warning: {bag_path}: {counted(count, "joint_states message")} '
          '(sensor_msgs/JointState commands) not replayed: solve replays the Float64 commands '
          'of --topic and steering_rack beside it', file=sys.stderr)
    return cli.DAMAGED


def _inputs(bag_path, scene):
    """Return every file this run reads: the bag (a bag folder stands for its files), the scene."""
    inputs = [bag_path] if bag_path else []
    if scene is not None and Path(scene.source).is_file():
        inputs.append(scene.source)
    return inputs


def _warn(read, verb, prog=PROG):
    """Print what a damaged bag or undecodable commands lost; return the exit status."""
    bag, status = read.bag, cli.DONE
    if bag.truncated:
        missing = (f'; no {read.topic} among what could be read'
                   if read.topic not in bag.topics else '')
        print(f'{prog}: warning: {bag.path}: {bag.describe()}{missing}; {verb} the '
              f'{counted(len(read.commands), "command")} read', file=sys.stderr)
        status = cli.DAMAGED
    for line in read.warnings():
        print(f'{prog}: warning: {line}', file=sys.stderr)
    return cli.DAMAGED if read.lost else status


def _publish(args, commands, source, status):
    from .replay_publish import check_rate, publish_commands
    from ..record.interfaces import qualified
    check_rate(commands, args.rate)
    if not commands:
        print(f'{PROG}: nothing to publish: no commands', file=sys.stderr)
        return status
    print(f'{PROG}: publishing {counted(len(commands), "command")} from {source} on '
          f'{qualified(args.topic)} at rate {args.rate:g}', file=sys.stderr)
    published = publish_commands(commands, args.topic, args.rate, args.wait,
                                 Progress(len(commands), 'commands published'), args.clock)
    return status if published == len(commands) else 130


def _copy(args, output):
    from ..record.mcap_reader import read_bag
    from ..record.mcap_writer import McapRecorder
    bag = read_bag(args.bag)
    status = cli.DAMAGED if bag.truncated else cli.DONE
    if bag.truncated:
        print(f'{PROG}: warning: {args.bag}: {bag.describe()}; copied the '
              f'{counted(len(bag.messages), "message")} read', file=sys.stderr)
    metadata = {name: values for name, values in bag.metadata.items() if name != 'rosbag2'}
    with McapRecorder(output, qos=bag.qos, custom_data=bag.custom_data,
                      definitions=bag.definitions, metadata=metadata) as recorder:
        skipped = copy_messages(bag, recorder, Progress(len(bag.messages), 'messages copied'))
    if skipped:
        print(f'{PROG}: warning: {skipped} messages left out: their topics have no ROS 2 '
              'type or are not CDR', file=sys.stderr)
    print(f'{PROG}: wrote {counted(len(bag.messages) - skipped, "message")} to {output}',
          file=sys.stderr)
    return status


def _solve(args, commands, scene, source, output, stored, status, changed=((), {})):
    from .replay_solve import latched_topics, solve_commands
    from ..record.interfaces import qualified
    from ..record.mcap_writer import McapRecorder
    print(f'{PROG}: {scene.name}: solving {counted(len(commands), "command")} from {source} on '
          f'{qualified(args.topic)}, method {args.method}', file=sys.stderr)
    custom = {'scene': scene.name, 'method': args.method, 'source': Path(source).name}
    with McapRecorder(output, custom_data=custom, qos=latched_topics(),
                      metadata=stored_text(scene, stored)) as recorder:
        failures = solve_commands(commands, scene, args.method, [recorder], args.topic,
                                  Progress(len(commands), 'commands solved'), args.frame_id,
                                  changes=changed[0], scenes=changed[1])
        written = recorder.message_count
    print(f'{PROG}: wrote {counted(written, "message")} to {output}; '
          f'{counted(len(commands) - failures, "command")} solved, {failures} not (see '
          '/diagnostics)', file=sys.stderr)
    return status


if __name__ == '__main__':
    sys.exit(main())
