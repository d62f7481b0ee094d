# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Stiff and extreme cases of linkage-bench.

Toggles, jumps, reversals, scaled scenes, perturbed hardpoints (config/stress). Each returns
lines of the report.
"""

import math
import time

import numpy as np

from . import reference
from .report import progress
from ..core.model import bundled_scenes, config_dir, load_scene, parse_scene
from ..core.solve import Continuation, MIN_STEP, Settings, sweep, travel_range

STRESS_DIR = config_dir() / 'stress'


def stress_scene(name):
    """Load the stress scene name from config/stress."""
    return load_scene(STRESS_DIR / f'{name}.yaml')


def perturbed(scene, offsets):
    """
    Return scene with every hardpoint moved by offsets (k, 3) mm.

    The order is: wheel centre, spin-axis point, then each constraint's base points and
    carrier point. Re-validated (SceneError if the result is not a valid scene); the design
    pose stays assembled.
    """
    offsets = np.asarray(offsets, dtype=float).reshape(-1, 3)
    it = iter(offsets)
    point = lambda p: [float(v) for v in np.asarray(p) + next(it)]   # noqa: E731
    data = {'name': scene.name, 'units': 'mm', 'side': scene.side,
            'carrier': {'wheel_center': point(scene.wheel_center),
                        'spin_axis_point': point(scene.spin_axis_point)},
            'constraints': [], 'travel': dict(zip(('min', 'max', 'step'), scene.travel))}
    for c in scene.constraints:
        item = {'name': c.name, 'type': c.type}
        bases = [point(b) for b in c.base]
        if c.type == 'circle':
            item['axis'] = bases
        else:
            item['base'] = bases[0]
        item['carrier'] = point(c.carrier)
        data['constraints'].append(item)
    return parse_scene(data, source=f'{scene.name} (perturbed)')


def hardpoint_count(scene):
    return 2 + sum(len(c.base) + 1 for c in scene.constraints)


# The paper's method runs in Python (about 1 ms a step): a scene grown 1e4 times, walked in
# steps of the default 5 mm, would take 320 000 of them.
PAPER_STEP_BUDGET = 20_000


def stress_lines(reversals=100_000):
    """Numbers of the stiff and extreme cases (the tests in test/core/test_stability.py)."""
    lines = []
    parts = (('toggles', stress_toggles), ('jumps', stress_jumps),
             ('reversals', lambda: stress_reversals(reversals)), ('scaling', stress_scaling),
             ('perturbed hardpoints', stress_perturbation),
             ('out of reach', stress_out_of_reach))
    for name, part in parts:
        lines += part() + ['']
        progress(f'stress: {name} done')
    return lines


def stress_toggles():
    """
    Compare travel limits at toggles.

    The core against the analytic fold and an independent bisection
    (reference.reachable_limit).
    """
    arm, vertical = stress_scene('trailing_arm_toggle'), stress_scene('five_link_vertical_link')
    cases = ((arm, -100.0 + math.hypot(150.0, 400.0) - 300.0, 'analytic'),
             (vertical, reference.reachable_limit(vertical, 1)[0], 'bisection'))
    lines = ['### Travel limits at a toggle (turning point)', '',
             '| scene | independent limit (mm) | method | core limit (mm) | difference (mm) '
             '| condition 0.001 mm before it | asked 1 mm beyond it |',
             '|---|---|---|---|---|---|---|']
    for scene, limit, how in cases:
        for method in ('fast', 'paper'):
            cont = Continuation(scene, method=method)
            beyond = cont.solve(limit + 1.0)
            found = beyond.reachable[1]
            near = cont.solve(found - 0.001)
            answer = 'a pose (wrong)' if beyond.success else f'error: "{beyond.message[:58]}..."'
            lines.append(f'| {scene.name} | {limit:.4f} ({how}) | {method} | {found:.4f} | '
                         f'{found - limit:+.1e} | {near.condition:.3g} | {answer} |')
    return lines


def stress_jumps():
    """One command from the bottom to the top of the travel range against fine continuation."""
    lines = ['### One command from -80 to +80 mm against fine continuation (0.25 mm steps)', '',
             '| scene | method | wheel-centre difference (mm) | camber difference (deg) |',
             '|---|---|---|---|']
    for name in bundled_scenes():
        scene = load_scene(name)
        low, high = scene.travel[0], scene.travel[1]
        fine = sweep(scene, travel_range(0.0, high, 0.25), method='fast')
        for method in ('fast', 'paper'):
            cont = Continuation(scene, method=method)
            cont.solve(low)
            jump = cont.solve(high)
            diff = np.max(np.abs(jump.wheel_center - fine.wheel_center[-1]))
            lines.append(f'| {name} | {method} | {diff:.1e} | '
                         f'{abs(math.degrees(jump.camber - fine.camber[-1])):.1e} |')
    return lines


def stress_reversals(count):
    """Compare a random walk of commands on five_link with a batched sweep of the same travels."""
    scene = load_scene('five_link')
    travels = random_walk(count, scene.travel[0], scene.travel[1], seed=5)
    cont = Continuation(scene, method='fast')
    start = time.perf_counter()
    sols = [cont.solve(float(t)) for t in travels]
    elapsed = time.perf_counter() - start
    table = sweep(scene, travels, method='fast')
    centers = np.array([s.wheel_center for s in sols])
    turns = int(np.sum(np.diff(np.sign(np.diff(travels))) != 0))
    return [f'### {count} random commands on five_link ({turns} reversals, steps up to 5 mm)',
            '', f'- all solved: {all(s.success for s in sols)}; largest residual '
            f'{max(s.residual for s in sols):.1e} mm (tol {Settings().tol:g} mm); largest '
            'deviation from a batched sweep of the same travels '
            f'{np.max(np.abs(centers - table.wheel_center)):.1e} mm; '
            f'{elapsed / count * 1e6:.0f} us per command.']


def stress_scaling():
    """Badly scaled scenes and P near the spin axis, default and size-scaled settings."""
    lines = ['### Badly scaled scenes, P near the spin axis (17 travels over the range)', '',
             '| scene | size (mm) | method | settings | range solved | error (mm) | message |',
             '|---|---|---|---|---|---|---|']
    for name in ('five_link_submillimetre', 'five_link_kilometres', 'five_link_length_ratio',
                 'five_link_p_near_axis'):
        scene = stress_scene(name)
        travels = np.linspace(scene.travel[0], scene.travel[1], 17)
        ref = reference.reference_poses(scene, travels)
        scale = scene.size / 1000.0
        for method in ('fast', 'paper'):
            scaled = {'tol': Settings().tol * scale, 'max_step': Settings().max_step * scale,
                      'min_step': MIN_STEP * scale}
            for label, options in (('default', {}), ('scaled', scaled)):
                max_step = options.get('max_step', Settings().max_step)
                steps = (travels[-1] - travels[0]) / max_step
                if method == 'paper' and steps > PAPER_STEP_BUDGET:
                    lines.append(f'| {name} | {scene.size:.3g} | {method} | {label} | not run '
                                 f'| | {steps:.0f} steps of max_step: minutes in Python |')
                    continue
                progress(f'stress: scaling: {name}, {method}, {label}')
                result = sweep(scene, travels, method=method, **options)
                error = math.nan
                if result.success:
                    err = reference.errors(ref, result.wheel_center, result.rotation)
                    error = max(err['residual_mm'], err['wheel_center_mm'])
                lines.append(f'| {name} | {scene.size:.3g} | {method} | {label} | '
                             f'{result.success} | {error:.1e} | {result.message[:70]} |')
    lines += ['', 'scaled: tol, max_step and min_step times (scene size / 1000 mm).']
    return lines


def stress_perturbation():
    """Hardpoints moved by 1e-9 mm: the change of the outputs, and condition numbers."""
    scene = load_scene('five_link')
    shift = np.random.default_rng(9).normal(size=(hardpoint_count(scene), 3))
    moved = perturbed(scene, 1e-9 * shift / np.linalg.norm(shift, axis=1, keepdims=True))
    travels = np.linspace(-80, 80, 9)
    a, b = sweep(scene, travels, tol=1e-12), sweep(moved, travels, tol=1e-12)
    conds = [Continuation(scene).solve(float(t)).condition for t in travels]
    change = np.max(np.abs(a.wheel_center - b.wheel_center))
    camber = np.max(np.abs(np.degrees(a.camber - b.camber)))
    return ['### Hardpoints moved by 1e-9 mm (five_link, tol 1e-12 mm)', '',
            f'- largest wheel-centre change {change:.1e} mm, camber change {camber:.1e} deg; '
            f'Jacobian condition number over -80..80 mm: {min(conds):.0f} to {max(conds):.0f}. '
            'The node says WARN above its condition_warn parameter (default 1e4), reached '
            'near toggles (table above).']


def stress_out_of_reach(rounds=5, count=200):
    """
    Time commands beyond a travel limit beside good ones (five_link, one at a time).

    The first is walked to the limit and beyond it by arclength; the later ones at the same
    rack are refused from the limit remembered (Continuation.limits). Medians over rounds,
    each from a new Continuation.
    """
    scene = load_scene('five_link')
    beyond = 500.0                        # mm, past the bump limit 387.469 mm
    travels = 60.0 * np.sin(np.arange(count) * 0.0125)   # good: steps of up to 0.75 mm
    times = {'good': [], 'first beyond the limit': [], 'later ones beyond it': []}
    for _ in range(rounds):
        cont = Continuation(scene)
        for travel in travels:
            start = time.perf_counter()
            cont.solve(float(travel))
            times['good'].append(time.perf_counter() - start)
        for i in range(count):
            start = time.perf_counter()
            answer = cont.solve(beyond + i)
            times['first beyond the limit' if i == 0 else 'later ones beyond it'].append(
                time.perf_counter() - start)
            assert not answer.success
    good = np.median(times['good'])
    lines = ['### Commands beyond a travel limit (five_link, bump limit 387.469 mm)', '',
             '| commands | count | median (us) | ratio to a good command |', '|---|---|---|---|']
    for name, values in times.items():
        lines.append(f'| {name} | {len(values)} | {np.median(values) * 1e6:.1f} | '
                     f'{np.median(values) / good:.2g} |')
    return lines


def random_walk(count, low, high, seed=0, largest=5.0):
    """
    Return count travels (mm) by a random walk of steps up to `largest` mm either way.

    The walk is reflected at the travel range [low, high]: the direction reverses about every
    other command.
    """
    rng = np.random.default_rng(seed)
    steps = rng.uniform(-largest, largest, count)
    out = np.empty(count)
    here = 0.0
    for i, s in enumerate(steps):
        here += s
        if here > high:
            here = 2 * high - here
        if here < low:
            here = 2 * low - here
        out[i] = here
    return out
