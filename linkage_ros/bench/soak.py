# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench soak: a long run of suspension_node in process, to show that it lasts.

    linkage-bench soak [--commands 1000000] [--scene five_link] [--batch 200] [--seed 0]

One million commands (by default) go through a SuspensionNode over real DDS in one process
(a private context, discovery off, on the user's ROS domain: ROS_DOMAIN_ID, 0 if unset; no
other process sees or reaches it): a random walk over the scene's travel range in steps of
about 0.5 mm, a jump across the range every 5000 commands, and a bad value every 1000 (NaN,
inf, -inf, 1e308 m, a travel beyond the bump limit). A probe node publishes them in batches
and reads every answer as it comes (poses and /diagnostics, as CDR). Printed at the end, in
one CSV table: commands per second, the resident memory (RSS) after a warm-up and at the end
and its growth per 100 000 commands, the largest constraint residual the node reported, and
the counts of poses, ERROR statuses and non-finite poses (which must be 0). Progress every
--progress commands on stderr.
"""

import argparse
import math
import sys
import time

import numpy as np
import rclpy
from rclpy.experimental import EventsExecutor
from rclpy.parameter import Parameter

from ..answer.cdr import float64_cdr, pose_of
from ..cli import EXIT_STATUS, Parser, program
from ..core.base import all_finite, LinkageError
from ..core.model import load_scene
from ..core.warmup import compile_if_cold
from ..outputs import write_table
from ..ros.isolation import init_context
from ..ros.messages import status_values
from ..ros.node import QOS, SuspensionNode

PROG = 'linkage-bench soak'

BAD_VALUES_M = (math.nan, math.inf, -math.inf, 1e308, 10.0)   # 10 m: beyond any limit


def rss_mb():
    """Return the resident set size of this process, MB (from /proc/self/status)."""
    with open('/proc/self/status') as status:
        for line in status:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024.0
    return math.nan


def command_batches(count, batch, low_mm, high_mm, seed):
    """
    Yield (first index, travels (m)) of count commands, a batch at a time.

    A random walk with jumps, bad values mixed in; made a batch at a time, so the soak's own
    memory does not grow with count.
    """
    rng = np.random.default_rng(seed)
    travel = 0.0
    for first in range(0, count, batch):
        steps = rng.normal(0.0, 0.5, min(batch, count - first))
        out = np.empty(len(steps))
        for j, i in enumerate(range(first, first + len(steps))):
            if i % 5000 == 4999:
                travel = rng.uniform(low_mm, high_mm)          # a jump across the range
            else:
                travel = min(max(travel + steps[j], low_mm), high_mm)
            out[j] = travel / 1000.0
            if i % 1000 == 999:
                out[j] = BAD_VALUES_M[(i // 1000) % len(BAD_VALUES_M)]
        yield first, out


class Counter:
    """
    What came back from the node.

    Poses (and how many were not finite), ERROR statuses, the worst residual reported (m).
    """

    def __init__(self):
        self.poses = self.not_finite = self.errors = 0
        self.residual_m = 0.0

    def on_pose(self, data):
        self.poses += 1
        position, orientation = pose_of(data)
        if not all_finite((*position, *orientation)):
            self.not_finite += 1

    def on_diagnostics(self, msg):
        for status in msg.status:
            self.errors += status.level == b'\x02'
            residual = float(status_values(status)['residual_max_m'])
            if not residual <= self.residual_m:
                self.residual_m = residual


def run(args):
    from diagnostic_msgs.msg import DiagnosticArray
    from geometry_msgs.msg import PoseStamped
    from std_msgs.msg import Float64
    scene = load_scene(args.scene)
    compile_if_cold(PROG)   # here, not at the first command: its answer is awaited
    context = init_context(args.domain_id, 'OFF')
    executor = EventsExecutor(context=context)
    node = SuspensionNode(context=context, parameter_overrides=[
        Parameter('scene', value=args.scene), Parameter('diagnostic_period', value=0.5)])
    probe = rclpy.create_node('soak_probe', context=context, enable_rosout=False,
                              start_parameter_services=False)
    counter = Counter()
    publisher = probe.create_publisher(Float64, 'wheel_travel', QOS)
    probe.create_subscription(PoseStamped, 'wheel_carrier_pose', counter.on_pose, QOS,
                              raw=True)
    probe.create_subscription(DiagnosticArray, '/diagnostics', counter.on_diagnostics, QOS)
    executor.add_node(node)
    executor.add_node(probe)
    batches = command_batches(args.commands, args.batch, scene.travel[0], scene.travel[1],
                              args.seed)
    rss, start, wanted = [], None, 0
    try:
        for first, travels in batches:
            for value in travels:
                publisher.publish(float64_cdr(value))
            wanted += int(np.count_nonzero(np.isfinite(travels) & (np.abs(travels) < 1.0)))
            deadline = time.monotonic() + 30.0
            while counter.poses < wanted:
                if time.monotonic() > deadline:
                    raise RuntimeError(f'commands {first}..{first + args.batch}: '
                                       f'{wanted - counter.poses} poses missing after 30 s')
                executor.spin_once(timeout_sec=1.0)
            done = first + len(travels)
            if start is None and done >= args.warmup:
                start, rss = (time.perf_counter(), done), [(done, rss_mb())]
            if done % args.progress < args.batch:
                rss.append((done, rss_mb()))
                print(f'{PROG}: {done}/{args.commands} commands, RSS {rss[-1][1]:.1f} MB',
                      file=sys.stderr, flush=True)
        end = time.perf_counter()
        executor.spin_once(timeout_sec=args.period_wait)   # the last diagnostics report
    finally:
        executor.remove_node(node)
        executor.remove_node(probe)
        node.destroy_node()
        probe.destroy_node()
        executor.shutdown()
        rclpy.try_shutdown(context=context)
    rss.append((args.commands, rss_mb()))
    done, mb = np.array(rss).T
    growth = float(np.polyfit(done, mb, 1)[0] * 1e5) if len(rss) > 2 else math.nan
    rate = (args.commands - start[1]) / (end - start[0])
    write_table(None, ('soak', 'commands', 'commands_per_s', 'rss_start_mb', 'rss_end_mb',
                       'rss_growth_mb_per_100k', 'residual_max_mm', 'poses', 'errors',
                       'not_finite_poses'),
                [[args.scene, args.commands, rate, float(mb[0]), float(mb[-1]), growth,
                  counter.residual_m * 1000.0, counter.poses, counter.errors,
                  counter.not_finite]])
    return 0 if counter.not_finite == 0 else 1


EPILOG = f"""examples:
  ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST linkage-bench soak > soak.csv
  ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST linkage-bench soak --commands 100000 --scene macpherson

