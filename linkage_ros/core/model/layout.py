# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The row map of a scene's guidance equations into its hardpoint table (Scene.points).

What the constraint types declare, before any geometry: which hardpoint each of the 5 equation
rows takes its carrier point and its body point from. solve/mechanism.py compiles the
geometry of those rows (geometry_of, equation_table).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class Layout(NamedTuple):
    """
    A scene's 5 equation rows as indices into its hardpoint table (Scene.points).

    Sphere rows first (each link, then an arm's two axis points), then a strut's two rows.
    The layout follows from the constraint types alone; the geometry from the points.
    """

    carrier: np.ndarray      # (5,) int: hardpoint of the row's carrier point
    base: np.ndarray         # (5,) int: hardpoint of its body point (A, an axis point, T)
    line: np.ndarray         # (5,) bool: a strut line row
    normal: np.ndarray       # (5,) int: which of the strut's two normals (line rows)
    steer: np.ndarray        # (5,) 1.0 where the body point moves with the rack
    center: int              # hardpoint index of wheel_center
    spin: int                # hardpoint index of spin_axis_point
    constraint: np.ndarray   # (5,) int: index into scene.constraints of the row


def layout_of(scene) -> Layout:
    """Return the row map of a Scene: sphere rows first, then the strut's two rows each."""
    names = scene.point_names
    spheres, lines = [], []
    for index, c in enumerate(scene.constraints):
        joint = names.index(f'{c.name}.carrier')
        steer = 1.0 if c.steer == 'rack' else 0.0
        if c.type == 'line':
            top = names.index(f'{c.name}.base')
            lines += [(joint, top, True, 0, 0.0, index), (joint, top, True, 1, 0.0, index)]
        else:
            ends = ('axis0', 'axis1') if c.type == 'circle' else ('base',)
            spheres += [(joint, names.index(f'{c.name}.{end}'), False, 0, steer, index)
                        for end in ends]
    rows = list(zip(*(spheres + lines)))
    return Layout(np.array(rows[0]), np.array(rows[1]), np.array(rows[2], dtype=bool),
                  np.array(rows[3]), np.array(rows[4], dtype=float),
                  names.index('wheel_center'), names.index('spin_axis_point'),
                  np.array(rows[5]))
