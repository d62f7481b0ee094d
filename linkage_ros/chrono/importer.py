# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Chrono::Vehicle suspension JSON -> a scene mapping (units m, left side), with notes.

The named templates map by templates.TEMPLATES; GenericWheeledSuspension by
generic.py. Springs and shocks become elements (a "Spring Coefficient" a rate, a
"Spring Curve Data" a force_table, Chrono's length stops bump and rebound stops, damping kept
as x_damping), "Bushing Data" a constraint's bushing. What has no place in a scene (masses,
inertias, a spring on a link body off the link's line) is named in the notes.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from .bushings import bushing_into
from .parts import mount_of, tsda_elements
from .reader import ChronoError, Fields
from .templates import (DESIGN_AXIS_M, GENERIC, KINGPIN, REFUSED, supported, TEMPLATES,
                        TRAVEL_M, WHEEL_RADIUS_M)
from ..core.base import spin_axis_of


class Imported(NamedTuple):
    """A scene mapping made from a Chrono file, and what was left out of it (one line each)."""

    scene: dict
    template: str
    notes: list


def import_suspension(data: dict, where: str, wheel_radius: float = WHEEL_RADIUS_M,
                      name: str = '', steered: bool = True) -> Imported:
    """
    Map a Chrono suspension file's object to a scene mapping (m, left side).

    steered: whether its tie rod follows a steering rack (steer: rack); a vehicle's axle
    without a "Steering Index" has its tie rod on the chassis.
    """
    top = Fields(where, data)
    kind = top.text('Type') if top.has('Type') else 'Suspension'
    if kind != 'Suspension':
        raise ChronoError(where, f'"Type": {kind!r} is not a suspension file')
    template = top.text('Template')
    if template in REFUSED:
        raise ChronoError(where, f'template {template} is not imported: {REFUSED[template]}')
    notes = []
    if template == GENERIC:
        from .generic import import_generic
        constraints, elements = import_generic(top, notes)
    elif template in TEMPLATES:
        constraints, elements = _named(top, TEMPLATES[template], notes)
    else:
        raise ChronoError(where, f'template {template} is not imported (solid axles and other '
                          f'templates are not independent corners); supported: {supported()}')
    if not steered:
        for item in constraints:
            item.pop('steer', None)
    center, spin = carrier_of(top)
    scene = {'name': name or _stem(where), 'description': f'Chrono::Vehicle {template}: '
             f'{top.text("Name") if top.has("Name") else _stem(where)}',
             'units': 'm', 'side': 'left', 'wheel_radius': float(wheel_radius),
             'carrier': {'wheel_center': center, 'spin_axis_point': spin},
             'constraints': constraints, 'travel': dict(TRAVEL_M)}
    if elements:
        scene['elements'] = elements
    if template in KINGPIN:
        scene['kingpin'] = KINGPIN[template]
    return Imported(scene, template, notes)


def carrier_of(top: Fields) -> tuple[list, list]:
    """Return (wheel centre, spin axis point) m: the spindle, its axis from camber and toe."""
    center = top.sub('Spindle').vector('COM')
    camber = math.radians(top.number('Camber Angle (deg)', 0.0))
    toe = math.radians(top.number('Toe Angle (deg)', 0.0))
    axis = spin_axis_of(camber, toe, 1.0)   # Chrono's left side
    return _list(center), _list(center - DESIGN_AXIS_M * axis)


def _named(top, template, notes):
    constraints, carried = [], {}
    for part in template.parts:
        obj = top.sub(part.key)
        if part.kind == 'arm':
            item = {'name': part.name, 'type': 'circle',
                    'axis': [_list(obj.vector('Location Chassis Front')),
                             _list(obj.vector('Location Chassis Back'))],
                    'carrier': _list(obj.vector('Location Upright'))}
        elif part.kind == 'strut':
            item = {'name': part.name, 'type': 'line',
                    'base': _list(obj.vector('Location Chassis')),
                    'carrier': _list(obj.vector('Location Upright'))}
        else:
            item = {'name': part.name, 'type': 'sphere',
                    'base': _list(obj.vector('Location Chassis')),
                    'carrier': _list(obj.vector('Location Upright'))}
            if part.steer:
                item['steer'] = 'rack'
        if part.kind == 'arm':
            bushing_into(item, obj, notes, part.name)
        elif obj.has('Bushing Data'):
            notes.append(f'{part.name}: its "Bushing Data" is not imported: ' + (
                "Chrono bushes the link body at both ends, a scene's link has one bushing at "
                'its base; the link is rigid here' if obj.has('Mass') else
                'Chrono uses it only for a link body with a "Mass" (here a distance)'))
        constraints.append(item)
        carried[part.name] = item
    elements = []
    for tsda in template.tsdas:
        if not top.has(tsda.key):
            continue
        obj = top.sub(tsda.key)
        body, point = obj.vector('Location Chassis'), obj.vector(tsda.point)
        mount = mount_of(carried.get(tsda.on), tsda.on, body, point, notes, tsda.key)
        if mount is not None:
            elements += tsda_elements(obj, tsda.key, body, mount, notes)
    return constraints, elements


def _list(v) -> list:
    return [float(x) for x in v]


def _stem(where: str) -> str:
    from pathlib import Path
    from ..core.model import safe_stem
    return safe_stem(Path(where).stem)