exit status: 0 no pose was non-finite; 1 a non-finite pose was published; {EXIT_STATUS}"""


def parse_args(argv):
    parser = Parser(PROG, __doc__, EPILOG)
    parser.add_argument('--commands', type=int, default=1_000_000,
                        help='commands to send (default 1000000)')
    parser.add_argument('--scene', default='five_link', help='bundled scene or YAML path')
    parser.add_argument('--batch', type=int, default=200,
                        help='commands published before waiting for their answers')
    parser.add_argument('--warmup', type=int, default=20_000,
                        help='commands before the first memory reading and the clock start')
    parser.add_argument('--progress', type=int, default=50_000,
                        help='a progress line (and a memory reading) every this many')
    parser.add_argument('--seed', type=int, default=0, help='of the random walk')
    parser.add_argument('--domain-id', type=int, default=None,
                        help='ROS domain (default: ROS_DOMAIN_ID, else 0)')
    parser.add_argument('--period-wait', type=float, default=1.0, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.commands < args.warmup + args.batch or args.batch < 1:
        parser.error('--commands must exceed --warmup by at least one --batch')
    try:
        load_scene(args.scene)
    except LinkageError as exc:
        parser.error(str(exc))
    return args


@program(PROG)
def main(argv=None):
    return run(parse_args(argv))


if __name__ == '__main__':
    sys.exit(main())
