"""
The quality of service of suspension_node's topics, in one place.

Every topic of the node, in and out, is reliable, volatile, keep-last depth: a burst of depth
commands is not lost, and a subscription holds at most depth samples, which bounds its memory
(depth times the largest sample: a JointState of 10^5 joints is 2.8 MB). depth is the node's
parameter qos_depth (QOS_DEPTH by default). The node's own /clock subscription (with
use_sim_time) is best effort, so that it matches any /clock publisher, with the same depth.
"""

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

QOS_DEPTH = 1000


def topic_qos(depth: int = QOS_DEPTH) -> QoSProfile:
    """Return the QoS of the node's topics: reliable, volatile, keep-last depth."""
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth,
                      reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.VOLATILE)


def clock_qos(depth: int = QOS_DEPTH) -> QoSProfile:
    """Return the QoS of the node's /clock subscription: best effort, keep-last depth."""
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth,
                      reliability=ReliabilityPolicy.BEST_EFFORT,
                      durability=DurabilityPolicy.VOLATILE)


QOS = topic_qos()
