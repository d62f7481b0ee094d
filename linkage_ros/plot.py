"""Camber and toe against wheel travel for scenes, as a PNG (needs matplotlib: the plot extra).

    python -m linkage_ros.plot OUT.png [SCENE ...]   (default: five_link, double_wishbone, macpherson)
"""

import sys

import numpy as np

from .kinematics import sweep, travel_range
from .scene import load_scene


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
    for ax, what in ((ax_camber, 'camber_deg (+ = top outboard)'), (ax_toe, 'toe_deg (+ = toe-in)')):
        ax.set_xlabel('travel_mm (+ = bump)')
        ax.set_ylabel(what)
        ax.grid(True, alpha=0.3)
    ax_camber.plot([], [], 'k.', label='reference (refdata)')
    ax_camber.legend(fontsize=8)
    fig.suptitle('linkage_ros: bundled scenes, left wheel')
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv:
        print(__doc__, file=sys.stderr)
        return 2
    names = argv[1:] or ['five_link', 'double_wishbone', 'macpherson']
    plot_camber_toe([load_scene(n) for n in names], argv[0])
    print(f'wrote {argv[0]}', file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
