# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The bare reference of linkage-bench node: an rclpy node that only echoes, one process."""

from geometry_msgs.msg import PoseStamped, WrenchStamped
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

from ...ros.entry import run
from ...ros.node import QOS

CORNERS = ('front_left', 'front_right', 'rear_left', 'rear_right')


class EchoNode(Node):
    """
    The bare reference: transport and executor cost only.

    Each wheel_travel (Float64) is answered by a PoseStamped with z = travel, under every
    corner prefix; a joint_states message naming '<corner>_travel' joints is answered by one
    pose per corner it names. A vehicle's echo takes each corner's contact_wrench too (the
    CDR bytes kept, as the node keeps the last wrench), so that it carries the same traffic.
    """

    def __init__(self, prefixes=('',), **kwargs):
        super().__init__('echo', **kwargs)
        self.pubs = {}
        for prefix in prefixes:
            pub = self.create_publisher(PoseStamped, prefix + 'wheel_carrier_pose', QOS)
            self.pubs[prefix.rstrip('/')] = pub
            self.create_subscription(Float64, prefix + 'wheel_travel',
                                     lambda msg, pub=pub: self.answer(pub, msg.data), QOS)
        if prefixes != ('',):
            self.create_subscription(JointState, 'joint_states', self.on_joint_states, QOS)
            self.wrenches = {}
            for prefix in prefixes:
                self.create_subscription(
                    WrenchStamped, prefix + 'contact_wrench',
                    lambda data, c=prefix: self.wrenches.__setitem__(c, data), QOS, raw=True)

    def answer(self, pub, travel):
        out = PoseStamped()
        out.header.stamp = self.get_clock().now().to_msg()
        out.header.frame_id = 'base_link'
        out.pose.position.z = travel
        pub.publish(out)

    def on_joint_states(self, msg):
        positions = dict(zip(msg.name, msg.position))
        for corner, pub in self.pubs.items():
            if f'{corner}_travel' in positions:
                self.answer(pub, positions[f'{corner}_travel'])


def echo_main(vehicle: bool, args: list[str] | None = None) -> int:
    """Run an echo node process: same executor and spin loop as suspension_node."""
    rclpy.init(args=args)
    return run(EchoNode(tuple(f'{c}/' for c in CORNERS) if vehicle else ('',)))
