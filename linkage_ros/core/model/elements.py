# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Force elements of a corner as a scene declares them: springs, dampers and plain lengths.

A scene may list elements, each between a body point and a point on the moving side
(mounts.py: on the carrier, on an arm, on a link's line, or along a strut):

    elements:
      - {name: damper, type: damper, body: [x, y, z], arm: lower_arm, point: [x, y, z]}
      - {name: spring, type: spring, body: [x, y, z], arm: lower_arm, point: [x, y, z],
         rate: 35.0, free_length: 320.0}
      - {name: strut, type: damper, along: strut}

Coordinates, free_length and rate are in the scene's units (rate in N per unit of length:
N/mm in a mm scene, N/m in an m scene); everything is mm and N/mm once loaded. Their values
at solved positions (length, motion ratio, force, wheel rate) are measure/elements.py's.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math
import re
from typing import TYPE_CHECKING

import numpy as np

from .mounts import KINDS, Mount, parse_mount

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .constraint import Constraint

TYPES = ('spring', 'damper', 'length')
KEYS = ('name', 'type', 'body', 'point', 'rate', 'free_length') + tuple(KINDS)
NAME = re.compile(r'^[A-Za-z][A-Za-z0-9_]*$')   # becomes the start of table column names


@dataclass(frozen=True)
class Element:
    """A spring, damper or length between a body point and a mount. mm, N/mm."""

    name: str
    type: str             # noqa: A003 (the scene files' key)
    body: np.ndarray      # (3,) body point, vehicle frame, design position
    mount: Mount          # the moving-side point
    rate: float = math.nan          # N/mm (springs; NaN if not given)
    free_length: float = math.nan   # mm (springs; NaN if not given)

    @property
    def has_rate(self) -> bool:
        """Whether force and wheel rate are defined (a spring with rate and free_length)."""
        return not math.isnan(self.rate)

    def transformed(self, flip: ArrayLike, offset: ArrayLike) -> Element:
        """Return the element with every point p at p * flip + offset (mirror, translate)."""
        return replace(self, body=self.body * flip + offset,
                       mount=self.mount.transformed(flip, offset))


def parse_elements(check, items: object,
                   constraints: tuple[Constraint, ...]) -> tuple[Element, ...]:
    """
    Read and validate a scene file's elements list (None: no elements).

    check is the scene parser's field reader (fields.Fields), so a mistake
    raises SceneError naming the file and the field.
    """
    if items is None:
        return ()
    if not isinstance(items, list):
        check.fail('elements', f'expected a list of elements, got {type(items).__name__}')
    elements = tuple(_parse_element(check, item, i, constraints) for i, item in enumerate(items))
    names = [e.name for e in elements]
    for i, name in enumerate(names):
        if name in names[:i]:
            check.fail(f'elements[{i}] ({name}).name', 'used twice: names make the table '
                       'columns, so each element needs its own')
    return elements


def _parse_element(check, item, index, constraints):
    where = f'elements[{index}]'
    if not isinstance(item, dict):
        check.fail(where, 'expected a mapping {name, type, body, and carrier, arm + point, '
                   'link + point or along}')
    name = item.get('name')
    if not isinstance(name, str) or not NAME.match(name):
        check.fail(f'{where}.name', f'expected a name of letters, digits and _ starting with a '
                   f'letter (it starts the table columns), got {name!r}')
    where = f'elements[{index}] ({name})'
    check.keys(item, KEYS, where)   # free keys (description, notes, x_...) pass
    kind = check.choice(item, 'type', TYPES, f'{where}.type')
    scale = check.scale
    mount, body = parse_mount(item, constraints, where, scale,
                              lambda key, field: check.point(item, key, field), check.fail)
    if body is None:
        body = check.point(item, 'body', f'{where}.body') * scale
    if np.linalg.norm(mount.point - body) <= 1e-9 * max(1.0, float(np.abs(body).max())):
        check.fail(where, 'the body point and the moving point coincide at design: an element '
                   'of zero length has no direction')
    rate, free_length = _spring(check, item, where, kind)
    return Element(name=name, type=kind, body=body, mount=mount, rate=rate,
                   free_length=free_length)


def _spring(check, item, where, kind):
    """Return (rate N/mm, free_length mm) of a spring, NaN, NaN if not given."""
    given = [key for key in ('rate', 'free_length') if item.get(key) is not None]
    if not given:
        return math.nan, math.nan
    if kind != 'spring':
        check.fail(f'{where}.{given[0]}', f'only a spring has a rate and a free length (this '
                   f'is a {kind})')
    if len(given) == 1:
        missing = ({'rate', 'free_length'} - set(given)).pop()
        check.fail(f'{where}.{missing}', 'missing: rate and free_length go together (the '
                   'force needs both)')
    unit = 'mm' if check.scale == 1.0 else 'm'
    values = []
    for key in given:
        value = check.number(item, key, f'{where}.{key}')
        if not value > 0:
            what = f'N/{unit}, a stiffness' if key == 'rate' else f'{unit}, a length'
            check.fail(f'{where}.{key}', f'must be positive ({what}), got {value!r}')
        values.append(value)
    return values[0] / check.scale, values[1] * check.scale
