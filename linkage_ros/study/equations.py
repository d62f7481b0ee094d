"""
The guidance equations as functions of the hardpoints, for values and for derivatives.

mechanism.compile_scene builds one mechanism's equation table from its Scene; here the same
arithmetic is written on the hardpoint array H (..., k, 3) mm (hardpoints.py's order), so
that it runs on numpy arrays batched over mechanism variants (the tolerance study) and on
jets.Jet values carrying d/dH (exact sensitivities). The formulas are kernel.linearize's:

    sphere row: F = (|d|^2 - l^2) / 2l,  d = M + R r - A - rack e_y steer,  l = |b - A|
    line row:   F = (T - M - R r) . (R n0)
    r = b - M0, the row's carrier point b relative to the design wheel centre M0.

Layout, the scene's row map, is fixed by the scene's constraint types; the geometry follows
H. Poses (M (..., 3), R (..., 3, 3)) broadcast against the rows as the leading axes allow.
"""

from __future__ import annotations

from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from . import jets as jt
from .hardpoints import point_names
from ..core.solve import kernel

if TYPE_CHECKING:
    from ..core.model import Scene

E_Y = np.array([0.0, 1.0, 0.0])
FREE = list(kernel.FREE)
# line_normals' test: the spin axis helps build a strut's normals unless nearly parallel
HELPER_SINE = 0.1


class Layout(NamedTuple):
    """A scene's rows as indices into its hardpoints, in compile_scene's row order."""

    carrier: np.ndarray   # (5,) int: hardpoint of the row's carrier point
    base: np.ndarray      # (5,) int: hardpoint of its body point (A, an axis point, T)
    line: np.ndarray      # (5,) bool: a strut line row
    normal: np.ndarray    # (5,) int: which of the strut's two normals (line rows)
    steer: np.ndarray     # (5,) 1.0 where the body point moves with the rack
    center: int           # hardpoint index of wheel_center
    spin: int             # hardpoint index of spin_axis_point


class Geometry(NamedTuple):
    """The equation rows of one design or of many (leading axes), arrays or Jets, mm."""

    center0: object   # (..., 3) design wheel centre M0
    spin_axis: object  # (..., 3) design outboard spin-axis unit vector
    offset: object    # (..., 5, 3) carrier point minus M0
    base: object      # (..., 5, 3) body point
    length: object    # (..., 5) link length (1.0 on line rows)
    normal: object    # (..., 5, 3) carrier-fixed unit normal (0 on sphere rows)


def layout_of(scene: Scene) -> Layout:
    """Return the row map of a scene: sphere rows first, then the strut's two rows each."""
    names = point_names(scene)
    spheres, lines = [], []
    for c in scene.constraints:
        joint = names.index(f'{c.name}.carrier')
        steer = 1.0 if c.steer == 'rack' else 0.0
        if c.type == 'line':
            top = names.index(f'{c.name}.base')
            lines += [(joint, top, True, 0, 0.0), (joint, top, True, 1, 0.0)]
        else:
            ends = ('axis0', 'axis1') if c.type == 'circle' else ('base',)
            spheres += [(joint, names.index(f'{c.name}.{end}'), False, 0, steer)
                        for end in ends]
    rows = list(zip(*(spheres + lines)))
    return Layout(np.array(rows[0]), np.array(rows[1]), np.array(rows[2], dtype=bool),
                  np.array(rows[3]), np.array(rows[4], dtype=float),
                  names.index('wheel_center'), names.index('spin_axis_point'))


def geometry(layout: Layout, points) -> Geometry:
    """Return the rows of the design(s) whose hardpoints are points (..., k, 3) mm."""
    center0 = points[..., layout.center, :]
    spin = center0 - points[..., layout.spin, :]
    joints = points[..., layout.carrier, :]
    bases = points[..., layout.base, :]
    offset = joints - _rows(center0)
    link = jt.norm(joints - bases)
    length = jt.where(layout.line, 1.0, link)
    n1, n2 = line_normals(bases - joints, _rows(spin))
    normal = jt.where(layout.line[:, None], jt.where((layout.normal == 0)[:, None], n1, n2), 0.0)
    return Geometry(center0, jt.unit(spin), offset, bases, length, normal)


