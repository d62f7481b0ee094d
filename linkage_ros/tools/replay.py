"""
linkage-replay: solve the wheel-travel commands of a recorded run, or republish them on ROS.

    linkage-replay solve BAG -o OUT.mcap         solve the commands, write commands + outputs
    linkage-replay sweep -o OUT.mcap             the same for the commands of a travel sweep
    linkage-replay copy BAG -o OUT.mcap          copy every readable message into a complete file
    linkage-replay publish BAG --rate 2 --clock  republish the commands on ROS 2 (and /clock)
    linkage-replay bench BAG                     time solving them, with and without recording

BAG is an MCAP file with the ROS 2 profile (ours, rosbag2's, Foxglove's) or a rosbag2 bag
folder holding one. The commands are std_msgs/msg/Float64 wheel travel in m on --topic
(default /wheel_travel). Outputs are what suspension_node publishes, answered by the node's
own protocol (linkage_ros.protocol), in the command topic's namespace: wheel_carrier_pose
(geometry_msgs/PoseStamped, m), camber and toe (std_msgs/Float64, rad) for a solved command,
stamped with its receive time, and /diagnostics (diagnostic_msgs/DiagnosticArray) as the node
sends it: a report every second of recorded time, at once for a command that cannot be
solved (ERROR, with the reason) or a change of level, and one after the last command. The new
bag keeps the recorded timeline. A bag cut short (hard kill) or damaged gives a warning
naming what was found (where the file is cut, which chunk fails its CRC, ...) and every
readable message is used; copy writes those into a complete file. Progress goes to stderr.

The spellings of earlier versions still work, with a note on stderr: BAG alone (solve),
--sweep, --copy, --publish, --benchmark.
"""

import argparse
import math
from pathlib import Path
import shlex
import sys
import textwrap
import time

from .replay_commands import (DEFAULT_TOPIC, file_stem, METADATA, read_commands, stored_scene,
                              stored_text, SWEEP_HZ)
from .. import cli
from ..core.errors import LinkageError
from ..core.kinematics import METHODS

PROG = 'linkage-replay'
FRAME_ID = 'base_link'
PROGRESS_PERIOD = 1.0   # s between progress lines

EXIT_STATUSES = """exit status:
  0  done; the input was complete
  1  done, but the input was damaged or held messages that do not decode: what could be
     read was used (even if that is nothing), and the warning says what was lost
  2  a mistake in the command: an unknown option, a bad value, a path that is not a bag
     (missing, or not MCAP), an output that cannot be written, a missing optional package
     (one line on stderr says which)"""

# subcommand: (summary, [(example arguments, what it does)])
COMMANDS = {
    'solve': ('solve the commands of a recorded run as suspension_node answers them',
              [('run.mcap', 'writes ./run_solved.mcap'),
               ('run.mcap -o again.mcap --scene macpherson', ''),
               ('car/ --topic /front_left/wheel_travel', 'a corner of a vehicle')]),
    'sweep': ("solve the commands of a travel sweep (the scene's range and step by default)",
              [('', 'writes ./five_link_sweep.mcap'),
               ('--scene macpherson --from -40 --to 40 --step 0.5 -o sweep.mcap', '')]),
    'copy': ('copy every readable message (any topic, type and QoS) into a complete MCAP: '
             'recovers a recording cut by a hard kill or damaged',
             [('run.mcap', 'writes ./run_copy.mcap'), ('cut.mcap -o fixed.mcap', '')]),
    'publish': ('republish the commands on ROS 2 (rclpy) at the recorded pace instead of '
                'solving them',
                [('run.mcap --rate 2 --clock', 'twice as fast, with /clock'),
                 ('--scene macpherson --hz 100', 'the commands of a sweep')]),
    'bench': ('time solving the commands with no recording, McapRecorder, RerunRecorder and '
              'both; print a CSV table on stdout (us per command)',
              [('run.mcap', ''), ('--from -80 --to 80 --step 0.1', 'the commands of a sweep')]),
}


def examples(*commands):
    """Return the example lines of commands, their comments in one column."""
    lines = []
    for command in commands:
        for arguments, comment in COMMANDS[command][1]:
            line = f'  {PROG} {command} {arguments}'.rstrip()
            lines.append(f'{line:<60} {comment}'.rstrip() if comment else line)
    return '\n'.join(lines)


LEGACY = {'--publish': 'publish', '--copy': 'copy', '--benchmark': 'bench', '--sweep': 'sweep'}
SWEEP_OPTIONS = ('--from', '--to', '--step', '--hz')


