# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
An independent statics of a scene with bushings: minimum potential energy over 6-DOF bodies.

Written apart from linkage_ros (EnergyModel takes the scene file's mapping as yaml.safe_load
gives it, and uses none of the package's parsers or solvers) to check
linkage_ros.core.statics, with the model of doc/kc.md: the carrier is a free rigid body
(6 DOF); an arm with a bushing is a free rigid body (6 DOF); an arm without one turns about
its axis (1 DOF); a link with a bushing has a movable body end
(3 DOF). Ball joints, link lengths, strut lines, the wheel centre's height and the rack are
equality constraints. The energy is that of the bushings and springs, minus the work of the
load. Newton on the Lagrange conditions (gradients exact by complex step) finds the
stationary point from the rigid kinematic pose, which this module also solves; the reduced
Hessian tells that it is a minimum. A moment is no potential's gradient at finite rotations,
so it enters the Lagrange conditions by its virtual work M . omega, omega the carrier's
spatial angular velocity.

Units inside: mm, N, N mm, rad, vehicle frame (x forward, y left, z up).
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math

import numpy as np
from scipy.linalg import null_space

UNIT_MM = {'mm': 1.0, 'm': 1000.0}
NM_PER_DEG = 1000.0 * 180.0 / math.pi     # N m/deg -> N mm/rad
STEP = 1e-30                               # complex step
EY = np.array([0.0, 1.0, 0.0])


def exp_so3(w):
    """Return the rotation matrix of rotation vector w (3,), complex-step safe."""
    t2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
    if abs(t2) < 1e-6:
        a = 1 - t2 / 6 + t2 * t2 / 120 - t2 ** 3 / 5040 + t2 ** 4 / 362880
        b = 0.5 - t2 / 24 + t2 * t2 / 720 - t2 ** 3 / 40320 + t2 ** 4 / 3628800
    else:
        t = np.sqrt(t2)
        a, b = np.sin(t) / t, (1 - np.cos(t)) / t2
    k = np.array([[0 * w[0], -w[2], w[1]], [w[2], 0 * w[0], -w[0]], [-w[1], w[0], 0 * w[0]]])
    return np.eye(3) + a * k + b * (k @ k)


def vee(s):
    """Return the vector of the skew part of s (3, 3)."""
    return 0.5 * np.array([s[2, 1] - s[1, 2], s[0, 2] - s[2, 0], s[1, 0] - s[0, 1]])


def spatial_jacobian(w):
    """Return (3, 3): exp_so3(w)'s spatial angular velocity per unit rate of each of w."""
    rot = exp_so3(w).real
    cols = [vee(exp_so3(w + 1j * STEP * e).imag / STEP @ rot.T) for e in np.eye(3)]
    return np.column_stack(cols)


def unit(v):
    """Return the unit vector of a real vector v."""
    return v / np.linalg.norm(v)


def camber_toe_deg(spin, side_sign):
    """Return camber (+ top outboard) and toe (+ toe-in), deg, of the outboard spin axis."""
    camber = -math.atan2(spin[2], math.hypot(spin[0], spin[1]))
    return math.degrees(camber), math.degrees(math.atan2(spin[0], side_sign * spin[1]))


def quad(d, a, k_along, k_across):
    """Return the energy 0.5 k_along (d.a)^2 + 0.5 k_across |d - (d.a)a|^2."""
    along = d @ a
    return 0.5 * k_along * along * along + 0.5 * k_across * (d @ d - along * along)


def stiffness(a, k_along, k_across):
    """Return the (3, 3) stiffness matrix of quad's energy."""
    return k_along * np.outer(a, a) + k_across * (np.eye(3) - np.outer(a, a))


@dataclass
class Part:
    """One guidance constraint as the reference models it (mm, N/mm, N mm/rad)."""

    name: str
    kind: str                      # 'arm', 'link' or 'line'
    carrier: np.ndarray            # (3,) carrier point at design
    base: np.ndarray               # (k, 3): arm axis (2) or link/line base (1)
    steer: bool = False
    bushing: dict | None = None    # axial, radial N/mm; torsion, conical N mm/rad; at
    index: int = 0                 # first unknown of the part's own coordinates
    size: int = 0                  # how many (arm 1 or 6, link 0 or 3, line 0)

    @property
    def axis(self):
        """Return the unit design axis of an arm (axis[0] to axis[1])."""
        return unit(self.base[1] - self.base[0])

    def bushing_points(self):
        """Return the body points where the arm's bushings sit, with their keys."""
        if self.bushing['at'] == 'centre':
            return [(f'{self.name}_centre', self.base.mean(axis=0))]
        return [(f'{self.name}_axis0', self.base[0]), (f'{self.name}_axis1', self.base[1])]


@dataclass
class Spring:
    """A spring element: body point, moving point and its carrier (mm, N/mm)."""

    name: str
    body: np.ndarray
    point: np.ndarray
    on: str                 # 'carrier', 'arm' or 'link'
    part: int = -1          # index into parts
    rate: float = 0.0
    free_length: float = 0.0
    fraction: float = 0.0   # link mounts: how far from body end to carrier end


@dataclass
class Result:
    """The reference's loaded equilibrium (mm, deg, N, vehicle frame)."""

    camber_deg: float
    toe_deg: float
    wheel_center_mm: np.ndarray
    rotation: np.ndarray
    holding_force_n: float
    link_forces_n: dict = field(default_factory=dict)
    pivot_forces_n: dict = field(default_factory=dict)
    ball_joint_forces_n: dict = field(default_factory=dict)
    spring_forces_n: dict = field(default_factory=dict)
    body_forces_n: dict = field(default_factory=dict)     # every force on the body, (3,):
    # keys: arm pivots as pivot_forces_n, f'{link}_base', f'{spring}_body'
    body_points_mm: dict = field(default_factory=dict)    # where each acts
    body_couples_nmm: np.ndarray = field(default_factory=lambda: np.zeros(3))
    residual: float = math.nan
    q: np.ndarray | None = None
    min_curvature: float = math.nan     # > 0: a minimum of the potential, not a saddle
    load_point_mm: np.ndarray | None = None   # where the load's point (carrier-fixed) is


class EnergyModel:
    """A scene's corner as free bodies with energies (read from the scene file's mapping)."""

    def __init__(self, data: dict):
        s = UNIT_MM[data.get('units', 'mm')]
        self.side = 1.0 if data.get('side', 'left') == 'left' else -1.0
        self.radius = float(data.get('wheel_radius', 0.0)) * s
        self.m0 = np.array(data['carrier']['wheel_center'], float) * s
        self.n0 = np.array(data['carrier']['spin_axis_point'], float) * s
        self.parts, n = [], 6
        for item in data['constraints']:
            kind = {'circle': 'arm', 'sphere': 'link', 'line': 'line'}[item['type']]
            base = np.array(item['axis'] if kind == 'arm' else [item['base']], float) * s
            part = Part(item['name'], kind, np.array(item['carrier'], float) * s, base,
                        item.get('steer') == 'rack', _bushing(item.get('bushing'), s), n)
            part.size = {'arm': 6 if part.bushing else 1, 'link': 3 if part.bushing else 0,
                         'line': 0}[kind]
            n += part.size
            self.parts.append(part)
        self.size = n
        self._free = {}
        items = [e for e in data.get('elements') or [] if e.get('type') == 'spring']
        if any('force_table' in e for e in items):
            raise ValueError('energy_reference models linear springs (rate) only')
        self.springs = [self._spring(e, s) for e in items if e.get('rate') is not None]

    def _spring(self, item, s):
        on = next(k for k in ('carrier', 'arm', 'link', 'along') if k in item)
        if on == 'along':   # a strut's own length: top mount to its carrier point
            strut = next(p for p in self.parts if p.name == item['along'])
            on, body, point = 'carrier', strut.base[0], strut.carrier
        else:
            body = np.array(item['body'], float) * s
            point = np.array(item['carrier'] if on == 'carrier' else item['point'], float) * s
        spring = Spring(item['name'], body, point, on,
                        rate=float(item['rate']) / s, free_length=float(item['free_length']) * s)
        if on != 'carrier':
            spring.part = [p.name for p in self.parts].index(item[on])
        if on == 'link':
            p = self.parts[spring.part]
            span = p.carrier - p.base[0]
            spring.fraction = (point - p.base[0]) @ span / (span @ span)
        return spring

    # --- positions of body points at the unknowns q (complex-step safe) -------------------

    def carrier_point(self, q, p):
        """Return where the carrier point p (design, (3,)) is."""
        return exp_so3(q[3:6]) @ (p - self.m0) + q[0:3]

    def arm_point(self, q, part, p):
        """Return where the arm's point p (design) is."""
        x = q[part.index:part.index + part.size]
        if part.size == 1:
            return exp_so3(x[0] * part.axis) @ (p - part.base[0]) + part.base[0]
        o = part.base.mean(axis=0)
        return exp_so3(x[3:6]) @ (p - o) + o + x[0:3]

    def link_base(self, q, part, rack):
        """Return where the link's body end is: its base moved by the rack and bushing."""
        b = part.base[0] + (rack * EY if part.steer else 0.0)
        return b + q[part.index:part.index + 3] if part.size == 3 else b + 0 * q[0]

    def mount(self, q, spring, rack):
        """Return where a spring's moving end is."""
        if spring.on == 'carrier':
            return self.carrier_point(q, spring.point)
        part = self.parts[spring.part]
        if spring.on == 'arm':
            return self.arm_point(q, part, spring.point)
        b = self.link_base(q, part, rack)
        return b + spring.fraction * (self.carrier_point(q, part.carrier) - b)

    # --- energy and constraints -----------------------------------------------------------

    def energy(self, q, rack, force, point):
        """Return the potential, N mm: bushings and springs, less the work of the force."""
        e = -(force @ self.carrier_point(q, point))
        for part in self.parts:
            if part.bushing is None:
                continue
            b = part.bushing
            if part.kind == 'arm':
                a, phi = part.axis, q[part.index + 3:part.index + 6]
                for _, at in part.bushing_points():
                    e = e + quad(self.arm_point(q, part, at) - at, a, b['axial'], b['radial'])
                    e = e + quad(phi, a, b['torsion'], b['conical'])
            else:
                u = unit(part.carrier - part.base[0])
                e = e + quad(q[part.index:part.index + 3], u, b['axial'], b['radial'])
        for sp in self.springs:
            d = self.mount(q, sp, rack) - sp.body
            e = e + 0.5 * sp.rate * (np.sqrt(d @ d) - sp.free_length) ** 2
        return e

    def constraints(self, q, rack, travel):
        """Return the rigid constraints g(q) = 0 (mm): ball joints, lengths, lines, height."""
        g = []
        for part in self.parts:
            c = self.carrier_point(q, part.carrier)
            if part.kind == 'arm':
                g.extend(self.arm_point(q, part, part.carrier) - c)
            elif part.kind == 'link':
                d = c - self.link_base(q, part, rack)
                g.append(np.sqrt(d @ d) - np.linalg.norm(part.carrier - part.base[0]))
            else:
                rot = exp_so3(q[3:6])
                for n in _normals(part.base[0] - part.carrier):
                    g.append((rot @ n) @ (part.base[0] - c))
        g.append(q[2] - (self.m0[2] + travel))
        return np.array(g)

    def gradient(self, f, q):
        """Return df/dq at real q by complex step (a row per output of f; exact)."""
        return np.array([np.imag(f(q + 1j * STEP * e)) / STEP for e in np.eye(len(q))]).T

    def lagrange(self, z, rack, travel, force, point, moment):
        """Return the Lagrange conditions (grad V - M.omega + J^T lam, g) at z = (q, lam)."""
        q, lam = z[:self.size], z[self.size:]
        grad = self.gradient(lambda x: self.energy(x, rack, force, point), q)
        grad[3:6] -= spatial_jacobian(q[3:6]).T @ moment
        jac = self.gradient(lambda x: self.constraints(x, rack, travel), q)
        return np.concatenate([grad + jac.T @ lam, self.constraints(q, rack, travel)])

    # --- the kinematic start ---------------------------------------------------------------

    def kinematic(self, travel, rack, steps=8):
        """Return the rigid kinematic pose (unknowns q) at travel and rack, from design."""
        q = np.zeros(self.size)
        q[0:3] = self.m0
        for k in range(1, steps + 1):
            q = self._rigid_newton(q, travel * k / steps, rack * k / steps)
        return q

    def _rigid_newton(self, q, travel, rack):
        def rigid(x):
            y = q.astype(complex) if np.iscomplexobj(x) else q.copy()
            y[:6] = x
            g = []
            for part in self.parts:
                c = self.carrier_point(y, part.carrier)
                if part.kind == 'arm':
                    g.extend(np.sqrt((c - b) @ (c - b)) - np.linalg.norm(part.carrier - b)
                             for b in part.base)
                elif part.kind == 'link':
                    d = c - (part.base[0] + (rack * EY if part.steer else 0.0))
                    g.append(np.sqrt(d @ d) - np.linalg.norm(part.carrier - part.base[0]))
                else:
                    rot = exp_so3(y[3:6])
                    g.extend((rot @ n) @ (part.base[0] - c)
                             for n in _normals(part.base[0] - part.carrier))
            g.append(y[2] - (self.m0[2] + travel))
            return np.array(g)

        x = q[:6].copy()
        for _ in range(50):
            r = rigid(x)
            x = x - np.linalg.solve(self.gradient(rigid, x), r)
            if np.max(np.abs(r)) < 1e-12:
                break
        out = q.copy()
        out[:6] = x
        for part in self.parts:     # arms follow their ball joints about their axes
            if part.kind == 'arm':
                angle = _angle_about(part, self.carrier_point(out, part.carrier))
                out[part.index:part.index + part.size] = (
                    [angle] if part.size == 1 else [0, 0, 0, *(angle * part.axis)])
        return out

    # --- the equilibrium -------------------------------------------------------------------

    def solve(self, travel_mm, rack_mm=0.0, force_n=(0.0, 0.0, 0.0), at='wc',
              moment_nm=(0.0, 0.0, 0.0), tol=1e-11):
        """
        Return the equilibrium at travel_mm, rack_mm under force_n (N) at 'wc' or 'cp', moment_nm.

        The contact patch is the lowest point of the wheel circle in the zero-load
        equilibrium at that travel and rack, fixed in the carrier.
        """
        force, moment = np.asarray(force_n, float), np.asarray(moment_nm, float) * 1000.0
        key = (float(travel_mm), float(rack_mm))
        if key not in self._free:       # the zero-load equilibrium, kept for later loads
            start = self.kinematic(travel_mm, rack_mm)
            self._free[key] = self.equilibrium(start, travel_mm, rack_mm, np.zeros(3), self.m0,
                                               np.zeros(3))
        free, point = self._free[key], self.m0
        start = free.q
        if at == 'cp':
            rot, wc = exp_so3(free.q[3:6]).real, free.q[0:3]
            spin = unit(rot @ (self.m0 - self.n0))
            up = np.array([0.0, 0.0, 1.0]) - spin[2] * spin
            cp = wc - self.radius * unit(up)
            point = rot.T @ (cp - wc) + self.m0
        return self.equilibrium(start, travel_mm, rack_mm, force, point, moment, tol)

    def equilibrium(self, q0, travel, rack, force, point, moment, tol=1e-13):
        """
        Newton on the Lagrange conditions from q0 (multipliers by least squares) to round-off.

        Newton's matrix is a difference quotient of the (exact) conditions, kept while it
        converges (chord steps) and renewed when not: it sets the speed, not the answer.
        """
        grad = self.gradient(lambda y: self.energy(y, rack, force, point), q0)
        jac = self.gradient(lambda y: self.constraints(y, rack, travel), q0)
        lam = np.linalg.lstsq(jac.T, -grad, rcond=None)[0]
        z = np.concatenate([q0, lam])

        def lagrange(x):
            return self.lagrange(x, rack, travel, force, point, moment)

        r, matrix, last = lagrange(z), None, math.inf
        for _ in range(60):
            if matrix is None:
                matrix = self._newton_matrix(lagrange, z, r)
            step = np.linalg.solve(matrix, r)
            z = z - step
            r = lagrange(z)
            size = np.max(np.abs(step[:self.size]) / np.maximum(1.0, np.abs(z[:self.size])))
            if size < tol:
                break
            if size > 0.5 * last:
                matrix = None
            last = size
        res = self.forces(z, rack, travel, force, point, moment, np.max(np.abs(r)))
        res.min_curvature = _least_curvature(self._newton_matrix(lagrange, z, r), self.size)
        return res

    def _newton_matrix(self, lagrange, z, r):
        """Return Newton's matrix: forward differences (exact in the multipliers: linear)."""
        out = np.empty((len(z), len(z)))
        for i in range(len(z)):
            h = 1.0 if i >= self.size else 1e-6 * max(1.0, abs(z[i]) if i < 3 else 0.0)
            step = z.copy()
            step[i] += h
            out[:, i] = (lagrange(step) - r) / h
        return out

    def forces(self, z, rack, travel, force, point, moment, residual):
        """Return the Result at the solution z = (q, lam)."""
        q, lam = z[:self.size], z[self.size:]
        rot = exp_so3(q[3:6]).real
        camber, toe = camber_toe_deg(rot @ (self.m0 - self.n0), self.side)
        res = Result(camber, toe, q[0:3].copy(), rot, -lam[-1], residual=residual, q=q,
                     load_point_mm=self.carrier_point(q, point).real)
        k = 0
        for part in self.parts:
            c = self.carrier_point(q, part.carrier)
            if part.kind == 'arm':
                res.ball_joint_forces_n[part.name] = lam[k:k + 3].copy()
                k += 3
                if part.bushing:
                    self._arm_body_forces(q, part, res)
                else:
                    self._pivot_forces(q, part, lam[k - 3:k], rack, res)
            elif part.kind == 'link':
                b = self.link_base(q, part, rack)
                u = unit(c - b)
                res.link_forces_n[part.name] = lam[k]
                res.ball_joint_forces_n[part.name] = -lam[k] * u
                res.body_forces_n[f'{part.name}_base'] = lam[k] * u
                if part.bushing:    # what the bushing passes on, springs on the link included
                    res.body_forces_n[f'{part.name}_base'] = stiffness(
                        unit(part.carrier - part.base[0]), part.bushing['axial'],
                        part.bushing['radial']) @ q[part.index:part.index + 3]
                res.body_points_mm[f'{part.name}_base'] = b.real
                k += 1
            else:
                k += 2
        for sp in self.springs:
            end = self.mount(q, sp, rack)
            length = np.linalg.norm(end - sp.body)
            res.spring_forces_n[sp.name] = sp.rate * (sp.free_length - length)
            push = res.spring_forces_n[sp.name] * unit(end - sp.body)    # on the moving end
            res.body_forces_n[f'{sp.name}_body'] = -push
            res.body_points_mm[f'{sp.name}_body'] = sp.body
            if sp.on == 'link':     # a link shares a load on its line between its two ends
                name = self.parts[sp.part].name
                res.ball_joint_forces_n[name] = res.ball_joint_forces_n[name] + sp.fraction * push
                if not self.parts[sp.part].bushing:
                    res.body_forces_n[f'{name}_base'] += (1 - sp.fraction) * push
        for sp in self.springs:     # such a link pulls its two ends apart unequally: each
            if sp.on != 'link':     # end's force along the link (+ = tension)
                continue
            part = self.parts[sp.part]
            end, base = self.carrier_point(q, part.carrier).real, self.link_base(q, part, rack)
            u = unit((end - base).real)
            res.link_forces_n.pop(part.name, None)
            res.link_forces_n[f'{part.name}_body_end'] = res.body_forces_n[f'{part.name}_base'] @ u
            res.link_forces_n[f'{part.name}_carrier_end'] = -res.ball_joint_forces_n[part.name] @ u
        return res

    def _pivot_forces(self, q, part, lam, rack, res):
        """
        Add the forces a rigid revolute arm's pivots put on the body to res.

        The arm (massless) balances the carrier's pull at its ball joint, its springs and
        the two pivots; the pivots' axial split, which a rigid revolute leaves open, is the
        least-norm (equal) one.
        """
        index = self.parts.index(part)
        loads = [(self.arm_point(q, part, part.carrier).real, -lam)]
        for sp in self.springs:
            if sp.on == 'arm' and sp.part == index:
                end = self.mount(q, sp, rack).real
                loads.append((end, sp.rate * (sp.free_length - np.linalg.norm(end - sp.body))
                              * unit(end - sp.body)))
        a0, a1 = part.base
        total = sum(f for _, f in loads)
        turning = sum(np.cross(p - a0, f) for p, f in loads)
        lhs = np.block([[np.eye(3), np.eye(3)],     # R0 + R1 = -total, (a1-a0) x R1 = -turning
                        [np.zeros((3, 3)), np.cross(a1 - a0, np.eye(3)).T]])
        react = np.linalg.lstsq(lhs, -np.r_[total, turning], rcond=None)[0]
        for key, at, f in ((f'{part.name}_axis0', a0, react[:3]),
                           (f'{part.name}_axis1', a1, react[3:])):
            res.pivot_forces_n[key] = res.body_forces_n[key] = -f
            res.body_points_mm[key] = at

    def _arm_body_forces(self, q, part, res):
        """Add the forces (and couples) the arm's bushings put on the body to res."""
        b, a = part.bushing, part.axis
        phi = q[part.index + 3:part.index + 6]
        for key, at in part.bushing_points():
            d = self.arm_point(q, part, at) - at
            res.pivot_forces_n[key] = stiffness(a, b['axial'], b['radial']) @ d
            res.body_forces_n[key] = res.pivot_forces_n[key]
            # where the arm takes it (the moving side): the moments balance there exactly
            res.body_points_mm[key] = self.arm_point(q, part, at).real
            # the couple on the arm is -J^-T dE/dphi; the body takes its opposite
            torque = stiffness(a, b['torsion'], b['conical']) @ phi
            res.body_couples_nmm = res.body_couples_nmm + np.linalg.solve(
                spatial_jacobian(phi).T, torque)


def _bushing(item, s):
    """Return the bushing's rates in N/mm and N mm/rad (None if rigid)."""
    if item is None:
        return None
    return {'axial': float(item['axial']) / s, 'radial': float(item['radial']) / s,
            'torsion': float(item.get('torsion', 0.0)) * NM_PER_DEG,
            'conical': float(item.get('conical', 0.0)) * NM_PER_DEG,
            'at': item.get('at', 'pivots')}


def _least_curvature(matrix, n):
    """
    Return the least eigenvalue of the Lagrangian's Hessian on the constraints' tangent space.

    matrix: Newton's matrix [[H, J^T], [J, 0]] with n unknowns q; > 0 at a strict minimum.
    """
    basis = null_space(matrix[n:, :n])
    if basis.shape[1] == 0:     # a rigid scene: nothing moves, nothing to be minimal over
        return math.inf
    hessian = basis.T @ matrix[:n, :n] @ basis
    return float(np.linalg.eigvalsh(0.5 * (hessian + hessian.T)).min())


def _normals(direction):
    """Return two unit vectors square to direction and to each other (a line's normals)."""
    d = unit(direction)
    helper = np.eye(3)[np.argmin(np.abs(d))]
    n1 = unit(np.cross(d, helper))
    return n1, np.cross(d, n1)


def _angle_about(part, joint):
    """Return the angle (rad) the arm turns about its axis to bring its ball joint to joint."""
    a, o = part.axis, part.base[0]
    r0, r1 = part.carrier - o, joint - o
    r0, r1 = r0 - (r0 @ a) * a, r1 - (r1 @ a) * a
    return math.atan2(np.cross(r0, r1) @ a, r0 @ r1)
