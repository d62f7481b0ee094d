"""Cost of the node's optional outputs per corner: callback time with and without them.

    ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST python -m linkage_ros.extras_bench [--commands N]

For each scene and each set of extras (none, alignment, markers, both) a SuspensionNode is
made in a private Context (discovery off, no subscribers: the publish cost is serialisation
only), and its corner's travel callback is called directly on N travel commands (a +-50 mm
sine, 1 mm apart at most, so each is one continuation step). Prints the median and mean
callback time in microseconds and the ratio to no extras, side by side.
"""

import argparse
import statistics
import sys
import time

import numpy as np
import rclpy
from rclpy.parameter import Parameter
from std_msgs.msg import Float64

from .node import SuspensionNode

SCENES = ('double_wishbone', 'five_link', 'macpherson')
EXTRAS = {'none': {}, 'alignment': {'alignment': True}, 'markers': {'markers': True},
          'both': {'alignment': True, 'markers': True}}


def callback_times(context, scene, extras, travels_m):
    """Seconds per travel callback of a node on scene with the extras parameters."""
    overrides = [Parameter('scene', value=scene)] + [
        Parameter(name, value=value) for name, value in extras.items()]
    node = SuspensionNode(context=context, parameter_overrides=overrides)
    try:
        corner = next(iter(node.corners.values()))
        messages = [Float64(data=float(t)) for t in travels_m]
        times = []
        for msg in messages:
            start = time.perf_counter()
            corner.on_travel(msg)
            times.append(time.perf_counter() - start)
        return times
    finally:
        node.destroy_node()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--commands', type=int, default=2000, help='commands per case')
    args = parser.parse_args(argv)
    context = rclpy.context.Context()
    rclpy.init(context=context, domain_id=77)
    travels = 0.05 * np.sin(np.linspace(0.0, 2 * np.pi * args.commands / 314, args.commands))
    try:
        print(f'{"scene":<16}{"extras":<11}{"median_us":>10}{"mean_us":>10}{"x none":>8}')
        for scene in SCENES:
            base = None
            for label, extras in EXTRAS.items():
                print(f'{scene} {label}...', file=sys.stderr)
                times = callback_times(context, scene, extras, travels)
                median = statistics.median(times) * 1e6
                base = base or median
                print(f'{scene:<16}{label:<11}{median:>10.1f}'
                      f'{statistics.fmean(times) * 1e6:>10.1f}{median / base:>8.2f}')
    finally:
        rclpy.try_shutdown(context=context)
    return 0


if __name__ == '__main__':
    sys.exit(main())
