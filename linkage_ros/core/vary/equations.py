# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The guidance equations' values and Jacobians at poses, on jets.Jet values carrying d/dH.

The rows come from the one compile, mechanism.geometry_of, run on the hardpoint table H
(..., k, 3) mm (Scene.points) as plain arrays or as Jets; here the residuals and Jacobians
are evaluated on them, so that the sensitivities get exact dF/dH. The formulas are
kernel.linearize's:

    sphere row: F = (|d|^2 - l^2) / 2l,  d = M + R r - A - rack e_y steer,  l = |b - A|
    line row:   F = (T - M - R r) . (R n0)
    r = b - M0, the row's carrier point b relative to the design wheel centre M0.

Layout (Scene.layout), the scene's row map, is fixed by the scene's constraint types; the
geometry follows H. Poses (M (..., 3), R (..., 3, 3)) broadcast against the rows as the
leading axes allow.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..base import jets as jt
from ..solve import kernel

if TYPE_CHECKING:
    from ..solve.mechanism import Geometry, Layout

E_Y = np.array([0.0, 1.0, 0.0])
FREE = list(kernel.FREE)


def _rows(vector):
    """Return vectors (..., 3) as (..., 1, 3), to broadcast against the rows."""
    if isinstance(vector, jt.Jet):
        return jt.Jet(vector.v[..., None, :], vector.g[..., None, :, :])
    return np.asarray(vector)[..., None, :]


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
