# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The pictures of linkage-kc --plot (needs matplotlib: the plot extra).

plot_rates: the compliance rates against travel, one panel per unit (toe and camber apart).
plot_loaded: the loaded mechanism in the front (y-z) and side (x-z) views, the unloaded pose
at the same travel behind it in grey, and the force of each pickup on the body drawn as an
arrow to one scale (mm of paper per kN), the load on the wheel and the holding force beside.
"""

import numpy as np

from .plot_labels import Labels
from ..core.measure import contact_patch
from ..core.model import link_polylines
from ..core.solve import compile_scene, sweep
from ..outputs import save_figure

# The panels of plot_rates: (title, unit, test on a rate's name); a rate goes to the first
# panel it fits (the names end in their unit: doc/kc.md).
PANELS = (('toe per force', 'deg/kN', lambda n: n.startswith('toe_') and n.endswith('_kN')),
          ('camber per force', 'deg/kN',
           lambda n: n.startswith('camber_') and n.endswith('_kN')),
          ('toe and camber per moment', 'deg/(kN m)', lambda n: n.endswith('_kNm')),
          ('displacement per force', 'mm/kN', lambda n: n.endswith('_mm_per_kN')),
          ('force per force', 'N/N', lambda n: True))
VIEWS = (('front view (seen from ahead: + y, left, to the right)', 1),
         ('side view (seen from the left: + x, forward, to the right)', 0))
ARROW_MM = 150.0   # the longest arrow, mm of the drawing
DPI = 100          # of the written pictures


def _pyplot():
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    return plt


def plot_rates(scene, header, rows, path):
    """
    Write the rates of a linkage-kc table (header, rows: (n, columns)) against travel to path.

    With a rack range, one line per rack (the legend names it).
    """
    plt = _pyplot()
    fig = rates_figure(scene, header, rows)
    save_figure(fig, path, dpi=DPI)
    plt.close(fig)


def rates_figure(scene, header, rows):
    """Return the figure of plot_rates, laid out: each panel's legend under it."""
    plt = _pyplot()
    rows = np.asarray(rows, float)
    lead = 2 if len(header) > 1 and header[1] == 'rack_mm' else 1
    names = header[lead:]
    panels = [(title, unit, [n for n in names if next(t for t, _, f in PANELS if f(n)) == title])
              for title, unit, _ in PANELS]
    panels = [panel for panel in panels if panel[2]]
    racks = np.unique(rows[:, 1]) if lead == 2 else [None]
    columns = min(3, len(panels))
    lines = -(-len(panels) // columns)
    fig, axes = plt.subplots(lines, columns, figsize=(5.2 * columns, 4.6 * lines),
                             squeeze=False)
    for ax, (title, unit, chosen) in zip(axes.flat, panels):
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
        ax.set_ylabel(unit, fontsize=9)
        ax.grid(True, alpha=0.3)
        # under the panel: inside, 'best' still covered a line where they cross the plot
        ax.legend(fontsize=7, loc='upper center', bbox_to_anchor=(0.5, -0.16),
                  frameon=False)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis('off')
    fig.suptitle(f'linkage_ros: {scene.name}: compliance at the held travel (toe + = toe-in, '
                 'camber + = top outboard, vehicle frame)', fontsize=11)
    fig.tight_layout()
    fig.set_dpi(DPI)
    return fig


def pickups(result):
    """
    Return (name, point mm (3,), force on the body N (3,)) of each pickup of a Loaded.

    The pickups are where the body carries the linkage: arm pivots, link bases, spring body
    ends, strut tops (Loaded.body_forces_n at Loaded.body_points_mm).
    """
    return [(key, np.asarray(result.body_points_mm[key], float), np.asarray(force, float))
            for key, force in result.body_forces_n.items()]


def named_in(name, force):
    """
    Return the view (1 front, 0 side: the axis across it) that names a pickup's arrow.

    An arm's two pivots lie on one axis, nearly one behind the other from the front: they are
    named in the side view; any other pickup where its arrow is the longer.
    """
    if name.endswith(('_axis0', '_axis1')):
        return 0
    return 1 if np.linalg.norm(force[[1, 2]]) >= np.linalg.norm(force[[0, 2]]) else 0


def wheel_outline(scene, center, rotation):
    """
    Return the wheel's two side circles (2, k, 3) mm in a pose (center (3,), rotation (3, 3)).

    Radius scene.wheel_radius, 0.6 radius apart along the spin axis: a rectangle seen from
    the front, a circle seen from the side.
    """
    axis = rotation @ unit(scene.wheel_center - scene.spin_axis_point)
    across = unit(np.cross(axis, [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 0.0, 1.0]))
    along = np.cross(axis, across)
    turn = np.linspace(0.0, 2.0 * np.pi, 73)[:, None]
    ring = scene.wheel_radius * (np.cos(turn) * across + np.sin(turn) * along)
    return np.stack([center + ring + side * 0.3 * scene.wheel_radius * axis
                     for side in (-1.0, 1.0)])


def unit(vector):
    """Return vector / |vector|."""
    vector = np.asarray(vector, float)
    return vector / np.linalg.norm(vector)


def load_point(scene, result, free, at):
    """
    Return where the load acts in the loaded pose (3,) mm: the wheel centre, or the patch.

    The contact patch is the unloaded pose's lowest wheel point at this travel, carried with
    the carrier into the loaded pose (doc/kc.md, The model).
    """
    wheel = np.asarray(result.wheel_center_mm, float)
    if getattr(result, 'load_point_mm', None) is not None:
        return np.asarray(result.load_point_mm, float)
    if at == 'wc' or not free.success:
        return wheel
    axis = unit(free.rotation[0] @ unit(scene.wheel_center - scene.spin_axis_point))
    patch = contact_patch(free.wheel_center[:1], axis[None, :], scene.wheel_radius)[0]
    return wheel + np.asarray(result.rotation) @ free.rotation[0].T @ (
        patch - free.wheel_center[0])


def plot_loaded(scene, result, load, path):
    """Write the loaded mechanism of a Loaded (one position) in front and side views to path."""
    plt = _pyplot()
    fig = loaded_figure(scene, result, load)
    save_figure(fig, path, dpi=DPI)
    plt.close(fig)


def moment_lever_mm(scene):
    """
    Return the lever (mm) that draws a moment to the forces' scale: the wheel radius.

    A moment M is drawn as long as the force M / lever would be, the force at the contact
    patch that makes M about the wheel centre (300 mm for a scene without a wheel).
    """
    return scene.wheel_radius if scene.wheel_radius > 0 else 300.0


def loaded_figure(scene, result, load):
    """
    Return the figure of plot_loaded, drawn and its labels placed (plot_labels.Labels).

    Every arrow is named in each view, with its size: the force of each pickup on the body,
    the load on the wheel, the holding force and the load's moment (a double-headed arrow
    along its vector, right-hand rule, to the forces' scale at moment_lever_mm). An arrow
    whose projection on a view is under a millimetre of the drawing is not drawn there; its
    label is, at its point.
    """
    plt = _pyplot()
    mech = compile_scene(scene)
    rotation = np.asarray(result.rotation, float)
    wheel = np.asarray(result.wheel_center_mm, float)
    joints = wheel + mech.offsets @ rotation.T
    free = sweep(scene, [result.travel_mm], rack=getattr(result, 'rack_mm', 0.0))
    lever = moment_lever_mm(scene)
    at = load_point(scene, result, free, load.at)
    moment = np.asarray(load.moment_nm, float)
    # (label, point mm, vector drawn: N, or N m as the force at lever, color, heads)
    arrows = [(f'{name} {np.linalg.norm(f):.0f} N', p, f, 'C3', 1)
              for name, p, f in pickups(result)]
    arrows.append((f'load {np.linalg.norm(load.force_n):.0f} N', at,
                   np.asarray(load.force_n, float), 'C0', 1))
    if np.any(moment):
        arrows.append((f'moment {np.linalg.norm(moment):.0f} N m', at,
                       moment * 1e3 / lever, 'C4', 2))
    arrows.append((f'holding {abs(result.holding_force_n):.0f} N', wheel,
                   np.array([0.0, 0.0, result.holding_force_n]), 'C2', 1))
    largest = max([np.linalg.norm(f) for _, _, f, _, _ in arrows] + [1e-9])
    scale = ARROW_MM / largest   # mm of drawing per N
    fig, axes = plt.subplots(1, 2, figsize=(15, 7.8))
    placing = []
    for ax, (title, across) in zip(axes, VIEWS):
        labels = Labels(ax)
        placing.append(labels)
        if scene.wheel_radius > 0:
            rings = wheel_outline(scene, wheel, rotation)
            for ring in rings:
                ax.plot(ring[:, across], ring[:, 2], '-', color='0.55', lw=1.0, zorder=1)
            for k in (np.argmax(rings[0, :, 2]), np.argmin(rings[0, :, 2])):   # tread edges
                ax.plot(rings[:, k, across], rings[:, k, 2], '-', color='0.55', lw=1.0)
        if free.success:
            for line in link_polylines(scene, free.joints[0]):
                ax.plot(line[:, across], line[:, 2], '-', color='0.82', lw=4, zorder=1)
        for line in link_polylines(scene, joints):
            ax.plot(line[:, across], line[:, 2], '-', color='0.2', lw=1.4, zorder=2)
            labels.obstacle(line[:, [across, 2]])
        ax.plot(joints[:, across], joints[:, 2], 'o', color='0.1', ms=4, zorder=3)
        ax.plot(wheel[across], wheel[2], 'P', color='k', ms=9, zorder=3)
        ends = []
        for label, point, vector, color, heads in arrows:
            tip = point + scale * vector
            ends += [point[[across, 2]], tip[[across, 2]]]
            drawn = np.linalg.norm(vector[[across, 2]]) * scale >= 1.0
            if drawn:   # under a millimetre of drawing an arrow would be a dot: label alone
                _arrow(ax, point[[across, 2]], tip[[across, 2]], color, heads)
                labels.obstacle([point[[across, 2]], tip[[across, 2]]])
            away = vector[[across, 2]] if drawn else (1.0, 0.0)
            labels.add(label, tip[[across, 2]] if drawn else point[[across, 2]], away, color)
        ax.set_aspect('equal')
        ax.set_title(title, fontsize=10)
        ax.set_xlabel('y, mm' if across == 1 else 'x, mm')
        ax.set_ylabel('z, mm')
        ax.grid(True, alpha=0.3)
        ax.update_datalim(np.array(ends))
        ax.margins(0.12)       # room for the labels of the arrows at the edges
        ax.autoscale_view()
    kinds = (('unloaded at this travel', '0.82', 4), ('loaded', '0.2', 1.4),
             ('wheel', '0.55', 1), ('force of each pickup on the body', 'C3', 2),
             ('load on the wheel', 'C0', 2)) + \
        ((('its moment (double head)', 'C4', 2),) if np.any(moment) else ()) + \
        (('holding force (the travel held)', 'C2', 2),)
    handles = [plt.Line2D([], [], color=color, lw=width, label=label)
               for label, color, width in kinds]
    fig.legend(handles=handles, loc='lower center', ncol=len(kinds), fontsize=9,
               frameon=False)
    force = ', '.join(f'{v:g}' for v in load.force_n)
    moments = ', '.join(f'{v:g}' for v in load.moment_nm)
    drawn_to = (f'; a moment, right-hand rule: 1 kN m = {1e6 * scale / lever:.3g} mm (as the '
                f'force at {lever:g} mm)') if np.any(moment) else ''
    fig.suptitle(f'linkage_ros: {scene.name} at travel {result.travel_mm:g} mm, loaded by '
                 f'F ({force}) N at {load.at} and M ({moments}) N m: camber '
                 f'{result.camber_deg:+.3f} deg, toe {result.toe_deg:+.3f} deg\n'
                 f'arrows to scale: 1 kN = {1e3 * scale:.3g} mm of the drawing{drawn_to}',
                 fontsize=11)
    fig.tight_layout(rect=(0, 0.06, 1, 0.93))
    fig.set_dpi(DPI)
    fig.canvas.draw()      # the axes' final places: the labels are measured against them
    for labels in placing:
        labels.place()
    return fig


def _arrow(ax, start, tip, color, heads):
    """Draw an arrow from start to tip (2,); heads 2: a moment's double head at the tip."""
    style = {'arrowstyle': '-|>', 'color': color, 'lw': 1.8}
    ax.annotate('', xy=tuple(tip), xytext=tuple(start), arrowprops=style, zorder=4)
    if heads == 2:
        ax.annotate('', xy=tuple(start + 0.8 * (tip - start)), xytext=tuple(start),
                    arrowprops=style, zorder=4)
