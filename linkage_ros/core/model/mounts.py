# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Points on the moving parts of a corner, as a scene declares them (a declaration; no solver).

A mount is where a spring, a damper or an anti-roll bar's drop link is fixed to the moving
side of a suspension, given at design position in a scene file:

    carrier: [x, y, z]                 fixed in the wheel carrier
    arm: lower_arm, point: [x, y, z]   on a circle constraint's arm: turns with it about the
                                       arm's body-fixed axis (angle set by its ball joint)
    link: tie_rod, point: [x, y, z]    on a binary link (sphere): only on the link's line,
                                       at a fixed fraction of the way from body to carrier
    along: strut                       a strut's (line constraint's) carrier point: with the
                                       top mount as body point, the strut's own length

Their motion at solved poses is measured in measure/mounts.py. mm, vehicle frame.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from ..base.errors import listed
from ..base.ranges import shown

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .constraint import Constraint

KINDS = {'carrier': None, 'arm': 'circle', 'link': 'sphere', 'along': 'line'}
# A point given on a link may lie this far (relative to the link length) off the link's
# line, as typed coordinates rounded to 0.1 mm do; it is then projected onto the line.
LINE_TOLERANCE = 1e-3


@dataclass(frozen=True)
class Mount:
    """
    A point on the moving side, at design position (mm, vehicle frame).

    kind: 'carrier', 'arm', 'link' or 'along'; constraint: index into scene.constraints (-1
    for the carrier); point (3,): the point at design (for 'link' projected onto the line,
    for 'along' the strut's carrier point).
    """

    kind: str
    point: np.ndarray
    constraint: int = -1

    def transformed(self, flip: ArrayLike, offset: ArrayLike) -> Mount:
        """Return the mount with its point p moved to p * flip + offset (mirror, translate)."""
        return replace(self, point=self.point * flip + offset)


def parse_mount(item: dict, constraints: tuple[Constraint, ...], where: str, scale: float,
                read_point, fail) -> tuple[Mount, np.ndarray | None]:
    """
    Read the moving-side point of an element (or a drop link) from its mapping.

    read_point(key, field) -> (3,) scene units and fail(field, problem) come from the scene
    parser, so mistakes name the file and field. Returns (Mount, implied body point or None:
    along a strut the body point is its top mount).
    """
    given = [k for k in KINDS if k in item]
    if len(given) != 1:
        fail(where, 'give exactly one of carrier: [x, y, z], arm: NAME with point, link: '
             f'NAME with point, or along: NAME (got {", ".join(given) or "none"})')
    kind = given[0]
    if kind == 'carrier':
        if 'point' in item:
            fail(f'{where}.point', 'a carrier point is given by carrier: [x, y, z] alone')
        return Mount('carrier', read_point('carrier', f'{where}.carrier') * scale), None
    name = item[kind]
    index = _constraint_index(constraints, name, KINDS[kind], f'{where}.{kind}', fail)
    c = constraints[index]
    if kind == 'along':
        if 'point' in item or 'body' in item:
            fail(where, f'along: {name} takes both ends from the strut (its top mount and its '
                 'carrier point); leave out body and point')
        return Mount('along', c.carrier.copy(), index), c.base[0].copy()
    point = read_point('point', f'{where}.point') * scale
    if kind == 'link':
        point = _on_link(c, point, f'{where}.point', scale, fail)
    return Mount(kind, point, index), None


def _constraint_index(constraints, name, wanted, where, fail):
    """Return the index of the constraint called name, of type wanted; else fail naming both."""
    what = {'circle': 'an arm (circle)', 'sphere': 'a link (sphere)', 'line': 'a strut (line)'}
    plural = {'circle': 'arms', 'sphere': 'links', 'line': 'struts'}
    fitting = [c.name for c in constraints if c.type == wanted]
    for i, c in enumerate(constraints):
        if c.name == name:
            if c.type != wanted:
                key = {v: k for k, v in KINDS.items()}[c.type]
                fail(where, f'{name} is {what[c.type]}, not {what[wanted]}: use '
                     f'{key}: {name}')
            return i
    fail(where, f'no {what[wanted][2:].lstrip()} named {shown(name)} in the scene (its '
         f'{plural[wanted]}: {listed(fitting) or "none"})')


def _on_link(c, point, where, scale, fail):
    """Return point projected onto the line of link c; fail if it is off the line."""
    base, end = c.base[0], c.carrier
    length = float(np.linalg.norm(end - base))
    s = float((point - base) @ (end - base)) / length**2
    off = float(np.linalg.norm(point - (base + s * (end - base))))
    if off > LINE_TOLERANCE * length:
        unit = 'mm' if scale == 1.0 else 'm'
        fail(where, f'{off / scale:.4g} {unit} off the line of link {c.name} (a binary link '
             'turns freely about its line, so only points on the line have a defined motion; '
             f'allowed: {LINE_TOLERANCE * length / scale:.3g} {unit}, {LINE_TOLERANCE:g} of '
             'its length)')
    return base + s * (end - base)