def _rows(vector):
    """Return vectors (..., 3) as (..., 1, 3), to broadcast against the rows."""
    if isinstance(vector, jt.Jet):
        return jt.Jet(vector.v[..., None, :], vector.g[..., None, :, :])
    return np.asarray(vector)[..., None, :]


def line_normals(direction, helper):
    """Return a strut line's two unit normals, as mechanism.line_normals chooses them."""
    d = jt.unit(direction)
    sine = jt.value(jt.norm(jt.cross(d, jt.unit(helper))))
    helper = jt.where((sine > HELPER_SINE)[..., None], helper, np.array([1.0, 0.0, 0.0]))
    n1 = jt.unit(jt.cross(d, helper))
    return n1, jt.cross(d, n1)


def table(layout: Layout, geom: Geometry) -> np.ndarray:
    """Pack plain-array geometry into kernel equation tables (..., 5, kernel.COLUMNS)."""
    offset = np.asarray(geom.offset)
    out = np.zeros(offset.shape[:-1] + (kernel.COLUMNS,))
    out[..., kernel.KIND] = np.where(layout.line, kernel.LINE, kernel.SPHERE)
    out[..., kernel.POINT:kernel.POINT + 3] = offset
    out[..., kernel.BASE:kernel.BASE + 3] = geom.base
    out[..., kernel.LENGTH] = np.where(layout.line, 0.0, geom.length)
    out[..., kernel.STEER] = layout.steer
    out[..., kernel.NORMAL:kernel.NORMAL + 3] = geom.normal
    return out


def arms(geom: Geometry, rotation):
    """Return the rows' carrier points relative to M at a pose, R r (..., 5, 3)."""
    return jt.matvec(_rows3(rotation), geom.offset)


def _rows3(rotation):
    """Return rotations (..., 3, 3) as (..., 1, 3, 3), to broadcast against the rows."""
    if isinstance(rotation, jt.Jet):
        return jt.Jet(rotation.v[..., None, :, :], rotation.g[..., None, :, :, :])
    return np.asarray(rotation)[..., None, :, :]


def _link_vectors(layout, geom, center, r, rack):
    """Return d = M + R r - A - rack e_y steer (..., 5, 3) of every row; rack mm, () or (...)."""
    rack = np.asarray(rack, dtype=float)
    return r + _rows(center) - geom.base - (rack[..., None] * layout.steer)[..., None] * E_Y


def residuals(layout: Layout, geom: Geometry, center, rotation, rack=0.0):
    """Return the 5 rows' values, (..., 5) mm, at poses: center (..., 3), rotation (..., 3, 3)."""
    r = arms(geom, rotation)
    d = _link_vectors(layout, geom, center, r, rack)
    sphere = (jt.dot(d, d) - geom.length * geom.length) / (2.0 * geom.length)
    n = jt.matvec(_rows3(rotation), geom.normal)
    line = jt.dot(geom.base - _rows(center) - r, n)
    return jt.where(layout.line, line, sphere)


def jacobian(layout: Layout, geom: Geometry, center, rotation, rack=0.0):
    """Return d(residuals)/d(M, omega) (..., 5, 6) at poses, as kernel.linearize does."""
    r = arms(geom, rotation)
    d = _link_vectors(layout, geom, center, r, rack) / jt.expand(geom.length)
    n = jt.matvec(_rows3(rotation), geom.normal)
    reach = geom.base - _rows(center) - r
    sphere = [d[..., 0], d[..., 1], d[..., 2]]
    sphere += list(_split(jt.cross(r, d)))
    line = [-n[..., 0], -n[..., 1], -n[..., 2]]
    line += list(_split(jt.cross(n, reach) - jt.cross(r, n)))
    columns = [jt.where(layout.line, a, b) for a, b in zip(line, sphere)]
    return jt.stack(columns, -1)


def rack_column(layout: Layout, geom: Geometry, center, rotation, rack=0.0):
    """Return d(residuals)/d(rack) (..., 5): steer rows' body points move along +y."""
    r = arms(geom, rotation)
    d = _link_vectors(layout, geom, center, r, rack)
    return -d[..., 1] / geom.length * layout.steer


def _split(v):
    return v[..., 0], v[..., 1], v[..., 2]


def free(jac):
    """Return the Jacobians' columns of the unknowns (kernel.FREE): (..., 5, 6) -> (..., 5, 5)."""
    return jac[..., FREE]
