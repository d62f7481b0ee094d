# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The kingpin as a scene declares it: two joints, real or virtual (a declaration; no solver).

A scene names its kingpin with the key `kingpin: [UPPER, LOWER]`, each entry a constraint name
(a circle's or sphere's carrier joint, a line's top mount) or a pair of link names (a virtual
ball joint), e.g. `kingpin: [[upper_front, upper_rear], [lower_front, lower_rear]]`. Without
the key, two circles or a circle and a line give the axis (measure/kingpin.kingpin_points);
other scenes have none. The parser (scene.py) keeps the checked key as Scene.kingpin.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from .yaml_file import SceneError
from ..base.errors import listed
from ..base.ranges import shown

if TYPE_CHECKING:
    from .constraint import Constraint

KEY = 'kingpin'


@dataclass(frozen=True)
class KingpinPoint:
    """
    One end of the kingpin: a joint of the scene, or the virtual joint of two links.

    constraints holds one index (a joint) or two (a pair of links); kind is 'carrier' (the
    constraint's carrier point), 'base' (a strut's top mount) or 'virtual'.
    """

    kind: str
    constraints: tuple[int, ...]


def check_kingpin(source: str, spec: object,
                  constraints: tuple[Constraint, ...]) -> tuple[KingpinPoint, KingpinPoint]:
    """Validate a scene's `kingpin` value; return its (upper, lower) points or raise."""
    names = {c.name: i for i, c in enumerate(constraints)}
    if not isinstance(spec, list) or len(spec) != 2:
        raise SceneError(source, KEY, 'expected [UPPER, LOWER]: two joint names, or pairs '
                         f'of link names for virtual ball joints, got {shown(spec)}')
    points = tuple(_point(source, f'{KEY}[{k}]', entry, names, constraints)
                   for k, entry in enumerate(spec))
    if points[0] == points[1]:
        raise SceneError(source, KEY, 'names the same joint twice: a kingpin needs two')
    return points


def _point(source, where, entry, names, constraints):
    if isinstance(entry, str):
        index = _index(source, where, entry, names)
        return KingpinPoint('base' if constraints[index].type == 'line' else 'carrier', (index,))
    if not isinstance(entry, list) or len(entry) != 2 or entry[0] == entry[1]:
        raise SceneError(source, where, 'expected a joint name or a pair of two link names '
                         f'[a, b], got {shown(entry)}')
    pair = tuple(_index(source, f'{where}[{k}]', name, names) for k, name in enumerate(entry))
    for k, index in enumerate(pair):
        if constraints[index].type != 'sphere':
            raise SceneError(source, f'{where}[{k}]', f'{entry[k]} is a '
                             f'{constraints[index].type}, not a link (sphere): a virtual ball '
                             'joint is where two link lines pass closest')
    return KingpinPoint('virtual', tuple(sorted(pair)))


def _index(source, where, name, names):
    if not isinstance(name, str) or name not in names:
        known = listed(names)
        raise SceneError(source, where, f'{shown(name)} is not a constraint of the scene '
                         f'(constraints: {known})')
    return names[name]
