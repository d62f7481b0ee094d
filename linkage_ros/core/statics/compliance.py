# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Compliance at one travel: first-order rates from the factorised KKT system (issue 29 item 3).

At the zero-load equilibrium (which holds the springs' preload), a generalized load Q moves
the coordinates and multipliers by the implicit function theorem:

    [ H  J^T ] [ dq      ]   [ Q ]
    [ J   0  ] [ dlambda ] = [ 0 ]

one LU factorisation for all the loads. The carrier's dq is its move dM (mm) and turn w
(rad); the holding force changes by -dlambda of the travel row. Rates as the quantity
registry names them (measure/quantities.py, groups kc_...); the 6x6 matrix is the wheel
centre's [dx, dy, dz mm, rx, ry, rz deg] per [Fx, Fy, Fz kN, Mx, My, Mz kN m] (its SI twin
per N and N m in m and rad: symmetric, Maxwell-Betti). Its z row and column are zero: the
travel is held.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
import math

import numpy as np

from . import kernel
from .loaded import load_point, unloaded
from .newton import kkt
from ..base.geometry import cross, point_velocity
from ..base.status import Status
from ..measure.quantities import names
from ..solve.continuation import Continuation
from ..solve.mechanism import compile_scene

RATE_COLUMNS = tuple(names('kc_fy_cp', 'kc_fx_cp', 'kc_fx_wc', 'kc_mz'))
PER_KN = 1000.0            # N per kN
PER_KNM = 1e6              # N mm per kN m
DEG = 180.0 / math.pi
EY_EX = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])   # Fy, Fx at the patch
EYE6 = np.eye(6)
# the rates of the last zero-load equilibrium (loaded.LAST), kept on the Scene: (it, rates)
LAST_RATES = '_statics_last_rates'


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
    """
    Return d camber / d w and d toe / d w (3,) rad/rad of a spin axis a turned by w.

    camber = -atan2(a_z, |a_xy|), toe = atan2(a_x, s a_y) (geometry.camber_toe); a moves by
    w x a, so d/dw = a x d/da.
    """
    ax, ay, az = spin_axis.tolist()   # Python floats: less overhead per number
    flat = math.hypot(ax, ay)
    tilt, turn = az * az + flat * flat, ax * ax + ay * ay
    by_axis = np.array([[az * ax / flat / tilt, az * ay / flat / tilt, -flat / tilt],  # camber
                        [side_sign * ay / turn, side_sign * -ax / turn, 0.0]])         # toe
    d_camber, d_toe = cross(spin_axis, by_axis)
    return d_camber, d_toe


def compliance(scene, travel_mm: float = 0.0, rack_mm: float = 0.0,
               continuation: Continuation | None = None, compiled: bool = True) -> Compliance:
    """
    Return the Compliance of a scene at travel and rack (mm).

    continuation: a solve.Continuation of the scene to take the kinematic pose from;
    compiled False: the zero-load equilibrium by newton_python (numpy), the kernel's check.
    """
    base = unloaded(scene, travel_mm, rack_mm, continuation, compiled)
    if base.status != Status.OK:
        return Compliance(base.status, base.message, float(travel_mm))
    last = scene.__dict__.get(LAST_RATES)
    if last is None or last[0] is not base:   # not yet at this zero-load state
        last = (base, _rates(scene, base, travel_mm))
        scene.__dict__[LAST_RATES] = last
    done = last[1]   # a copy: the caller may change what it is given
    return replace(done, rates=dict(done.rates), matrix=done.matrix.copy(),
                   matrix_si=done.matrix_si.copy())


def _rates(scene, base, travel_mm: float) -> Compliance:
    """Return the Compliance at a solved zero-load state (loaded.Unloaded)."""
    system, eq = base.system, base.eq
    n, m = system.size, len(system.constraints)
    rot = eq.pose.r[0]
    mech = compile_scene(scene)
    d_camber, d_toe = angle_gradients(rot @ mech.spin_axis, scene.side_sign)
    patch = np.zeros(3)
    if scene.wheel_radius > 0:
        patch = rot @ (load_point(scene, base, 'cp') - mech.design_center)
    # generalized loads (columns): [force (3,), moment about the wheel centre (3,)] per N or
    # per N mm: Fx, Fy, Fz, Mx, My, Mz at the wheel centre, then Fy and Fx at the patch
    loads = np.zeros((n + m, 8))
    loads[:6, :6] = EYE6
    loads[1, 6] = loads[0, 7] = 1.0
    loads[3:6, 6:8] = cross(patch, EY_EX).T
    # one solve of the KKT matrix for every load (implicit function theorem)
    sol = (np.linalg.solve(kkt(eq.hess, eq.rows), loads) if base.model is None
           else kernel.kkt_solve(eq.hess, eq.rows, loads))
    dm, w, held = sol[:3], sol[3:6], -sol[n + m - 1]
    # as Python floats (the same arithmetic, less overhead per number)
    toe, camber, held = (d_toe @ w).tolist(), (d_camber @ w).tolist(), held.tolist()
    dx, dy = dm[:2].tolist()
    rates = {'toe_per_fx_wc_deg_per_kn': toe[0] * DEG * PER_KN,
             'wc_dx_per_fx_wc_mm_per_kn': dx[0] * PER_KN,
             'toe_per_mz_deg_per_knm': toe[5] * DEG * PER_KNM,
             'camber_per_mz_deg_per_knm': camber[5] * DEG * PER_KNM}
    if scene.wheel_radius > 0:
        patch_dy = float(point_velocity(dm[:, 6], w[:, 6], patch)[1])   # the patch's move
        rates.update({'toe_per_fy_cp_deg_per_kn': toe[6] * DEG * PER_KN,
                      'camber_per_fy_cp_deg_per_kn': camber[6] * DEG * PER_KN,
                      'wc_dy_per_fy_cp_mm_per_kn': dy[6] * PER_KN,
                      'cp_dy_per_fy_cp_mm_per_kn': patch_dy * PER_KN,
                      'jacking_per_fy_cp': held[6],
                      'toe_per_fx_cp_deg_per_kn': toe[7] * DEG * PER_KN,
                      'camber_per_fx_cp_deg_per_kn': camber[7] * DEG * PER_KN,
                      'wc_dx_per_fx_cp_mm_per_kn': dx[7] * PER_KN})
    si = np.vstack((dm[:, :6] * 1e-3, w[:, :6]))   # m and rad per N and per N mm
    si[:, 3:] *= 1e3                                # per N m
    matrix = si.copy()
    matrix[:3] *= 1e3 * PER_KN     # m/N -> mm/kN; m/(N m) -> mm/(kN m)
    matrix[3:] *= DEG * PER_KN     # rad/N -> deg/kN; rad/(N m) -> deg/(kN m)
    ordered = {k: float(rates[k]) for k in RATE_COLUMNS if k in rates}
    return Compliance(Status.OK, 'ok', float(travel_mm), ordered, matrix, si)
