"""
The pictures of linkage-kc --plot (needs matplotlib: the plot extra).

plot_rates: the compliance rates against travel, one panel per unit (toe and camber apart).
plot_loaded: the loaded mechanism in the front (y-z) and side (x-z) views, the unloaded pose
at the same travel behind it in grey, and the force of each pickup on the body drawn as an
arrow to one scale (mm of paper per kN), the load on the wheel and the holding force beside.
"""

import numpy as np

from ..cli import save_figure
from ..core.measure import quantity
from ..core.model import link_polylines
from ..core.solve import compile_scene, sweep

# The panels of plot_rates: (title, test on a rate's name, its unit in the registry's
# spelling); a rate goes to the first panel it fits.
PANELS = (('toe per force', lambda n: n.startswith('toe_') and n.endswith('_kn')),
          ('camber per force', lambda n: n.startswith('camber_') and n.endswith('_kn')),
          ('toe and camber per moment', lambda n: n.endswith('_knm')),
          ('displacement per force', lambda n: n.endswith('_mm_per_kn')),
          ('force per force', lambda n: True))
VIEWS = (('front view (seen from ahead: + y, left, to the right)', 1),
         ('side view (seen from the left: + x, forward, to the right)', 0))
ARROW_MM = 150.0   # the longest arrow, mm of the drawing


def _pyplot():
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    return plt


def _unit(name):
    """Return a rate's unit as its name ends ('deg_per_kn' -> 'deg/kN'), for axis labels."""
    try:
        return quantity(name).unit
    except KeyError:
        return name.rsplit('_per_', 1)[-1]


