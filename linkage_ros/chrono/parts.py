# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The parts of a Chrono file that every template shares: springs, shocks, bushings, mounts.

A TSDA (spring, shock or both) becomes scene elements: a "Spring Coefficient" a rate, a
"Spring Curve Data" a force_table (Chrono's sign turned: deflection L0 - L, force +
compressed), Chrono's length stops ("Minimum Length", "Maximum Length") bump and rebound
stops, a damping coefficient or curve kept as x_damping or x_damping_curve (bushings.py
has "Bushing Data"). m, N, N/m, N s/m.
"""

from __future__ import annotations

import numpy as np

from .reader import Fields
from ..core.base import MM_PER_M
from ..core.model import LINE_TOLERANCE

# Chrono's length stops (utils::SpringForce::enable_stops, "From ADAMS/Car example"): force
# (N) per penetration (m) past "Minimum Length" (bump) and "Maximum Length" (rebound).
BUMP = ((0.0, 0.0), (2e-3, 200.0), (4e-3, 400.0), (6e-3, 600.0), (8e-3, 800.0),
        (10e-3, 1000.0), (20e-3, 2500.0), (30e-3, 4500.0), (40e-3, 7500.0), (50e-3, 12500.0),
        (60e-3, 125000.0))
REBOUND = BUMP[:9]


def mount_of(item, on, body, point, notes, name):
    """
    Return an element's mount keys for a point on constraint item (None: the carrier).

    A point on a link body is kept only on the link's line (a scene's link has no turn about
    its line); off it, the element is left out with a note. A strut's own two points are
    the strut (along).
    """
    if item is None:
        return {'carrier': _list(point)}
    if item['type'] == 'circle':
        return {'arm': on, 'point': _list(point)}
    base, joint = np.array(item['base']), np.array(item['carrier'])
    if item['type'] == 'line':
        if np.allclose(body, base, atol=1e-12) and np.allclose(point, joint, atol=1e-12):
            return {'along': on}
        return {'carrier': _list(point)}
    span = joint - base
    off = np.linalg.norm(np.cross(point - base, span)) / (span @ span)
    if off > LINE_TOLERANCE:
        notes.append(f'{name}: not imported: its point on {on} is {off * np.linalg.norm(span):.3g}'
                     ' m off the line of that link (a link of a scene has no turn about its line)')
        return None
    return {'link': on, 'point': _list(point)}


def tsda_elements(obj: Fields, name: str, body, mount: dict, notes: list) -> list:
    """Return the elements of a Chrono spring, shock or spring-damper (TSDA) object."""
    spring = obj.has('Spring Coefficient') or obj.has('Spring Curve Data')
    damper = obj.has('Damping Coefficient') or obj.has('Damping Curve Data') \
        or obj.has('Map Data')
    ends = {'body': _list(body), **mount} if 'along' not in mount else dict(mount)
    out = []
    if spring:
        free = obj.number('Free Length')
        preload = obj.number('Preload', 0.0)
        item = {'name': f'{name}Spring' if damper else name, 'type': 'spring', **ends}
        if _idle(obj):   # a length only (the export writes a spring without a rate so)
            notes.append(f'{name}: "Spring Coefficient" 0 and no preload: a spring without a '
                         'rate (its length only)')
        elif not obj.has('Spring Curve Data'):   # Chrono: a curve wins over a coefficient
            rate = obj.number('Spring Coefficient')
            # Chrono's force P + k (L0 - L), compression +: the free length L0 + P / k
            item.update(rate=rate, free_length=free + (preload / rate if rate else 0.0))
        else:
            curve = obj.table('Spring Curve Data')
            # Chrono: force = P - f(L - L0); the table's deflection L0 - L, force + compressed
            item.update(free_length=free,
                        force_table=[[-d, preload - f] for d, f in curve[::-1]])
        out.append(item)
        if obj.has('Minimum Length') and obj.has('Maximum Length'):
            out.append({'name': f'{name}Bump', 'type': 'spring', **ends,
                        'free_length': obj.number('Minimum Length'),
                        'force_table': [list(r) for r in BUMP]})
            out.append({'name': f'{name}Rebound', 'type': 'spring', **ends,
                        'free_length': obj.number('Maximum Length'),
                        'force_table': [[-d, -f] for d, f in REBOUND[::-1]]})
    if damper:
        item = {'name': f'{name}Damper' if spring else name, 'type': 'damper', **ends}
        if obj.has('Map Data'):
            notes.append(f'{name}: its "Map Data" (force by speed and deformation) is not '
                         'imported: a damper without a coefficient')
        elif obj.has('Damping Coefficient'):
            item['x_damping'] = obj.number('Damping Coefficient')   # N s/m
        else:
            item['x_damping_curve'] = obj.table('Damping Curve Data').tolist()   # m/s, N
        out.append(item)
    if not out:
        notes.append(f'{name}: neither a spring nor a damper: not imported')
    return out


def _idle(obj: Fields) -> bool:
    """Whether obj's spring is "Spring Coefficient" 0 with no curve and no preload."""
    return obj.has('Spring Coefficient') and obj.number('Spring Coefficient') == 0.0 \
        and not obj.has('Spring Curve Data') and obj.number('Preload', 0.0) == 0.0


def length_stops(elements) -> tuple[dict, set]:
    """
    Return Chrono's length stops of a scene's springs, and the stop elements they fold.

    The import makes "Minimum Length" and "Maximum Length" two stops, <spring>Bump and
    <spring>Rebound, on the spring's points with Chrono's own curves; the export folds such
    a pair back: ({spring: {"Minimum Length": m, "Maximum Length": m}}, {stop names}).
    """
    by_name = {e.name: e for e in elements}
    limits, folded = {}, set()
    curves = {'Bump': np.array(BUMP), 'Rebound': -np.array(REBOUND)[::-1]}
    for e in elements:
        pair = [by_name.get(f'{e.name}{kind}') for kind in curves]
        if e.type != 'spring' or e.is_stop or None in pair:
            continue
        if all(s.force_table is not None and s.force_table.shape == c.shape
               and np.allclose(s.force_table / [MM_PER_M, 1.0], c, rtol=1e-12, atol=1e-12)
               and np.allclose(s.body, e.body) and np.allclose(s.mount.point, e.mount.point)
               for s, c in zip(pair, curves.values())):
            limits[e.name] = {'Minimum Length': pair[0].free_length / MM_PER_M,
                              'Maximum Length': pair[1].free_length / MM_PER_M}
            folded |= {s.name for s in pair}
    return limits, folded


def _list(v) -> list:
    return [float(x) for x in v]
