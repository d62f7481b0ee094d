# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench: every benchmark of linkage_ros, one subcommand each.

    linkage-bench accuracy [...]       error against run time of every solver (accuracy.py)
    linkage-bench node [...]           the node over DDS: latency, throughput (node_bench/)
    linkage-bench soak [...]           a million commands through the node (soak.py)
    linkage-bench sweep SCENE [...]    paper and fast sweeps side by side (sweep.py)
    linkage-bench axle [VEHICLE] [...] an axle position against corner positions (axle.py)
    linkage-bench map SCENE [...]      map answers with and without the elements (map.py)
    linkage-bench vehicle VEHICLE [...] the setup sheet at 1x, 10x, 100x its tables (sheet.py)
    linkage-bench study [...]          tolerance, sensitivity and fit (study.py)
    linkage-bench replay [BAG] [...]   solving recorded commands with and without recording
                                       (replay.py)
    linkage-bench kc SCENE [...]       compliance rates and a loaded solve against a
                                       kinematic solve (kc.py)
    linkage-bench statics [SCENE...]   a loaded solve and the rates per command against a
                                       continuation step, along a sine (statics.py)
    linkage-bench loads VEHICLE [...]  load cases at 1x, 10x, 100x beside one loaded solve
                                       per corner (loads.py)
    linkage-bench chrono [FILE...]     import, solve and write Chrono files (chrono.py)

Each subcommand takes the options of the program it times (sweep, axle, map, vehicle, kc,
loads: linkage-sweep's, ... parsed by that program; SUBCOMMAND --help lists them); those six
take --rounds N too, which linkage-bench reads. The timing is bench's: the programs only turn
their options into the work's inputs (their request()), which the benchmark times.
"""

import sys

from ..cli import EXIT_STATUS, fail, program

PROG = 'linkage-bench'
ROUNDS = 5   # default --rounds of sweep, axle, map, vehicle, kc and loads

EPILOG = """examples:
  linkage-bench accuracy --quick -o bench-report
  linkage-bench sweep five_link --travel -80:80:1 --rounds 5
  linkage-bench axle demo_vehicle --axle front --rounds 21
  linkage-bench map double_wishbone --rounds 20
  linkage-bench vehicle demo_vehicle --rounds 3
  linkage-bench kc double_wishbone_bushings --travel -40:40:20 --rounds 5
  linkage-bench statics five_link_bushings --commands 200 --rounds 3
  linkage-bench loads demo_vehicle_loads --rounds 1

exit status: as the program timed; """ + EXIT_STATUS


def _accuracy(argv):
    from .accuracy import main
    return main(argv)


def _node(argv):
    from .node_bench.cli import main
    return main(argv)


def _soak(argv):
    from .soak import main
    return main(argv)


def _study(argv):
    from .study import main
    return main(argv)


def _replay(argv):
    from .replay import main
    return main(argv)


def _chrono(argv):
    from .chrono import main
    return main(argv)


def _statics(argv, prog=f'{PROG} statics'):
    from .statics import main
    return main(argv, prog=prog)


def _timed(command, module):
    """Return the runner of bench/<module>.py: its main(argv, rounds), --rounds taken here."""
    def run(argv):
        import importlib
        rounds, rest = _rounds(argv, f'{PROG} {command}')
        return importlib.import_module(f'.{module}', __package__).main(rest, rounds)
    return run


COMMANDS = {'accuracy': _accuracy, 'node': _node, 'soak': _soak,
            'sweep': _timed('sweep', 'sweep'), 'axle': _timed('axle', 'axle'),
            'map': _timed('map', 'map'), 'vehicle': _timed('vehicle', 'sheet'),
            'study': _study, 'replay': _replay, 'kc': _timed('kc', 'kc'), 'chrono': _chrono,
            'statics': _statics, 'loads': _timed('loads', 'loads')}


def _rounds(argv, prog):
    """Take --rounds N (or --rounds=N) out of argv: (N, the other arguments); exit 2 if bad."""
    rounds, rest, i = ROUNDS, [], 0
    while i < len(argv):
        arg = argv[i]
        if arg == '--rounds' or arg.startswith('--rounds='):
            text = arg.split('=', 1)[1] if '=' in arg else (
                argv[i + 1] if i + 1 < len(argv) else '')
            i += 1 if '=' in arg else 2
            if not text.isdigit() or int(text) < 1:
                sys.exit(fail(prog, f'error: argument --rounds: expected a whole number of '
                                    f'rounds >= 1, got {text!r}'))
            rounds = int(text)
        else:
            rest.append(arg)
            i += 1
    return rounds, rest


@program(PROG)
def main(argv: list[str] | None = None) -> int:
    """Run the benchmark the first argument names: 0, 1 or 2 as that benchmark ends."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] in ('-h', '--help'):
        print(f'usage: {PROG} {{{",".join(COMMANDS)}}} [options]\n\n{__doc__.strip()}\n\n'
              f'{EPILOG}')
        return 0
    if argv and argv[0] in COMMANDS:
        return COMMANDS[argv[0]](argv[1:])
    if not argv:
        return fail(PROG, f'error: choose a benchmark: {", ".join(COMMANDS)} (see {PROG} '
                          '--help)')
    if argv[0].startswith('-'):
        return fail(PROG, f'error: unrecognized arguments: {argv[0]}: the benchmark comes '
                          f'first, one of {", ".join(COMMANDS)} (see {PROG} --help)')
    return fail(PROG, f'error: unknown benchmark {argv[0]!r}: choose one of '
                      f'{", ".join(COMMANDS)} (see {PROG} --help)')


if __name__ == '__main__':
    sys.exit(main())