class Parser(cli.Parser):
    """A subcommand's parser: its mistakes are one line that starts with linkage-replay."""

    def error(self, message):
        """Print one line naming the mistake and exit with status 2."""
        sys.exit(cli.fail(PROG, f'error: {message} (see {self.prog} --help)'))


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


def _options(parser, command):
    """Add the options of a subcommand to its parser; return their option strings."""
    source = command in ('publish', 'bench')   # a BAG, or without one a sweep
    known = set()

    def option(*names, **kwargs):
        known.update(names)
        parser.add_argument(*names, **kwargs)

    if command != 'sweep':
        parser.add_argument('bag', nargs='?' if source else None, metavar='BAG',
                            help='recorded run: an .mcap file, or a rosbag2 bag folder holding '
                            'one' + ('; without it, the commands of a sweep' if source else ''))
    if command in ('solve', 'sweep', 'copy'):
        suffix = {'solve': "BAG's name + _solved.mcap", 'copy': "BAG's name + _copy.mcap",
                  'sweep': "the scene's name (its letters, digits, _ . -) + _sweep.mcap"
                  }[command]
        option('-o', '--output', metavar='OUT', help='MCAP file to write; its folder must '
               f'exist (default: {suffix}, in the current folder)')
    if command != 'copy':
        option('--topic', default=DEFAULT_TOPIC, help='wheel-travel topic, '
               f'std_msgs/msg/Float64 in m (default {DEFAULT_TOPIC})')
        stored = (' (default: the scene the recording stores, else five_link)'
                  if command in ('solve', 'bench') else ' (default five_link)')
        option('--scene', help=('sweep: ' if command == 'publish' else '') +
               'bundled scene name or scene YAML path' + stored)
    if command in ('solve', 'sweep', 'bench'):
        option('--method', choices=METHODS, default='fast', help='solver (default fast)')
    if command in ('solve', 'sweep'):
        option('--frame-id', default=FRAME_ID,
               help=f'frame of wheel_carrier_pose (default {FRAME_ID})')
    if command == 'publish':
        option('--rate', type=_number(0.0, True), default=1.0,
               help='playback speed factor, > 0 (default 1; 2 = twice as fast)')
        option('--clock', action='store_true', help='also publish /clock (rosgraph_msgs/Clock) '
               "at the commands' recorded times, for nodes with use_sim_time:=true")
        option('--wait', type=_number(0.0, False), default=10.0,
               help='s to wait for a subscriber, >= 0 (default 10)')
    if command in ('sweep', 'publish', 'bench'):
        which = 'sweep: ' if source else ''
        option('--from', dest='start', type=_finite,
               help=f"{which}first travel, mm (default: the scene's travel min)")
        option('--to', dest='stop', type=_finite,
               help=f"{which}last travel, mm (default: the scene's travel max)")
        option('--step', type=_number(0.0, True),
               help=f"{which}travel step, mm, > 0 (default: the scene's step)")
        option('--hz', type=_number(0.0, True),
               help=f'{which}command rate, Hz, > 0 (default {SWEEP_HZ:g})')
    return known


def make_parser():
    """
    Return the parser of linkage-replay and its subcommands.

    parser.commands: {subcommand: (its parser, its option strings)}.
    """
    summary, text = __doc__.strip().split('\n', 1)
    parser = cli.Parser(prog=PROG, description=summary, epilog=f'{text}\n\nexamples:\n'
                        f'{examples(*COMMANDS)}\n\n{EXIT_STATUSES}')
    subparsers = parser.add_subparsers(dest='command', metavar='COMMAND',
                                       parser_class=Parser)
    parser.commands = {}
    for command, (summary, _) in COMMANDS.items():
        sub = subparsers.add_parser(
            command, help=summary, description=textwrap.fill(f'{PROG} {command}: {summary}.',
                                                             92),
            epilog=f'examples:\n{examples(command)}\n\n{EXIT_STATUSES}')
        parser.commands[command] = sub, _options(sub, command)
    return parser


def translate(argv):
    """
    Return (argv in the subcommand spelling, the note to print or None).

    The earlier spellings: BAG alone solves; --sweep, --copy, --publish and --benchmark
    chose the others (--publish and --benchmark with --sweep: of a sweep's commands). Taken
    as such when a mode flag or a word that can be a BAG is among the arguments.
    """
    if not argv or argv[0] in COMMANDS or argv[0] in ('-h', '--help') or not any(
            a in LEGACY or not a.startswith('-') for a in argv):
        return list(argv), None
    modes = [a for a in argv if a in LEGACY]
    rest = [a for a in argv if a not in LEGACY]
    chosen = [m for m in dict.fromkeys(modes) if m != '--sweep']
    if len(chosen) > 1:
        raise cli.Mistake(f'error: {chosen[0]} and {chosen[1]}: choose one (see {PROG} --help)')
    if chosen == ['--copy'] and '--sweep' in modes:
        raise cli.Mistake(f'error: --copy needs a BAG (see {PROG} --help)')
    command = LEGACY[chosen[0]] if chosen else 'sweep' if '--sweep' in modes else 'solve'
    new = [command, *rest]
    return new, f'{PROG}: note: {shlex.join([PROG, *argv])} is now spelled ' \
                f'{shlex.join([PROG, *new])}'


