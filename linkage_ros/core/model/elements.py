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
      - {name: bump_stop, type: spring, body: [x, y, z], arm: lower_arm, point: [x, y, z],
         free_length: 300.0, force_table: [[0, 0], [10, 500], [20, 3000]]}

A spring has a rate (linear) or a force_table: rows [deflection, force] (scene units and N,
deflection free_length - length, + = compressed; force + = compressed), deflections rising,
at least two rows. Between rows the force is interpolated linearly and outside the table it
is held at the end rows' forces (as Chrono's ChFunctionInterp): its stiffness is the slope
of the segment. A bump stop is such a spring whose force is zero up to a deflection.

Coordinates, free_length and rate are in the scene's units (rate in N per unit of length:
N/mm in a mm scene, N/m in an m scene); everything is mm and N/mm once loaded. Their values
at solved positions (length, motion ratio, force, wheel rate) are measure/elements.py's.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math
from typing import TYPE_CHECKING

import numpy as np

from .mounts import KINDS, Mount, parse_mount
from ..base.force_table import table_force
from ..base.ranges import DOC as RANGES_DOC, RANGE, shown

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .constraint import Constraint

TYPES = ('spring', 'damper', 'length')
KEYS = ('name', 'type', 'body', 'point', 'rate', 'free_length', 'force_table') + tuple(KINDS)


@dataclass(frozen=True)
class Element:
    """A spring, damper or length between a body point and a mount. mm, N/mm."""

    name: str
    type: str             # noqa: A003 (the scene files' key)
    body: np.ndarray      # (3,) body point, vehicle frame, design position
    mount: Mount          # the moving-side point
    rate: float = math.nan          # N/mm (springs; NaN if not given)
    free_length: float = math.nan   # mm (springs; NaN if not given)
    # (n, 2) rows [deflection mm, force N] of a nonlinear spring (then rate is NaN)
    force_table: np.ndarray | None = None

    @property
    def has_rate(self) -> bool:
        """Whether force and wheel rate are defined (a spring with a rate or a force table)."""
        return not math.isnan(self.rate) or self.force_table is not None

    def spring_at(self, length: float) -> tuple[float, float, float]:
        """
        Return the spring's (force N, + = compressed; stiffness N/mm; energy N mm) at length.

        length mm. A rate: k (L0 - L), k, k (L0 - L)^2 / 2. A force table: the force
        interpolated at the deflection L0 - L and held outside the table, the slope of its
        segment (0 outside; base.table_force, which the kernels compile in too), and the
        integral of the force from deflection 0.
        """
        deflection = self.free_length - length
        if self.force_table is None:
            return self.rate * deflection, self.rate, 0.5 * self.rate * deflection ** 2
        d, f = (np.ascontiguousarray(column, float) for column in self.force_table.T)
        force, slope = table_force(d, f, float(deflection))
        return float(force), float(slope), _work(d, f, deflection) - _work(d, f, 0.0)

    @property
    def is_stop(self) -> bool:
        """Whether the element is a stop: a force table whose force is zero at either end."""
        table = self.force_table
        return table is not None and (table[0, 1] == 0.0 or table[-1, 1] == 0.0)

    def transformed(self, flip: ArrayLike, offset: ArrayLike) -> Element:
        """Return the element with every point p at p * flip + offset (mirror, translate)."""
        return replace(self, body=self.body * flip + offset,
                       mount=self.mount.transformed(flip, offset))


def _work(d: np.ndarray, f: np.ndarray, x: float) -> float:
    """Return the integral of the held, interpolated table force from d[0] to x (N mm)."""
    if x <= d[0]:
        return float(f[0] * (x - d[0]))
    k = int(np.searchsorted(d, x))   # d[k - 1] < x <= d[k], or k = len(d) past the end
    whole = float(np.sum(0.5 * (f[1:k] + f[:k - 1]) * np.diff(d[:k])))
    if k == len(d):
        return whole + float(f[-1] * (x - d[-1]))
    at = f[k - 1] + (f[k] - f[k - 1]) * (x - d[k - 1]) / (d[k] - d[k - 1])
    return whole + 0.5 * float(f[k - 1] + at) * (x - d[k - 1])


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
    # it starts the table columns, and a spring's pickup topic pickup/<name>_body
    name = check.token(item, 'name', f'{where}.name')
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
    table = _force_table(check, item, where, kind)
    rate, free_length = _spring(check, item, where, kind, table is not None)
    return Element(name=name, type=kind, body=body, mount=mount, rate=rate,
                   free_length=free_length, force_table=table)


