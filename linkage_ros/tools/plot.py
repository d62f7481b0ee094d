"""
Camber and toe against wheel travel for scenes, as a PNG (needs matplotlib: the plot extra).

    python -m linkage_ros.tools.plot OUT.png [--alignment] [SCENE ...]
    (default scenes: five_link, double_wishbone, macpherson; --alignment: the alignment set)
"""

import sys

import numpy as np

from ..core.kinematics import sweep, travel_range
from ..core.scene import load_scene


def plot_camber_toe(scenes, path):
    """Write a two-panel PNG (camber, toe in deg against travel in mm) of the given scenes."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    fig, (ax_camber, ax_toe) = plt.subplots(1, 2, figsize=(10, 4), sharex=True)
    for scene in scenes:
        low, high, step = scene.travel
        result = sweep(scene, travel_range(low, high, step))
        ax_camber.plot(result.travel, np.degrees(result.camber), label=scene.name)
        ax_toe.plot(result.travel, np.degrees(result.toe), label=scene.name)
        reference = scene.extras.get('reference')
        if reference:
            rows = np.array(reference['rows'], dtype=float)
            ax_camber.plot(rows[:, 0], rows[:, 1], 'k.', ms=5)
            ax_toe.plot(rows[:, 0], rows[:, 2], 'k.', ms=5)
    for ax, what in ((ax_camber, 'camber_deg (+ = top outboard)'),
                     (ax_toe, 'toe_deg (+ = toe-in)')):
        ax.set_xlabel('travel_mm (+ = bump)')
        ax.set_ylabel(what)
        ax.grid(True, alpha=0.3)
    ax_camber.plot([], [], 'k.', label='reference (refdata)')
    ax_camber.legend(fontsize=8)
    fig.suptitle('linkage_ros: bundled scenes, left wheel')
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


ALIGNMENT_PANELS = [
    ('camber_gain', 'camber gain, deg/mm', True), ('bump_steer', 'bump steer, deg/mm', True),
    ('caster', 'caster, deg', True), ('kingpin_inclination', 'kingpin inclination, deg', True),
    ('scrub_radius', 'scrub radius, mm', False),
    ('mechanical_trail', 'mechanical trail, mm', False),
    ('track_change', 'track change, mm', False),
    ('lateral_shift', 'wheel-centre lateral shift, mm', False)]


def plot_alignment(scenes, path):
    """Write a PNG of the alignment set against travel (mm) for the given scenes."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    from ..core.alignment import alignment
    from ..core.mechanism import compile_scene

    fig, axes = plt.subplots(2, 4, figsize=(16, 7), sharex=True)
    for scene in scenes:
        low, high, step = scene.travel
        result = sweep(scene, travel_range(low, high, step))
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
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    """Write the plot named on the command line: 0 when written, 2 without arguments."""
    argv = sys.argv[1:] if argv is None else argv
    if not argv:
        # the usage: the docstring without its first newline
        print(__doc__.lstrip('\n'), file=sys.stderr)
        return 2
    names = ([n for n in argv[1:] if n != '--alignment']
             or ['five_link', 'double_wishbone', 'macpherson'])
    scenes = [load_scene(n) for n in names]
    if '--alignment' in argv:
        plot_alignment(scenes, argv[0])
    else:
        plot_camber_toe(scenes, argv[0])
    print(f'wrote {argv[0]}', file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
