# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The statics of linkage_ros.core.statics in numpy: the tests' reference for the compiled one.

The same equations (the System of core/statics/system.py: its bodies, constraint rows and
energies), written with numpy arrays and np.linalg.solve on the full KKT system, term by
term as system.py's docstring states them: assemble (the gradient, the symmetric Hessian,
the constraint values and rows), Newton from the kinematic pose (newton), the pickup forces
(pickup_forces) and the rates (rates). Slow (milliseconds), and kept out of the package: the
package has one path, the compiled one (kernel.py, kkt.py, newton.py, forces.py, command.py).
test_statics_kernel compares the two.
"""

from __future__ import annotations

import math

from linkage_ros.core.base import cross, exp_so3, point_velocity
from linkage_ros.core.measure import patch_offset
from linkage_ros.core.solve import Continuation
from linkage_ros.core.solve.mechanism import compile_scene
from linkage_ros.core.statics.rotation import energy_terms, log_so3
from linkage_ros.core.statics.system import build, CARRIER, initial_pose, Item, Pose
import numpy as np

EYE = np.eye(3)
TOL_STEP, MAX_ITER, MAX_HALVINGS, PREDICTED = 1e-11, 30, 6, 1e-3


def blocks(body):
    """Return T (3, n) and W (3, n) of a body: dc = T dq, w = W dq."""
    n = body.size
    t, w = np.zeros((3, n)), np.zeros((3, n))
    if body.kind in ('carrier', 'arm'):
        t[:, :3], w[:, 3:] = EYE, EYE
    elif body.kind == 'base':
        t[:] = EYE
    else:
        w[:, 0] = body.axis
    return t, w


def position(system, pose, item, rack):
    """Return where an item is, x (a point or a direction), and v = R (x0 - ref0), (3,) mm."""
    if item.body < 0:
        return item.x0 + np.array([0.0, rack if item.rack else 0.0, 0.0]), np.zeros(3)
    body = system.bodies[item.body]
    if not item.translates:
        v = pose.r[item.body] @ item.x0
        return v, v
    v = pose.r[item.body] @ (item.x0 - body.ref0)
    return pose.c[item.body] + v, v


def skew(v):
    """Return [v]x (3, 3)."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


class Assembly:
    """Accumulates gradient (n,), Hessian (n, n), constraint values and rows at one pose."""

    def __init__(self, system, pose, rack):
        self.system, self.pose, self.rack = system, pose, rack
        n = system.size
        self.grad, self.hess = np.zeros(n), np.zeros((n, n))
        self.blocks = [blocks(b) for b in system.bodies]

    def jac(self, weighted):
        """Return d x / d q (3, n) of weighted items."""
        out = np.zeros((3, self.system.size))
        for w, it in weighted:
            if it.body < 0:
                continue
            body = self.system.bodies[it.body]
            t, wb = self.blocks[it.body]
            _, v = position(self.system, self.pose, it, self.rack)
            out[:, body.start:body.start + body.size] += w * (
                -skew(v) @ wb + (t if it.translates else 0.0))
        return out

    def term(self, points, grads, hess, factor=1.0):
        """Add factor times a term of points; return its row d/dq (n,), unscaled."""
        jacs = [self.jac(p) for p in points]
        row = sum(g @ j for g, j in zip(grads, jacs))
        self.grad += factor * row
        if hess is not None:
            for i, ji in enumerate(jacs):
                for k, jk in enumerate(jacs):
                    if hess[i][k] is not None:
                        self.hess += factor * (ji.T @ hess[i][k] @ jk)
        for p, g in zip(points, grads):
            for w, it in p:
                if it.body < 0:
                    continue
                body = self.system.bodies[it.body]
                _, v = position(self.system, self.pose, it, self.rack)
                wb = self.blocks[it.body][1]
                second = 0.5 * (np.outer(v, g) + np.outer(g, v)) - (g @ v) * EYE
                s = slice(body.start, body.start + body.size)
                self.hess[s, s] += factor * w * (wb.T @ second @ wb)
        return row

    def body_term(self, body, grad, hess):
        """Add an energy's gradient (3,) and Hessian (3, 3) in a body's rotation w."""
        b = self.system.bodies[body]
        wb = self.blocks[body][1]
        s = slice(b.start, b.start + b.size)
        self.grad[s] += wb.T @ grad
        if hess is not None:
            self.hess[s, s] += wb.T @ hess @ wb


