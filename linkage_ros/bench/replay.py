# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench replay: a run's commands solved with no recording, McapRecorder, RerunRecorder, both.

    linkage-bench replay [BAG] [--topic T] [--scene S] [--method M] [--travel ...] [--hz HZ]

The commands are those linkage-replay solve (BAG) or sweep (without BAG) would answer, read by
linkage-replay's own functions (replay.request), and answered as it answers them
(replay_solve.solve_commands, the node's protocol). Prints a CSV table on stdout: per mode, the
best of 3 runs in microseconds per command, its ratio to no recording, and what each recorded
message adds.
"""

import math
from pathlib import Path
import sys
import time

from ..cli import check_input, counted, fail, Mistake
from ..core.base import LinkageError
from ..core.warmup import compile_if_cold, wants_statics
from ..tools.replay import BAGS, check_imports, given_scene, request, SOLVING
from ..tools.replay_args import EXIT_STATUSES, parse_source
from ..tools.replay_solve import latched_topics, solve_commands

PROG = 'linkage-bench replay'
EPILOG = f"""examples:
  {PROG} bags/five_link_sweep.mcap
  {PROG} --travel -80:80:0.1   the commands of a sweep

{EXIT_STATUSES}"""


def benchmark(commands, scene, method, repeat=3, stream=None):
    """
    Time solving the commands alone and with each sink; print a table (us per command).

    'no recording' solves and builds the messages (as the node does to publish them); the
    other rows add McapRecorder, RerunRecorder or both, file closing included. Best of repeat.
    """
    import tempfile

    from ..record.mcap_writer import McapRecorder
    from ..record.rerun_view import RerunRecorder
    if not commands:
        raise LinkageError('bench', 'no commands to time')
    stream = stream or sys.stdout
    modes = {'no recording': lambda d: [],
             'McapRecorder': lambda d: [McapRecorder(d / 'bench.mcap', qos=latched_topics())],
             'RerunRecorder': lambda d: [RerunRecorder(d / 'bench.rrd', scene)],
             'both': lambda d: [McapRecorder(d / 'bench.mcap', qos=latched_topics()),
                                RerunRecorder(d / 'bench.rrd', scene)]}
    messages = 5 * len(commands)   # the command, pose, camber, toe, tf (diagnostics: a few)
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


def main(argv: list[str]) -> int:
    """Time the commands of BAG or a sweep: 0, 1 if the bag was damaged, 2 for a mistake."""
    args = parse_source(argv, PROG, __doc__.strip().split('\n\n')[0] + ' A CSV table on '
                        'stdout, us per command.', EPILOG)
    try:
        check_imports(BAGS, SOLVING, ('timing RerunRecorder', 'linkage_ros.record.rerun_view'))
        if args.bag:
            check_input(args.bag)
        commands, scene, status, _ = request(args, given_scene(args), 'timing', PROG)
    except (Mistake, LinkageError) as exc:   # SceneError, RecordingError, ReplayError
        return fail(PROG, exc)
    # a corner of a scene with bushings answers loaded poses (warmup.wants_statics)
    compile_if_cold(PROG, statics=wants_statics(scene))
    if not commands:
        print(f'{PROG}: nothing to time: no commands', file=sys.stderr)
        return status
    print(f'{PROG}: {scene.name}: timing {counted(len(commands), "command")}, method '
          f'{args.method}, best of 3', file=sys.stderr)
    benchmark(commands, scene, args.method)
    return status
