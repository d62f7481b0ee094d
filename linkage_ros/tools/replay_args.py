# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The command line of linkage-replay: its subcommands and their options.

    parse_args(argv, description)  -> argparse Namespace (args.command: solve, sweep, copy or
                                      publish)
    parse_source(argv, prog, description, epilog)
                                   -> the options that name commands to solve and how, alone
                                      (a BAG or a sweep; --topic, --scene, --method), for a
                                      program that answers them its own way (linkage-bench
                                      replay)

Each subcommand has its own parser, --help, examples and exit statuses; an option given to a
subcommand that does not take it is named with the subcommands that do.
"""

import argparse
import sys
import textwrap

from .replay_commands import DEFAULT_TOPIC, SWEEP_HZ
from .. import cli
from ..core.base import is_finite_number
from ..core.solve import METHODS

PROG = 'linkage-replay'
FRAME_ID = 'base_link'

EXIT_STATUSES = """exit status:
  0  done; the input was complete
  1  done, but the input was damaged or held messages that do not decode: what could be
     read was used (even if that is nothing), and the warning says what was lost
  2  a mistake in the command: an unknown option, a bad value, a path that is not a bag
     (missing, or not MCAP), an output that cannot be written, a missing optional package
     (one line on stderr says which)"""

# subcommand: (summary, [(example arguments, what it does)])
COMMANDS = {
    'solve': ('solve the commands of a recorded run as suspension_node answers them: travel, '
              'the steering rack beside it, and the scene and solver changes of '
              '/parameter_events, in the recorded order',
              [('run.mcap', 'writes ./run_solved.mcap'),
               ('run.mcap -o again.mcap --scene macpherson', ''),
               ('car/ --topic /front_left/wheel_travel', 'a corner of a vehicle')]),
    'sweep': ("solve the commands of a travel sweep (the scene's range and step by default)",
              [('', 'writes ./five_link_sweep.mcap'),
               ('--scene macpherson --travel -40:40:0.5 -o sweep.mcap', '')]),
    'copy': ('copy every readable message (any topic, type and QoS) into a complete MCAP: '
             'recovers a recording cut by a hard kill or damaged',
             [('run.mcap', 'writes ./run_copy.mcap'), ('cut.mcap -o fixed.mcap', '')]),
    'publish': ('republish the commands on ROS 2 (rclpy) at the recorded pace instead of '
                'solving them',
                [('run.mcap --rate 2 --clock', 'twice as fast, with /clock'),
                 ('--scene macpherson --hz 100', 'the commands of a sweep')]),
}
SOURCE = 'source'   # not a subcommand: the options of parse_source


def examples(*commands):
    """Return the example lines of commands, their comments in one column."""
    lines = []
    for command in commands:
        for arguments, comment in COMMANDS[command][1]:
            line = f'  {PROG} {command} {arguments}'.rstrip()
            lines.append(f'{line:<60} {comment}'.rstrip() if comment else line)
    return '\n'.join(lines)


SWEEP_OPTIONS = ('--travel', '--hz')


class Parser(cli.Parser):
    """A subcommand's parser: its mistakes are one line that starts with linkage-replay."""

    def error(self, message):
        """Print one line naming the mistake and exit with status 2."""
        sys.exit(cli.fail(PROG, f'error: {message} (see {self.prog} --help)'))


def _number(minimum=None, strict=False):
    """Return an argparse type: a finite number above (strict) or at least minimum (None: any)."""
    def parse(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f'expected a number, got {text!r}') from None
        if minimum is None:
            if not is_finite_number(value):
                raise argparse.ArgumentTypeError(f'must be a finite number, got {text}')
        elif not is_finite_number(value) or value < minimum or (strict and value == minimum):
            relation = 'above' if strict else 'at least'
            raise argparse.ArgumentTypeError(f'must be a finite number {relation} '
                                             f'{minimum:g}, got {text}')
        return value
    return parse


