# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A scene moved: mirrored to the other side, translated onto a vehicle, or given new hardpoints.

Each returns a new Scene (scene.py) and leaves the one given as it was. mm.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from .scene import choose_third_point, Scene

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import ArrayLike

    from .constraint import Constraint


def mirror(scene: Scene) -> Scene:
    """Return the scene of the opposite wheel: every point mirrored in the x-z plane (y -> -y)."""
    flip = np.array([1.0, -1.0, 1.0])
    constraints = tuple(replace(c, base=c.base * flip, carrier=c.carrier * flip)
                        for c in scene.constraints)
    side = 'right' if scene.side == 'left' else 'left'
    return Scene(name=f'{scene.name}_{side}', source=scene.source, side=side, units=scene.units,
                 wheel_center=scene.wheel_center * flip,
                 spin_axis_point=scene.spin_axis_point * flip,
                 third_point=scene.third_point * flip, constraints=constraints,
                 travel=scene.travel, wheel_radius=scene.wheel_radius,
                 description=scene.description, extras=scene.extras, warnings=scene.warnings,
                 elements=tuple(e.transformed(flip, 0.0) for e in scene.elements),
                 kingpin=scene.kingpin)   # joints named by index: the same on either side


def translate(scene: Scene, offset: ArrayLike) -> Scene:
    """Return the scene moved by offset (3,) mm: a corner placed on the vehicle."""
    offset = np.asarray(offset, dtype=float)
    constraints = tuple(replace(c, base=c.base + offset, carrier=c.carrier + offset)
                        for c in scene.constraints)
    return replace(scene, wheel_center=scene.wheel_center + offset,
                   spin_axis_point=scene.spin_axis_point + offset,
                   third_point=scene.third_point + offset, constraints=constraints,
                   elements=tuple(e.transformed(1.0, offset) for e in scene.elements))


def with_points(scene: Scene, points: ArrayLike) -> Scene:
    """
    Return the same scene with its hardpoints at points (k, 3) mm, rows as scene.point_names.

    A moved design, without a file: the constraints, wheel centre and spin axis point take
    the new rows; a spring or damper on a link keeps its fraction of the link, one along a
    strut follows the strut, one on an arm or the carrier keeps its coordinates; a third
    point that was chosen is chosen again (a given one is kept). Not validated, and without
    warnings: the caller tells a variant that is no mechanism by its solve.
    """
    points = np.array(points, dtype=float).reshape(scene.points.shape)
    row = {name: i for i, name in enumerate(scene.point_names)}
    constraints = []
    for c in scene.constraints:
        ends = ('axis0', 'axis1') if c.type == 'circle' else ('base',)
        constraints.append(replace(c, base=points[[row[f'{c.name}.{e}'] for e in ends]],
                                   carrier=points[row[f'{c.name}.carrier']]))
    center, spin = points[row['wheel_center']], points[row['spin_axis_point']]
    third = scene.third_point
    if np.array_equal(third, choose_third_point(scene.wheel_center, scene.spin_axis_point,
                                                [c.carrier for c in scene.constraints])):
        third = choose_third_point(center, spin, [c.carrier for c in constraints])
    elements = tuple(_moved_element(e, scene.constraints, constraints)
                     for e in scene.elements)
    return replace(scene, wheel_center=center, spin_axis_point=spin, third_point=third,
                   constraints=tuple(constraints), elements=elements, warnings=())


def _moved_element(element, before, after):
    """Return an element of a moved design (with_points says where its points go)."""
    mount = element.mount
    if mount.kind == 'link':
        fraction, new = link_fraction(element, before), after[mount.constraint]
        point = new.base[0] + fraction * (new.carrier - new.base[0])
        return replace(element, mount=replace(mount, point=point))
    if mount.kind == 'along':
        new = after[mount.constraint]
        return replace(element, body=new.base[0].copy(),
                       mount=replace(mount, point=new.carrier.copy()))
    return element


def link_fraction(element, constraints: Sequence[Constraint]) -> float | None:
    """Return an element's fraction along its link from the body end (None if not on one)."""
    if element.mount.kind != 'link':
        return None
    c = constraints[element.mount.constraint]
    span = c.carrier - c.base[0]
    return float((element.mount.point - c.base[0]) @ span / (span @ span))
