# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Bushings of a scene's arms and links as the file declares them (issue 29; a declaration).

    - {name: lower_arm, type: circle, axis: [...], carrier: [...],
       bushing: {axial: 1500, radial: 6000, torsion: 0.5, conical: 0.0, at: pivots}}
    - {name: tie_rod, type: sphere, base: [...], carrier: [...],
       bushing: {axial: 3000, radial: 3000}}

axial and radial are in N per scene unit of length (N/mm in a mm scene, N/m in an m scene),
N/mm once loaded; torsion and conical in N m/deg in every scene; each within its stated
range (base/ranges.py, doc/scenes.md#ranges). An arm (circle) takes one
bushing at each pivot (at: pivots) or one at the pivots' midpoint (at: centre); a link
(sphere) one at its base. A strut (line) takes none. The statics that use them are
core/statics; this module is read only by a scene that declares a bushing.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..base.ranges import shown

KEYS = ('axial', 'radial', 'torsion', 'conical', 'at')
PLACES = ('pivots', 'centre')
TAKES = ('circle', 'sphere')


@dataclass(frozen=True)
class Bushing:
    """A linear bushing: rates N/mm (axial, radial) and N m/deg (torsion, conical)."""

    axial: float          # N/mm along the pivot axis (arm) or the link (link)
    radial: float         # N/mm across it
    torsion: float = 0.0  # N m/deg about the pivot axis (arms only), per bushing
    conical: float = 0.0  # N m/deg about the two radial directions (arms only)
    at: str = 'pivots'    # arms: 'pivots' (one at each axis point) or 'centre' (midpoint)


def parse_bushing(check, item: object, where: str, kind: str) -> Bushing:
    """
    Read and validate a constraint's bushing mapping; check is the scene's fields.Fields.

    where: the constraint's field path ('constraints[1] (lower_arm)'); kind its type. A
    mistake raises SceneError naming the file, the constraint and the field; a rate outside
    its stated range (base.ranges: bushing_rate, bushing_angular_rate) is one. An empty
    bushing (`bushing:` or `bushing: null`) is refused too: a rigid joint leaves the key out.
    """
    where = f'{where}.bushing'
    if item is None:
        check.fail(where, 'empty (null): give {axial, radial} (an arm also torsion, conical, '
                   'at), or leave the key out for a rigid joint')
    if kind not in TAKES:
        check.fail(where, f'a {kind} takes no bushing (only an arm, circle, or a link, '
                   'sphere: a strut top mount is rigid)')
    if not isinstance(item, dict):
        check.fail(where, 'expected a mapping {axial, radial, torsion, conical, at}')
    check.keys(item, KEYS, where)
    unit = 'mm' if check.scale == 1.0 else 'm'
    rates = {}
    for key in ('axial', 'radial'):
        if item.get(key) is None:
            check.fail(f'{where}.{key}', f'missing (required, N/{unit})')
        rates[key] = check.ranged(item, key, f'{where}.{key}', 'bushing_rate')   # N/mm
    for key in ('torsion', 'conical'):
        rates[key] = check.ranged(item, key, f'{where}.{key}', 'bushing_angular_rate', 0.0)
    at = item.get('at', 'pivots')
    if at not in PLACES:
        check.fail(f'{where}.at', f'unknown value {shown(at)} (expected one of: pivots, '
                   'centre)')
    if kind == 'sphere' and ('at' in item or rates['torsion'] or rates['conical']):
        key = 'at' if 'at' in item else ('torsion' if rates['torsion'] else 'conical')
        check.fail(f'{where}.{key}', 'only an arm (circle) takes it: a link turns freely '
                   'about its ball joints, so its bushing has axial and radial only')
    return Bushing(at=at, **rates)
