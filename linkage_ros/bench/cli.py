# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench: every benchmark of linkage_ros, one subcommand each.

    linkage-bench accuracy [...]       error against run time of every solver (accuracy.py)
    linkage-bench node [...]           the node over DDS: latency, throughput (node_bench/)
    linkage-bench soak [...]           a million commands through the node (soak.py)
    linkage-bench sweep SCENE [...]    paper and fast sweeps side by side (linkage-sweep)
    linkage-bench axle [VEHICLE] [...] an axle position against corner positions
    linkage-bench map SCENE [...]      map answers with and without the elements
    linkage-bench vehicle VEHICLE [...] the setup sheet at 1x, 10x, 100x its tables (sheet.py)
    linkage-bench study [...]          tolerance, sensitivity and fit (study.py)
    linkage-bench replay [BAG] [...]   solving recorded commands with and without recording
    linkage-bench kc SCENE [...]       compliance rates and a loaded solve against a
                                       kinematic solve (linkage-kc; kc_bench.py)
    linkage-bench chrono [FILE...]     import, solve and write Chrono files (bench/chrono.py)

Each subcommand takes the options of the program it times (SUBCOMMAND --help lists them);
sweep, axle, map, vehicle and kc take --rounds N too.
"""

import sys

from ..cli import EXIT_STATUS, fail, program

PROG = 'linkage-bench'
ROUNDS = 5   # default --rounds of sweep, axle, map and kc

EPILOG = """examples:
  linkage-bench accuracy --quick -o bench-report
  linkage-bench sweep five_link --travel -80:80:1 --rounds 5
  linkage-bench axle demo_vehicle --axle front --rounds 21
  linkage-bench map double_wishbone --rounds 20
  linkage-bench vehicle demo_vehicle --rounds 3
  linkage-bench kc double_wishbone_bushings --travel -40:40:20 --rounds 5

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
    from ..tools.replay import main
    return main(['bench', *argv])


def _chrono(argv):
    from .chrono import main
    return main(argv)


def _timed(module):
    """Return the runner of a program whose main(argv, rounds) times instead of solving."""
    def run(argv):
        import importlib
        rounds, rest = _rounds(argv, f'{PROG} {module.rsplit(".", 1)[-1]}')
        return importlib.import_module(f'..tools.{module}', __package__).main(rest,
                                                                              rounds=rounds)
    return run


COMMANDS = {'accuracy': _accuracy, 'node': _node, 'soak': _soak,
            'sweep': _timed('sweep'), 'axle': _timed('axle'), 'map': _timed('kinematic_map'),
            'vehicle': _timed('vehicle'), 'study': _study, 'replay': _replay,
            'kc': _timed('kc'), 'chrono': _chrono}


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
