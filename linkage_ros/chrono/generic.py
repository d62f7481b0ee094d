# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Chrono's GenericWheeledSuspension: bodies, joints, distance constraints and TSDAs, both ways.

Import takes the topologies a scene expresses: a body held by a "Revolute" joint to the
chassis (its axis the z axis of the joint's quaternion [w, x, y, z]) and a "Spherical" joint
to the upright is an arm (circle); a body held by a "Universal" or "Spherical" joint to the
chassis and a "Spherical" joint to the upright is a link (sphere); a distance constraint
from "Chassis" or "Steering" to the upright is a link (sphere, steer: rack from
"Steering"). Anything else is refused, naming the joint or body. Export writes the same
shapes back: arms as bodies with a revolute and a spherical joint, links as distance
constraints, or as bodies (universal + spherical) where an element is mounted on them.
"""

from __future__ import annotations

import numpy as np

from .bushings import bushing_data, bushing_into, bushing_springs, fold_springs, places
from .names import body_name, KEEP, named, Tokens
from .parts import mount_of, tsda_elements
from .reader import ChronoError, Fields
from .templates import DESIGN_AXIS_M
from ..core.base import MM_PER_M

FIXED = ('Chassis', 'Steering')
BODY_DEFAULTS = {'Mass': 1.0, 'Moments of Inertia': [0.01, 0.01, 0.01],
                 'Products of Inertia': [0.0, 0.0, 0.0]}


def import_generic(top: Fields, notes: list) -> tuple[list, list]:
    """Return (constraints, elements) of a GenericWheeledSuspension's object (m)."""
    upright = body_name(top.sub('Spindle').raw('Attachment Body'))
    joints = top.objects('Joints')
    constraints, carried, bushed = [], {}, {}
    tokens, element_tokens = Tokens(), Tokens()
    for body in top.objects('Bodies'):
        name = body.text('Name')
        if name == upright:
            continue
        item, fixed, at = _body_item(top, name, joints, upright, notes)
        constraints.append(named(item, name, tokens))
        carried[name] = item
        if 'bushing' in item:
            bushed[name] = (item, fixed, at)
    for dist in top.objects('Distance Constraints'):
        pair = [body_name(dist.raw('Body1')), body_name(dist.raw('Body2'))]
        if upright not in pair or not set(pair) - {upright} <= set(FIXED):
            raise ChronoError(top.where, f'"Distance Constraints" {dist.text("Name")!r}: '
                              f'between {pair}: only chassis (or steering) to upright is '
                              'imported')
        ends = (dist.vector('Point1'), dist.vector('Point2'))
        base, joint = ends if pair[1] == upright else ends[::-1]
        item = {'name': '', 'type': 'sphere', 'base': _list(base), 'carrier': _list(joint)}
        if 'Steering' in pair:
            item['steer'] = 'rack'
        constraints.append(named(item, dist.text('Name'), tokens))
    elements = []
    tsdas = top.objects('TSDAs')
    folded = fold_springs(tsdas, bushed, notes)
    for tsda in (t for i, t in enumerate(tsdas) if i not in folded):
        pair = [body_name(tsda.raw('Body1')), body_name(tsda.raw('Body2'))]
        points = (tsda.vector('Point1'), tsda.vector('Point2'))
        if pair[1] in FIXED:
            pair, points = pair[::-1], points[::-1]
        if pair[0] not in FIXED:
            notes.append(f'{tsda.text("Name")}: between two moving bodies: not imported')
            continue
        on = '' if pair[1] == upright else pair[1]
        if on and on not in carried:
            raise ChronoError(top.where, f'"TSDAs" {tsda.text("Name")!r}: no body {on!r}')
        name = tsda.text('Name')
        mount = mount_of(carried.get(on), carried[on]['name'] if on else '', points[0],
                         points[1], notes, name)
        if mount is not None:
            ours = element_tokens(name)
            made = tsda_elements(tsda, ours, points[0], mount, notes)
            if made and made[0]['name'] == ours != name:
                made[0][KEEP] = name   # the spring (or damper) itself, not its stops
            elements += made
    return constraints, elements


def _body_item(top, name, joints, upright, notes):
    """
    Return (scene item, fixed body, {place: point m}) of a body between chassis and upright.

    A link: a Universal or Spherical joint to the chassis (or "Steering": steer: rack) and a
    Spherical one to the upright. An arm: a Revolute joint to the chassis, or two coaxial
    Revolute joints with the same "Bushing Data" (a bushing at each pivot, at: pivots).
    """
    fixed, upper, stray = [], [], []
    for joint in joints:
        pair = [body_name(joint.raw('Body1')), body_name(joint.raw('Body2'))]
        if name not in pair:
            continue
        other = pair[1] if pair[0] == name else pair[0]
        (fixed if other in FIXED else upper if other == upright else stray).append(joint)
    kinds = [j.text('Type') for j in fixed]
    pivots = kinds == ['Revolute', 'Revolute'] and _pivot_pair(fixed)
    if stray or len(upper) != 1 or upper[0].text('Type') != 'Spherical' \
            or not (len(fixed) == 1 or pivots):
        every = fixed + upper + stray
        joined = sorted({body_name(j.raw(k)) for j in every for k in ('Body1', 'Body2')} - {name})
        types = ', '.join(j.text('Type') for j in every) or 'no joint'
        raise ChronoError(top.where, f'"Bodies" {name!r}: joined by {joined or "nothing"} '
                          f'({types}): a topology scenes do not have (a body held by one '
                          'joint to the chassis, or two coaxial bushed revolutes, and a '
                          'spherical joint to the upright is needed)')
    if upper[0].has('Bushing Data'):
        notes.append(f'{name}: the "Bushing Data" of its joint to the upright is not imported:'
                     " a scene's ball joint at the wheel carrier is rigid")
    carrier = _list(upper[0].vector('Position'))
    joint = fixed[0]
    steer = 'Steering' in {body_name(joint.raw('Body1')), body_name(joint.raw('Body2'))}
    at = joint.vector('Position')
    if pivots:
        ends = [fixed[0].vector('Position'), fixed[1].vector('Position')]
        item = {'name': name, 'type': 'circle', 'axis': [_list(e) for e in ends],
                'carrier': carrier}
        places = {'axis0': ends[0], 'axis1': ends[1]}
    elif kinds[0] == 'Revolute':
        axis = rotation(joint.vector('Rotation', 4))[:, 2]
        item = {'name': name, 'type': 'circle',
                'axis': [_list(at + DESIGN_AXIS_M * axis), _list(at - DESIGN_AXIS_M * axis)],
                'carrier': carrier}
        places = {'centre': at}
    elif kinds[0] in ('Universal', 'Spherical'):
        item = {'name': name, 'type': 'sphere', 'base': _list(at), 'carrier': carrier}
        places = {'base': at}
    else:
        raise ChronoError(top.where, f'"Joints" {joint.text("Name")!r}: a {kinds[0]} '
                          'joint to the chassis is not imported (Revolute, Universal or '
                          'Spherical are)')
    if steer and item['type'] == 'sphere':
        item['steer'] = 'rack'
    bushing_into(item, joint, notes, name)
    if pivots and 'bushing' in item:
        item['bushing']['at'] = 'pivots'
    return item, 'Steering' if steer else 'Chassis', places


def _pivot_pair(joints) -> bool:
    """Whether two revolute joints are one arm's two bushed pivots (the same data, coaxial)."""
    first, second = joints
    if not (first.has('Bushing Data') and second.has('Bushing Data')) \
            or first.raw('Bushing Data') != second.raw('Bushing Data') \
            or body_name(first.raw('Body1')) != body_name(second.raw('Body1')) \
            or body_name(first.raw('Body2')) != body_name(second.raw('Body2')):
        return False
    line = second.vector('Position') - first.vector('Position')
    if not np.linalg.norm(line) > 0:
        return False
    line = line / np.linalg.norm(line)
    return all(abs(rotation(j.vector('Rotation', 4))[:, 2] @ line) > 1.0 - 1e-9 for j in joints)


def rotation(q) -> np.ndarray:
    """Return the rotation matrix (3, 3) of a Chrono quaternion [w, x, y, z] (normalised)."""
    w, x, y, z = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def quaternion_z(axis) -> list:
    """Return a Chrono quaternion [w, x, y, z] turning the z axis onto axis (unit)."""
    a = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    if a[2] < -1.0 + 1e-12:
        return [0.0, 1.0, 0.0, 0.0]
    q = np.array([1.0 + a[2], -a[1], a[0], 0.0])   # half-way rotation z -> a
    return [float(v) for v in q / np.linalg.norm(q)]


def generic_of(scene, mounted: set, elements: list, notes: list,
               upright: str = 'Upright') -> dict:
    """Return the GenericWheeledSuspension fields of a scene (m): bodies, joints, constraints."""
    m = 1e-3
    bodies = [{'Name': upright, 'Mirrored': True, 'Position': _list(scene.wheel_center * m),
               'Rotation': [1.0, 0.0, 0.0, 0.0], **BODY_DEFAULTS}]
    joints, dists, springs = [], [], []
    for c in scene.constraints:
        base, joint = c.base * m, c.carrier * m
        if c.type == 'line':
            raise ChronoError(scene.source, f'{c.name}: a strut (line) goes out only in the '
                              'MacPhersonStrut template, with one arm and one tie rod')
        fixed = 'Steering' if c.steer == 'rack' else 'Chassis'
        if c.type == 'sphere' and c.name not in mounted and c.bushing is None:
            dists.append({'Name': c.name, 'Mirrored': True, 'Body1': fixed, 'Body2': upright,
                          'Point1': _list(base[0]), 'Point2': _list(joint)})
            continue
        if c.type == 'circle':
            axis, kind = base[1] - base[0], 'Revolute'
        else:   # a body: an element is mounted on it, or it has a bushing
            axis, kind = joint - base[0], 'Universal'
        at = places(c)
        middle = sum(p for _, p in at) / len(at) * m
        bodies.append({'Name': c.name, 'Mirrored': True, 'Position': _list((middle + joint) / 2),
                       'Rotation': [1.0, 0.0, 0.0, 0.0], **BODY_DEFAULTS})
        for place, point in at:
            joints.append({'Name': f'{kind}{c.name}' + (f'_{place}' if len(at) > 1 else ''),
                           'Type': kind, 'Mirrored': True, 'Body1': fixed, 'Body2': c.name,
                           'Position': [float(v) / MM_PER_M for v in point],
                           'Rotation': quaternion_z(axis)})
            if c.bushing is not None:
                joints[-1]['Bushing Data'] = bushing_data(c)
        if c.bushing is not None:
            springs += bushing_springs(c, fixed)
        joints.append({'Name': f'Spherical{c.name}', 'Type': 'Spherical', 'Mirrored': True,
                       'Body1': c.name, 'Body2': upright, 'Position': _list(joint),
                       'Rotation': [1.0, 0.0, 0.0, 0.0]})
    arms = [b['Name'] for b in bodies[1:]]
    return {'Independent': True, 'Steerable': scene.steered, 'Bodies': bodies,
            'Joints': joints, 'Distance Constraints': dists, 'TSDAs': elements + springs,
            'Antiroll Body': arms[0] if arms else upright}


def same_axis(old, new) -> bool:
    """Whether two Chrono quaternions [w, x, y, z] turn z onto one line (either way, 1e-9)."""
    try:
        return abs(float(rotation(old)[:, 2] @ rotation(new)[:, 2])) > 1.0 - 1e-9
    except (TypeError, ValueError):
        return False


def _list(v) -> list:
    return [float(x) for x in v]
