# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A bushing's rotational energy on SO(3): the rotation vector of an arm and its derivatives.

The arm's rotation R from design is updated on the left, R <- exp(w) R (w a small rotation,
rad, vehicle frame), as the carrier's is. Its rotation vector phi = log(R) then moves as
d phi = A(phi) w, A the inverse of SO(3)'s left Jacobian (Barfoot, State Estimation for
Robotics, 2017, eq. 7.77b):

    A(phi) = I - [phi]x / 2 + c(theta) [phi]x^2,
    c = 1/theta^2 - (1 + cos theta) / (2 theta sin theta)

so the energy E = phi.K phi / 2 has the gradient A^T K phi, and its Hessian in w (at w = 0)
adds to A^T K A the term from A's own change (dA/dphi, exact, below). Compiled (numba), so
that the statics kernel (kernel.py) calls them too; Python calls them alike.
"""

import math

import numpy as np

from ..base.compiled import jit


# Below this angle (rad) c and c'/theta come from their Taylor series (sympy, to theta^10):
# the closed forms lose digits to cancellation there (c' as eps / theta^3).
SERIES_BELOW = 0.1


@jit
def skew(v):
    """Return [v]x (3, 3), the matrix of v x ."""
    out = np.zeros((3, 3))
    out[0, 1], out[0, 2], out[1, 2] = -v[2], v[1], -v[0]
    out[1, 0], out[2, 0], out[2, 1] = v[2], -v[1], v[0]
    return out


@jit
def log_so3(rotation):
    """Return the rotation vector (3,) rad of a rotation matrix (angle below pi)."""
    cos = min(1.0, max(-1.0, 0.5 * (rotation[0, 0] + rotation[1, 1] + rotation[2, 2] - 1.0)))
    axis = np.empty(3)   # 2 sin(theta) * unit axis
    axis[0] = rotation[2, 1] - rotation[1, 2]
    axis[1] = rotation[0, 2] - rotation[2, 0]
    axis[2] = rotation[1, 0] - rotation[0, 1]
    sin = 0.5 * np.linalg.norm(axis)
    theta = math.atan2(sin, cos)
    scale = 0.5 / (1.0 - theta * theta / 6.0) if sin < 1e-8 else 0.5 * theta / sin
    return scale * axis


@jit
def coefficients(theta):
    """Return c(theta) and c'(theta) / theta of A (module docstring)."""
    t2 = theta * theta
    if theta < SERIES_BELOW:
        c = 1 / 12 + t2 * (1 / 720 + t2 * (1 / 30240 + t2 * (1 / 1209600 + t2 / 47900160)))
        dc = 1 / 360 + t2 * (1 / 7560 + t2 * (1 / 201600 + t2 * (1 / 5987520
                                                                 + t2 * 691 / 130767436800)))
        return c, dc
    sin, cos = math.sin(theta), math.cos(theta)
    c = 1.0 / t2 - (1.0 + cos) / (2.0 * theta * sin)
    dc = (-2.0 / (t2 * theta) + (1.0 + cos) / (2.0 * t2 * sin)
          + (1.0 + cos) / (2.0 * theta * sin * sin))
    return c, dc / theta


@jit
def _mul(a, b):
    """Return a @ b of (3, 3) matrices, without a BLAS call (they are small)."""
    out = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            out[i, j] = a[i, 0] * b[0, j] + a[i, 1] * b[1, j] + a[i, 2] * b[2, j]
    return out


@jit
def energy_terms(phi, stiffness):
    """
    Return E, its gradient (3,) and Hessian (3, 3) in w of E = phi.K phi / 2 (N mm, rad).

    stiffness K (3, 3) N mm/rad, symmetric. Gradient A^T K phi; Hessian A^T K A plus the
    symmetrised (K phi) . (dA/dphi_k w2) (A w1)_k, exact (module docstring).
    """
    theta = math.sqrt(phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2])
    c, dc = coefficients(theta)
    big = skew(phi)
    big2 = _mul(big, big)
    eye = np.eye(3)
    a = eye - 0.5 * big + c * big2
    k_phi = np.empty(3)
    for i in range(3):
        k_phi[i] = stiffness[i, 0] * phi[0] + stiffness[i, 1] * phi[1] + stiffness[i, 2] * phi[2]
    z = np.empty((3, 3))
    for k in range(3):
        e = skew(eye[k])
        d_a = -0.5 * e + dc * phi[k] * big2 + c * (_mul(e, big) + _mul(big, e))
        for j in range(3):   # (K phi)^T dA/dphi_k
            z[k, j] = k_phi[0] * d_a[0, j] + k_phi[1] * d_a[1, j] + k_phi[2] * d_a[2, j]
    a_t = a.T.copy()
    az = _mul(a_t, z)
    hess = _mul(_mul(a_t, stiffness), a) + 0.5 * (az + az.T)
    grad = np.empty(3)
    for i in range(3):
        grad[i] = a[0, i] * k_phi[0] + a[1, i] * k_phi[1] + a[2, i] * k_phi[2]
    energy = 0.5 * (phi[0] * k_phi[0] + phi[1] * k_phi[1] + phi[2] * k_phi[2])
    return energy, grad, hess
