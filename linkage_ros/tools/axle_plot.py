# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-plot roll-centre: an axle in the front view beside its roll centre's migration.

    linkage-plot roll-centre OUT.png [VEHICLE [AXLE]]    (default: demo_vehicle front)

Left: the axle at design seen from the front (links, wheels, ground), the lines through the
contact patches square to their velocities meeting at the roll centre. Right: the roll
centre's height above the ground against heave and roll, its lateral position against roll
(in heave a symmetric axle keeps it on the centreline), and its path relative to the body.
Needs matplotlib (the plot extra). A heave or roll that takes a wheel out of reach ends that
curve there: the picture is written, the line says where (status 1).
"""

import sys

import numpy as np

from ..cli import fail, plot_problem, warn
from ..core.axle import axle_of, solve_axle
from ..core.measure import patch_offset
from ..core.model import link_polylines, load_target, SceneError
from ..core.warmup import compile_if_cold
from ..outputs import save_figure

PROG = 'linkage-plot'
ROLL_DEG = 4.0       # the roll sweep, +-
HEAVE_SHARE = 0.75   # of the left corner's travel block


def migration(axle):
    """Return (heave result, roll result) of the axle: heave over its travel, roll +-4 deg."""
    low, high, _ = axle.left.travel
    heave = np.linspace(HEAVE_SHARE * low, HEAVE_SHARE * high, 61)
    roll = np.radians(np.linspace(-ROLL_DEG, ROLL_DEG, 41))
    return solve_axle(axle, heave), solve_axle(axle, 0.0, roll)


def draw_front_view(ax, axle, design):
    """Draw the axle at design in the y-z plane (mm): links, wheels, ground, patch lines."""
    for k, scene in enumerate(axle.scenes):
        joints = np.array([c.carrier for c in scene.constraints])
        for line in link_polylines(scene, joints):
            ax.plot(line[:, 1], line[:, 2], '-', color='0.35', lw=1.2)
            ax.plot(line[::len(line) - 1, 1], line[::len(line) - 1, 2], 's', color='0.35',
                    ms=3)
        ax.plot(joints[:, 1], joints[:, 2], 'o', color='0.15', ms=3.5)
        draw_wheel(ax, scene)
        patch = design.contact_patch[0, k]
        ax.plot([patch[1], design.roll_centre[0, 0]], [patch[2], design.roll_centre[0, 1]],
                '--', color='C3', lw=0.9)
        ax.plot(patch[1], patch[2], 'v', color='C3', ms=6)
    patches = design.contact_patch[0]
    span = np.array([patches[1, 1], patches[0, 1]]) * 1.25
    ax.plot(span, [patches[0, 2]] * 2, '-', color='0.5', lw=2)   # the ground at design
    ax.plot(*design.roll_centre[0], 'o', color='C3', ms=8, label='roll centre at design')


def draw_wheel(ax, scene):
    """Draw a wheel at design as seen from the front: a rectangle radius x 0.6 radius."""
    radius = scene.wheel_radius
    axis = scene.wheel_center - scene.spin_axis_point
    axis = axis / np.linalg.norm(axis)
    up = -np.array(patch_offset(*axis, 1.0))   # unit, square to the axis: the patch's way
    corners = [scene.wheel_center + a * radius * up + b * 0.3 * radius * axis
               for a, b in ((1, 1), (1, -1), (-1, -1), (-1, 1), (1, 1))]
    corners = np.array(corners)
    ax.fill(corners[:, 1], corners[:, 2], color='0.85', zorder=0)
    ax.plot(corners[:, 1], corners[:, 2], '-', color='k', lw=1.5)


def plot_roll_centre(axle, title, path):
    """
    Write the roll-centre picture of an axle (see the module docstring) to path.

    Returns the messages of the solves that ended early (AxleResult.message), [] if none.
    """
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    heave, roll = migration(axle)
    design = solve_axle(axle, 0.0)
    fig = plt.figure(figsize=(15, 7))
    grid = fig.add_gridspec(2, 3, width_ratios=[2.2, 1, 1])
    front = fig.add_subplot(grid[:, 0])
    draw_front_view(front, axle, design)
    front.set_aspect('equal')
    front.set_xlabel('y, mm (vehicle frame; seen from the front, + = left is on the right)')
    front.set_ylabel('z, mm')
    front.legend(fontsize=8, loc='lower center', bbox_to_anchor=(0.5, 1.0))
    front.set_title('front view at design: the lines through the contact patches, square to '
                    'their\nvelocities under travel, meet at the roll centre\n\n', fontsize=10)
    body = fig.add_subplot(grid[1, 1])
    body.plot(heave.roll_centre[:, 0], heave.roll_centre[:, 1], '.-', color='C0', ms=3,
              label=f'heave {HEAVE_SHARE * axle.left.travel[0]:g} to '
                    f'{HEAVE_SHARE * axle.left.travel[1]:+g} mm')
    body.plot(roll.roll_centre[:, 0], roll.roll_centre[:, 1], '.-', color='C1', ms=3,
              label=f'roll -{ROLL_DEG:g} to +{ROLL_DEG:g} deg')
    body.plot(*design.roll_centre[0], 'o', color='C3', ms=7)
    body.set_xlabel('roll centre y, mm (vehicle frame)', fontsize=9)
    body.set_ylabel('roll centre z, mm (vehicle frame)', fontsize=9)
    body.set_title('its path relative to the body', fontsize=9)
    body.legend(fontsize=8)
    body.grid(True, alpha=0.3)
    panels = [(grid[0, 1], heave.heave, heave.roll_centre_height, 'heave_mm (+ = bump)',
               'roll_centre_height_mm', 'C0'),
              (grid[0, 2], np.degrees(roll.roll), roll.roll_centre_height,
               'roll_deg (+ = right side down)', 'roll_centre_height_mm', 'C1'),
              (grid[1, 2], np.degrees(roll.roll), roll.roll_centre[:, 0],
               'roll_deg (+ = right side down)', 'roll_centre_y_mm', 'C1')]
    for cell, x, y, xlabel, ylabel, color in panels:
        ax = fig.add_subplot(cell)
        ax.plot(x, y, '-', color=color)
        ax.set_xlabel(xlabel, fontsize=9)
        ax.set_ylabel(ylabel, fontsize=9)
        ax.grid(True, alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    save_figure(fig, path, dpi=100)
    plt.close(fig)
    return [r.message for r in (design, heave, roll) if not r.success]


def main(paths):
    """Write the picture of `linkage-plot roll-centre OUT.png [VEHICLE [AXLE]]`: 0, 1 or 2."""
    if not 1 <= len(paths) <= 3:
        return fail(PROG, 'roll-centre: expected OUT.png [VEHICLE [AXLE]]')
    out, vehicle_name, axle_name = (list(paths) + ['demo_vehicle', 'front'])[:3]
    try:
        target = load_target(vehicle_name, 'vehicle')
        vehicle = target.vehicle
        axle = axle_of(vehicle, axle_name)
    except SceneError as exc:
        return fail(PROG, exc)
    warn(PROG, vehicle.warnings)
    if not axle.has_patches:
        return fail(PROG, f'{vehicle.name} {axle_name} axle: roll-centre needs wheel_radius in '
                          'both scenes (the contact patches)')
    problem = plot_problem(out, target.files)
    if problem:
        return fail(PROG, problem)
    compile_if_cold(PROG)
    failed = plot_roll_centre(axle, f'linkage_ros: {vehicle.name}, {axle_name} axle '
                              f'({axle.left.name} / {axle.right.name}): roll centre', out)
    print(f'{PROG}: wrote {out}', file=sys.stderr)
    for message in failed:
        print(f'{PROG}: {message}', file=sys.stderr)
    return 1 if failed else 0
