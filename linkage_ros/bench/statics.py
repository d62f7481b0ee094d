# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench statics: a loaded solve and the rates per command against a continuation step.

Along a slow sine, as a simulator steps a corner at 1 kHz (a 1 Hz travel sine of 30 mm,
and a cornering wrench at the contact patch that follows it: 200 N longitudinal and 3 kN
lateral as sines, 4 kN vertical, 50 N m aligning torque), each command is timed in one run,
side by side: a continuation step (Continuation.solve, the kinematics), a loaded solve
(Statics.solve, from the last loaded equilibrium) and the rates (Statics.rates, from the
last zero-load one), at 1x, 10x and 100x the commands. CPU time of this process per command
(the machine is shared: wall time moves with the others' load, which is printed), the median
of rounds that alternate the three. The goal (issue 37): a loaded solve and the rates each
at most 3 continuation steps. --parts also times the pieces of a loaded command: where the
time goes.
"""

from __future__ import annotations

import math
import os
import statistics
import sys
import time

from ..cli import counted, fail, Parser
from ..outputs import write_table

PROG = 'linkage-bench statics'
SCENES = ('double_wishbone_bushings', 'five_link_bushings',
          'chrono_sedan_doublewishbone_bushings')
SCALES = (1, 10, 100)
RATE_HZ, SINE_HZ, AMPLITUDE_MM = 1000.0, 1.0, 30.0
COLUMNS = ('scene', 'commands', 'continuation_us', 'loaded_us', 'rates_us', 'loaded_ratio',
           'rates_ratio')

EPILOG = """examples:
  linkage-bench statics
  linkage-bench statics five_link_bushings --commands 200 --rounds 3 --parts

columns: scene, commands, continuation_us (a continuation step), loaded_us (Statics.solve),
  rates_us (Statics.rates), loaded_ratio and rates_ratio (to the continuation step); CPU
  time per command, the median of the rounds. The load average is printed before and after.
"""


def commands(count: int, first: int = 0):
    """Return (travels mm, loads) of count commands along the sine (1 kHz, 1 Hz, 30 mm)."""
    from ..core.statics import Load
    travels, loads = [], []
    for k in range(first, first + count):
        phase = 2.0 * math.pi * SINE_HZ * k / RATE_HZ
        travels.append(AMPLITUDE_MM * math.sin(phase))
        loads.append(Load((200.0 * math.cos(phase), 3000.0 * math.sin(phase), 4000.0), 'cp',
                          (0.0, 0.0, 50.0)))
    return travels, loads


def timings(scene, count: int, rounds: int) -> dict:
    """Return the median CPU time per command (us) of each of the three, count commands each."""
    from ..core.base import Status
    from ..core.solve import Continuation
    from ..core.statics import Statics
    continuation, loaded, rates = Continuation(scene), Statics(scene), Statics(scene)

    def kinematic(travels, loads):
        for travel in travels:
            continuation.solve(travel)

    def solve(travels, loads):
        for travel, load in zip(travels, loads):
            if loaded.solve(travel, load).status != Status.OK:
                raise RuntimeError(f'{scene.name}: travel {travel:g} mm not solved')

    def compliance(travels, loads):
        for travel in travels:
            rates.rates(travel)

    runs = {'continuation_us': kinematic, 'loaded_us': solve, 'rates_us': compliance}
    times = {name: [] for name in runs}
    for k in range(rounds + 1):   # each round goes on along the sine; the first warms up
        sine = commands(count, k * count)
        for name, run in runs.items():
            start = time.process_time()
            run(*sine)
            if k:
                times[name].append((time.process_time() - start) / count * 1e6)
    out = {name: statistics.median(values) for name, values in times.items()}
    out['loaded_ratio'] = out['loaded_us'] / out['continuation_us']
    out['rates_ratio'] = out['rates_us'] / out['continuation_us']
    return out


def parts(scene, count: int) -> dict:
    """Return CPU time (us) of the pieces of a loaded command (bench/statics_parts.py)."""
    from .statics_parts import parts as measured
    return measured(scene, commands(count), commands(count, count))


def main(argv=None, prog=PROG) -> int:
    """Run the benchmark; returns the exit status."""
    parser = Parser(prog, __doc__.strip().splitlines()[0], EPILOG)
    parser.add_argument('scenes', nargs='*', metavar='SCENE',
                        help='bundled scene names or YAML paths with bushings (default: the '
                        'three bundled bushed scenes)')
    parser.add_argument('--commands', type=int, default=1000,
                        help='commands at 1x (default 1000: one second at 1 kHz)')
    parser.add_argument('--rounds', type=int, default=5,
                        help='alternating rounds per scale (default 5)')
    parser.add_argument('--parts', action='store_true',
                        help='also time the pieces of a loaded command')
    args = parser.parse_args(argv)
    if args.commands < 1 or args.rounds < 1:
        parser.error('--commands and --rounds must be at least 1')
    from ..core.model import load_scene
    from ..core.warmup import compile_if_cold
    try:
        scenes = [load_scene(name) for name in args.scenes or SCENES]
    except ValueError as exc:
        return fail(prog, exc)
    compile_if_cold(prog, statics=True)
    print(f'{prog}: load average {os.getloadavg()[0]:.2f} (1 min), {os.cpu_count()} cores; '
          f'{counted(args.commands, "command")} at 1x, {args.rounds} rounds', file=sys.stderr)
    rows = []
    for scene in scenes:
        for scale in SCALES:
            row = timings(scene, args.commands * scale, args.rounds)
            rows.append([scene.name, args.commands * scale] + [row[c] for c in COLUMNS[2:]])
            print(f'{prog}: {scene.name}: {counted(rows[-1][1], "command")}: loaded '
                  f'{row["loaded_ratio"]:.2f}x, rates {row["rates_ratio"]:.2f}x a continuation '
                  'step', file=sys.stderr, flush=True)
        if args.parts:
            measured = parts(scene, args.commands)
            print(f'{prog}: {scene.name}: a loaded command, us: ' + ', '.join(
                f'{name} {value:.2f}' for name, value in measured.items()), file=sys.stderr)
    print(f'{prog}: load average {os.getloadavg()[0]:.2f} (1 min) at the end', file=sys.stderr)
    write_table(None, COLUMNS, rows)
    return 0


if __name__ == '__main__':
    sys.exit(main())