def parse_args(argv):
    """
    Parse linkage-replay's arguments (either spelling); a mistake exits with status 2.

    args.note: for an earlier spelling, the line that names the new one, else None.
    """
    parser = make_parser()
    try:
        argv, note = translate(list(sys.argv[1:] if argv is None else argv))
        argv = _joined_values(argv, parser)
    except cli.Mistake as exc:
        sys.exit(cli.fail(PROG, exc))
    args, extras = parser.parse_known_args(argv)
    if args.command is None:
        parser.error(f'unrecognized arguments: {" ".join(extras)}' if extras else
                     f'choose what to do: {", ".join(COMMANDS)}')
    sub = parser.commands[args.command][0]
    if extras:
        sub.error(_misplaced(parser, args.command, extras, note))
    args.note = note
    if args.command in ('publish', 'bench') and args.bag:
        given = [o for o, dest in zip(SWEEP_OPTIONS, ('start', 'stop', 'step', 'hz'))
                 if getattr(args, dest) is not None]
        if given or (args.command == 'publish' and args.scene):
            sub.error(f'{(given or ["--scene"])[0]} makes a sweep: give it without BAG')
    return args


def _joined_values(argv, parser):
    """
    Join a number option and a value that starts with '-' ('--from', '-1e300': --from=-1e300).

    argparse takes '-1e300' or '-80mm' for an option of its own ('expected one argument');
    joined, the value is checked as a number, and a mistake is said as such.
    """
    numeric = {'--from', '--to', '--step', '--hz', '--rate', '--wait'}
    known = set().union(*(options for _, options in parser.commands.values()))
    joined, i = [], 0
    while i < len(argv):
        if argv[i] in numeric and i + 1 < len(argv) and argv[i + 1].startswith('-') \
                and argv[i + 1] not in known:
            joined.append(f'{argv[i]}={argv[i + 1]}')
            i += 2
        else:
            joined.append(argv[i])
            i += 1
    return joined


def _misplaced(parser, command, extras, note):
    """Say what is wrong with arguments a subcommand does not take."""
    option = next((e.split('=')[0] for e in extras if e.startswith('-')), None)
    if option is None and command == 'sweep':
        return f'a sweep takes no BAG (unrecognized arguments: {" ".join(extras)})'
    owners = [name for name, (_, known) in parser.commands.items() if option in known]
    if not owners:
        return f'unrecognized arguments: {" ".join(extras)}'
    if note is None:
        return f'{option} is not an option of {PROG} {command} (it is one of: ' \
               f'{", ".join(owners)})'
    flags = {command: flag for flag, command in LEGACY.items()}
    if owners == ['publish']:
        return f'{option} needs --publish'
    if 'sweep' in owners and set(owners) <= {'sweep', 'publish', 'bench'}:
        return f'{option} needs --sweep'
    return f'{option} is not used with {flags.get(command, "a BAG alone")}'


