# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Timing of the statics (issue 29): rates and one loaded solve against one kinematic solve.

    python -m linkage_ros.bench.statics SCENE [--travel T] [--rounds N ...]

Each is timed in the same run, one call at a time, warm (numba compiled and loaded): the
kinematic solve (Continuation.solve), compliance() and solve_loaded() of a lateral force at
the contact patch (at the wheel centre without wheel_radius), each alternating between two
travels so that each call solves anew; and the last two again at one travel, where the
zero-load equilibrium is kept (a rig loading one position). timings() returns the numbers for other
programs (linkage-kc's --benchmark); main() prints a table, microseconds per call, and the
ratios to the kinematic solve (goals: rates <= 3x, loaded <= 10x).
"""

from __future__ import annotations

import argparse
import sys
import time

from ..core.model import load_scene
from ..core.solve import Continuation
from ..core.statics import compliance, Load, solve_loaded
from ..outputs import write_table

ROUNDS = (1, 10, 100)


def _per_call(run, rounds: int) -> float:
    """Return the best of 3 mean times (us) of rounds calls of run()."""
    best = float('inf')
    for _ in range(3):
        start = time.perf_counter()
        for _ in range(rounds):
            run()
        best = min(best, (time.perf_counter() - start) / rounds * 1e6)
    return best


def timings(scene, travel: float = 10.0, rounds=ROUNDS) -> list[dict]:
    """Return one row per round count: microseconds per call and the ratios (dicts)."""
    cont = Continuation(scene)
    load = Load((0.0, 1000.0, 0.0), 'cp' if scene.wheel_radius > 0 else 'wc')
    travels = [travel, travel + 1.0]

    def turn():   # every other call at the other travel: each call solves anew
        travels.reverse()
        return travels[0]

    calls = {'kinematic_us': lambda: cont.solve(turn()),
             'rates_us': lambda: compliance(scene, turn(), continuation=cont),
             'loaded_us': lambda: solve_loaded(scene, turn(), load, continuation=cont),
             'rates_same_travel_us': lambda: compliance(scene, travel, continuation=cont),
             'loaded_same_travel_us': lambda: solve_loaded(scene, travel, load,
                                                           continuation=cont)}
    for run in calls.values():   # compile or load the kernels, fill the caches
        run()
    rows = []
    for count in rounds:
        row = {'rounds': count}
        row.update({name: _per_call(run, count) for name, run in calls.items()})
        for name in ('rates', 'loaded', 'rates_same_travel', 'loaded_same_travel'):
            row[f'{name}_ratio'] = row[f'{name}_us'] / row['kinematic_us']
        rows.append(row)
    return rows


def main(argv=None) -> int:
    """Print the timings of a scene's statics; returns the exit status."""
    parser = argparse.ArgumentParser(prog='python -m linkage_ros.bench.statics',
                                     description=__doc__.split('\n\n')[0].strip())
    parser.add_argument('scene', help='bundled scene name or YAML path')
    parser.add_argument('--travel', type=float, default=10.0, help='travel, mm (default 10)')
    parser.add_argument('--rounds', type=int, nargs='+', default=list(ROUNDS),
                        help='calls per timing (default 1 10 100)')
    args = parser.parse_args(argv)
    try:
        scene = load_scene(args.scene)
    except ValueError as exc:
        print(exc, file=sys.stderr)
        return 2
    columns = ('rounds', 'kinematic_us', 'rates_us', 'loaded_us', 'rates_same_travel_us',
               'loaded_same_travel_us', 'rates_ratio', 'loaded_ratio', 'rates_same_travel_ratio',
               'loaded_same_travel_ratio')
    write_table(None, columns, [[row[c] for c in columns]
                                for row in timings(scene, args.travel, args.rounds)])
    return 0


if __name__ == '__main__':
    sys.exit(main())
