"""
linkage-replay: solve the wheel-travel commands of a recorded run, or republish them on ROS.

    linkage-replay BAG -o OUT.mcap               solve the commands, write commands + outputs
    linkage-replay BAG --publish --rate 2        republish the commands at twice the recorded pace
    linkage-replay BAG --publish --clock         ... with /clock at the recorded times (for
                                                 nodes with use_sim_time:=true)
    linkage-replay --sweep -o OUT.mcap           commands of a travel sweep (scene's range)
    linkage-replay BAG --copy -o OUT.mcap        copy every readable message into a complete file

BAG is an MCAP file with the ROS 2 profile (ours, rosbag2's, Foxglove's) or a rosbag2 bag
folder holding one. The commands are std_msgs/msg/Float64 wheel travel in m on --topic
(default /wheel_travel). Outputs are what the node publishes (built by
linkage_ros.ros.messages), in the command topic's namespace: wheel_carrier_pose
(geometry_msgs/PoseStamped, m), camber and toe (std_msgs/Float64, rad) for a solved command,
stamped with its receive time, and /diagnostics (diagnostic_msgs/DiagnosticArray) as the node
sends it: a report every second of recorded time, at once for a command that cannot be
solved (ERROR, with the reason) or a change of level, and one after the last command. The new
bag keeps the recorded timeline. A bag cut short (hard kill) or damaged gives a warning
naming what was found (where the file is cut, which chunk fails its CRC, ...) and every
readable message is used; --copy writes those into a complete file. Progress goes to stderr.
"""

import argparse
from dataclasses import dataclass
import math
from pathlib import Path
import sys
import time

import numpy as np

from .. import cli
from ..core.errors import LinkageError
from ..core.kinematics import Continuation, METHODS, travel_range
from ..core.scene import load_scene

PROG = 'linkage-replay'
FLOAT64 = 'std_msgs/msg/Float64'
DIAGNOSTIC_ARRAY = 'diagnostic_msgs/msg/DiagnosticArray'
DIAGNOSTICS_TOPIC = '/diagnostics'
FRAME_ID = 'base_link'
DEFAULT_TOPIC = '/wheel_travel'
SWEEP_HZ = 50.0
PROGRESS_PERIOD = 1.0   # s between progress lines
DIAGNOSTIC_PERIOD_S = 1.0   # the node's default diagnostic_period


class ReplayError(LinkageError):
    """A bag cannot be replayed: ReplayError(file or option, problem)."""


@dataclass(frozen=True)
class Command:
    """One wheel-travel command: receive (log) and publish time in ns, travel in m."""

    log_time: int
    publish_time: int
    travel: float


# --- reading commands ----------------------------------------------------------------------

def read_commands(path, topic=DEFAULT_TOPIC):
    """
    Return the commands on topic in a bag, in file order, and the bag: (commands, bag).

    Raises ReplayError if the topic is missing or is not std_msgs/msg/Float64 in CDR.
    """
    from ..record.interfaces import qualified
    from ..record.mcap_reader import read_bag
    from ..cdr import from_cdr
    bag = read_bag(path)
    name = qualified(topic)
    if name not in bag.topics:
        cut = f'; {truncation(bag)}' if bag.truncated else ''
        raise ReplayError(path, f'no topic {name} (topics present: {topic_list(bag)}{cut}); '
                          'choose the wheel-travel topic with --topic')
    if bag.topics[name] != FLOAT64 or bag.encodings.get(name) != 'cdr':
        raise ReplayError(path, f'topic {name} carries {bag.topics[name] or "no schema"} '
                          f"('{bag.encodings.get(name)}' encoding), but wheel-travel commands "
                          f'must be {FLOAT64} in cdr (topics present: {topic_list(bag)})')
    commands = [Command(m.log_time, m.publish_time, float(from_cdr(m.type_name, m.data).data))
                for m in bag.messages if m.topic == name]
    return commands, bag


def topic_list(bag):
    return ', '.join(f'{t} ({kind})' for t, kind in bag.topics.items()) or 'none'


def truncation(bag):
    """Return what a damaged bag gives: 'bag truncated after N messages (cut at ...)'."""
    return bag.describe()


