# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""CI, colcon route: send one wheel travel to a running suspension_node and check its pose.

Exits 0 when the pose of a 50 mm bump arrives (wheel centre 50 mm above design), 1 if no
answer comes within the deadline (which covers a cold numba cache: the first solve compiles).
Where linkage_ros_interfaces imports (colcon built it beside linkage_ros), the node's solve
service must answer a 30 mm bump too.
"""

import sys
import time

from geometry_msgs.msg import PoseStamped
import rclpy
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_msgs.msg import Float64

DEADLINE_S = 180.0
DESIGN_Z_M = 0.30      # five_link's wheel centre at design


def main():
    rclpy.init()
    node = rclpy.create_node('ci_probe')
    qos = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE)
    poses = []
    node.create_subscription(PoseStamped, 'wheel_carrier_pose', poses.append, qos)
    travel = node.create_publisher(Float64, 'wheel_travel', qos)
    deadline = time.monotonic() + DEADLINE_S
    while not poses and time.monotonic() < deadline:
        travel.publish(Float64(data=0.05))     # m, + = bump; repeated until one is answered
        rclpy.spin_once(node, timeout_sec=1.0)
    # the pose of the bump, before the solve service's answer publishes another
    z = poses[0].pose.position.z if poses else None
    served = solve(node, deadline) if poses else None
    node.destroy_node()
    rclpy.try_shutdown()
    if z is None:
        print('ci: suspension_node did not answer within the deadline', file=sys.stderr)
        return 1
    print(f'ci: installed suspension_node answered: wheel centre z {z:.4f} m')
    if served is not None:
        print(f'ci: its solve service answered: wheel centre z {served:.4f} m')
        if abs(served - (DESIGN_Z_M + 0.03)) > 1e-9:
            return 1
    return 0 if abs(z - (DESIGN_Z_M + 0.05)) < 1e-9 else 1


def solve(node, deadline):
    """Return the wheel centre z (m) the solve service gives for 30 mm; None without it."""
    try:
        from linkage_ros_interfaces.srv import Solve
    except ImportError:
        print('ci: no linkage_ros_interfaces here: the solve service is not checked')
        return None
    client = node.create_client(Solve, 'solve')
    if not client.wait_for_service(timeout_sec=max(0.0, deadline - time.monotonic())):
        print('ci: suspension_node serves no solve service', file=sys.stderr)
        return float('nan')
    future = client.call_async(Solve.Request(travel=0.03))
    rclpy.spin_until_future_complete(node, future, timeout_sec=30.0)
    return future.result().pose.position.z if future.done() else float('nan')


if __name__ == '__main__':
    sys.exit(main())