def constraint_terms(kind, data, xs, z):
    """Return c, d/dx (p, 3), d2/dx2 (p, p, 3, 3) or None of a constraint row at xs."""
    if kind == 'link':
        d = xs[0] - xs[1]
        h = EYE / data
        return (d @ d - data * data) / (2.0 * data), np.array([d / data, -d / data]), \
            [[h, -h], [-h, h]]
    if kind == 'ball':
        e = EYE[data]
        return xs[0][data] - xs[1][data], np.array([e, -e]), None
    if kind == 'line':
        gap = data - xs[0]
        return gap @ xs[1], np.array([-xs[1], gap]), [[None, -EYE], [-EYE, None]]
    return xs[0][2] - z, np.array([EYE[2]]), None


def spring_terms(element, x_body, x_move):
    """Return E, d/dx (2, 3), d2/dx2 of a spring between x_body and x_move (N mm)."""
    d = x_move - x_body
    length = float(np.linalg.norm(d))
    u = d / length
    pushed, stiffness, energy = element.spring_at(length)   # a rate or a force table
    f = -pushed   # the tension, N
    h = stiffness * np.outer(u, u) + f / length * (EYE - np.outer(u, u))
    return energy, np.array([-f * u, f * u]), [[h, -h], [-h, h]]


def bush_anchor(b, rack):
    """Return where a bushing holds its point, B (3,) mm, at a rack."""
    return b.at + np.array([0.0, rack if b.rack else 0.0, 0.0])


def assemble(system, pose, multipliers, z, rack, x_load, force, moment):
    """
    Return (gradient of L - M (n,), Hessian of L (n, n), c (m,), dc/dq (m, n), energy).

    force (3,) N at the carrier point x_load (design), moment (3,) N mm fixed in space.
    """
    asm = Assembly(system, pose, rack)
    m = len(system.constraints)
    values, rows = np.empty(m), np.empty((m, system.size))
    energy = 0.0
    for i, (_, kind, items, data) in enumerate(system.constraints):
        xs = [position(system, pose, it, rack)[0] for it in items]
        c, g, h = constraint_terms(kind, data, xs, z)
        values[i] = c
        rows[i] = asm.term([((1.0, it),) for it in items], g, h, multipliers[i])
    for element, body, moving in system.springs:
        x_move = sum(w * position(system, pose, it, rack)[0] for w, it in moving)
        e, g, h = spring_terms(element, body.x0, x_move)
        energy += e
        asm.term([((1.0, body),), moving], g, h)
    for b in system.bushings:
        d = position(system, pose, Item(b.body, b.x0), rack)[0] - bush_anchor(b, rack)
        energy += 0.5 * d @ b.stiff @ d
        asm.term([((1.0, Item(b.body, b.x0)),)], np.array([b.stiff @ d]), [[b.stiff]])
    for k, turn in system.rotations:
        e, g, h = energy_terms(log_so3(pose.r[k]), turn)
        energy += e
        asm.body_term(k, g, h)
    load = Item(0, x_load)
    energy -= force @ position(system, pose, load, rack)[0]
    asm.term([((1.0, load),)], np.array([-force]), None)
    asm.body_term(0, -moment, None)
    return asm.grad, 0.5 * (asm.hess + asm.hess.T), values, rows, energy


def moved(system, pose, step):
    """Return the pose moved by a coordinate step (n,): c += T dq, R <- exp(W dq) R."""
    c, r = pose.c.copy(), pose.r.copy()
    for k, body in enumerate(system.bodies):
        t, w = blocks(body)
        dq = step[body.start:body.start + body.size]
        c[k] = c[k] + t @ dq
        omega = w @ dq
        if omega.any():
            r[k] = exp_so3(omega) @ r[k]
    return Pose(c, r)


def kkt(hess, rows):
    """Return the KKT matrix [[H, J^T], [J, 0]] (n + m, n + m)."""
    n, m = hess.shape[0], rows.shape[0]
    out = np.zeros((n + m, n + m))
    out[:n, :n], out[:n, n:], out[n:, :n] = hess, rows.T, rows
    return out


def _scaled(system, vec, lever, divide):
    scaled = vec.copy()
    for body in system.bodies:
        turn = (slice(body.start + 3, body.start + 6) if body.kind in ('carrier', 'arm')
                else slice(body.start, body.start + 1) if body.kind == 'hinge' else None)
        if turn is not None:
            scaled[turn] = scaled[turn] / lever if divide else scaled[turn] * lever
    return float(np.max(np.abs(scaled))) if scaled.size else 0.0