def sweep_commands(scene, start=None, stop=None, step=None, hz=SWEEP_HZ, t0=None):
    """Commands of a travel sweep (mm arguments; scene.travel by default) at hz from t0 (ns)."""
    low, high, default_step = scene.travel
    start = low if start is None else start
    stop = high if stop is None else stop
    step = default_step if step is None else step
    if not (step > 0 and hz > 0 and np.isfinite([start, stop, step, hz]).all()):
        raise ReplayError('--from, --to, --step, --hz', f'must be finite, --step and --hz > 0 '
                          f'(got {start}, {stop}, {step}, {hz})')
    t0 = time.time_ns() if t0 is None else t0
    period = int(round(1e9 / hz))
    return [Command(t0 + i * period, t0 + i * period, float(travel) / 1000.0)
            for i, travel in enumerate(travel_range(start, stop, step))]


# --- solving -------------------------------------------------------------------------------

def stamp_of(time_ns):
    from builtin_interfaces.msg import Time
    return Time(sec=int(time_ns // 10**9), nanosec=int(time_ns % 10**9))


def solve_commands(commands, scene, method, sinks, topic=DEFAULT_TOPIC, progress=None,
                   frame_id=FRAME_ID, period_s=DIAGNOSTIC_PERIOD_S):
    """
    Solve each command by continuation; hand it and what the node publishes to each sink.

    Sinks: McapRecorder, RerunRecorder (.record(topic, type, CDR, t, t_pub)). On the recorded
    timeline: pose, camber and toe (messages.answer) for a solved command, at its
    receive time; /diagnostics as the node sends them (health.Health): a report every
    period_s of recorded time, at once for a failed command or a change of level, and a last
    one after the last command (a gap in the commands gives one report, not one per period).

    Returns the number of commands that could not be solved.
    """
    from ..cdr import float64_cdr, to_cdr
    from ..record.interfaces import qualified
    from ..ros import messages
    from ..ros.health import Health
    from ..ros.node import NODE_NAME, PARAMETERS
    topic = qualified(topic)
    namespace = topic.rsplit('/', 1)[0]
    health = Health(PARAMETERS['condition_warn'][0])
    status_name = f'{NODE_NAME}: {scene.name}'
    cont = Continuation(scene, method=method)
    period = int(round(period_s * 1e9))
    failures, next_report, t = 0, None, 0

    def emit(name, type_name, data, time_ns, publish_ns=None):
        for sink in sinks:
            sink.record(name, type_name, data, time_ns,
                        time_ns if publish_ns is None else publish_ns)

    def report(time_ns):
        emit(DIAGNOSTICS_TOPIC, DIAGNOSTIC_ARRAY, to_cdr(messages.diagnostics(
            [messages.health_status(health, status_name, scene.name, method)],
            stamp_of(time_ns))), time_ns)

    for i, command in enumerate(commands):
        t = command.log_time
        next_report = t + period if next_report is None else next_report
        if t >= next_report:           # the period ended before this command
            report(next_report)
            health.reset_period()
            next_report += period * ((t - next_report) // period + 1)
        emit(topic, FLOAT64, float64_cdr(command.travel), t, command.publish_time)
        solution = cont.solve(command.travel * 1000.0)
        if solution.success:
            for name, data in messages.answer(solution, divmod(t, 10**9), frame_id):
                emit(f'{namespace}/{name}', messages.ANSWER_TYPES[name], data, t)
        else:
            failures += 1
        if health.add(solution):
            report(t)
        if progress:
            progress.update(i + 1)
    if commands:
        report(t)
    return failures


def benchmark(commands, scene, method, repeat=3, stream=None):
    """
    Time solving the commands alone and with each sink; print a table (us per command).

    'no recording' solves and builds the messages (as the node does to publish them); the
    other rows add McapRecorder, RerunRecorder or both, file closing included. Best of repeat.
    """
    import tempfile
    from ..record.mcap_writer import McapRecorder
    from ..record.rerun_view import RerunRecorder
    stream = stream or sys.stdout
    modes = {'no recording': lambda d: [],
             'McapRecorder': lambda d: [McapRecorder(d / 'bench.mcap')],
             'RerunRecorder': lambda d: [RerunRecorder(d / 'bench.rrd', scene)],
             'both': lambda d: [McapRecorder(d / 'bench.mcap'),
                                RerunRecorder(d / 'bench.rrd', scene)]}
    messages = 4 * len(commands)   # the command, pose, camber, toe (diagnostics: a few)
    print('mode,commands,us_per_command,ratio,extra_us_per_message', file=stream)
    base = None
    for mode, make in modes.items():
        best = math.inf
        for _ in range(repeat):
            with tempfile.TemporaryDirectory() as folder:
                start = time.perf_counter()
                sinks = make(Path(folder))
                solve_commands(commands, scene, method, sinks)
                for sink in sinks:
                    sink.close()
                best = min(best, time.perf_counter() - start)
        per_command = 1e6 * best / len(commands)
        base = per_command if base is None else base
        extra = 1e6 * best / messages - base * len(commands) / messages
        print(f'{mode},{len(commands)},{per_command:.1f},{per_command / base:.3f},{extra:.1f}',
              file=stream)


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


# --- republishing --------------------------------------------------------------------------

def publish_commands(commands, topic, rate=1.0, wait=10.0, progress=None, clock=False):
    """
    Publish the commands as std_msgs/Float64 on topic at the recorded pace / rate.

    rate > 0 (2 = twice as fast). Waits up to wait s for a subscriber first (with clock, for
    one on /clock too). clock: before each command, publish rosgraph_msgs/Clock on /clock
    holding the command's recorded receive time, so that a node with use_sim_time stamps
    its answer with the recorded time. Returns the number of commands published.
    """
    import rclpy
    from rclpy.qos import QoSProfile
    from std_msgs.msg import Float64

    from ..record.interfaces import qualified
    rclpy.init()
    node = rclpy.create_node('linkage_replay', start_parameter_services=False)
    published = 0
    try:
        # Reliable, keep last 1000: a burst is never overwritten before it is acknowledged.
        publisher = node.create_publisher(Float64, qualified(topic), QoSProfile(depth=1000))
        publishers = [publisher]
        if clock:
            from rosgraph_msgs.msg import Clock
            clock_publisher = node.create_publisher(Clock, '/clock', QoSProfile(depth=1000))
            publishers.append(clock_publisher)
        deadline = time.monotonic() + wait
        while (not all(p.get_subscription_count() for p in publishers)
               and time.monotonic() < deadline):
            time.sleep(0.01)
        for p in publishers:
            if p.get_subscription_count() == 0:
                print(f'{PROG}: no subscriber on {p.topic_name} after {wait:g} s; publishing '
                      'anyway', file=sys.stderr)
        start, first = time.monotonic(), commands[0].log_time if commands else 0
        for command in commands:
            delay = start + (command.log_time - first) / 1e9 / rate - time.monotonic()
            if delay > 0:
                time.sleep(delay)
            if clock:   # the time first: the command's answer is stamped with it
                clock_publisher.publish(Clock(clock=stamp_of(command.log_time)))
            publisher.publish(Float64(data=command.travel))
            published += 1
            if progress:
                progress.update(published)
        # Reliable delivery of the last commands before the process goes away.
        from rclpy.duration import Duration
        for p in publishers:
            p.wait_for_all_acked(Duration(seconds=min(wait, 5.0)))
    except KeyboardInterrupt:
        print(f'{PROG}: interrupted after {published} commands', file=sys.stderr)
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return published


# --- command line --------------------------------------------------------------------------

EXAMPLES = """examples:
  linkage-replay run.mcap                       solve into ./run_solved.mcap
  linkage-replay run.mcap --copy -o fixed.mcap  recover a cut or damaged recording
  linkage-replay --sweep --from -40 --to 40 --step 0.5 -o sweep.mcap
  linkage-replay run.mcap --publish --rate 2 --clock
"""
# Options that only one way of running uses: option -> (dest, the modes that use it).
_ONLY = {'--rate': ('rate', {'publish'}), '--clock': ('clock', {'publish'}),
         '--wait': ('wait', {'publish'}), '--from': ('start', {'sweep'}),
         '--to': ('stop', {'sweep'}), '--step': ('step', {'sweep'}), '--hz': ('hz', {'sweep'}),
         '--scene': ('scene', {'solve', 'benchmark', 'sweep'}),
         '--method': ('method', {'solve', 'benchmark'}), '--frame-id': ('frame_id', {'solve'}),
         '--topic': ('topic', {'solve', 'benchmark', 'publish'}),
         '-o': ('output', {'solve', 'copy'})}


def _number(minimum, strict):
    """Return an argparse type: a finite number above (strict) or at least minimum."""
    def parse(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f'expected a number, got {text!r}') from None
        if not math.isfinite(value) or value < minimum or (strict and value == minimum):
            relation = 'above' if strict else 'at least'
            raise argparse.ArgumentTypeError(f'must be a finite number {relation} '
                                             f'{minimum:g}, got {text}')
        return value
    return parse


def _finite(text):
    """Parse a finite number (an argparse type)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f'expected a number, got {text!r}') from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f'must be a finite number, got {text}')
    return value


def parse_args(argv):
    summary, text = __doc__.strip().split('\n', 1)
    parser = cli.Parser(prog=PROG, description=summary,
                        epilog=text + '\n' + EXAMPLES + '\n' + cli.EXIT_STATUSES)
    parser.add_argument('bag', nargs='?', metavar='BAG',
                        help='recorded run: an .mcap file, or a rosbag2 bag folder holding one')
    parser.add_argument('-o', '--output', metavar='OUT',
                        help="MCAP file to write; its folder must exist (default: BAG's name "
                        '+ _solved.mcap, with --copy + _copy.mcap, with --sweep '
                        'SCENE_sweep.mcap, in the current folder)')
    parser.add_argument('--topic', help=f'wheel-travel topic, std_msgs/msg/Float64 in m '
                        f'(default {DEFAULT_TOPIC})')
    parser.add_argument('--scene', help='bundled scene name or scene YAML path (default '
                        'five_link)')
    parser.add_argument('--method', choices=METHODS, help='solver (default fast)')
    parser.add_argument('--frame-id', help=f'frame of wheel_carrier_pose (default {FRAME_ID})')
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument('--publish', action='store_true',
                      help='republish the commands on ROS (rclpy) at the recorded timing '
                      'instead of solving them')
    mode.add_argument('--copy', action='store_true',
                      help='copy every readable message (any topic, type and QoS) into a '
                      'complete MCAP: recovers a recording cut by a hard kill or damaged')
    mode.add_argument('--benchmark', action='store_true',
                      help='time solving the commands with no recording, McapRecorder, '
                      'RerunRecorder and both; print a CSV table on stdout (us per command)')
    parser.add_argument('--rate', type=_number(0.0, True),
                        help='--publish: playback speed factor, > 0 (default 1; 2 = twice as '
                        'fast)')
    parser.add_argument('--clock', action='store_true',
                        help='--publish: also publish /clock (rosgraph_msgs/Clock) at the '
                        "commands' recorded times, for nodes with use_sim_time:=true")
    parser.add_argument('--wait', type=_number(0.0, False),
                        help='--publish: s to wait for a subscriber, >= 0 (default 10)')
    parser.add_argument('--sweep', action='store_true',
                        help='instead of BAG: the commands of a travel sweep (default: the '
                        "scene's travel range and step)")
    parser.add_argument('--from', dest='start', type=_finite,
                        help="--sweep: first travel, mm (default: the scene's travel min)")
    parser.add_argument('--to', dest='stop', type=_finite,
                        help="--sweep: last travel, mm (default: the scene's travel max)")
    parser.add_argument('--step', type=_number(0.0, True),
                        help="--sweep: travel step, mm, > 0 (default: the scene's step)")
    parser.add_argument('--hz', type=_number(0.0, True),
                        help=f'--sweep: command rate, Hz, > 0 (default {SWEEP_HZ:g})')
    args = parser.parse_args(argv)
    if args.sweep == bool(args.bag):
        parser.error('give a BAG or --sweep (one of them)')
    if args.sweep and args.copy:
        parser.error('--copy needs a BAG')
    primary = next((m for m in ('publish', 'copy', 'benchmark') if getattr(args, m)), 'solve')
    modes = {primary} | ({'sweep'} if args.sweep else set())
    for option, (dest, used) in _ONLY.items():
        if getattr(args, dest) not in (None, False) and not modes & used:
            if used in ({'publish'}, {'sweep'}):
                parser.error(f'{option} needs --{min(used)}')
            parser.error(f'{option} is not used with --{primary}')
    args.topic = args.topic or DEFAULT_TOPIC
    args.scene = args.scene or 'five_link'
    args.method = args.method or 'fast'
    args.frame_id = args.frame_id or FRAME_ID
    args.rate = 1.0 if args.rate is None else args.rate
    args.wait = 10.0 if args.wait is None else args.wait
    args.hz = SWEEP_HZ if args.hz is None else args.hz
    return args


def _imports(args):
    """Import what this run needs; a missing optional package is a Mistake naming it."""
    needs = [('reading and writing bags', 'linkage_ros.record.mcap_writer')]
    if not args.copy:
        needs.append(('solving commands', 'linkage_ros.ros.messages'))
    if args.publish:
        needs.append(('--publish', 'rclpy'))
    if args.benchmark:
        needs.append(('--benchmark', 'linkage_ros.record.rerun_view'))
    import importlib
    for feature, module in needs:
        try:
            importlib.import_module(module)
        except ImportError as exc:
            raise cli.Mistake(cli.missing_package(exc, feature)) from None


@cli.program(PROG)
def main(argv=None):
    """Run linkage-replay; returns the exit status (0, 1 or 2; 130 if interrupted)."""
    args = parse_args(argv)
    try:
        return run(args)
    except (cli.Mistake, LinkageError) as exc:   # SceneError, RecordingError, ReplayError
        return cli.fail(PROG, exc)


def run(args):
    """Carry out parsed arguments; raises Mistake or LinkageError for a user mistake."""
    _imports(args)
    from ..record.interfaces import qualified
    from ..record.mcap_writer import McapRecorder
    if args.bag:
        cli.check_input(args.bag)
    scene = None if args.copy else load_scene(args.scene)
    output = None
    if not (args.publish or args.benchmark):
        suffix = '_copy.mcap' if args.copy else '_solved.mcap'
        output = args.output or (cli.default_output(args.bag, suffix) if args.bag else
                                 str(Path.cwd() / f'{scene.name}_sweep.mcap'))
        cli.check_output(output, '-o' if args.output else 'output', inputs=[args.bag])
    if args.sweep:
        commands, bag = sweep_commands(scene, args.start, args.stop, args.step, args.hz), None
    elif args.copy:
        from ..record.mcap_reader import read_bag
        bag, commands = read_bag(args.bag), []
    else:
        commands, bag = read_commands(args.bag, args.topic)
    source = args.bag or 'sweep'
    status = cli.DAMAGED if bag is not None and bag.truncated else cli.DONE
    if status == cli.DAMAGED:
        what = ('copied' if args.copy else 'publishing' if args.publish else
                'timing' if args.benchmark else 'solving')
        count = len(bag.messages) if args.copy else len(commands)
        print(f'{PROG}: warning: {args.bag}: {truncation(bag)}; {what} the {count} '
              f'{"messages" if args.copy else "commands"} read', file=sys.stderr)
    if args.benchmark:
        print(f'{PROG}: {scene.name}: timing {len(commands)} commands, method {args.method}, '
              'best of 3', file=sys.stderr)
        benchmark(commands, scene, args.method)
        return status
    if args.publish:
        print(f'{PROG}: publishing {len(commands)} commands from {source} on '
              f'{qualified(args.topic)} at rate {args.rate:g}', file=sys.stderr)
        published = publish_commands(commands, args.topic, args.rate, args.wait,
                                     Progress(len(commands), 'commands published'), args.clock)
        return status if published == len(commands) else 130
    if args.copy:
        with McapRecorder(output, qos=bag.qos, custom_data=bag.custom_data,
                          definitions=bag.definitions) as recorder:
            skipped = copy_messages(bag, recorder, Progress(len(bag.messages),
                                                            'messages copied'))
        if skipped:
            print(f'{PROG}: warning: {skipped} messages left out: their topics have no ROS 2 '
                  'type or are not CDR', file=sys.stderr)
        print(f'{PROG}: wrote {len(bag.messages) - skipped} messages to {output}',
              file=sys.stderr)
        return status
    print(f'{PROG}: {scene.name}: solving {len(commands)} commands from {source} on '
          f'{qualified(args.topic)}, method {args.method}', file=sys.stderr)
    custom = {'scene': scene.name, 'method': args.method, 'source': Path(source).name}
    with McapRecorder(output, custom_data=custom) as recorder:
        failures = solve_commands(commands, scene, args.method, [recorder], args.topic,
                                  Progress(len(commands), 'commands solved'), args.frame_id)
        written = recorder.message_count
    print(f'{PROG}: wrote {written} messages to {output}; {len(commands) - failures} commands '
          f'solved, {failures} not (see /diagnostics)', file=sys.stderr)
    return status


if __name__ == '__main__':
    sys.exit(main())
