# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The quality of service of suspension_node's topics, in one place.

Every topic of the node, in and out, is reliable, volatile, keep-last depth: a burst of depth
commands is not lost, and a subscription holds at most depth samples, which bounds its memory
(depth times the largest sample: a JointState of 10^5 joints is 2.8 MB). depth is the node's
parameter qos_depth (QOS_DEPTH by default). The node's own /clock subscription (with
use_sim_time) is best effort, so that it matches any /clock publisher, with the same depth.
/tf_static and robot_description are latched as tf2 and robot_state_publisher latch them:
reliable, transient local, keep-last 1 (a subscriber that comes later gets the last one).

QoS by parameter, the rclpy way: every topic of the node is made with QoSOverridingOptions
(OVERRIDES: history, depth, reliability), so that a parameter
qos_overrides.<fully qualified topic>.<publisher|subscription>.<policy> given at start (-p,
a params file) wins over the node's default for that topic alone, qos_depth included:

    -p qos_overrides./wheel_carrier_pose.publisher.depth:=1
    -p qos_overrides./wheel_travel.subscription.reliability:=best_effort

publisher() and subscription() make the node's topics so; check_overrides() refuses a value
or policy that rclpy cannot apply (one line); offered() gives the profile a topic ends up
with, for the recordings' metadata.
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from rclpy.qos_overriding_options import QoSOverridingOptions

from ..core.base import LinkageError

if TYPE_CHECKING:
    from rclpy.node import Node

QOS_DEPTH = 1000
MAX_DEPTH = 100000     # as qos_depth: each input holds at most this many messages
PREFIX = 'qos_overrides.'
OVERRIDES = QoSOverridingOptions.with_default_policies()
# policy -> the values it takes (None: a number of messages)
POLICIES = {'history': ('keep_last', 'keep_all', 'system_default'), 'depth': None,
            'reliability': ('reliable', 'best_effort', 'system_default')}
ENTITIES = ('publisher', 'subscription')


def topic_qos(depth: int = QOS_DEPTH) -> QoSProfile:
    """Return the QoS of the node's topics: reliable, volatile, keep-last depth."""
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth,
                      reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.VOLATILE)


def latched_qos() -> QoSProfile:
    """Return the QoS of /tf_static and robot_description: reliable, transient local, depth 1."""
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=1,
                      reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL)


def clock_qos(depth: int = QOS_DEPTH) -> QoSProfile:
    """Return the QoS of the node's /clock subscription: best effort, keep-last depth."""
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth,
                      reliability=ReliabilityPolicy.BEST_EFFORT,
                      durability=DurabilityPolicy.VOLATILE)


QOS = topic_qos()


def publisher(node: Node, kind: type, topic: str, profile: QoSProfile):
    """Create a publisher of the node with its qos_overrides parameters applied."""
    return node.create_publisher(kind, topic, copy.copy(profile),
                                 qos_overriding_options=OVERRIDES)


def subscription(node: Node, kind: type, topic: str, callback, profile: QoSProfile,
                 raw: bool = False):
    """Create a subscription of the node with its qos_overrides parameters applied."""
    return node.create_subscription(kind, topic, callback, copy.copy(profile), raw=raw,
                                    qos_overriding_options=OVERRIDES)


def check_overrides(values: dict) -> None:
    """
    Refuse a qos_overrides parameter rclpy could not apply; LinkageError naming it.

    values: {parameter name: value} of the node. A policy other than history, depth and
    reliability, a value those do not take, a name not of the form
    qos_overrides./topic.publisher|subscription.policy.
    """
    for name, value in values.items():
        if not name.startswith(PREFIX):
            continue
        topic, _, rest = name[len(PREFIX):].rpartition('.')
        topic, _, entity = topic.rpartition('.')
        policy = rest
        if not topic.startswith('/') or entity not in ENTITIES:
            raise LinkageError(f'parameter {name}', 'expected qos_overrides./TOPIC.publisher.'
                               'POLICY or qos_overrides./TOPIC.subscription.POLICY (the '
                               'fully qualified topic)')
        if policy not in POLICIES:
            raise LinkageError(f'parameter {name}', f'the node takes overrides of '
                               f'{", ".join(POLICIES)}, not {policy}')
        choices = POLICIES[policy]
        if choices is None:
            if isinstance(value, bool) or not isinstance(value, int) \
                    or not 1 <= value <= MAX_DEPTH:
                raise LinkageError(name, f'expected a number of messages from 1 to '
                                   f'{MAX_DEPTH}, got {value!r}')
        elif value not in choices:
            raise LinkageError(name, f'expected one of {", ".join(choices)}, got {value!r}')


def offered(node: Node, topic: str, entity: str, profile: QoSProfile) -> QoSProfile:
    """
    Return the profile a topic of the node has once its overrides are applied, as rclpy does.

    topic: fully qualified; entity: 'publisher' or 'subscription'. For the recordings'
    metadata, which are written before the node's topics are made.
    """
    profile = copy.copy(profile)
    for policy, choices in POLICIES.items():
        name = f'{PREFIX}{topic}.{entity}.{policy}'
        if node.has_parameter(name):
            value = node.get_parameter(name).value
            if choices is None:
                profile.depth = value
            else:
                enum = HistoryPolicy if policy == 'history' else ReliabilityPolicy
                setattr(profile, policy, enum[value.upper()])
    return profile


def unknown_overrides(node: Node, known: set[tuple[str, str]]) -> dict[str, str]:
    """
    Return {parameter name: problem} of the node's qos_overrides naming none of its topics.

    known: {(fully qualified topic, 'publisher' or 'subscription')} the node makes or may
    make. rclpy would ignore such a parameter: a misspelt topic would change nothing, unseen.
    """
    import difflib
    problems = {}
    names = [f'{PREFIX}{topic}.{entity}' for topic, entity in sorted(known)]
    for name in node.list_parameters([], 0).names:
        if not name.startswith(PREFIX):
            continue
        head, _, policy = name.rpartition('.')
        if head not in names:
            topic, _, entity = head[len(PREFIX):].rpartition('.')
            other = 'subscription' if entity == 'publisher' else 'publisher'
            if (topic, other) in known:       # the right topic, the wrong end of it
                close = [f'{PREFIX}{topic}.{other}']
            else:                             # a misspelt topic: the nearest of its kind
                close = [f'{PREFIX}{t}.{entity}' for t in difflib.get_close_matches(
                    topic, sorted(t for t, e in known if e == entity), n=1)]
            guess = f' (did you mean {close[0]}.{policy}?)' if close else ''
            problems[name] = f'{_no_such(entity, topic, known)}{guess}'
    return problems


def _no_such(entity: str, topic: str, known: set[tuple[str, str]]) -> str:
    """Say that the node has no entity ('publisher' or 'subscription') on topic (resolved)."""
    verbs = {'publisher': ('publish', 'publishes'),
             'subscription': ('subscribe to', 'subscribes to')}
    if entity not in verbs:     # check_overrides refuses these first
        return f'{entity!r} is neither publisher nor subscription'
    other = 'subscription' if entity == 'publisher' else 'publisher'
    also = f' (it {verbs[other][1]} it)' if (topic, other) in known else ''
    return f'the node does not {verbs[entity][0]} {topic}{also}'
