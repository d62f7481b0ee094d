# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The TF outputs of suspension_node: /tf, /tf_static and robot_description.

    outputs = TfOutputs(node, outlet, corners, frame_id, robot_name)
    outputs.send(data)      one corner's answer on /tf (what Corner.answer hands the outlet)
    outputs.describe(stamp) /tf_static (every corner's wheel frame, one message) and the URDF
                            on robot_description: at start and after a change of scene
    outputs.close()         stop: the corners' frames and the publishers go

Imported only while the node's parameter tf is true. Every message is recorded (the node's
outlet hands it to the sinks) whatever the machine; /tf and /tf_static are published only
where tf2_msgs imports (ros/tf.tf2_msgs_missing says why not, which the node logs once at
start). /tf: reliable, keep-last qos_depth like every topic of the node; /tf_static and
robot_description: reliable, transient local, keep-last 1 (ros/qos.latched_qos), as tf2's
static broadcaster and robot_state_publisher offer them. All three take qos_overrides.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from std_msgs.msg import String

from .qos import latched_qos, publisher, topic_qos
from ..answer.cdr import string_cdr
from ..answer.frames import CornerFrames, static_cdr, tf2_msgs_missing, tf_message_class, \
    TF_STATIC_TOPIC, TF_TOPIC, TF_TYPE
from ..answer.robot_description import robot_description

if TYPE_CHECKING:
    from rclpy.node import Node

    from .corner import Corner

DESCRIPTION_TOPIC = 'robot_description'
STRING = 'std_msgs/msg/String'


class TfOutputs:
    """
    The node's /tf, /tf_static and robot_description, and the frames of its corners.

    outlet: the node (publish(publisher, msg) and record(topic, type, data)); corners:
    {name: Corner}, each given its CornerFrames under its topic prefix.
    """

    def __init__(self, node: Node, outlet, corners: dict[str, Corner], frame_id: str,
                 robot_name: str, depth: int) -> None:
        self.node, self.outlet, self.corners = node, outlet, corners
        self.frame_id, self.robot_name = frame_id, robot_name
        self.missing = tf2_msgs_missing()
        self.tf = self.static = None
        if not self.missing:
            kind = tf_message_class()
            self.tf = publisher(node, kind, TF_TOPIC, topic_qos(depth))
            self.static = publisher(node, kind, TF_STATIC_TOPIC, latched_qos())
        self.description = publisher(node, String, DESCRIPTION_TOPIC, latched_qos())
        self.attach()

    def attach(self) -> None:
        """Give every corner the frames of its present scene."""
        for corner in self.corners.values():
            # the pickups' frames only where /tf_static is published: the pickup wrenches
            # name them then, else the vehicle frame (answer/pickups.py)
            pickups = corner.statics.frame_points() \
                if corner.statics is not None and not self.missing else None
            corner.frames = CornerFrames(corner.scene, self.frame_id, corner.prefix, pickups)

    def send(self, data: bytes) -> None:
        """Publish one TFMessage (CDR bytes) on /tf, or only record it without tf2_msgs."""
        if self.tf is not None:
            self.outlet.publish(self.tf, data)
        else:
            self.outlet.record(TF_TOPIC, TF_TYPE, data)

    def describe(self, stamp: tuple[int, int]) -> str:
        """Send /tf_static (stamped (sec, nanosec)) and the URDF; return the URDF."""
        frames = [corner.frames for corner in self.corners.values()]
        static = static_cdr(frames, stamp)
        if self.static is not None:
            self.outlet.publish(self.static, static)
        else:
            self.outlet.record(TF_STATIC_TOPIC, TF_TYPE, static)
        text = robot_description({c.prefix: c.scene for c in self.corners.values()},
                                 self.frame_id, self.robot_name)
        self.outlet.publish(self.description, string_cdr(text))
        return text

    def close(self) -> None:
        """Stop: the corners lose their frames, the publishers are destroyed."""
        for corner in self.corners.values():
            corner.frames = None
        for out in (self.tf, self.static, self.description):
            if out is not None:
                self.node.destroy_publisher(out)
        self.tf = self.static = self.description = None
