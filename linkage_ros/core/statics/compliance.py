"""
Compliance at one travel: first-order rates from the factorised KKT system (issue 29 item 3).

At the zero-load equilibrium (which holds the springs' preload), a generalized load Q moves
the coordinates and multipliers by the implicit function theorem:

    [ H  J^T ] [ dq      ]   [ Q ]
    [ J   0  ] [ dlambda ] = [ 0 ]

one LU factorisation, one solve per load. The carrier's dq is its move dM (mm) and turn w
(rad); the holding force changes by -dlambda of the travel row. Rates as the quantity
registry names them (measure/quantities.py, groups kc_...); the 6x6 matrix is the wheel
centre's [dx, dy, dz mm, rx, ry, rz deg] per [Fx, Fy, Fz kN, Mx, My, Mz kN m] (its SI twin
per N and N m in m and rad: symmetric, Maxwell-Betti). Its z row and column are zero: the
travel is held.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from .loaded import load_point, unloaded
from .newton import kkt
from ..base import jets as jt
from ..base.status import Status
from ..measure.quantities import names
from ..solve.continuation import Continuation
from ..solve.mechanism import compile_scene

RATE_COLUMNS = tuple(names('kc_fy_cp', 'kc_fx_cp', 'kc_fx_wc', 'kc_mz'))
PER_KN = 1000.0            # N per kN
PER_KNM = 1e6              # N mm per kN m
DEG = 180.0 / math.pi


@dataclass(frozen=True)
class Compliance:
    """The rates at one travel and rack (registry units), the 6x6 matrices; NaN on failure."""

    status: Status
    message: str
    travel_mm: float
    rates: dict = field(default_factory=dict)
    matrix: np.ndarray = field(default_factory=lambda: np.full((6, 6), math.nan))
    matrix_si: np.ndarray = field(default_factory=lambda: np.full((6, 6), math.nan))


def angle_gradients(spin_axis: np.ndarray, side_sign: float) -> tuple[np.ndarray, np.ndarray]:
    """Return d camber / d w and d toe / d w (3,) rad/rad of a spin axis turned by w."""
    w = jt.seed(np.zeros(3))
    a = jt.cross(w, spin_axis) + spin_axis
    ax, ay, az = a[0], a[1], a[2]
    camber = -jt.atan2(az, jt.hypot(ax, ay))
    toe = jt.atan2(ax, ay * side_sign)
    return camber.g, toe.g


def compliance(scene, travel_mm: float = 0.0, rack_mm: float = 0.0,
               continuation: Continuation | None = None) -> Compliance:
    """Return the Compliance of a scene at travel and rack (mm)."""
    base = unloaded(scene, travel_mm, rack_mm, continuation)
    if base.status != Status.OK:
        return Compliance(base.status, base.message, float(travel_mm))
    system, eq = base.system, base.eq
    n, m = system.size, len(system.constraints)
    factors = lu_factor(kkt(eq.hess, eq.rows))
    rot = eq.pose.r[0]
    mech = compile_scene(scene)
    d_camber, d_toe = angle_gradients(rot @ mech.spin_axis, scene.side_sign)

    def respond(force, arm, moment=np.zeros(3)):
        """Return (dM (3,) mm, w (3,) rad, d holding N) per unit load (N, N mm)."""
        rhs = np.zeros(n + m)
        rhs[:3], rhs[3:6] = force, np.cross(arm, force) + moment
        sol = lu_solve(factors, rhs)
        return sol[:3], sol[3:6], -sol[n + m - 1]

    ex, ey, zero = np.eye(3)[0], np.eye(3)[1], np.zeros(3)
    rates = {}
    dm, w, _ = respond(ex, zero)
    rates['toe_per_fx_wc_deg_per_kn'] = d_toe @ w * DEG * PER_KN
    rates['wc_dx_per_fx_wc_mm_per_kn'] = dm[0] * PER_KN
    dm, w, _ = respond(zero, zero, np.eye(3)[2])
    rates['toe_per_mz_deg_per_knm'] = d_toe @ w * DEG * PER_KNM
    rates['camber_per_mz_deg_per_knm'] = d_camber @ w * DEG * PER_KNM
    if scene.wheel_radius > 0:
        patch = rot @ (load_point(scene, base, 'cp') - mech.design_center)
        dm, w, dh = respond(ey, patch)
        rates['toe_per_fy_cp_deg_per_kn'] = d_toe @ w * DEG * PER_KN
        rates['camber_per_fy_cp_deg_per_kn'] = d_camber @ w * DEG * PER_KN
        rates['wc_dy_per_fy_cp_mm_per_kn'] = dm[1] * PER_KN
        rates['cp_dy_per_fy_cp_mm_per_kn'] = (dm + np.cross(w, patch))[1] * PER_KN
        rates['jacking_per_fy_cp'] = dh
        dm, w, _ = respond(ex, patch)
        rates['toe_per_fx_cp_deg_per_kn'] = d_toe @ w * DEG * PER_KN
        rates['camber_per_fx_cp_deg_per_kn'] = d_camber @ w * DEG * PER_KN
        rates['wc_dx_per_fx_cp_mm_per_kn'] = dm[0] * PER_KN
    si = np.empty((6, 6))
    for j in range(6):
        unit = np.eye(3)[j % 3]
        dm, w, _ = respond(unit, zero) if j < 3 else respond(zero, zero, unit * 1000.0)
        si[:3, j], si[3:, j] = dm * 1e-3, w   # per N (forces) or per N m (moments)
    matrix = si.copy()
    matrix[:3] *= 1e3 * PER_KN     # m/N -> mm/kN; m/(N m) -> mm/(kN m)
    matrix[3:] *= DEG * PER_KN     # rad/N -> deg/kN; rad/(N m) -> deg/(kN m)
    ordered = {k: float(rates[k]) for k in RATE_COLUMNS if k in rates}
    return Compliance(Status.OK, 'ok', float(travel_mm), ordered, matrix, si)
