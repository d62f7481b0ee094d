# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Pack a System (system.py) into the two flat arrays of the compiled statics (kernel.Model).

Besides the terms: the reduced KKT system's order (kkt.py: bushed bodies as clusters, the
carrier, rigid arms and rigid parts' rows as the root) and the pickups' layout (forces.py),
with the names a Loaded gives them, in the order linkage-kc writes its columns.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import kernel
from .system import ARM, BASE, HINGE, Item, System

BODY_KINDS = {'carrier': kernel.CARRIER, 'arm': kernel.ARM, 'hinge': kernel.HINGE,
              'base': kernel.BASE}
TERM_KINDS = {'link': kernel.LINK, 'ball': kernel.BALL, 'line': kernel.LINE,
              'travel': kernel.TRAVEL}
NOTHING, PICKUP = kernel.NOTHING, kernel.PICKUP   # what a spring passes its share to
BALL_JOINT, RIGID_ARM = kernel.BALL_JOINT, kernel.RIGID_ARM


class Names(NamedTuple):
    """What each output slot is called (forces.py reads the slots by these)."""

    pickups: tuple        # (P,) body pickups: '<link>_base', '<arm>_axis0', '<spring>_body'...
    balls: tuple          # (Q,) ball joint forces, by constraint name
    links: tuple          # (L,) links, by constraint name
    carries: tuple        # (L,) bool: the link carries a spring (its two ends differ)
    springs: tuple        # (S,) springs, by element name
    bushings: tuple       # (U,) index of each bushing's pickup
    pivots: tuple         # indices of the arms' pivots among the pickups, in table order


class Packed(NamedTuple):
    """A System packed: kernel.unpack(ints, reals) is its Model; names label the outputs."""

    ints: np.ndarray
    reals: np.ndarray
    names: Names
    system: System


def pack(system: System, scene, mech) -> Packed:
    """Return the Packed System of a scene (mech: its solve.Mechanism)."""
    terms, table = _terms(system)
    layout, names = _layout(system, scene)
    bodies = system.bodies
    count = len(terms)
    it_body = np.full((count, 3), -2, dtype=np.int64)
    it_point = np.zeros((count, 3), dtype=np.int64)
    it_x0, it_trans = np.zeros((count, 3, 3)), np.zeros((count, 3))
    it_w, it_rack = np.zeros((count, 3)), np.zeros((count, 3))
    for t, (_, slots, _, _, _, _, _) in enumerate(terms):
        for a, (point, weight, item) in enumerate(slots):
            it_body[t, a], it_x0[t, a], it_point[t, a] = item.body, item.x0, point
            it_trans[t, a], it_w[t, a] = float(item.translates), weight
            it_rack[t, a] = float(item.rack)
    zero3 = np.zeros(3)
    arrays = [
        np.array([BODY_KINDS[b.kind] for b in bodies], dtype=np.int64),
        np.array([b.start for b in bodies], dtype=np.int64),
        np.array([b.ref0 for b in bodies], dtype=float),
        np.array([b.axis if b.axis is not None else zero3 for b in bodies], dtype=float),
        np.array([t[0] for t in terms], dtype=np.int64), it_body, it_point,
        np.array([t[5] for t in terms], dtype=np.int64).reshape(count, 2), it_x0, it_trans,
        it_w, it_rack, np.array([t[2] for t in terms], dtype=float),
        np.array([t[3] for t in terms], dtype=float),
        np.array([t[6] for t in terms], dtype=float),
        np.array([t[4] for t in terms], dtype=float),
        np.array([k for k, _ in system.rotations], dtype=np.int64),
        np.array([turn for _, turn in system.rotations], dtype=float).reshape(-1, 3, 3),
        np.array(table, dtype=float).reshape(-1, 2),
        *_kkt_order(system),
        *layout,
        np.concatenate((mech.design_center, mech.spin_axis, [scene.side_sign,
                        scene.wheel_radius, mech.lever, 0.0, 0.0])),
    ]
    ints, reals = _flatten(arrays, system.size, len(system.constraints))
    return Packed(ints, reals, names, system)