def plot_rates(scene, header, rows, path):
    """
    Write the rates of a linkage-kc table (header, rows: (n, columns)) against travel to path.

    With a rack range, one line per rack (the legend names it).
    """
    plt = _pyplot()
    rows = np.asarray(rows, float)
    lead = 2 if len(header) > 1 and header[1] == 'rack_mm' else 1
    names = header[lead:]
    panels = [(title, [n for n in names if next(t for t, f in PANELS if f(n)) == title])
              for title, _ in PANELS]
    panels = [(title, chosen) for title, chosen in panels if chosen]
    racks = np.unique(rows[:, 1]) if lead == 2 else [None]
    columns = min(3, len(panels))
    lines = -(-len(panels) // columns)
    fig, axes = plt.subplots(lines, columns, figsize=(5.2 * columns, 3.8 * lines),
                             squeeze=False)
    for ax, (title, chosen) in zip(axes.flat, panels):
        for k, name in enumerate(chosen):
            for j, rack in enumerate(racks):
                mine = rows if rack is None else rows[rows[:, 1] == rack]
                label = name if rack is None else f'{name}, rack {rack:g} mm'
                ax.plot(mine[:, 0], mine[:, lead + names.index(name)],
                        '.-' if len(mine) > 1 else 'o', color=f'C{k}',
                        alpha=1.0 - 0.6 * j / max(1, len(racks) - 1), label=label)
        ax.axhline(0.0, color='0.6', lw=0.8)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel('travel_mm (+ = bump)', fontsize=9)
        ax.set_ylabel(_unit(chosen[0]), fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis('off')
    fig.suptitle(f'linkage_ros: {scene.name}: compliance at the held travel (toe + = toe-in, '
                 'camber + = top outboard, vehicle frame)', fontsize=11)
    fig.tight_layout()
    save_figure(fig, path, dpi=100)
    plt.close(fig)


def pickups(result):
    """
    Return (name, point mm (3,), force on the body N (3,)) of each pickup of a Loaded.

    An arm's pivots carry pivot_forces_n; a link, a two-force member, pushes on the body with
    the opposite of its force on the carrier (ball_joint_forces_n).
    """
    points = result.body_points_mm
    found = [(key, points[key], np.asarray(force, float))
             for key, force in result.pivot_forces_n.items() if key in points]
    found += [(name, points[name], -np.asarray(result.ball_joint_forces_n[name], float))
              for name in result.link_forces_n
              if name in points and name in result.ball_joint_forces_n]
    return found


def plot_loaded(scene, result, load, path):
    """Write the loaded mechanism of a Loaded (one position) in front and side views to path."""
    plt = _pyplot()
    mech = compile_scene(scene)
    joints = result.wheel_center_mm + mech.offsets @ np.asarray(result.rotation).T
    free = sweep(scene, [result.travel_mm], rack=getattr(result, 'rack_mm', 0.0))
    found = pickups(result)
    wheel = np.asarray(result.wheel_center_mm, float)
    at = wheel if load.at == 'wc' else getattr(result, 'load_point_mm', wheel)
    arrows = [(name, p, f, 'C3') for name, p, f in found]
    arrows.append(('load', np.asarray(at, float), np.asarray(load.force_n, float), 'C0'))
    arrows.append(('holding', wheel, np.array([0.0, 0.0, result.holding_force_n]), 'C2'))
    largest = max([np.linalg.norm(f) for _, _, f, _ in arrows] + [1e-9])
    scale = ARROW_MM / largest   # mm of drawing per N
    fig, axes = plt.subplots(1, 2, figsize=(15, 7.5))
    for ax, (title, across) in zip(axes, VIEWS):
        if free.success:
            for line in link_polylines(scene, free.joints[0]):
                ax.plot(line[:, across], line[:, 2], '-', color='0.8', lw=3, zorder=1)
        for line in link_polylines(scene, joints):
            ax.plot(line[:, across], line[:, 2], '-', color='0.25', lw=1.3, zorder=2)
        ax.plot(joints[:, across], joints[:, 2], 'o', color='0.1', ms=4, zorder=3)
        ax.plot(wheel[across], wheel[2], 'P', color='k', ms=9, zorder=3)
        for name, point, force, color in arrows:
            if np.linalg.norm(force[[across, 2]]) * scale < 1.0:
                continue   # less than a millimetre of drawing: a dot would say nothing
            ax.annotate('', xy=(point[across] + scale * force[across],
                                point[2] + scale * force[2]),
                        xytext=(point[across], point[2]),
                        arrowprops={'arrowstyle': '-|>', 'color': color, 'lw': 1.8}, zorder=4)
            ax.text(point[across] + scale * force[across], point[2] + scale * force[2],
                    f' {name} {np.linalg.norm(force):.0f} N', fontsize=7, color=color)
        ax.set_aspect('equal')
        ax.set_title(title, fontsize=10)
        ax.set_xlabel('y, mm' if across == 1 else 'x, mm')
        ax.set_ylabel('z, mm')
        ax.grid(True, alpha=0.3)
        ax.update_datalim(np.array([[p[across] + scale * f[across], p[2] + scale * f[2]]
                                    for _, p, f, _ in arrows]))
        ax.autoscale_view()
    axes[0].plot([], [], '-', color='0.8', lw=3, label='unloaded at this travel')
    axes[0].plot([], [], '-', color='0.25', lw=1.3, label='loaded')
    for label, color in (('force of each pickup on the body', 'C3'), ('load on the wheel', 'C0'),
                         ('holding force (the travel held)', 'C2')):
        axes[0].plot([], [], '-', color=color, lw=2, label=label)
    axes[0].legend(fontsize=8, loc='upper left')
    force = ', '.join(f'{v:g}' for v in load.force_n)
    moment = ', '.join(f'{v:g}' for v in load.moment_nm)
    fig.suptitle(f'linkage_ros: {scene.name} at travel {result.travel_mm:g} mm, loaded by '
                 f'F ({force}) N at {load.at} and M ({moment}) N m: camber '
                 f'{result.camber_deg:+.3f} deg, toe {result.toe_deg:+.3f} deg\n'
                 f'arrows to scale: 1 kN = {1e3 * scale:.3g} mm of the drawing', fontsize=11)
    fig.tight_layout()
    save_figure(fig, path, dpi=100)
    plt.close(fig)