def newton(system, pose, multipliers, z, rack, x_load, force, moment, lever):
    """Solve one equilibrium by Newton (full KKT, symmetric Hessian); (ok, pose, lambda)."""
    last, tol = 0.0, TOL_STEP * max(1.0, lever)
    for _ in range(MAX_ITER):
        grad, hess, values, rows, _ = assemble(system, pose, multipliers, z, rack, x_load,
                                               force, moment)
        rhs = -np.concatenate((grad - rows.T @ multipliers, values))
        sol = np.linalg.solve(kkt(hess, rows), rhs)
        if not np.isfinite(sol).all():
            break
        step, multipliers = sol[:system.size], sol[system.size:]
        pose = moved(system, pose, step)
        size = _scaled(system, step, lever, False)
        if size < tol or size ** 3 < PREDICTED * tol * last * last:
            return True, pose, multipliers
        if not size < 1e3 * lever:
            break
        last = size
    return False, pose, multipliers


def loaded(system, pose, multipliers, z, rack, x_load, force, moment, lever):
    """Solve under a load from an equilibrium, in 1, 2, 4 ... increments as needed."""
    for halvings in range(MAX_HALVINGS + 1):
        parts, here = 2 ** halvings, (True, pose, multipliers)
        for k in range(1, parts + 1):
            here = newton(system, here[1], here[2], z, rack, x_load, force * k / parts,
                          moment * k / parts, lever)
            if not here[0]:
                break
        else:
            return here
    return here


class Solved:
    """A numpy solve of a scene at a travel and rack: the zero-load and loaded equilibria."""

    def __init__(self, scene, travel, rack=0.0):
        self.scene, self.rack = scene, rack
        self.mech = mech = compile_scene(scene)
        self.system = system = build(scene)
        self.z = float(mech.design_center[2] + travel)
        self.lever = mech.lever
        kin = Continuation(scene).solve(travel, rack if scene.steered else None)
        assert kin.success, kin.message
        start = initial_pose(system, scene, np.asarray(kin.wheel_center),
                             np.asarray(kin.rotation))
        ok, self.pose0, self.lam0 = newton(system, start, np.zeros(len(system.constraints)),
                                           self.z, rack, mech.design_center, np.zeros(3),
                                           np.zeros(3), self.lever)
        assert ok

    def load_point(self, at):
        """Return the load's carrier point (design) x0 (3,) mm: wheel centre or patch."""
        center0 = self.mech.design_center
        if at == 'wc':
            return center0.copy()
        c, r = self.pose0.c[0], self.pose0.r[0]
        axis = r @ self.mech.spin_axis
        patch = c + np.array(patch_offset(axis[0], axis[1], axis[2], self.scene.wheel_radius))
        return center0 + r.T @ (patch - c)

    def loaded(self, load):
        """Return (pose, lambda, x_load, force, moment N mm) of the loaded equilibrium."""
        x_load = self.load_point(load.at)
        force = np.array(load.force_n, dtype=float)
        moment = 1000.0 * np.array(load.moment_nm, dtype=float)
        ok, pose, lam = loaded(self.system, self.pose0, self.lam0, self.z, self.rack, x_load,
                               force, moment, self.lever)
        assert ok
        return pose, lam, x_load, force, moment

    def rates(self):
        """Return (dm (3, 8), w (3, 8), held (8,), patch) per generalized load, as rates."""
        system, pose = self.system, self.pose0
        n, m = system.size, len(system.constraints)
        _, hess, _, rows, _ = assemble(system, pose, self.lam0, self.z, self.rack,
                                       self.mech.design_center, np.zeros(3), np.zeros(3))
        rot = pose.r[0]
        patch = (rot @ (self.load_point('cp') - self.mech.design_center)
                 if self.scene.wheel_radius > 0 else np.zeros(3))
        loads = np.zeros((n + m, 8))
        loads[:6, :6] = np.eye(6)
        loads[1, 6] = loads[0, 7] = 1.0
        loads[3:6, 6] = cross(patch, np.array([0.0, 1.0, 0.0]))
        loads[3:6, 7] = cross(patch, np.array([1.0, 0.0, 0.0]))
        sol = np.linalg.solve(kkt(hess, rows), loads)
        return sol[:3], sol[3:6], -sol[n + m - 1], patch