def _terms(system):
    """Return the terms (kind, slots, data, vec, stiffness, table rows, rack) and tables."""
    terms, table = [], []   # slots: [(point, weight, Item)]
    zero3, zero33, none = np.zeros(3), np.zeros((3, 3)), (-1, -1)
    for _, kind, items, data in system.constraints:
        vec = data if kind == 'line' else zero3
        value = 0.0 if kind in ('line', 'travel') else float(data)
        terms.append((TERM_KINDS[kind], [(p, 1.0, it) for p, it in enumerate(items)],
                      (value, 0.0), vec, zero33, none, 0.0))
    for element, end, moving in system.springs:
        slots = [(0, 1.0, end)] + [(1, w, it) for w, it in moving]
        rows = none
        if element.force_table is not None:
            rows = (len(table), len(table) + len(element.force_table))
            table.extend(np.asarray(element.force_table, dtype=float).tolist())
        terms.append((kernel.SPRING, slots, (element.rate, element.free_length), zero3,
                      zero33, rows, 0.0))
    for b in system.bushings:
        terms.append((kernel.BUSH, [(0, 1.0, Item(b.body, b.x0))],
                      (0.0, 0.0), b.at, b.stiff, none, float(b.rack)))
    terms.append((kernel.LOAD, [(0, 1.0, system.load_item)], (0.0, 0.0), zero3, zero33, none,
                  0.0))
    return terms, table


def _kkt_order(system):
    """
    Return perm and bounds of the reduced KKT system (kkt.py).

    Clusters: each bushed body (arm, link base) with the rows that hold it, in body order;
    then the root: the carrier's coordinates but z, the rigid arms' angles, the other rows.
    """
    n = system.size
    clusters = {k: ([b.start + i for i in range(b.size)], []) for k, b in
                enumerate(system.bodies) if b.kind in (ARM, BASE)}
    root_coords = [0, 1, 3, 4, 5] + [b.start for b in system.bodies if b.kind == HINGE]
    root_rows = []
    for i, (_, _, items, _) in enumerate(system.constraints[:-1]):   # the travel: reduced
        owner = next((it.body for it in items if it.body in clusters), None)
        (clusters[owner][1] if owner is not None else root_rows).append(n + i)
    perm, bounds = [], []
    for coords, rows in clusters.values():
        bounds.append(len(perm))
        perm += coords + rows
    bounds.append(len(perm))
    perm += root_coords + root_rows
    bounds += [len(perm), len(root_coords)]
    return np.array(perm, dtype=np.int64), np.array(bounds, dtype=np.int64)


