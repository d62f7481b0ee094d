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
that the statics kernels (kernel.py, forces.py) call them without allocating (energy_into,
log_into: they run in every Newton iteration); energy_terms and log_so3 call them from
Python.
"""

import math

import numpy as np

from ..base.compiled import bare


# Below this angle (rad) c and c'/theta come from their Taylor series (sympy, to theta^10):
# the closed forms lose digits to cancellation there (c' as eps / theta^3).
SERIES_BELOW = 0.1


@bare
def log_into(rotation, out):
    """Write the rotation vector (3,) rad of a rotation matrix (angle below pi) into out."""
    cos = min(1.0, max(-1.0, 0.5 * (rotation[0, 0] + rotation[1, 1] + rotation[2, 2] - 1.0)))
    x = rotation[2, 1] - rotation[1, 2]   # 2 sin(theta) * unit axis
    y = rotation[0, 2] - rotation[2, 0]
    z = rotation[1, 0] - rotation[0, 1]
    sin = 0.5 * math.sqrt(x * x + y * y + z * z)
    theta = math.atan2(sin, cos)
    scale = 0.5 / (1.0 - theta * theta / 6.0) if sin < 1e-8 else 0.5 * theta / sin
    out[0], out[1], out[2] = scale * x, scale * y, scale * z


def log_so3(rotation):
    """Return the rotation vector (3,) rad of a rotation matrix (angle below pi): Python's."""
    out = np.empty(3)
    log_into(np.ascontiguousarray(rotation, dtype=float), out)
    return out


@bare
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


@bare
def _skew_into(x, y, z, out):
    out[0, 0], out[0, 1], out[0, 2] = 0.0, -z, y
    out[1, 0], out[1, 1], out[1, 2] = z, 0.0, -x
    out[2, 0], out[2, 1], out[2, 2] = -y, x, 0.0


@bare
def energy_into(phi, stiffness, grad, hess, work):
    """
    Write the gradient (3,) and Hessian (3, 3) in w of E = phi.K phi / 2; return E (N mm).

    stiffness K (3, 3) N mm/rad, symmetric; work (5, 3, 3) scratch. Gradient A^T K phi;
    Hessian A^T K A plus the symmetrised (K phi) . (dA/dphi_k w2) (A w1)_k, exact (module
    docstring). Nothing is allocated: the kernel calls it in every Newton iteration.
    """
    big, big2, a, z, e = work[0], work[1], work[2], work[3], work[4]
    theta = math.sqrt(phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2])
    c, dc = coefficients(theta)
    _skew_into(phi[0], phi[1], phi[2], big)
    for i in range(3):
        for j in range(3):
            big2[i, j] = big[i, 0] * big[0, j] + big[i, 1] * big[1, j] + big[i, 2] * big[2, j]
    for i in range(3):
        for j in range(3):
            a[i, j] = (1.0 if i == j else 0.0) - 0.5 * big[i, j] + c * big2[i, j]
    k0 = stiffness[0, 0] * phi[0] + stiffness[0, 1] * phi[1] + stiffness[0, 2] * phi[2]
    k1 = stiffness[1, 0] * phi[0] + stiffness[1, 1] * phi[1] + stiffness[1, 2] * phi[2]
    k2 = stiffness[2, 0] * phi[0] + stiffness[2, 1] * phi[1] + stiffness[2, 2] * phi[2]
    for k in range(3):
        _skew_into(1.0 if k == 0 else 0.0, 1.0 if k == 1 else 0.0, 1.0 if k == 2 else 0.0, e)
        for j in range(3):   # z[k] = (K phi)^T dA/dphi_k
            total = 0.0
            for i, kp in ((0, k0), (1, k1), (2, k2)):
                eb = e[i, 0] * big[0, j] + e[i, 1] * big[1, j] + e[i, 2] * big[2, j]
                be = big[i, 0] * e[0, j] + big[i, 1] * e[1, j] + big[i, 2] * e[2, j]
                total += kp * (-0.5 * e[i, j] + dc * phi[k] * big2[i, j] + c * (eb + be))
            z[k, j] = total
    for i in range(3):
        grad[i] = a[0, i] * k0 + a[1, i] * k1 + a[2, i] * k2
    for i in range(3):   # A^T K A + (A^T z + z^T A) / 2
        for j in range(i, 3):
            total = 0.0
            for p in range(3):
                kaj = stiffness[p, 0] * a[0, j] + stiffness[p, 1] * a[1, j] \
                    + stiffness[p, 2] * a[2, j]
                total += a[p, i] * kaj
            az_ij = a[0, i] * z[0, j] + a[1, i] * z[1, j] + a[2, i] * z[2, j]
            az_ji = a[0, j] * z[0, i] + a[1, j] * z[1, i] + a[2, j] * z[2, i]
            hess[i, j] = hess[j, i] = total + 0.5 * (az_ij + az_ji)
    return 0.5 * (phi[0] * k0 + phi[1] * k1 + phi[2] * k2)


def energy_terms(phi, stiffness):
    """
    Return E, its gradient (3,) and Hessian (3, 3) in w of E = phi.K phi / 2 (N mm, rad).

    stiffness K (3, 3) N mm/rad, symmetric: energy_into for Python callers (the tests).
    """
    grad, hess = np.empty(3), np.empty((3, 3))
    energy = energy_into(np.ascontiguousarray(phi, dtype=float),
                         np.ascontiguousarray(stiffness, dtype=float), grad, hess,
                         np.empty((5, 3, 3)))
    return energy, grad, hess
