# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-vehicle --plot: the setup sheet in pictures (needs matplotlib, the plot extra).

Eight panels: the side view with the roll axis, the centre of gravity and the roll moment arm;
the ride frequencies; the lateral load transfer split by path; motion ratio and wheel rate
against heave; the anti quantities against heave; roll stiffness against roll (exact and the
textbook 0.5 k t^2); Ackermann against steer; the steering ratio against the rack.
"""

import numpy as np

from ..outputs import save_figure

AXLES = ('front', 'rear')
COLOURS = {'front': 'C0', 'rear': 'C1'}


def plot_sheet(sheet, path):
    """Write the pictures of a SetupSheet (core/vehicle/sheet.py) to path (PNG)."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(18, 15))
    grid = fig.add_gridspec(3, 3)
    side_view(fig.add_subplot(grid[0, :2]), sheet)
    panels = (ride_frequencies, load_transfer, motion_ratio, anti, roll_stiffness, ackermann,
              steering_ratio)
    cells = [grid[0, 2]] + [grid[r, c] for r in (1, 2) for c in range(3)]
    for draw, cell in zip(panels, cells):
        draw(fig.add_subplot(cell), sheet)
    fig.suptitle(f'linkage_ros: {sheet.name}, setup sheet')
    fig.tight_layout()
    save_figure(fig, path, dpi=90)
    plt.close(fig)


def side_view(ax, sheet):
    """Draw the side view: wheels, ground, roll centres, roll axis, cg and moment arm (mm)."""
    from matplotlib.patches import Circle

    vehicle = sheet.rows['vehicle']
    for name in AXLES:
        s = sheet.axles[name]
        x, radius = s.row['axle_x_mm'], s.axle.left.wheel_radius
        centre_z = radius
        ax.add_patch(Circle((x, centre_z), radius, fill=False, color='0.4', lw=1.5))
        ax.plot(x, s.row['roll_centre_height_mm'], 'o', color=COLOURS[name], ms=7,
                label=f"{name} roll centre, {s.row['roll_centre_height_mm']:.0f} mm")
    xs = [sheet.axles[n].row['axle_x_mm'] for n in AXLES]
    zs = [sheet.axles[n].row['roll_centre_height_mm'] for n in AXLES]
    span = np.array([xs[1] - 600.0, xs[0] + 600.0])
    slope = (zs[0] - zs[1]) / (xs[0] - xs[1])
    ax.plot(span, zs[1] + slope * (span - xs[1]), '--', color='C3', label='roll axis')
    ax.plot(span, [0.0, 0.0], '-', color='0.5', lw=2)
    cg_x, cg_z = vehicle['cg_x_mm'], vehicle['cg_height_mm']
    ax.plot(cg_x, cg_z, 'X', color='k', ms=11, label=f'sprung cg, {cg_z:.0f} mm')
    axis_z = vehicle['roll_axis_height_at_cg_mm']
    ax.annotate('', xy=(cg_x, axis_z), xytext=(cg_x, cg_z),
                arrowprops={'arrowstyle': '<->', 'color': 'C2', 'lw': 1.5})
    ax.text(cg_x + 80, 0.5 * (cg_z + axis_z),
            f"roll moment arm\n{vehicle['roll_moment_arm_mm']:.0f} mm", color='C2', fontsize=9)
    ax.set_aspect('equal')
    ax.set_ylim(-100, max(cg_z, 2 * max(sheet.axles[n].axle.left.wheel_radius
                                        for n in AXLES)) + 350)
    ax.set_xlabel('x, mm (vehicle frame, + = forward: front on the right)')
    ax.set_ylabel('height above the ground, mm')
    ax.set_title(f"side view: roll gradient {vehicle['roll_gradient_deg_per_g']:.2f} deg/g",
                 fontsize=10)
    ax.legend(fontsize=8, loc='upper center', ncol=4)


def ride_frequencies(ax, sheet):
    """Draw each axle's ride frequency (Hz) as a bar, its ride and wheel rates written on it."""
    for k, name in enumerate(AXLES):
        row = sheet.axles[name].row
        ax.bar(k, row['ride_frequency_Hz'], color=COLOURS[name], width=0.6)
        ax.text(k, row['ride_frequency_Hz'] * 0.5,
                f"{row['ride_frequency_Hz']:.2f} Hz\nride {row['ride_rate_N_per_mm']:.1f} N/mm"
                f"\nwheel {row['wheel_rate_N_per_mm']:.1f} N/mm", ha='center', fontsize=9,
                color='w')
    ax.set_xticks([0, 1], AXLES)
    ax.set_ylabel('ride_frequency_Hz')
    ax.set_title('ride frequency per axle', fontsize=10)
    ax.grid(True, axis='y', alpha=0.3)


