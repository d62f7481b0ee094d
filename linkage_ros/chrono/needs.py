# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
What Chrono's readers ask of a suspension file, as data, and a check of an object against it.

Every export is checked before it is written, so that what linkage-chrono writes is a file
Chrono reads (an --like original lacking a field Chrono asks for is refused, naming it).
The tables follow the readers (projectchrono/chrono src/chrono_vehicle/wheeled_vehicle/
suspension/<Template>.cpp, Create(); ChPart::Create; ChUtilsJSON.cpp ReadBushingDataJSON,
ReadTSDAFunctorJSON, ReadJointTypeJSON): a field they read without HasMember is needed. Kinds:
n a number, v three numbers, q four numbers (a quaternion), s a string, b a boolean, id a body
identifier (a name or [name, side]), tsda a spring or damper's force fields.
"""

from __future__ import annotations

import math

from .reader import ChronoError

SPINDLE = {'Mass': 'n', 'COM': 'v', 'Inertia': 'v', 'Radius': 'n', 'Width': 'n'}
BODY = {'Mass': 'n', 'COM': 'v', 'Inertia': 'v', 'Radius': 'n'}
BODY_PRODUCTS = {'Mass': 'n', 'COM': 'v', 'Moments of Inertia': 'v',
                 'Products of Inertia': 'v', 'Radius': 'n'}
ARM = {'Location Chassis Front': 'v', 'Location Chassis Back': 'v', 'Location Upright': 'v'}
LINK = {'Location Chassis': 'v', 'Location Upright': 'v'}
UNIVERSAL = {'Universal Joint Axis Link': 'v', 'Universal Joint Axis Chassis': 'v'}
AXLE = {'Inertia': 'n'}


def _tsda(point: str) -> dict:
    return {'Location Chassis': 'v', point: 'v', '': 'tsda'}


NEEDS = {
    'DoubleWishbone': {
        'Spindle': SPINDLE, 'Upright': BODY_PRODUCTS,
        'Upper Control Arm': {**BODY_PRODUCTS, **ARM},
        'Lower Control Arm': {**BODY_PRODUCTS, **ARM}, 'Tierod': LINK,
        'Spring': _tsda('Location Arm'), 'Shock': _tsda('Location Arm'), 'Axle': AXLE},
    'DoubleWishboneReduced': {
        'Spindle': SPINDLE, 'Upright': BODY, 'Upper Control Arm': ARM,
        'Lower Control Arm': ARM, 'Tierod': LINK, 'Shock': _tsda('Location Upright'),
        'Axle': AXLE},
    'MacPhersonStrut': {
        'Spindle': SPINDLE, 'Upright': BODY, 'Control Arm': {**BODY, **ARM},
        'Strut': {'Mass': 'n', 'Inertia': 'v', 'Radius': 'n'}, 'Tierod': LINK,
        'Spring': _tsda('Location Upright'), 'Shock': _tsda('Location Upright'), 'Axle': AXLE},
    'MultiLink': {
        'Spindle': SPINDLE, 'Upright': BODY, 'Upper Arm': {**BODY, **ARM},
        'Lateral': {**BODY, **LINK, **UNIVERSAL}, 'Trailing Link': {**BODY, **LINK, **UNIVERSAL},
        'Tierod': LINK, 'Spring': _tsda('Location Link'), 'Shock': _tsda('Location Link'),
        'Axle': AXLE},
    'GenericWheeledSuspension': {
        '': {'Steerable': 'b', 'Independent': 'b'},
        'Spindle': {**SPINDLE, 'Attachment Body': 'id'}, 'Axle': AXLE},
}
# GenericWheeledSuspension's lists: the fields of each item
LISTS = {
    'Bodies': {'Name': 's', 'Mirrored': 'b', 'Position': 'v', 'Rotation': 'q', 'Mass': 'n',
               'Moments of Inertia': 'v', 'Products of Inertia': 'v'},
    'Joints': {'Name': 's', 'Mirrored': 'b', 'Type': 's', 'Body1': 'id', 'Body2': 'id',
               'Position': 'v', 'Rotation': 'q'},
    'Distance Constraints': {'Name': 's', 'Mirrored': 'b', 'Body1': 'id', 'Body2': 'id',
                             'Point1': 'v', 'Point2': 'v'},
    'TSDAs': {'Name': 's', 'Mirrored': 'b', 'Body1': 'id', 'Body2': 'id', 'Point1': 'v',
              'Point2': 'v', '': 'tsda'},
}
JOINT_TYPES = ('Lock', 'Point Line', 'Point Plane', 'Revolute', 'Spherical', 'Universal')
FIXED_BODIES = ('Chassis', 'Subchassis', 'Steering')
BUSHING = ('Stiffness Linear', 'Damping Linear', 'Stiffness Rotational', 'Damping Rotational')
SIZES = {'v': 3, 'q': 4}


def check_chrono(data: dict, where: str) -> None:
    """Raise a ChronoError naming the first field Chrono's reader would miss in data."""
    _need(data, {'Type': 's', 'Template': 's', 'Name': 's'}, '', where)   # ChPart::Create
    if data['Type'] != 'Suspension' or data['Template'] not in NEEDS:
        raise ChronoError(where, f'"Type" {data["Type"]!r}, "Template" {data["Template"]!r}: '
                          f'not a suspension of the templates linkage-chrono writes '
                          f'({", ".join(NEEDS)})')
    for key, fields in NEEDS[data['Template']].items():
        obj = data if not key else data.get(key)
        if not isinstance(obj, dict):
            raise ChronoError(where, f'"{key}": expected an object {{...}}, Chrono\'s '
                              f'{data["Template"]} reader asks for it')
        _need(obj, fields, f'"{key}" / ' if key else '', where)
        if 'Bushing Data' in obj:
            _bushing(obj['Bushing Data'], f'"{key}" / ', where)
        if key == 'Tierod' and 'Mass' in obj:   # a tie rod body
            _need(obj, {'Mass': 'n', 'Inertia': 'v', 'Radius': 'n'}, '"Tierod" / ', where)
    if data['Template'] == 'GenericWheeledSuspension':
        _generic(data, where)