def pickup_forces(scene, system, pose, lam, rack):
    """Return the Loaded's force dicts (before issue 36: a spring's link by its multiplier)."""
    links, balls, points, body, moments = {}, {}, {}, {}, {}
    arm_loads = {}

    def add(key, point, f, m=None):
        points[key] = np.asarray(point, dtype=float)
        body[key] = f if key not in body else body[key] + f
        if m is not None:
            moments[key] = m if key not in moments else moments[key] + m

    for i, (name, kind, items, data) in enumerate(system.constraints[:-1]):
        xs = [position(system, pose, it, rack)[0] for it in items]
        if kind == 'link':
            d = xs[0] - xs[1]
            scale = lam[i] / data
            links[name] = float(scale * math.sqrt(d @ d))
            balls[name] = -scale * d
            if items[1].body < 0:
                add(f'{name}_base', xs[1], scale * d)
        elif kind == 'ball':
            if data == 0:
                balls[name] = lam[i:i + 3].copy()
                if system.bodies[items[0].body].kind == 'hinge':
                    arm_loads.setdefault(items[0].body, []).append((xs[0], -lam[i:i + 3]))
        elif kind == 'line':
            balls[name] = balls.get(name, np.zeros(3)) + lam[i] * xs[1]
            add(f'{name}_top', data, -lam[i] * xs[1])
    springs = {}
    for element, end, moving in system.springs:
        xs = [position(system, pose, it, rack)[0] for _, it in moving]
        x_move = sum(w * x for (w, _), x in zip(moving, xs))
        _, grads, _ = spring_terms(element, end.x0, x_move)
        gap = x_move - end.x0
        springs[element.name] = element.spring_at(math.sqrt(gap @ gap))[0]
        add(f'{element.name}_body', end.x0, -grads[0])
        for (w, it), x in zip(moving, xs):
            on_move = -w * grads[1]
            if it.body < 0:
                add(f'{scene.constraints[element.mount.constraint].name}_base', x, on_move)
            elif system.bodies[it.body].kind == CARRIER and element.mount.kind != 'carrier':
                link = scene.constraints[element.mount.constraint].name
                balls[link] = balls.get(link, np.zeros(3)) + on_move
            elif system.bodies[it.body].kind == 'hinge':
                arm_loads.setdefault(it.body, []).append((x, on_move))
    torques = {}
    for b in system.bushings:
        d = position(system, pose, Item(b.body, b.x0), rack)[0] - bush_anchor(b, rack)
        f = b.stiff @ d
        couple = cross(d, f)
        if b.turn is not None:
            if b.body not in torques:
                torques[b.body] = energy_terms(log_so3(pose.r[b.body]), b.turn)[1]
            couple = couple + torques[b.body]
        add(b.key, bush_anchor(b, rack), f, couple / 1000.0)
    for j, k in system.body_of.items():
        if system.bodies[k].kind == 'hinge':
            c = scene.constraints[j]
            for end, f in zip(('axis0', 'axis1'), _pivots(c.base, arm_loads.get(k, []))):
                add(f'{c.name}_{end}', c.base[0 if end == 'axis0' else 1], f)
    arms = [b.key for b in system.bushings if scene.constraints[b.constraint].type == 'circle']
    arms += [f'{c.name}_{end}' for c in scene.constraints
             if c.type == 'circle' and c.bushing is None for end in ('axis0', 'axis1')]
    return {'link_forces_n': links, 'ball_joint_forces_n': balls, 'spring_forces_n': springs,
            'pivot_forces_n': {key: body[key] for key in arms}, 'body_forces_n': body,
            'body_points_mm': points, 'body_moments_nm': moments}


def _pivots(axis_points, loads):
    """Return the forces (3,) N a rigid revolute's pivots exert on the body (least norm)."""
    a0, a1 = axis_points
    total = sum((f for _, f in loads), np.zeros(3))
    moment = sum((cross(p - a0, f) for p, f in loads), np.zeros(3))
    span = a1 - a0
    along = span / np.linalg.norm(span)
    p1 = -cross(moment, span) / (span @ span) - 0.5 * (total @ along) * along
    return total + p1, -p1


def patch_move(dm, w, patch):
    """Return the move (3,) of the patch as a carrier point per load (a column of rates)."""
    return np.array(point_velocity(dm, w, patch))
