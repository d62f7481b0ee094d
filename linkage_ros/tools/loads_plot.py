# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The picture of linkage-loads --plot (needs matplotlib: the plot extra).

Top: for each axle's left corner (the right one mirrors it) and the anti-roll bars, the force
on the body at every body pickup, one bar per case (what a bracket designer reads: which
case loads which bracket most). Bottom: the vehicle under the case that puts the largest
force on any pickup, in the front view (y-z) and the side view (x-z): each corner's members
from their body pickups to their carrier joints in the loaded pose, the wheels, the force
on the body at each pickup (red) and the ground's force on each tyre (blue) as arrows to one
scale (the title says how many mm of the drawing are a kN).
"""

import math

import numpy as np

from ..core.loads import tables
from ..outputs import save_figure

ARROW_MM = 400.0   # the longest arrow, mm of the drawing


def _pyplot():
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    return plt


def body_forces(answers, corner):
    """Return ([pickup], {case: [force N]}) of a corner's (or axle's) body-end pickups."""
    pickups, by_case = [], {}
    for answer in answers:
        rows = [r for r in tables.pickup_rows(answer) if r[1] == corner and r[3] == 'body']
        by_case[answer.case.name] = {r[2]: r[10] for r in rows}
        pickups += [r[2] for r in rows if r[2] not in pickups]
    return pickups, {c: [f.get(p, math.nan) for p in pickups] for c, f in by_case.items()}


def plot_bars(ax, answers, corner):
    """Draw a corner's body pickups as horizontal bars, one per case."""
    pickups, forces = body_forces(answers, corner)
    count = len(forces)
    height = 0.8 / max(1, count)
    y = np.arange(len(pickups))
    for k, (case, values) in enumerate(forces.items()):
        ax.barh(y + (k - (count - 1) / 2) * height, np.asarray(values) / 1000.0, height,
                label=case, color=f'C{k}')
    ax.set_yticks(y, pickups, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel('force on the body, kN (force_magnitude_N / 1000)', fontsize=9)
    ax.set_title(f'{corner}: force at each body pickup, by case', fontsize=10)
    ax.grid(True, axis='x', alpha=0.3)


def heaviest(answers):
    """Return the answer whose largest pickup force is the largest of all."""
    def largest(answer):
        return max((r[10] for r in tables.pickup_rows(answer)), default=0.0)
    return max(answers, key=largest)


def plot_view(ax, loads, answer, corners, axis, scale, title):
    """Draw corners of the vehicle under one case in one view (axis 1: y-z, 0: x-z)."""
    for name in corners:
        corner = answer.corners[name]
        if corner.loaded is None:
            continue
        pickups = tables.corner_pickups(corner)
        joints = {p[:-len('_carrier')]: point for p, end, point, _, _ in pickups
                  if end == 'carrier'}
        for pickup, end, point, force, _ in pickups:
            member = next((j for j in joints if pickup.startswith(f'{j}_')), None)
            if end != 'carrier' and member is not None:
                ax.plot([point[axis], joints[member][axis]], [point[2], joints[member][2]],
                        color='0.3', lw=1.2)
            if end == 'body':
                ax.annotate('', xy=(point[axis] + scale * force[axis],
                                    point[2] + scale * force[2]),
                            xytext=(point[axis], point[2]),
                            arrowprops={'arrowstyle': '->', 'color': 'C3', 'lw': 1.0})
        wheel(ax, corner, axis)
        patch, force = corner.pose.patch, corner.tyre.force_n
        ax.annotate('', xy=(patch[axis], patch[2]),
                    xytext=(patch[axis] - scale * force[axis], patch[2] - scale * force[2]),
                    arrowprops={'arrowstyle': '->', 'color': 'C0', 'lw': 1.6})
    ground = loads.data.ground_z_mm
    ax.axhline(ground, color='0.6', lw=0.8)
    ax.set_aspect('equal', adjustable='datalim')
    ax.set_title(title, fontsize=10)
    ax.set_xlabel('y, mm (+ = left)' if axis == 1 else 'x, mm (+ = forward)', fontsize=9)
    ax.set_ylabel('z, mm', fontsize=9)
    ax.grid(True, alpha=0.2)


def arrow_scale(answer):
    """Return mm of drawing per N: the largest force of a case drawn ARROW_MM long."""
    rows = tables.pickup_rows(answer)
    largest = max([r[10] for r in rows] + [float(np.linalg.norm(c.tyre.force_n))
                                           for c in answer.corners.values()])
    return ARROW_MM / largest


def wheel(ax, corner, axis):
    """Draw a wheel: its rim in the side view, its outline seen edge-on in the front view."""
    centre = corner.loaded.wheel_center_mm
    radius = float(np.linalg.norm(corner.pose.centre - corner.pose.patch))
    if axis == 0:
        angles = np.linspace(0.0, 2.0 * math.pi, 73)
        ax.plot(centre[0] + radius * np.cos(angles), centre[2] + radius * np.sin(angles),
                color='0.5', lw=0.8)
        return
    camber = math.radians(corner.loaded.camber_deg) * (1.0 if centre[1] > 0 else -1.0)
    up = np.array([math.sin(camber), math.cos(camber)]) * radius   # top outboard: + camber
    side = np.array([math.cos(camber), -math.sin(camber)]) * 100.0
    corners = [np.array([centre[1], centre[2]]) + a * up + b * side
               for a, b in ((1, 1), (1, -1), (-1, -1), (-1, 1), (1, 1))]
    ax.plot([c[0] for c in corners], [c[1] for c in corners], color='0.5', lw=0.8)


def plot_loads(loads, answers, path):
    """Write the picture of solved load cases to path (PNG)."""
    plt = _pyplot()
    axles = loads.data.axles
    bars = [name for name in axles if any(name in a.bars for a in answers)]
    top = [a.corners[0] for a in axles.values()] + bars
    fig = plt.figure(figsize=(16, 12))
    grid = fig.add_gridspec(2, len(top), height_ratios=[1.2, 1.0])
    for k, corner in enumerate(top):
        plot_bars(fig.add_subplot(grid[0, k]), answers, corner)
    handles, labels = fig.axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, title='case', fontsize=8, title_fontsize=8,
               loc='upper center', bbox_to_anchor=(0.5, 0.955), ncols=len(labels))
    answer = heaviest(answers)
    scale = arrow_scale(answer)
    bottom = fig.add_gridspec(2, 3, height_ratios=[1.2, 1.0]) if len(top) != 3 else grid
    front, rear = (list(a.corners) for a in axles.values())
    first = front[0]
    views = ((front, 1, 'front axle, seen from ahead (y-z)'),
             (rear, 1, 'rear axle, seen from ahead (y-z)'),
             ([first], 0, f'{first}, seen from the left (x-z)'))
    for k, (corners, axis, title) in enumerate(views):
        plot_view(fig.add_subplot(bottom[1, k]), loads, answer, corners, axis, scale, title)
    fig.suptitle(f'linkage_ros: {loads.vehicle.name}: the force on the body at each pickup, '
                 f'by case\nbelow, the {answer.case.name} case, the heaviest (red: the force '
                 f"on the body, blue: the ground's on the tyre; {scale * 1000.0:.3g} mm of "
                 'drawing per kN)', fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.92))
    save_figure(fig, path, dpi=90)
    plt.close(fig)