def load_transfer(ax, sheet):
    """Draw each axle's lateral load transfer at 1 g, stacked by path (N)."""
    paths = (('geometric', 'sprung, through the roll centre'),
             ('elastic', 'through the roll stiffness'), ('unsprung', 'unsprung masses'))
    for k, name in enumerate(AXLES):
        row, bottom = sheet.axles[name].row, 0.0
        for j, (path, label) in enumerate(paths):
            value = row[f'load_transfer_{path}_N']
            ax.bar(k, value, bottom=bottom, color=f'C{j + 4}', width=0.6,
                   label=label if k == 0 else None)
            bottom += value
        ax.text(k, bottom, f'{bottom:.0f} N', ha='center', va='bottom', fontsize=9)
    ax.set_xticks([0, 1], AXLES)
    ax.set_ylabel('lateral load transfer at 1 g, N')
    ax.set_title('load transfer: front share (LLTD) '
                 f"{sheet.rows['vehicle']['lltd_front_pct']:.1f} %", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(True, axis='y', alpha=0.3)


def motion_ratio(ax, sheet):
    """Draw each axle's spring motion ratio and wheel rate against heave (left corner)."""
    rate = ax.twinx()
    for name in AXLES:
        table = sheet.axles[name].tables['heave']
        for column in table:
            if column.endswith('_ratio'):
                ax.plot(table['heave_mm'], -table[column], '-', color=COLOURS[name],
                        label=f'{name} {column[:-6]}: motion ratio -dL/dz')
        rate.plot(table['heave_mm'], table['wheel_rate_N_per_mm'], '--', color=COLOURS[name],
                  label=f'{name} wheel rate')
    ax.set_xlabel('heave_mm (+ = bump)')
    ax.set_ylabel('motion ratio (solid)')
    rate.set_ylabel('wheel_rate_N_per_mm (dashed)')
    ax.set_title('motion ratio and wheel rate against travel', fontsize=10)
    lines = ax.get_legend_handles_labels()
    more = rate.get_legend_handles_labels()
    ax.legend(lines[0] + more[0], lines[1] + more[1], fontsize=8)
    ax.grid(True, alpha=0.3)


def anti(ax, sheet):
    """Draw the anti-dive, -lift and -squat (%) of each axle against heave."""
    styles = {'anti_dive_pct': '-', 'anti_lift_pct': '--', 'anti_squat_pct': ':'}
    for name in AXLES:
        table = sheet.axles[name].tables['heave']
        for column, style in styles.items():
            if column in table:
                ax.plot(table['heave_mm'], table[column], style, color=COLOURS[name],
                        label=f'{name} {column[:-4].replace("_", "-")}')
    ax.axhline(0.0, color='0.5', lw=0.8)
    _finish(ax, 'heave_mm (+ = bump)', '%', 'anti-dive, anti-lift and anti-squat against travel')


def roll_stiffness(ax, sheet):
    """Draw each axle's roll stiffness against roll: exact (springs + bar) and textbook."""
    for name in AXLES:
        s = sheet.axles[name]
        table = s.tables['roll']
        ax.plot(table['roll_deg'], table['roll_stiffness_Nm_per_deg'], '-',
                color=COLOURS[name], label=f'{name}: exact d2V/dphi2')
        ax.plot(table['roll_deg'], table['roll_stiffness_springs_Nm_per_deg'], ':',
                color=COLOURS[name], label=f'{name}: springs only')
        ax.axhline(s.row['roll_stiffness_textbook_Nm_per_deg'], ls='--', color=COLOURS[name],
                   lw=0.8, label=f'{name}: textbook 0.5 k MR^2 t^2 (+ bar)')
    ax.set_ylim(bottom=0.0)
    _finish(ax, 'roll_deg (+ = right side down)', 'roll_stiffness_Nm_per_deg',
            'roll stiffness against roll')


def ackermann(ax, sheet):
    """Draw Ackermann (%) against the mean steer of each steered axle."""
    _rack_panel(ax, sheet, 'mean_steer_deg', 'ackermann_pct', '.-',
                'ackermann_pct (100 = Ackermann, 0 = parallel)',
                'Ackermann against steer (none below 1 deg)', ms=3)


def steering_ratio(ax, sheet):
    """Draw the steering ratio (deg of mean steer per mm of rack) against the rack."""
    _rack_panel(ax, sheet, 'rack_mm', 'steering_ratio_deg_per_mm', '-',
                'steering_ratio_deg_per_mm', 'steering ratio against rack travel')


def _rack_panel(ax, sheet, x, y, style, ylabel, title, **line):
    """Draw column y against column x of each steered axle's rack table (x + = to the left)."""
    for name in AXLES:
        table = sheet.axles[name].tables.get('rack')
        if table is not None:
            ax.plot(table[x], table[y], style, color=COLOURS[name], label=f'{name} axle', **line)
    _finish(ax, f'{x} (+ = to the left)', ylabel, title)


def _finish(ax, xlabel, ylabel, title):
    """Label a panel's axes, title it, and give it a legend and a light grid."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
