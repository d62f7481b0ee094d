"""
Points on the moving parts of a corner: on the carrier, on an arm, on a link, on a strut.

A mount is where a spring, a damper or (later) an anti-roll bar's drop link is fixed to the
moving side of a suspension, given at design position in a scene file:

    carrier: [x, y, z]                 fixed in the wheel carrier
    arm: lower_arm, point: [x, y, z]   on a circle constraint's arm: turns with it about the
                                       arm's body-fixed axis (angle set by its ball joint)
    link: tie_rod, point: [x, y, z]    on a binary link (sphere): only on the link's line,
                                       at a fixed fraction of the way from body to carrier
    along: strut                       a strut's (line constraint's) carrier point: with the
                                       top mount as body point, the strut's own length

mount_motion gives the points' positions and their first and second derivatives with respect
to wheel travel, exact (motion.py), at n solved poses, compiled (element_kernel.py). mm,
vehicle frame.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from ..base.geometry import unit
from ..solve import element_kernel
from ..solve.element_kernel import ALONG, ARM, CARRIER, LINK, MountTable

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import ArrayLike

    from .motion import Rows
    from ..model.scene import Constraint, Scene
    from ..solve.element_kernel import Poses

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
    fail(where, f'no {what[wanted][2:].lstrip()} named {name!r} in the scene (its '
         f'{plural[wanted]}: {", ".join(fitting) or "none"})')


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


def mount_table(scene: Scene, mounts: Sequence[Mount]) -> MountTable:
    """Build the compiled kernels' table (element_kernel.MountTable) of mounts in a scene."""
    k = len(mounts)
    kind = np.empty(k, dtype=np.int64)
    offset, base, axis, coeff = (np.zeros((k, 3)) for _ in range(4))
    steer = np.zeros(k)
    codes = {'carrier': CARRIER, 'arm': ARM, 'link': LINK, 'along': ALONG}
    for j, mount in enumerate(mounts):
        kind[j] = codes[mount.kind]
        if mount.kind == 'carrier':
            offset[j] = mount.point - scene.wheel_center
            continue
        c = scene.constraints[mount.constraint]
        offset[j] = c.carrier - scene.wheel_center      # the joint moves the point
        if mount.kind == 'link':
            base[j] = c.base[0]
            coeff[j, 0] = ((mount.point - c.base[0]) @ (c.carrier - c.base[0])
                           / ((c.carrier - c.base[0]) @ (c.carrier - c.base[0])))
            steer[j] = 1.0 if c.steer == 'rack' else 0.0
        elif mount.kind == 'arm':
            # The arm's frame follows its joint: e1 along the joint's offset from the axis,
            # square to it; e2 = u x e1. The point keeps its design coordinates in (u, e1, e2).
            u = unit(c.base[1] - c.base[0])
            rho = c.carrier - c.base[0]
            e1 = unit(rho - (rho @ u) * u)
            q = mount.point - c.base[0]
            base[j], axis[j] = c.base[0], u
            coeff[j] = (q @ u, q @ e1, q @ np.cross(u, e1))
    return MountTable(kind, offset, base, axis, coeff, steer)


def mount_motion(rows: Rows, table: MountTable,
                 poses: Poses) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Return the mounts' positions (mm), d/dtravel (mm/mm), d2/dtravel2 (1/mm), (n, k, 3) each.

    rows: motion.guidance_rows; table: mount_table; poses: motion.pose_batch. Exact: the
    carrier's motion to second order (motion.py), then an arm's angle rates from its joint:
    theta' = (u x rho) . C' / |u x rho|^2, theta'' likewise with C''.
    """
    points = np.empty((len(poses.center), len(table.kind), 3, 3))
    element_kernel.mounts_many(element_kernel.pack_rows(rows), element_kernel.pack_elements(table),
                               tuple(poses), points)
    return points[:, :, 0], points[:, :, 1], points[:, :, 2]