def _generic(data: dict, where: str) -> None:
    names = set(FIXED_BODIES)
    for key, fields in LISTS.items():
        items = data.get(key, [])
        if not isinstance(items, list):
            raise ChronoError(where, f'"{key}": expected an array [...]')
        for i, item in enumerate(items):
            field = f'"{key}"[{i}] / '
            if not isinstance(item, dict):
                raise ChronoError(where, f'"{key}"[{i}]: expected an object {{...}}')
            _need(item, fields, field, where)
            if key == 'Bodies':
                names.add(item['Name'])
            if key == 'Joints' and item['Type'] not in JOINT_TYPES:
                raise ChronoError(where, f'{field}"Type": {item["Type"]!r} is none of '
                                  f'{", ".join(JOINT_TYPES)}')
            if key == 'Joints' and isinstance(item.get('Bushing Data'), dict):
                _bushing(item['Bushing Data'], field, where)
    bodies = [(f'"{key}"[{i}] / "{end}"', item[end]) for key in LISTS if key != 'Bodies'
              for i, item in enumerate(data.get(key, [])) for end in ('Body1', 'Body2')]
    bodies += [('"Spindle" / "Attachment Body"', data['Spindle']['Attachment Body'])]
    if data['Independent']:
        _need(data, {'Antiroll Body': 'id'}, '', where)
        bodies.append(('"Antiroll Body"', data['Antiroll Body']))
    for field, ident in bodies:
        name = ident[0] if isinstance(ident, list) else ident
        if name not in names:
            raise ChronoError(where, f'{field}: no body {name!r} (the "Bodies", or '
                              f'{", ".join(FIXED_BODIES)})')


def _need(obj: dict, fields: dict, path: str, where: str) -> None:
    for key, kind in fields.items():
        if kind == 'tsda':
            _force(obj, path, where)
            continue
        if key not in obj:
            raise ChronoError(where, f'{path}"{key}": missing (Chrono\'s reader asks for it)')
        if not _is(obj[key], kind):
            raise ChronoError(where, f'{path}"{key}": expected {WHAT[kind]}, got '
                              f'{str(obj[key])[:40]}')


def _force(obj: dict, path: str, where: str) -> None:
    """Check a TSDA's force fields as ReadTSDAFunctorJSON picks its kind."""
    spring = 'Spring Coefficient' in obj or 'Spring Curve Data' in obj
    if not (spring or {'Damping Coefficient', 'Damping Curve Data', 'Map Data'} & set(obj)):
        raise ChronoError(where, f'{path}no "Spring Coefficient", "Damping Coefficient" or '
                          'curve (Chrono: "Unsupported TSDA element")')
    if 'Map Data' in obj:
        deformation = obj.get('Deformation')
        rows = obj['Map Data']
        if not (isinstance(deformation, list) and deformation and all(
                _is(d, 'n') for d in deformation) and _rows(rows, len(deformation) + 1)):
            raise ChronoError(where, f'{path}"Map Data": expected rows of a speed and one '
                              'force per "Deformation"')
        return
    if spring:
        _need(obj, {'Free Length': 'n'}, path, where)
    for key, kind in (('Spring Coefficient', 'n'), ('Damping Coefficient', 'n'),
                      ('Preload', 'n'), ('Minimum Length', 'n'), ('Maximum Length', 'n')):
        if key in obj:
            _need(obj, {key: kind}, path, where)
    for key in ('Spring Curve Data', 'Damping Curve Data'):
        if key in obj and not _rows(obj[key], 2):
            raise ChronoError(where, f'{path}"{key}": expected rows [x, y]')


def _bushing(data, path: str, where: str) -> None:
    """Check a "Bushing Data" as ReadBushingDataJSON reads it."""
    if not isinstance(data, dict):
        raise ChronoError(where, f'{path}"Bushing Data": expected an object {{...}}')
    _need(data, dict.fromkeys(BUSHING, 'n'), f'{path}"Bushing Data" / ', where)
    if 'DOF' in data:
        if not isinstance(data['DOF'], dict):
            raise ChronoError(where, f'{path}"Bushing Data" / "DOF": expected an object {{...}}')
        _need(data['DOF'], dict.fromkeys(BUSHING, 'n'), f'{path}"Bushing Data" / "DOF" / ',
              where)


def _rows(rows, size: int) -> bool:
    return isinstance(rows, list) and bool(rows) and all(
        isinstance(r, list) and len(r) == size and all(_is(v, 'n') for v in r) for r in rows)


def _is(value, kind: str) -> bool:
    if kind == 'n':
        return isinstance(value, (int, float)) and not isinstance(value, bool) \
            and math.isfinite(value)
    if kind in SIZES:
        return isinstance(value, list) and len(value) == SIZES[kind] \
            and all(_is(v, 'n') for v in value)
    if kind == 's':
        return isinstance(value, str)
    if kind == 'b':
        return isinstance(value, bool)
    return isinstance(value, str) or (isinstance(value, list) and bool(value)
                                      and isinstance(value[0], str))   # id


WHAT = {'n': 'a finite number', 'v': 'three numbers [x, y, z]', 'q': 'four numbers [w, x, y, z]',
        's': 'a string', 'b': 'true or false', 'id': 'a body name'}