def _force_table(check, item, where, kind):
    """
    Return a spring's force table (n, 2) in mm and N, or None if not given.

    Deflections are coordinates, forces and the slope of each segment within their stated
    ranges (base/ranges.py: coordinate, force_table_force, force_table_slope).
    """
    rows = item.get('force_table')
    if rows is None:
        return None
    field_name = f'{where}.force_table'
    if kind != 'spring':
        check.fail(field_name, f'only a spring has a force table (this is a {kind})')
    if item.get('rate') is not None:
        check.fail(field_name, 'give rate or force_table, not both')
    if not isinstance(rows, list) or len(rows) < 2:
        check.fail(field_name, 'expected at least two rows [deflection, force]')
    for i, row in enumerate(rows):
        if not isinstance(row, (list, tuple)) or len(row) != 2:
            check.fail(f'{field_name}[{i}]', f'expected a row [deflection, force], got '
                       f'{shown(row)}')
        for j, (key, kind_of) in enumerate((('deflection', 'coordinate'),
                                            ('force', 'force_table_force'))):
            check.ranged({key: row[j]}, key, f'{field_name}[{i}][{j}] ({key})', kind_of)
    table = np.array(rows, dtype=float)
    steps = np.diff(table[:, 0])
    if not np.all(steps > 0):
        i = int(np.argmin(steps > 0)) + 1
        check.fail(f'{field_name}[{i}]', f'deflection {table[i, 0]:g} does not rise above '
                   f'the row before ({table[i - 1, 0]:g}): the rows must be sorted by '
                   'deflection, each once')
    slope = RANGE['force_table_slope']
    for i, rise, run in zip(range(1, len(table)), np.diff(table[:, 1]), steps):
        value = float(rise) / float(run)   # N per file unit; inf past the float range
        if slope.problem(value, check.scale):
            said = (f'{value:g} {slope.unit_of(check.scale)}' if math.isfinite(value)
                    else 'beyond the float range')
            check.fail(f'{field_name}[{i}]', f'the segment from the row before rises '
                       f'{rise:g} N over {run:g} {_unit(check)}: a slope of {said}, outside '
                       f'{slope.said(check.scale)} ({RANGES_DOC})')
    return table * np.array([check.scale, 1.0])


def _unit(check):
    """Return the scene's unit of length ('mm' or 'm')."""
    return 'mm' if check.scale == 1.0 else 'm'


def _spring(check, item, where, kind, tabled=False):
    """Return (rate N/mm, free_length mm) of a spring, NaN, NaN if not given."""
    given = [key for key in ('rate', 'free_length') if item.get(key) is not None]
    if tabled:
        if 'free_length' not in given:
            check.fail(f'{where}.free_length', 'missing: a force table needs the free length '
                       'its deflections are measured from')
        return math.nan, check.ranged(item, 'free_length', f'{where}.free_length', 'height')
    if not given:
        return math.nan, math.nan
    if kind != 'spring':
        check.fail(f'{where}.{given[0]}', f'only a spring has a rate and a free length (this '
                   f'is a {kind})')
    if len(given) == 1:
        missing = ({'rate', 'free_length'} - set(given)).pop()
        check.fail(f'{where}.{missing}', 'missing: rate and free_length go together (the '
                   'force needs both)')
    return (check.ranged(item, 'rate', f'{where}.rate', 'spring_rate'),
            check.ranged(item, 'free_length', f'{where}.free_length', 'height'))
