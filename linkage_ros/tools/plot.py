# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-plot: the pictures of README.md and doc/, as PNG files (needs matplotlib: the plot extra).

    linkage-plot camber-toe -o OUT.png [SCENE ...]   camber and toe against travel
    linkage-plot alignment -o OUT.png [SCENE ...]    the alignment set against travel
    linkage-plot latency BENCH.csv -o OUT.png        latency against command rate, node and
                                                     echo, from the tables linkage-bench node
                                                     wrote
    linkage-plot roll-centre -o OUT.png [VEHICLE [AXLE]]   an axle's roll centre in heave and
                                                     roll (default demo_vehicle front;
                                                     axle_plot.py)
Default scenes: five_link, double_wishbone, macpherson, in that order (one colour each).
A scene whose travel block is not solved whole (a travel out of reach, a singular scene) is
drawn as far as it was solved, and named on stderr in one line with where it stopped: the
picture is written, and the status is 1.
"""

import argparse
import csv
from pathlib import Path
import sys

import numpy as np

from ..cli import counted, EXIT_STATUS, fail, Parser, plot_problem, program, warn
from ..core.model import load_scene, scene_dir, SceneError
from ..core.solve import sweep, travel_range
from ..core.warmup import compile_if_cold
from ..outputs import save_figure


def swept(scenes):
    """Return the Sweep of each scene over its travel block: what the pictures draw."""
    return [sweep(scene, travel_range(*scene.travel)) for scene in scenes]


def plot_camber_toe(scenes, path, results=None):
    """Write a two-panel PNG (camber, toe in deg against travel in mm) of the given scenes."""
    import matplotlib.pyplot as plt
    fig = camber_toe_figure(scenes, results)
    save_figure(fig, path, dpi=110)
    plt.close(fig)


def camber_toe_figure(scenes, results=None):
    """
    Return the figure of plot_camber_toe: camber and toe (deg) against travel (mm).

    results: the scenes' Sweeps (swept(scenes), which is the default). The scenes'
    reference tables are drawn as dots, with a legend entry if any has one; the title names
    the scenes unless they are all bundled.
    """
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    fig, (ax_camber, ax_toe) = plt.subplots(1, 2, figsize=(10, 4), sharex=True)
    references = 0
    for scene, result in zip(scenes, results or swept(scenes)):
        ax_camber.plot(result.travel, np.degrees(result.camber), label=scene.name)
        ax_toe.plot(result.travel, np.degrees(result.toe), label=scene.name)
        rows = reference_rows(scene)
        if len(rows):
            references += 1
            ax_camber.plot(rows[:, 0], rows[:, 1], 'k.', ms=5)
            ax_toe.plot(rows[:, 0], rows[:, 2], 'k.', ms=5)
    for ax, what in ((ax_camber, 'camber_deg (+ = top outboard)'),
                     (ax_toe, 'toe_deg (+ = toe-in)')):
        ax.set_xlabel('travel_mm (+ = bump)')
        ax.set_ylabel(what)
        ax.grid(True, alpha=0.3)
    if references:
        ax_camber.plot([], [], 'k.', label='reference (refdata)')
    ax_camber.legend(fontsize=8)
    fig.suptitle(f'linkage_ros: {title(scenes)}')
    fig.tight_layout()
    return fig


def reference_rows(scene):
    """
    Return the rows (travel_mm, camber_deg, toe_deg) of a scene's reference table, (k, 3).

    Empty when the scene has none, or when its reference block is not such a table (the
    block is free text to the loader).
    """
    reference = scene.extras.get('reference')
    try:
        rows = np.array(reference['rows'], dtype=float)
    except (TypeError, KeyError, ValueError, IndexError):
        return np.empty((0, 3))
    return rows if rows.ndim == 2 and rows.shape[1] >= 3 else np.empty((0, 3))


def title(scenes):
    """
    Say what the scenes are, for a picture's title: 'bundled scenes, left wheel'.

    Scenes not from the bundled folder are named; the side is each scene's own.
    """
    bundled = all(Path(s.source).resolve().parent == scene_dir().resolve() for s in scenes)
    what = 'bundled scenes' if bundled else ', '.join(s.name for s in scenes)
    sides = sorted({s.side for s in scenes})
    return f'{what}, ' + (f'{sides[0]} wheel' if len(sides) == 1 else 'left and right wheels')


ALIGNMENT_PANELS = [
    ('camber_gain', 'camber gain, deg/mm', True), ('bump_steer', 'bump steer, deg/mm', True),
    ('caster', 'caster, deg', True), ('kingpin_inclination', 'kingpin inclination, deg', True),
    ('scrub_radius', 'scrub radius, mm', False),
    ('mechanical_trail', 'mechanical trail, mm', False),
    ('track_change', 'track change, mm', False),
    ('lateral_shift', 'wheel-centre lateral shift, mm', False)]


def plot_alignment(scenes, path, results=None):
    """Write a PNG of the alignment set against travel (mm) of scenes (their Sweeps: results)."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    from ..core.measure import alignment
    from ..core.solve import compile_scene

    fig, axes = plt.subplots(2, 4, figsize=(16, 7), sharex=True)
    for scene, result in zip(scenes, results or swept(scenes)):
        values = alignment(scene, compile_scene(scene), result.wheel_center, result.rotation)
        for ax, (field, label, degrees) in zip(axes.flat, ALIGNMENT_PANELS):
            data = getattr(values, field)
            ax.plot(result.travel, np.degrees(data) if degrees else data, label=scene.name)
            ax.set_title(label, fontsize=10)
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel('travel_mm (+ = bump)')
    axes.flat[0].legend(fontsize=8)
    fig.suptitle('linkage_ros: alignment set (steer quantities need a steer: rack link)')
    fig.tight_layout()
    save_figure(fig, path, dpi=100)
    plt.close(fig)


