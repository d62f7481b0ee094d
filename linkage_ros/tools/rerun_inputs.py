# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
What linkage-rerun draws beyond a bag's own topics: the parts of a run, and joint_states.

    parts = run_parts(bag, scene)              [Part]: the scene of each part of a run
    roots, messages = split_parts(parts, msgs) each part drawn under its own root
    joint_commands(bag, joints)                a vehicle's joint_states as each corner's
                                               wheel_travel and steering_rack

A node whose scene was changed while it ran (SetParameters, recorded on /parameter_events)
answered each part of its run with another scene: each part is drawn with its own. The
vehicle input of doc/node.md is one sensor_msgs/JointState on joint_states for every corner (the
vehicle file names each corner's travel_joint and rack_joint): its positions are drawn as
the corners' travel and rack, as if they had come on their wheel_travel and steering_rack.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..core.model import Scene
    from ..record.mcap_reader import Bag, BagMessage

JOINT_STATE = 'sensor_msgs/msg/JointState'
FLOAT64 = 'std_msgs/msg/Float64'


@dataclass(frozen=True)
class Part:
    """A part of a run: from start (ns, log time; None for the run's start) with scene."""

    start: int | None
    scene: Scene


def run_parts(bag: Bag, scene: Scene) -> tuple[list[Part], str]:
    """
    Return the parts of a run of one scene, and a warning ('' if none).

    The first part has scene (the one the recording stores, or --scene); each scene change
    the node recorded starts another, with the scene it names. A change whose scene does not
    load here ends the parts: the warning names it, and what comes later is drawn with the
    scene before it.
    """
    from .replay_commands import load_changed_scenes, parameter_changes, seconds
    changes = [c for c in parameter_changes(bag) if 'scene' in c.values]
    scenes, failed = load_changed_scenes(changes)
    parts = [Part(None, scene)]
    for change in changes:
        if failed is not None and change is failed[0]:
            return parts, (f'the node changed its scene to {change.values["scene"]!r} at '
                           f'{seconds(change.log_time)} s, which does not load here '
                           f'({failed[1]}); what follows is drawn with {parts[-1].scene.name}')
        parts.append(Part(change.log_time, scenes[change.values['scene']]))
    return parts, ''


def split_parts(parts: list[Part], messages: list) -> tuple[dict, list]:
    """
    Return {root: Scene} of the parts and the messages moved under their part's root.

    A message (BagMessage) belongs to the part whose start is the last at or before its log
    time; its topic becomes /<root>/<last name>. Roots are the scenes' names, numbered
    where a scene comes back ('five_link', 'double_wishbone', 'five_link_3').
    """
    roots = {}
    for k, part in enumerate(parts):
        name = part.scene.name if part.scene.name not in roots else f'{part.scene.name}_{k + 1}'
        roots[name] = part.scene
    names = list(roots)
    starts = [p.start for p in parts[1:]]
    moved = []
    for m in messages:
        root = names[bisect.bisect_right(starts, m.log_time)]
        moved.append(replace(m, topic=f'/{root}/{m.topic.rstrip("/").rsplit("/", 1)[-1]}'))
    return roots, moved


def joint_commands(bag: Bag, joints: dict[str, tuple[str, str]]) -> list[BagMessage]:
    """
    Return the joint_states of a vehicle run as its corners' Float64 commands (m).

    joints: {corner: (travel joint, rack joint)} of the vehicle file ('' = none). Each
    JointState on a topic named joint_states gives, for every corner whose joint it holds,
    a message on /<corner>/wheel_travel (or steering_rack) at its log time, in CDR. One
    that does not decode is left out (Bag.decode counts it).
    """
    from ..answer.cdr import CdrError, float64_cdr, from_cdr
    made = []
    for m in bag.messages:
        if m.topic.rstrip('/').rsplit('/', 1)[-1] != 'joint_states' or not m.carries(
                JOINT_STATE):
            continue
        try:
            msg = from_cdr(JOINT_STATE, m.data)
        except CdrError:
            continue
        positions = dict(zip(msg.name, msg.position))
        for corner, pair in joints.items():
            for joint, name in zip(pair, ('wheel_travel', 'steering_rack')):
                if joint and joint in positions:
                    made.append(replace(m, topic=f'/{corner}/{name}', type_name=FLOAT64,
                                        data=float64_cdr(float(positions[joint])),
                                        schema=None))
    return made
