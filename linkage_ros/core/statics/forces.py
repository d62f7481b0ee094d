# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The force at every pickup of a solved equilibrium (STATICS_SPEC.md, 'Units and signs').

From the multipliers (a constraint's force on a point is -lambda dc/dx, on the body as on the
moving parts) and the energies (a bushing's force on the body is K d at its point B, with the
couple d x K d of its offset and its rotational torque; a spring pulls its body end with
rate (length - free length) along itself). An arm without a bushing is a rigid revolute: its
pivot forces balance the arm (ball joint and spring mounts), the axial force, which a rigid
revolute leaves undetermined, shared equally (the least-norm pair). N, N m, mm.
"""

from __future__ import annotations

import math

import numpy as np

from . import kernel
from .rotation import energy_terms, log_so3
from .system import CARRIER, Item, position, spring_terms
from ..base.geometry import cross

EYE = np.eye(3)


def item_places(system, model, pose) -> np.ndarray:
    """
    Return where every item of a System is at a pose, (T, 3, 3) mm, in pack.py's term order.

    model: the System's kernel.Model (kernel.places), or None: by system.position (the
    numpy path). Terms: the constraints in order, then the springs (slot 0 the body end,
    then the moving items), the bushings, the load; unused slots NaN.
    """
    if model is not None:
        out = np.empty((len(model.t_kind), 3, 3))
        kernel.places(tuple(model), pose.c, pose.r, out)
        return out
    terms = ([items for _, _, items, _ in system.constraints]
             + [[end] + [it for _, it in moving] for _, end, moving in system.springs]
             + [[Item(b.body, b.x0)] for b in system.bushings] + [[system.load_item]])
    out = np.full((len(terms), 3, 3), np.nan)
    for t, items in enumerate(terms):
        for a, item in enumerate(items):
            out[t, a] = position(system, pose, item)[0]
    return out


def pickup_forces(scene, system, eq, force: np.ndarray, at: np.ndarray) -> dict:
    """Return the Loaded force fields of an equilibrium (dicts keyed by pickup); at: places."""
    pose, lam = eq.pose, eq.multipliers
    m, springs_at = len(system.constraints), len(system.constraints) + len(system.springs)
    links, balls, points, body, moments = {}, {}, {}, {}, {}
    arm_loads = {}   # hinge body -> list of (point, force on the arm)

    def add(key, point, f, m=None):
        points[key] = np.asarray(point, dtype=float)
        before = body.get(key)
        body[key] = f if before is None else before + f
        if m is not None:
            moments[key] = m if key not in moments else moments[key] + m

    for i, ((name, kind, items, data), xs) in enumerate(zip(system.constraints, at)):
        if kind == 'link':
            d = xs[0] - xs[1]
            scale = lam[i] / data
            links[name] = float(scale * math.sqrt(d @ d))
            balls[name] = -scale * d
            if items[1].body < 0:
                add(f'{name}_base', xs[1], scale * d)
        elif kind == 'ball':
            if data == 0:   # the first of a ball joint's three rows, x, y, z (system.build)
                balls[name] = lam[i:i + 3].copy()
                if system.bodies[items[0].body].kind == 'hinge':
                    arm_loads.setdefault(items[0].body, []).append((xs[0], -lam[i:i + 3]))
        elif kind == 'line':
            balls[name] = balls.get(name, np.zeros(3)) + lam[i] * xs[1]
            add(f'{name}_top', data, -lam[i] * xs[1])
    springs = {}
    for (element, end, moving), xs in zip(system.springs, at[m:springs_at]):
        x_move = sum(w * x for (w, _), x in zip(moving, xs[1:]))
        _, grads, _ = spring_terms(element, end.x0, x_move)
        gap = x_move - end.x0
        springs[element.name] = element.spring_at(math.sqrt(gap @ gap))[0]   # rate or table
        add(f'{element.name}_body', end.x0, -grads[0])
        for (w, it), x in zip(moving, xs[1:]):
            on_move = -w * grads[1]
            if it.body < 0:   # the share at a rigid link's base goes to the body there
                link = scene.constraints[element.mount.constraint].name
                add(f'{link}_base', it.x0, on_move)
            elif system.bodies[it.body].kind == CARRIER:
                # a link that carries the spring passes its share at the carrier end on to
                # the carrier, beside its axial force (STATICS_SPEC.md DISAGREEMENTS 1)
                link = scene.constraints[element.mount.constraint].name
                balls[link] = balls.get(link, np.zeros(3)) + on_move
            elif system.bodies[it.body].kind == 'hinge':
                arm_loads.setdefault(it.body, []).append((x, on_move))
    if system.bushings:   # all at once: K d at B, its couple d x K d, the rotational torque
        bushes = system.bushings
        d = at[springs_at:springs_at + len(bushes), 0] - np.array([b.at for b in bushes])
        f = (np.array([b.stiff for b in bushes]) @ d[:, :, None])[:, :, 0]
        couples = cross(d, f)
        torques = {}   # per arm body: its bushings share one rotation
        for b, fb, couple in zip(bushes, f, couples):
            if b.turn is not None:
                if b.body not in torques:
                    torques[b.body] = energy_terms(log_so3(pose.r[b.body]), b.turn)[1]
                couple = couple + torques[b.body]
            add(b.key, b.at, fb, couple / 1000.0)
    for j, k in system.body_of.items():
        if system.bodies[k].kind == 'hinge':
            c = scene.constraints[j]
            for end, f in zip(('axis0', 'axis1'), _pivots(c.base, arm_loads.get(k, []))):
                add(f'{c.name}_{end}', c.base[0 if end == 'axis0' else 1], f)
    arms = [b.key for b in system.bushings if scene.constraints[b.constraint].type == 'circle']
    arms += [f'{c.name}_{end}' for c in scene.constraints
             if c.type == 'circle' and c.bushing is None for end in ('axis0', 'axis1')]
    pivots = {key: body[key] for key in arms}
    return {'link_forces_n': links, 'ball_joint_forces_n': balls, 'spring_forces_n': springs,
            'pivot_forces_n': pivots, 'body_forces_n': body, 'body_points_mm': points,
            'body_moments_nm': moments}


def _pivots(axis_points, loads):
    """
    Return the forces (3,) N a rigid revolute's pivots exert on the body.

    loads: those on its arm [(point (3,), force (3,)), ...]. The reactions on the arm, P0 at
    axis[0] and P1 at axis[1], balance them: P0 + P1 = -F, L x P1 = -M (moments about axis[0],
    L = axis[1] - axis[0]; M has no part along L at equilibrium). That fixes P1 across L,
    -(M x L) / |L|^2; along L the axial force is shared equally (the least-norm pair).
    """
    a0, a1 = axis_points
    total = sum((f for _, f in loads), np.zeros(3))
    moment = sum((cross(p - a0, f) for p, f in loads), np.zeros(3))
    span = a1 - a0
    along = span / np.linalg.norm(span)
    p1 = -cross(moment, span) / (span @ span) - 0.5 * (total @ along) * along
    return total + p1, -p1   # on the body: -P0 = F + P1, -P1