def counted(n, noun):
    """Say a count with its noun: '1 command', '3 commands'."""
    return f'{n} {noun}{"" if n == 1 else "s"}'


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

    recorder is made with the bag's QoS and definitions. Returns how many messages were left
    out (no ROS 2 type, or not CDR).
    """
    skipped = 0
    for i, m in enumerate(bag.messages):
        if m.type_name and bag.encodings.get(m.topic) == 'cdr':
            recorder.record(m.topic, m.type_name, m.data, m.log_time, m.publish_time)
        else:
            skipped += 1
        if progress:
            progress.update(i + 1)
    return skipped


# --- running -------------------------------------------------------------------------------

def _imports(args):
    """Import what this run needs; a missing optional package is a Mistake naming it."""
    needs = [('reading and writing bags', 'linkage_ros.record.mcap_writer')]
    if args.command != 'copy':
        needs.append(('solving commands', 'linkage_ros.ros.messages'))
    if args.command == 'publish':
        needs.append(('publishing on ROS 2', 'rclpy'))
    if args.command == 'bench':
        needs.append(('timing RerunRecorder', 'linkage_ros.record.rerun_view'))
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
        status = run(args)
    except (cli.Mistake, LinkageError) as exc:   # SceneError, RecordingError, ReplayError
        return cli.fail(PROG, exc)               # one line: no note after a mistake
    if args.note:
        print(args.note, file=sys.stderr)
    return status


def run(args):
    """Carry out parsed arguments; raises Mistake or LinkageError for a user mistake."""
    _imports(args)
    bag_path = getattr(args, 'bag', None)
    if bag_path:
        cli.check_input(bag_path)
    scene = None
    if args.command != 'copy' and (args.scene or not bag_path):
        from ..core.scene import load_scene
        scene = load_scene(args.scene or 'five_link')
    output = None
    if args.command in ('solve', 'sweep', 'copy'):
        suffix = {'solve': '_solved.mcap', 'copy': '_copy.mcap'}.get(args.command)
        output = args.output or (cli.default_output(bag_path, suffix) if bag_path else
                                 str(Path.cwd() / f'{file_stem(scene.name)}_sweep.mcap'))
        cli.check_output(output, '-o' if args.output else 'output',
                         inputs=_inputs(bag_path, scene))
    if args.command == 'copy':
        return _copy(args, output)
    if bag_path:
        read = read_commands(bag_path, args.topic)
        commands, bag, stored = read.commands, read.bag, read.bag.metadata.get(METADATA)
        status = _warn(read, {'solve': 'solving', 'publish': 'publishing',
                              'bench': 'timing'}[args.command])
        if scene is None and args.command != 'publish':   # publishing needs no scene
            scene = stored_scene(bag, read.topic)
            if scene is not None:
                print(f'{PROG}: the scene stored in {bag_path}: {scene.name}', file=sys.stderr)
            else:
                from ..core.scene import load_scene
                scene = load_scene('five_link')
    else:
        from .replay_commands import sweep_commands
        commands = sweep_commands(scene, args.start, args.stop, args.step,
                                  SWEEP_HZ if args.hz is None else args.hz)
        status, stored = cli.DONE, None
    source = bag_path or 'sweep'
    if args.command == 'publish':
        return _publish(args, commands, source, status)
    if args.command == 'bench':
        if not commands:
            print(f'{PROG}: nothing to time: no commands', file=sys.stderr)
            return status
        print(f'{PROG}: {scene.name}: timing {counted(len(commands), "command")}, method '
              f'{args.method}, '
              'best of 3', file=sys.stderr)
        from .replay_solve import benchmark
        benchmark(commands, scene, args.method)
        return status
    return _solve(args, commands, scene, source, output, stored, status)


def _inputs(bag_path, scene):
    """Return every file this run reads: the bag, the files of a bag folder, the scene file."""
    inputs = []
    if bag_path:
        inputs.append(bag_path)
        if Path(bag_path).is_dir():
            inputs += [str(p) for p in sorted(Path(bag_path).iterdir()) if p.is_file()]
    if scene is not None and Path(scene.source).is_file():
        inputs.append(scene.source)
    return inputs


def _warn(read, verb):
    """Print what a damaged bag or undecodable commands lost; return the exit status."""
    bag, status = read.bag, cli.DONE
    if bag.truncated:
        missing = (f'; no {read.topic} among what could be read'
                   if read.topic not in bag.topics else '')
        print(f'{PROG}: warning: {bag.path}: {bag.describe()}{missing}; {verb} the '
              f'{counted(len(read.commands), "command")} read', file=sys.stderr)
        status = cli.DAMAGED
    for line in read.warnings():
        print(f'{PROG}: warning: {line}', file=sys.stderr)
    return cli.DAMAGED if read.lost else status


def _publish(args, commands, source, status):
    from ..record.interfaces import qualified
    from .replay_publish import check_rate, publish_commands
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


def _solve(args, commands, scene, source, output, stored, status):
    from ..record.interfaces import qualified
    from ..record.mcap_writer import McapRecorder
    from .replay_solve import solve_commands
    print(f'{PROG}: {scene.name}: solving {counted(len(commands), "command")} from {source} on '
          f'{qualified(args.topic)}, method {args.method}', file=sys.stderr)
    custom = {'scene': scene.name, 'method': args.method, 'source': Path(source).name}
    with McapRecorder(output, custom_data=custom,
                      metadata=stored_text(scene, stored)) as recorder:
        failures = solve_commands(commands, scene, args.method, [recorder], args.topic,
                                  Progress(len(commands), 'commands solved'), args.frame_id)
        written = recorder.message_count
    print(f'{PROG}: wrote {counted(written, "message")} to {output}; '
          f'{counted(len(commands) - failures, "command")} solved, {failures} not (see '
          '/diagnostics)', file=sys.stderr)
    return status


if __name__ == '__main__':
    sys.exit(main())