def _options(parser, command):
    """Add the options of a subcommand (or SOURCE) to its parser; return their option strings."""
    source = command in ('publish', SOURCE)   # a BAG, or without one a sweep
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
                  if command in ('solve', SOURCE) else ' (default five_link)')
        option('--scene', help=('sweep: ' if command == 'publish' else '') +
               'bundled scene name or scene YAML path' + stored)
    if command in ('solve', 'sweep', SOURCE):
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
    if command in ('sweep', 'publish', SOURCE):
        which = 'sweep: ' if source else ''
        option('--travel', type=cli.span, metavar=cli.SPAN,
               help=f'{which}travels, mm: FROM:TO:STEP (TO included) or one value (default: '
               "the scene's travel block)")
        option('--hz', type=_number(0.0, True),
               help=f'{which}command rate, Hz, > 0 (default {SWEEP_HZ:g})')
    return known


def make_parser(description):
    """
    Return the parser of linkage-replay and its subcommands.

    parser.commands: {subcommand: (its parser, its option strings)}.
    """
    summary, text = description.strip().split('\n', 1)
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


def parse_args(argv, description):
    """Parse linkage-replay's arguments; a mistake exits with one line and status 2."""
    parser = make_parser(description)
    known = set().union(*(options for _, options in parser.commands.values()))
    argv = _joined_values(list(sys.argv[1:] if argv is None else argv), known)
    args, extras = parser.parse_known_args(argv)
    if args.command is None:
        parser.error(f'unrecognized arguments: {" ".join(extras)}' if extras else
                     f'choose what to do: {", ".join(COMMANDS)}')
    sub = parser.commands[args.command][0]
    if extras:
        sub.error(_misplaced(parser, args.command, extras))
    return _sweep_checked(args, args.command, sub)


def parse_source(argv, prog, description, epilog):
    """
    Parse the options that name commands to solve (SOURCE's), with prog's own --help.

    BAG, or without it a sweep (--travel, --hz); --topic, --scene, --method, as linkage-replay
    reads them (args.bag, args.start, args.stop, args.step as for its subcommands). A mistake
    exits with one line, prog first, and status 2.
    """
    parser = cli.Parser(prog, description, epilog)
    known = _options(parser, SOURCE)
    args = parser.parse_args(_joined_values(list(argv), known))
    return _sweep_checked(args, SOURCE, parser)


def _sweep_checked(args, command, parser):
    """Refuse a sweep's option given with BAG (parser.error); set the sweep's range; args."""
    if command in ('publish', SOURCE) and args.bag:
        given = [o for o in SWEEP_OPTIONS if getattr(args, o[2:]) is not None]
        if given or (command == 'publish' and args.scene):
            parser.error(f'{(given or ["--scene"])[0]} makes a sweep: give it without BAG')
    if 'travel' in args:   # a sweep's range: None, the scene's travel block
        args.start, args.stop, args.step = args.travel or (None, None, None)
    return args


def _joined_values(argv, known):
    """
    Join a number option and a value that starts with '-' ('--hz', '-1e300': --hz=-1e300).

    argparse takes '-1e300' or '-80mm' for an option of its own ('expected one argument');
    joined, the value is checked as a number, and a mistake is said as such.
    """
    numeric = {'--travel', '--hz', '--rate', '--wait'}
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


def _misplaced(parser, command, extras):
    """Say what is wrong with arguments a subcommand does not take."""
    option = next((e.split('=')[0] for e in extras if e.startswith('-')), None)
    if option is None and command == 'sweep':
        return f'a sweep takes no BAG (unrecognized arguments: {" ".join(extras)})'
    owners = [name for name, (_, known) in parser.commands.items() if option in known]
    if not owners:
        return f'unrecognized arguments: {" ".join(extras)}'
    return f'{option} is not an option of {PROG} {command} (it is one of: ' \
           f'{", ".join(owners)})'