def _layout(system, scene):
    """Return the pickups' layout arrays (kernel.Model, c_ball to p_rack) and their Names."""
    points, racks, pickups = [], [], {}

    def slot(key, point, rack=False):
        if key not in pickups:
            pickups[key] = len(pickups)
            points.append(np.asarray(point, dtype=float))
            racks.append(float(rack))
        return pickups[key]

    m = len(system.constraints)
    c_ball, c_body, c_hinge = (np.full(m, -1, dtype=np.int64) for _ in range(3))
    balls = {}
    hinges = [k for k, b in enumerate(system.bodies) if b.kind == HINGE]
    links, l_row = [], []
    for i, (name, kind, items, data) in enumerate(system.constraints[:-1]):
        c_ball[i] = balls.setdefault(name, len(balls))
        if kind == 'link':
            links.append(name)
            l_row.append(i)
            if items[1].body < 0:
                c_body[i] = slot(f'{name}_base', items[1].x0, items[1].rack)
        elif kind == 'line':
            c_body[i] = slot(f'{name}_top', data)
        elif kind == 'ball' and data == 0 and items[0].body in hinges:
            c_hinge[i] = hinges.index(items[0].body)
    carried = set()
    s_body = np.zeros(len(system.springs), dtype=np.int64)
    s_move = np.zeros((len(system.springs), 2, 2), dtype=np.int64)
    for s, (element, end, moving) in enumerate(system.springs):
        s_body[s] = slot(f'{element.name}_body', end.x0)
        mount = element.mount
        for a, (_, it) in enumerate(moving):
            if it.body < 0:   # a rigid link's base: the body takes the share there
                target = (PICKUP, slot(f'{scene.constraints[mount.constraint].name}_base',
                                       it.x0, it.rack))
            elif it.body == 0 and mount.kind != 'carrier':
                # a link (or strut) that carries the spring passes its share at the carrier
                # end on to the carrier, beside its own force (doc/kc.md); a spring on the
                # carrier itself pushes the carrier alone
                target = (BALL_JOINT, balls[scene.constraints[mount.constraint].name])
            elif it.body in hinges:
                target = (RIGID_ARM, hinges.index(it.body))
            else:   # a bushed body's bushings carry it
                target = (NOTHING, 0)
            s_move[s, a] = target
        if mount.kind == 'link':
            carried.add(scene.constraints[mount.constraint].name)
    turns = [k for k, _ in system.rotations]
    places = {}
    for b in system.bushings:
        places[b.body] = places.get(b.body, 0) + 1
    u_body = np.array([slot(b.key, b.at, b.rack) for b in system.bushings], dtype=np.int64)
    u_rot = np.array([turns.index(b.body) if b.body in turns else -1 for b in system.bushings],
                     dtype=np.int64)
    u_share = np.array([1.0 / places[b.body] for b in system.bushings])
    h_slot, h_axis = np.zeros((len(hinges), 2), dtype=np.int64), np.zeros((len(hinges), 2, 3))
    by_body = {k: j for j, k in system.body_of.items()}
    for h, k in enumerate(hinges):
        c = scene.constraints[by_body[k]]
        h_slot[h] = [slot(f'{c.name}_axis0', c.base[0]), slot(f'{c.name}_axis1', c.base[1])]
        h_axis[h] = c.base[0], c.base[1]
    l_slot = np.array([[pickups[f'{name}_base'], balls[name]] for name in links],
                      dtype=np.int64).reshape(-1, 2)
    names = list(pickups)
    arms = [b.key for b in system.bushings if scene.constraints[b.constraint].type == 'circle']
    arms += [names[i] for pair in h_slot for i in pair]
    layout = (c_ball, c_body, c_hinge, s_body, s_move, u_body, u_rot, h_slot,
              np.array(l_row, dtype=np.int64), l_slot, u_share,
              np.array([b.axis for b in system.bushings], dtype=float).reshape(-1, 3), h_axis,
              np.array(points, dtype=float).reshape(-1, 3), np.array(racks, dtype=float))
    return layout, Names(tuple(names), tuple(balls), tuple(links),
                         tuple(name in carried for name in links),
                         tuple(e.name for e, _, _ in system.springs),
                         tuple(int(i) for i in u_body), tuple(pickups[k] for k in arms))


def _flatten(arrays, n, m):
    """Return (ints, reals): kernel.Model's scalars, header and int fields; its real fields."""
    assert len(arrays) == len(kernel.FIELDS)
    header = kernel.N_SCALARS + 4 * len(arrays)
    int_parts, real_parts, head = [], [], np.zeros(header, dtype=np.int64)
    head[kernel.N], head[kernel.M] = n, m
    at_int, at_real = header, 0
    for k, (array, (kind, dims)) in enumerate(zip(arrays, kernel.FIELDS)):
        array = np.ascontiguousarray(array, dtype=np.int64 if kind == 'i' else float)
        assert array.ndim == dims, (k, array.shape)
        shape = list(array.shape) + [1] * (3 - array.ndim)
        offset = at_int if kind == 'i' else at_real
        head[kernel.N_SCALARS + 4 * k:kernel.N_SCALARS + 4 * k + 4] = [offset] + shape
        (int_parts if kind == 'i' else real_parts).append(array.ravel())
        if kind == 'i':
            at_int += array.size
        else:
            at_real += array.size
    ints = np.concatenate([head] + int_parts)
    reals = np.concatenate(real_parts) if real_parts else np.zeros(0)
    return ints, reals
