# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Bushings both ways: a scene's bushing as Chrono's "Bushing Data" and springs, and back.

Chrono (ChJoint::CreateBushing, ReadBushingDataJSON) replaces a joint by one bushing at the
joint's frame: "Stiffness Linear" (N/m) in every direction, "Stiffness Rotational" (N m/rad)
on the turns the joint would hold and "DOF" "Stiffness Rotational" on those it frees (a
revolute's own axis, z). A scene's bushing (model/bushing.py) has an axial and a radial rate,
N/mm, and an arm's at one place (at: centre) or at each pivot (at: pivots). So:

- the isotropic part, the smaller of axial and radial, is the joint's "Bushing Data";
  conical and torsion (N m/deg) its "Stiffness Rotational" and "DOF" "Stiffness Rotational";
- the rest is linear springs (TSDAs) from the fixed body to the bushing's point: one along
  the axis with axial - radial, or two across it (at right angles) with radial - axial,
  named <body>_bushing_<place>_<axial|radial1|radial2>, free at their design length, so that
  they hold nothing at design and add the rate in their direction (to first order, which is
  what a bushing's linear rates are);
- an arm at: pivots is a body with a revolute joint at each pivot, each with its bushing.

The named templates have one bushing per arm at the middle of its axis (isotropic) and bush
a tie rod at both ends: named_misfit says what they cannot hold, and such a scene goes out as
GenericWheeledSuspension. The import folds the springs back (fold_springs) when they have
exactly that shape; any other spring stays a spring.
"""

from __future__ import annotations

import math
import re

import numpy as np

from .reader import Fields
from ..core.base import MM_PER_M, unit

SPRING_M = 0.1   # a bushing spring's length (m): its direction is what counts
SPRING_NAME = re.compile(r'^(?P<body>.+)_bushing_(?P<place>centre|axis0|axis1|base)_'
                         r'(?P<way>axial|radial1|radial2)$')
SPRING_KEYS = {'Name', 'Mirrored', 'Body1', 'Body2', 'Point1', 'Point2', 'Free Length',
               'Spring Coefficient'}
ALONG, ACROSS = 1.0 - 1e-12, 1e-9   # cosines: a spring along the axis, across it (at design)
ZERO = {'Stiffness Linear': 0.0, 'Damping Linear': 0.0, 'Stiffness Rotational': 0.0,
        'Damping Rotational': 0.0}


def named_misfit(c) -> str:
    """Return why a named template's "Bushing Data" cannot hold c's bushing ('' if it can)."""
    b = c.bushing
    if b is None:
        return ''
    if c.type != 'circle':
        return ("a link's bushing at its base (a named template bushes a tie rod body at "
                'both ends)')
    if b.at != 'centre':
        return 'at: pivots (a named template has one bushing, at the middle of the axis)'
    if b.axial != b.radial:
        return (f'axial {b.axial:g} and radial {b.radial:g} N/mm (a named template has one '
                'linear stiffness)')
    return ''


def bushing_data(c) -> dict:
    """Return Chrono's "Bushing Data" (N/m, N m/rad) of c's bushing: its isotropic part."""
    b = c.bushing
    out = {**ZERO, 'Stiffness Linear': min(b.axial, b.radial) * MM_PER_M, 'DOF': dict(ZERO)}
    if c.type == 'circle':   # a link turns freely about its ball joints: no rotational rate
        out['Stiffness Rotational'] = math.degrees(b.conical)
        out['DOF']['Stiffness Rotational'] = math.degrees(b.torsion)
    return out


def places(c) -> list:
    """Return [(place, point mm)] of constraint c's bushings (a link: its base)."""
    if c.type != 'circle':
        return [('base', c.base[0])]
    if c.bushing is None or c.bushing.at == 'centre':
        return [('centre', 0.5 * (c.base[0] + c.base[1]))]
    return [('axis0', c.base[0]), ('axis1', c.base[1])]


def bushing_springs(c, fixed: str) -> list:
    """Return the TSDAs (m, N/m) that give c's bushing its axial or radial excess."""
    b = c.bushing
    axis = unit(c.base[1] - c.base[0] if c.type == 'circle' else c.carrier - c.base[0])
    excess = (b.axial - b.radial) * MM_PER_M   # N/m
    if excess == 0.0:
        return []
    ways = [('axial', axis)] if excess > 0 else list(zip(('radial1', 'radial2'), across(axis)))
    out = []
    for place, at in places(c):
        end = [float(v) / MM_PER_M for v in at]
        for way, e in ways:
            start = [p + SPRING_M * float(d) for p, d in zip(end, e)]
            out.append({'Name': f'{c.name}_bushing_{place}_{way}', 'Mirrored': True,
                        'Body1': fixed, 'Body2': c.name, 'Point1': start, 'Point2': end,
                        'Free Length': float(np.linalg.norm(np.subtract(start, end))),
                        'Spring Coefficient': abs(excess)})
    return out


def across(axis) -> tuple:
    """Return two unit vectors at right angles to axis and to each other."""
    helper = np.array([0.0, 0.0, 1.0]) if abs(axis[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    first = unit(np.cross(axis, helper))
    return first, np.cross(axis, first)


def bushing_into(item: dict, obj: Fields, notes: list, name: str) -> None:
    """
    Give item a bushing from its object's "Bushing Data" (N/m, N m/rad; m scene).

    K_lin -> axial and radial; an arm's K_rot -> conical and DOF K_rot -> torsion, N m/deg,
    at: centre (Chrono's one bushing at the middle of the axis; fold_springs and the generic
    import make the rest). A link takes axial and radial only: a rotational rate of its
    bushing is named in a note. No linear stiffness: the joint stays rigid (a note).
    """
    if not obj.has('Bushing Data'):
        return
    data = obj.sub('Bushing Data')
    linear = data.number('Stiffness Linear')
    rotational = data.number('Stiffness Rotational')
    dof = data.sub('DOF').number('Stiffness Rotational') if data.has('DOF') else 0.0
    if not linear > 0:
        notes.append(f'{name}: "Bushing Data" with "Stiffness Linear" {linear:g}: a rigid '
                     'joint is used')
        return
    bushing = {'axial': linear, 'radial': linear}
    if item['type'] == 'circle':
        bushing.update(torsion=math.radians(dof) if dof > 0 else 0.0,
                       conical=math.radians(rotational) if rotational > 0 else 0.0, at='centre')
    elif rotational > 0 or dof > 0:
        notes.append(f"{name}: its bushing's rotational stiffness ({rotational:g}, DOF "
                     f'{dof:g} N m/rad) is not imported: a link turns freely about its ends')
    item['bushing'] = bushing


def fold_springs(tsdas: list, bushed: dict, notes: list) -> set:
    """
    Fold the springs bushing_springs wrote back into their bushings; return their indices.

    tsdas: the file's TSDA objects (Fields); bushed: {body name: (scene item, fixed body,
    {place: point (3,) m})} of the bodies with a bushing. A body's springs fold only when
    they are exactly bushing_springs' shape (every place, one rate, along or across the axis,
    free at design); else they stay springs, and a note says so.
    """
    groups = {}
    for i, tsda in enumerate(tsdas):
        name = tsda.data.get('Name')
        match = SPRING_NAME.match(name) if isinstance(name, str) else None
        if match and match['body'] in bushed:
            groups.setdefault(match['body'], []).append((i, match['place'], match['way'], tsda))
    folded = set()
    for body, rows in groups.items():
        item, fixed, at = bushed[body]
        ends = item['axis'] if item['type'] == 'circle' else (item['base'], item['carrier'])
        axis = unit(np.subtract(ends[1], ends[0]))
        rate = _excess(rows, axis, fixed, at, body)
        if rate is None:
            notes.append(f"{body}: springs named as its bushing's parts but not of their shape:"
                         ' imported as springs')
            continue
        way = 'axial' if rows[0][2] == 'axial' else 'radial'
        item['bushing'][way] += rate
        folded |= {row[0] for row in rows}
    return folded


def _excess(rows, axis, fixed, at, body):
    """Return the one rate (N/m) of a body's bushing springs, or None if they are not that."""
    ways = {way for _, _, way, _ in rows}
    if ways not in ({'axial'}, {'radial1', 'radial2'}) \
            or sorted((p, w) for _, p, w, _ in rows) != sorted((p, w) for p in at for w in ways):
        return None
    rates, directions = set(), {}
    for _, place, way, tsda in rows:
        data = tsda.data
        if set(data) - SPRING_KEYS or not {'Free Length', 'Spring Coefficient'} <= set(data) \
                or data.get('Body1') != fixed or data.get('Body2') != body:
            return None
        start, end = tsda.vector('Point1'), tsda.vector('Point2')
        length = float(np.linalg.norm(start - end))
        rate = tsda.number('Spring Coefficient')
        if not (rate > 0 and length > 0 and np.allclose(end, at[place], rtol=0.0, atol=1e-12)
                and abs(length - tsda.number('Free Length')) <= 1e-12 * max(1.0, length)):
            return None
        e = (start - end) / length
        if abs(e @ axis) < ALONG if way == 'axial' else abs(e @ axis) > ACROSS:
            return None
        directions[place, way] = e
        rates.add(rate)
    if len(rates) != 1 or ('radial1' in ways and any(
            abs(directions[p, 'radial1'] @ directions[p, 'radial2']) > ACROSS for p in at)):
        return None
    return rates.pop()
