# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The force at every pickup of a solved equilibrium, compiled (doc/kc.md, The loaded table).

From the multipliers (a constraint's force on a point is -lambda dc/dx, on the body as on the
moving parts) and the energies (a bushing's force on the body is K d at its point B, with the
couple d x K d of its offset and its rotational torque; a spring pulls its body end with its
force along itself). A link that carries a spring is no two-force member: its force along
itself differs at its two ends by the spring's push along it, and both ends are reported
(the force of the link on its base, and on the carrier, each along the link). An arm without
a bushing is a rigid revolute: its pivot forces balance the arm (ball joint and spring
mounts), the axial force, which a rigid revolute leaves undetermined, shared equally (the
least-norm pair). N, N m, mm. The validity check (a bushing deflected or turned beyond the
model) reads the same deflections.

The answer of a solve is one float array (answer_offsets: the pose, then the pickups'
forces); pack.Names says which slot is which pickup, and the dicts of a Loaded are built from
it when they are read (pickups.Pickups).
"""

from __future__ import annotations

import math

import numpy as np

from . import kernel
from .rotation import energy_into, log_into
from ..base.compiled import bare, jitable
from ..base.so3 import camber_toe

# The model's validity (doc/kc.md): beyond these a load is not carried
MAX_DEFLECTION_MM = 10.0
MAX_CONICAL_DEG = 5.0
VALID, DEFLECTS, TURNS = 0, 1, 2
# the head of an answer: wheel centre (3,), rotation (3, 3), camber and toe (rad), holding
# force (N, + = up), the load's point (3,), residual (N), iterations, validity (kind,
# bushing, value: mm or deg)
CENTER, ROTATION, CAMBER, TOE, HOLDING, LOAD_POINT, RESIDUAL, ITERATIONS = \
    0, 3, 12, 13, 14, 15, 18, 19
VALIDITY, VALIDITY_BUSHING, VALIDITY_VALUE, HEAD = 20, 21, 22, 24


@jitable
def answer_offsets(pickups, balls, links, springs):
    """
    Return the offsets of an answer's parts, and its size.

    The parts after the head: body forces (P, 3) N, body moments (P, 3) N m, body points
    (P, 3) mm, ball joint forces (Q, 3) N, link forces (L,), link ends (L, 2), spring forces
    (S,), for P pickups, Q ball joints, L links and S springs.
    """
    force = HEAD
    moment = force + 3 * pickups
    point = moment + 3 * pickups
    ball = point + 3 * pickups
    link = ball + 3 * balls
    end = link + links
    spring = end + 2 * links
    return force, moment, point, ball, link, end, spring, spring + springs


@bare
def counts(model):
    """Return the numbers of body pickups, ball joints, links and springs of a Model."""
    balls, c_ball = 0, model.c_ball
    for i in range(len(c_ball)):
        balls = max(balls, c_ball[i] + 1)
    return len(model.p_rack), balls, len(model.l_row), len(model.s_body)


@bare
def _cross(a0, a1, a2, b0, b1, b2):
    """Return a x b as three numbers."""
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@bare
def places(model, c, r, inputs, out):
    """
    Write where every item of every term is at a pose into out (T, 3, 3), mm; unused: NaN.

    In one function (kernel.place's arithmetic): a call per item taking the arrays would cost
    more in reference counts (numba) than the arithmetic.
    """
    b_ref0, it_body, it_x0 = model.b_ref0, model.it_body, model.it_x0
    it_trans, it_rack, rack, load = model.it_trans, model.it_rack, inputs.rack, inputs.x_load
    last = len(model.t_kind) - 1
    for t in range(len(model.t_kind)):
        for a in range(3):
            body = it_body[t, a]
            if body == -2:
                out[t, a, 0] = out[t, a, 1] = out[t, a, 2] = np.nan
                continue
            if t == last:
                x0x, x0y, x0z = load[0], load[1], load[2]
            else:
                x0x, x0y, x0z = it_x0[t, a, 0], it_x0[t, a, 1], it_x0[t, a, 2]
            if body < 0:
                out[t, a, 0], out[t, a, 1], out[t, a, 2] = x0x, x0y + rack * it_rack[t, a], x0z
                continue
            trans = it_trans[t, a]
            d0 = x0x - b_ref0[body, 0] * trans
            d1 = x0y - b_ref0[body, 1] * trans
            d2 = x0z - b_ref0[body, 2] * trans
            for i in range(3):
                out[t, a, i] = (r[body, i, 0] * d0 + r[body, i, 1] * d1 + r[body, i, 2] * d2
                                + c[body, i] * trans)


@bare
def pickups(model, c, r, lam, inputs, out, work):
    """
    Write the answer of the equilibrium (c, r, lam) under inputs into out (answer_offsets).

    work: a kernel.Scratch. Forces N on the body (pickups) and on the carrier (ball joints),
    moments N m, points mm; the head as its constants say.
    """
    p_count, q_count, l_count, s_count = counts(model)
    o_force, o_moment, o_point, o_ball, o_link, o_end, o_spring, size = answer_offsets(
        p_count, q_count, l_count, s_count)
    for i in range(size):
        out[i] = 0.0
    force = out[o_force:o_moment].reshape((p_count, 3))
    moment = out[o_moment:o_point].reshape((p_count, 3))
    point = out[o_point:o_ball].reshape((p_count, 3))
    ball = out[o_ball:o_link].reshape((q_count, 3))
    rigid, at = work.rigid, work.at   # per rigid arm: force, moment about axis[0]; places
    for h in range(rigid.shape[0]):
        for k in range(6):
            rigid[h, k] = 0.0
    places(model, c, r, inputs, at)
    g3, phi = work.g3, work.phi
    rack, m = inputs.rack, model.m
    t_kind, t_data, c_ball, c_body, c_hinge = (model.t_kind, model.t_data, model.c_ball,
                                               model.c_body, model.c_hinge)
    h_axis, it_w, it_body = model.h_axis, model.it_w, model.it_body
    # (fields read into names first: numba counts a reference to a tuple's field at each
    # read in a loop)
    p_point, p_rack, t_table, table = model.p_point, model.p_rack, model.t_table, model.table
    s_body, s_move, t_vec, t_rack = model.s_body, model.s_move, model.t_vec, model.t_rack
    t_stiff, u_body, u_rot, r_turn = model.t_stiff, model.u_body, model.u_rot, model.r_turn
    u_share, b_kind, u_axis, h_slot = model.u_share, model.b_kind, model.u_axis, model.h_slot
    l_row, l_slot, h3, rot = model.l_row, model.l_slot, work.h3, work.rot
    for p in range(p_count):
        for i in range(3):
            point[p, i] = p_point[p, i]
        point[p, 1] += rack * p_rack[p]
    for i in range(m - 1):
        kind, q = t_kind[i], c_ball[i]
        if kind == kernel.LINK:
            scale = lam[i] / t_data[i, 0]
            for k in range(3):
                d = at[i, 0, k] - at[i, 1, k]
                ball[q, k] = -scale * d
                if c_body[i] >= 0:
                    force[c_body[i], k] += scale * d
        elif kind == kernel.BALL:
            ball[q, int(t_data[i, 0])] = lam[i]
            h = c_hinge[i]
            if h >= 0:   # the carrier pulls the rigid arm at its ball joint
                for k in range(3):
                    rigid[h, k] -= lam[i + k]
                m0, m1, m2 = _cross(at[i, 0, 0] - h_axis[h, 0, 0], at[i, 0, 1] - h_axis[h, 0, 1],
                                    at[i, 0, 2] - h_axis[h, 0, 2], lam[i], lam[i + 1],
                                    lam[i + 2])
                rigid[h, 3] -= m0
                rigid[h, 4] -= m1
                rigid[h, 5] -= m2
        elif kind == kernel.LINE:
            for k in range(3):
                ball[q, k] += lam[i] * at[i, 1, k]
                force[c_body[i], k] -= lam[i] * at[i, 1, k]
    pushed = out[o_spring:size]
    for s in range(s_count):   # each spring's pulls on the body, ball joints and rigid arms
        t = m + s
        g0 = g1 = g2 = 0.0
        for a in range(1, 3):
            if it_body[t, a] != -2:
                w = it_w[t, a]
                g0, g1, g2 = g0 + w * at[t, a, 0], g1 + w * at[t, a, 1], g2 + w * at[t, a, 2]
        g0, g1, g2 = g0 - at[t, 0, 0], g1 - at[t, 0, 1], g2 - at[t, 0, 2]
        length = math.sqrt(g0 * g0 + g1 * g1 + g2 * g2)
        tension, _ = kernel.spring_at(t_data[t, 0], t_data[t, 1], t_table[t, 0],
                                      t_table[t, 1], table, length)
        pushed[s] = -tension
        u0, u1, u2 = g0 / length, g1 / length, g2 / length
        slot = s_body[s]
        force[slot, 0] += tension * u0
        force[slot, 1] += tension * u1
        force[slot, 2] += tension * u2
        for a in range(1, 3):
            if it_body[t, a] == -2:
                continue
            share = -it_w[t, a] * tension   # the spring's push on the moving end
            kind, target = s_move[s, a - 1, 0], s_move[s, a - 1, 1]
            if kind == kernel.PICKUP:
                force[target, 0] += share * u0
                force[target, 1] += share * u1
                force[target, 2] += share * u2
            elif kind == kernel.BALL_JOINT:
                ball[target, 0] += share * u0
                ball[target, 1] += share * u1
                ball[target, 2] += share * u2
            elif kind == kernel.RIGID_ARM:
                rigid[target, 0] += share * u0
                rigid[target, 1] += share * u1
                rigid[target, 2] += share * u2
                m0, m1, m2 = _cross(at[t, a, 0] - h_axis[target, 0, 0],
                                    at[t, a, 1] - h_axis[target, 0, 1],
                                    at[t, a, 2] - h_axis[target, 0, 2], share * u0, share * u1,
                                    share * u2)
                rigid[target, 3] += m0
                rigid[target, 4] += m1
                rigid[target, 5] += m2
    for b in range(len(u_body)):
        t = m + s_count + b
        d0 = at[t, 0, 0] - t_vec[t, 0]
        d1 = at[t, 0, 1] - t_vec[t, 1] - rack * t_rack[t]
        d2 = at[t, 0, 2] - t_vec[t, 2]
        k = t_stiff[t]
        f0 = k[0, 0] * d0 + k[0, 1] * d1 + k[0, 2] * d2
        f1 = k[1, 0] * d0 + k[1, 1] * d1 + k[1, 2] * d2
        f2 = k[2, 0] * d0 + k[2, 1] * d1 + k[2, 2] * d2
        slot = u_body[b]
        force[slot, 0] += f0
        force[slot, 1] += f1
        force[slot, 2] += f2
        g3[0] = g3[1] = g3[2] = 0.0
        turn = u_rot[b]
        body = it_body[t, 0]
        if turn >= 0:   # the arm's bushings share its rotational torque
            log_into(r[body], phi)
            energy_into(phi, r_turn[turn], g3, h3, rot)
        share = u_share[b] if turn >= 0 else 0.0
        m0, m1, m2 = _cross(d0, d1, d2, f0, f1, f2)   # the couple of B's offset, d x K d
        moment[slot, 0] += (m0 + share * g3[0]) / 1000.0
        moment[slot, 1] += (m1 + share * g3[1]) / 1000.0
        moment[slot, 2] += (m2 + share * g3[2]) / 1000.0
        if out[VALIDITY] == VALID:
            _validity(b_kind[body] == kernel.ARM, r[body], u_axis[b], b, d0, d1,
                      d2, out, phi)
    for h in range(len(h_slot)):
        rigid_arm(h_axis[h], rigid[h], force[h_slot[h, 0]], force[h_slot[h, 1]])
    for j in range(l_count):
        i = l_row[j]
        d0, d1, d2 = at[i, 0, 0] - at[i, 1, 0], at[i, 0, 1] - at[i, 1, 1], at[i, 0, 2] - at[
            i, 1, 2]
        length = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
        out[o_link + j] = lam[i] / t_data[i, 0] * length
        base, joint = l_slot[j, 0], l_slot[j, 1]
        out[o_end + 2 * j] = (force[base, 0] * d0 + force[base, 1] * d1
                              + force[base, 2] * d2) / length
        out[o_end + 2 * j + 1] = -(ball[joint, 0] * d0 + ball[joint, 1] * d1
                                   + ball[joint, 2] * d2) / length
    _head(model, c, r, lam, inputs, out, at[len(model.t_kind) - 1, 0])


@bare
def rigid_arm(axis, loads, p0, p1):
    """
    Add to p0, p1 the forces (3,) N a rigid revolute's pivots exert on the body.

    loads: those on its arm, the force (3,) and its moment about axis[0] (3,). The reactions
    on the arm, P0 at axis[0] and P1 at axis[1], balance them: P0 + P1 = -F, L x P1 = -M
    (L = axis[1] - axis[0]; M has no part along L at equilibrium). That fixes P1 across L,
    -(M x L) / |L|^2; along L the axial force is shared equally (the least-norm pair).
    """
    s0, s1, s2 = axis[1, 0] - axis[0, 0], axis[1, 1] - axis[0, 1], axis[1, 2] - axis[0, 2]
    span2 = s0 * s0 + s1 * s1 + s2 * s2
    norm = math.sqrt(span2)
    a0, a1, a2 = s0 / norm, s1 / norm, s2 / norm
    f0, f1, f2, m0, m1, m2 = loads[0], loads[1], loads[2], loads[3], loads[4], loads[5]
    axial = 0.5 * (f0 * a0 + f1 * a1 + f2 * a2)
    q0 = -(m1 * s2 - m2 * s1) / span2 - axial * a0
    q1 = -(m2 * s0 - m0 * s2) / span2 - axial * a1
    q2 = -(m0 * s1 - m1 * s0) / span2 - axial * a2
    p0[0] += f0 + q0   # on the body: -P0 = F + P1, -P1
    p0[1] += f1 + q1
    p0[2] += f2 + q2
    p1[0] -= q0
    p1[1] -= q1
    p1[2] -= q2


@bare
def _validity(arm, rotation, axis, b, d0, d1, d2, out, phi):
    """Note bushing b if deflected (d, mm) or, on an arm, turned conically beyond the model."""
    size = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
    if not size <= MAX_DEFLECTION_MM:
        out[VALIDITY], out[VALIDITY_BUSHING], out[VALIDITY_VALUE] = DEFLECTS, b, size
        return
    if not arm:
        return
    log_into(rotation, phi)
    along = phi[0] * axis[0] + phi[1] * axis[1] + phi[2] * axis[2]
    x0, x1, x2 = phi[0] - along * axis[0], phi[1] - along * axis[1], phi[2] - along * axis[2]
    conical = math.degrees(math.sqrt(x0 * x0 + x1 * x1 + x2 * x2))
    if not conical <= MAX_CONICAL_DEG:
        out[VALIDITY], out[VALIDITY_BUSHING], out[VALIDITY_VALUE] = TURNS, b, conical


@bare
def _head(model, c, r, lam, inputs, out, load_point):
    """Write the pose, the holding force and the load's point (3,) into out's head."""
    for i in range(3):
        out[CENTER + i] = c[0, i]
        for j in range(3):
            out[ROTATION + 3 * i + j] = r[0, i, j]
    spin = model.consts[kernel.SPIN:kernel.SPIN + 3]
    a0 = r[0, 0, 0] * spin[0] + r[0, 0, 1] * spin[1] + r[0, 0, 2] * spin[2]
    a1 = r[0, 1, 0] * spin[0] + r[0, 1, 1] * spin[1] + r[0, 1, 2] * spin[2]
    a2 = r[0, 2, 0] * spin[0] + r[0, 2, 1] * spin[1] + r[0, 2, 2] * spin[2]
    out[CAMBER], out[TOE] = camber_toe(a0, a1, a2, model.consts[kernel.SIDE])
    out[HOLDING] = -lam[model.m - 1]
    for i in range(3):
        out[LOAD_POINT + i] = load_point[i]