def read_ladder(path: str) -> dict[str, list[tuple[float, float, float]]]:
    """
    Read the rate table of a linkage-bench node output (its CSV tables).

    Returns {node name: [(rate Hz, median us, p99 us)]} for the rates where commands were
    answered.
    """
    ladder, in_table = {}, False
    with open(path, newline='') as stream:
        for row in csv.reader(stream):
            if not row:
                in_table = False
            elif row[0] == 'rate':
                in_table = True
                columns = row
            elif in_table:
                values = dict(zip(columns, row))
                if int(values['answered']):
                    ladder.setdefault(row[0], []).append((
                        float(values['hz']), float(values['median_us']),
                        float(values['p99_us'])))
    return ladder


def plot_latency(ladder: dict[str, list[tuple[float, float, float]]], path: str) -> None:
    """Write median and p99 latency (ms) against command rate (Hz), node and echo, as PNG."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from matplotlib.ticker import ScalarFormatter
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for name, label, color in (('node', 'suspension_node', 'C0'),
                               ('echo', 'bare rclpy echo node', 'C1')):
        rates, median, p99 = np.array(ladder.get(name, [])).reshape(-1, 3).T
        ax.plot(rates, median / 1000.0, 'o-', color=color, label=f'{label}, median')
        ax.plot(rates, p99 / 1000.0, 'o--', color=color, alpha=0.6, label=f'{label}, p99')
    ax.set_xscale('log')
    ax.set_yscale('log')
    ax.set_xticks(sorted({r for rows in ladder.values() for r, _, _ in rows}))
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(plt.NullFormatter())
    ax.yaxis.set_major_formatter(ScalarFormatter())
    ax.set_xlabel('command rate, Hz')
    ax.set_ylabel('latency, ms (command sent to pose received)')
    ax.grid(True, which='both', alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title('suspension_node and a bare echo node, across processes')
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)


DEFAULT_SCENES = ['five_link', 'double_wishbone', 'macpherson']


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = Parser('linkage-plot', __doc__, 'examples:\n'
                    '  linkage-plot camber-toe -o bags/plots/camber_toe.png\n'
                    '  linkage-plot latency doc/bench/node_bench.csv -o bags/plots/'
                    'node_latency.png'
                    '\n\nexit status: 0 written; 1 written, but a scene is drawn only as far '
                    'as its travel block was solved (said on stderr); ' + EXIT_STATUS)
    parser.add_argument('what', choices=('camber-toe', 'alignment', 'latency', 'roll-centre'),
                        help='which picture')
    parser.add_argument('paths', nargs='*', metavar='PATH',
                        help='[SCENE ...]; for latency: BENCH.csv; for roll-centre: '
                        '[VEHICLE [AXLE]]')
    parser.add_argument('-o', '--output', metavar='OUT.png',
                        help='the picture to write (PNG, or another format by its suffix)')
    args = parser.parse_intermixed_args(argv)   # SCENE ... after -o OUT.png too
    if args.output is None:
        parser.error('-o/--output OUT.png is required')
    # the pictures read their paths with the output among them: latency's last, others' first
    args.paths = (args.paths + [args.output] if args.what == 'latency'
                  else [args.output] + args.paths)
    return args


@program('linkage-plot')
def main(argv: list[str] | None = None) -> int:
    """Write the picture named on the command line: 0 written, 1 drawn in part, 2 a mistake."""
    args = parse_args(argv)
    prog = 'linkage-plot'
    scenes = []
    if args.what == 'roll-centre':
        from .axle_plot import main as roll_centre
        return roll_centre(args.paths)
    if args.what == 'latency':
        if len(args.paths) != 2:
            return fail(prog, 'latency: expected BENCH.csv -o OUT.png')
        source, out = args.paths
        try:
            ladder = read_ladder(source)
        except (OSError, KeyError, ValueError) as exc:
            return fail(prog, f'{source}: not the output of linkage-bench node ({exc})')
        if not ladder:
            return fail(prog, f'{source}: no rate table (run linkage-bench node with latency)')
    else:
        out, names = args.paths[0], args.paths[1:] or DEFAULT_SCENES
        try:
            scenes = [load_scene(n) for n in names]
        except SceneError as exc:
            return fail(prog, exc)
        for scene in scenes:
            warn(prog, scene.warnings)
    problem = plot_problem(out, [source] if args.what == 'latency' else
                           [s.source for s in scenes])
    if problem:
        return fail(prog, problem)
    results = []
    if args.what == 'latency':
        plot_latency(ladder, out)
    else:
        compile_if_cold(prog)
        results = swept(scenes)
        (plot_alignment if args.what == 'alignment' else plot_camber_toe)(scenes, out, results)
    print(f'{prog}: wrote {out}', file=sys.stderr)
    failed = [(s, r) for s, r in zip(scenes, results) if not r.success]
    for scene, result in failed:
        print(f'{prog}: {scene.name}: {result.message} (drawn: '
              f'{counted(len(result.travel), "position")})', file=sys.stderr)
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
