# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""CI, colcon route: send one wheel travel to a running suspension_node and check its pose.

Exits 0 when the pose of a 50 mm bump arrives (wheel centre 50 mm above design), 1 if no
answer comes within the deadline (which covers a cold numba cache: the first solve compiles).
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
    node.destroy_node()
    rclpy.try_shutdown()
    if not poses:
        print('ci: suspension_node did not answer within the deadline', file=sys.stderr)
        return 1
    z = poses[-1].pose.position.z
    print(f'ci: installed suspension_node answered: wheel centre z {z:.4f} m')
    return 0 if abs(z - (DESIGN_Z_M + 0.05)) < 1e-9 else 1


if __name__ == '__main__':
    sys.exit(main())
