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

from .parts import bushing_data, bushing_into, mount_of, tsda_elements
from .reader import ChronoError, Fields
from .templates import DESIGN_AXIS_M

FIXED = ('Chassis', 'Steering')
BODY_DEFAULTS = {'Mass': 1.0, 'Moments of Inertia': [0.01, 0.01, 0.01],
                 'Products of Inertia': [0.0, 0.0, 0.0]}


def import_generic(top: Fields, notes: list) -> tuple[list, list]:
    """Return (constraints, elements) of a GenericWheeledSuspension's object (m)."""
    upright = _ident(top.sub('Spindle').raw('Attachment Body'))
    joints = top.objects('Joints')
    constraints, carried = [], {}
    for body in top.objects('Bodies'):
        name = body.text('Name')
        if name == upright:
            continue
        ends = {}
        for joint in joints:
            pair = {_ident(joint.raw('Body1')), _ident(joint.raw('Body2'))}
            if name in pair:
                other = (pair - {name}).pop() if len(pair) == 2 else name
                ends['chassis' if other in FIXED else other] = joint
        to_chassis, to_upright = ends.get('chassis'), ends.get(upright)
        if to_chassis is None or to_upright is None or len(ends) != 2 \
                or to_upright.text('Type') != 'Spherical':
            raise ChronoError(top.where, f'"Bodies" {name!r}: joined by '
                              f'{sorted(ends) or "nothing"}: a topology scenes do not have '
                              '(a body between the chassis and the upright is needed)')
        kind = to_chassis.text('Type')
        carrier = _list(to_upright.vector('Position'))
        at = to_chassis.vector('Position')
        if kind == 'Revolute':
            axis = rotation(to_chassis.vector('Rotation', 4))[:, 2]
            item = {'name': name, 'type': 'circle',
                    'axis': [_list(at + DESIGN_AXIS_M * axis), _list(at - DESIGN_AXIS_M * axis)],
                    'carrier': carrier}
        elif kind in ('Universal', 'Spherical'):
            item = {'name': name, 'type': 'sphere', 'base': _list(at), 'carrier': carrier}
        else:
            raise ChronoError(top.where, f'"Joints" {to_chassis.text("Name")!r}: a {kind} '
                              'joint to the chassis is not imported (Revolute, Universal or '
                              'Spherical are)')
        bushing_into(item, to_chassis, notes, name)
        constraints.append(item)
        carried[name] = item
    for dist in top.objects('Distance Constraints'):
        pair = [_ident(dist.raw('Body1')), _ident(dist.raw('Body2'))]
        if upright not in pair or not set(pair) - {upright} <= set(FIXED):
            raise ChronoError(top.where, f'"Distance Constraints" {dist.text("Name")!r}: '
                              f'between {pair}: only chassis (or steering) to upright is '
                              'imported')
        ends = (dist.vector('Point1'), dist.vector('Point2'))
        base, joint = ends if pair[1] == upright else ends[::-1]
        item = {'name': dist.text('Name'), 'type': 'sphere', 'base': _list(base),
                'carrier': _list(joint)}
        if 'Steering' in pair:
            item['steer'] = 'rack'
        constraints.append(item)
    elements = []
    for tsda in top.objects('TSDAs'):
        pair = [_ident(tsda.raw('Body1')), _ident(tsda.raw('Body2'))]
        points = (tsda.vector('Point1'), tsda.vector('Point2'))
        if pair[1] in FIXED:
            pair, points = pair[::-1], points[::-1]
        if pair[0] not in FIXED:
            notes.append(f'{tsda.text("Name")}: between two moving bodies: not imported')
            continue
        on = '' if pair[1] == upright else pair[1]
        if on and on not in carried:
            raise ChronoError(top.where, f'"TSDAs" {tsda.text("Name")!r}: no body {on!r}')
        mount = mount_of(carried.get(on), on, points[0], points[1], notes, tsda.text('Name'))
        if mount is not None:
            elements += tsda_elements(tsda, tsda.text('Name'), points[0], mount, notes)
    return constraints, elements


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
    joints, dists = [], []
    for c in scene.constraints:
        base, joint = c.base * m, c.carrier * m
        if c.type == 'line':
            raise ChronoError(scene.source, f'{c.name}: a strut (line) goes out only in the '
                              'MacPhersonStrut template, with one arm and one tie rod')
        fixed = 'Steering' if c.steer == 'rack' else 'Chassis'
        if c.type == 'sphere' and c.name not in mounted:
            dists.append({'Name': c.name, 'Mirrored': True, 'Body1': fixed, 'Body2': upright,
                          'Point1': _list(base[0]), 'Point2': _list(joint)})
            continue
        if c.type == 'circle':
            at, axis, kind = (base[0] + base[1]) / 2, base[1] - base[0], 'Revolute'
        else:
            at, axis, kind = base[0], joint - base[0], 'Universal'
        bodies.append({'Name': c.name, 'Mirrored': True, 'Position': _list((at + joint) / 2),
                       'Rotation': [1.0, 0.0, 0.0, 0.0], **BODY_DEFAULTS})
        joints.append({'Name': f'{kind}{c.name}', 'Type': kind, 'Mirrored': True,
                       'Body1': fixed, 'Body2': c.name, 'Position': _list(at),
                       'Rotation': quaternion_z(axis)})
        if c.bushing is not None and c.type == 'circle':
            joints[-1]['Bushing Data'] = bushing_data(c.bushing, notes, c.name)
        joints.append({'Name': f'Spherical{c.name}', 'Type': 'Spherical', 'Mirrored': True,
                       'Body1': c.name, 'Body2': upright, 'Position': _list(joint),
                       'Rotation': [1.0, 0.0, 0.0, 0.0]})
    arms = [b['Name'] for b in bodies[1:]]
    return {'Independent': True, 'Steerable': scene.steered, 'Bodies': bodies,
            'Joints': joints, 'Distance Constraints': dists, 'TSDAs': elements,
            'Antiroll Body': arms[0] if arms else upright}


def same_axis(old, new) -> bool:
    """Whether two Chrono quaternions [w, x, y, z] turn z onto one line (either way, 1e-9)."""
    try:
        return abs(float(rotation(old)[:, 2] @ rotation(new)[:, 2])) > 1.0 - 1e-9
    except (TypeError, ValueError):
        return False


def _ident(value) -> str:
    """Return the body name of a Chrono body identifier ("Name" or ["Name", "Left"])."""
    if isinstance(value, list) and value and isinstance(value[0], str):
        return value[0]
    if isinstance(value, str):
        return value
    raise ChronoError('body identifier', f'expected a name or [name, side], got {value!r}')


def _list(v) -> list:
    return [float(x) for x in v]
