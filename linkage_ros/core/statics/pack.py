# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Pack a System (system.py) into the arrays of the compiled statics (kernel.Model)."""

from __future__ import annotations

import numpy as np

from . import kernel
from .system import Item, System

BODY_KINDS = {'carrier': kernel.CARRIER, 'arm': kernel.ARM, 'hinge': kernel.HINGE,
              'base': kernel.BASE}
TERM_KINDS = {'link': kernel.LINK, 'ball': kernel.BALL, 'line': kernel.LINE,
              'travel': kernel.TRAVEL}


def pack(system: System) -> kernel.Model:
    """Return the kernel.Model of a System (constraints first, in order; then energies)."""
    terms = []   # (kind, [(point, weight, Item)], data (2,), vec (3,), stiffness (3, 3))
    zero3, zero33 = np.zeros(3), np.zeros((3, 3))
    for _, kind, items, data in system.constraints:
        vec = data if kind == 'line' else zero3
        value = 0.0 if kind == 'line' else float(data)
        terms.append((TERM_KINDS[kind], [(p, 1.0, it) for p, it in enumerate(items)],
                      (value, 0.0), vec, zero33))
    for element, end, moving in system.springs:
        slots = [(0, 1.0, end)] + [(1, w, it) for w, it in moving]
        terms.append((kernel.SPRING, slots, (element.rate, element.free_length), zero3,
                      zero33))
    for b in system.bushings:
        terms.append((kernel.BUSH, [(0, 1.0, Item(b.body, b.x0))], (0.0, 0.0), b.at,
                      b.stiff))
    terms.append((kernel.LOAD, [(0, 1.0, system.load_item)], (0.0, 0.0), zero3, zero33))
    count = len(terms)
    it_body = np.full((count, 3), -2, dtype=np.int64)
    it_x0, it_trans = np.zeros((count, 3, 3)), np.zeros((count, 3))
    it_w, it_point = np.zeros((count, 3)), np.zeros((count, 3), dtype=np.int64)
    for t, (_, slots, _, _, _) in enumerate(terms):
        for a, (point, weight, item) in enumerate(slots):
            it_body[t, a], it_x0[t, a] = item.body, item.x0
            it_trans[t, a], it_w[t, a], it_point[t, a] = float(item.translates), weight, point
    bodies = system.bodies
    return kernel.Model(
        b_kind=np.array([BODY_KINDS[b.kind] for b in bodies], dtype=np.int64),
        b_start=np.array([b.start for b in bodies], dtype=np.int64),
        b_ref0=np.array([b.ref0 for b in bodies], dtype=float),
        b_axis=np.array([b.axis if b.axis is not None else zero3 for b in bodies]),
        t_kind=np.array([t[0] for t in terms], dtype=np.int64), it_body=it_body, it_x0=it_x0,
        it_trans=it_trans, it_w=it_w, it_point=it_point,
        t_data=np.array([t[2] for t in terms], dtype=float),
        t_vec=np.array([t[3] for t in terms], dtype=float),
        t_stiff=np.array([t[4] for t in terms], dtype=float),
        r_body=np.array([k for k, _ in system.rotations], dtype=np.int64),
        r_turn=np.array([turn for _, turn in system.rotations], dtype=float).reshape(-1, 3, 3),
        n=system.size, m=len(system.constraints))
