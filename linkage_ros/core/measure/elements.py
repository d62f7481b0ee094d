# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Force elements of a corner: springs, dampers and plain lengths, with their motion ratios.

A scene may list elements (model/elements.py: each between a body point and a mount).

At every solved position each element has (element_values):
    length L (mm); ratio = dL/dz (mm/mm, z = wheel travel, + = bump; negative where the
    element shortens in bump); ratio_rate = d ratio/dz (1/mm); and, for a spring with a rate
    k and a free length L0, its force F = k (L0 - L) (N, + = compressed: pushing its ends
    apart) and the wheel rate dW/dz = k ratio^2 - F ratio_rate (N/mm), W = -F ratio being the
    vertical wheel load it carries (virtual work). With the installation ratio MR = -ratio
    this is the textbook k MR^2 + F dMR/dz. A spring with a force table (model/elements.py)
    has F from the table at its deflection L0 - L and k the slope of the table there.
ratio and ratio_rate are exact (the implicit function theorem to second order, motion.py),
computed compiled (element_kernel.py): a few microseconds per answer. Where an element's
ends meet or pass through each other (its moving point no longer ahead of its body point
along its design direction) every quantity is NaN (element_kernel.MIN_LENGTH), and
crossing_notes says where.
"""

from __future__ import annotations

from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from .motion import guidance_rows, pose_batch
from .mounts import mount_table
from .quantities import columns_of_element
from ..solve import element_kernel
from ..solve.element_kernel import pack_elements, pack_rows, SpringTable
from ..solve.mechanism import compile_scene, Mechanism

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene


class ElementValues(NamedTuple):
    """Quantities of k elements at n positions, arrays (n, k); NaN where undefined."""

    length: np.ndarray       # mm
    ratio: np.ndarray        # d length / d travel, mm/mm
    ratio_rate: np.ndarray   # d ratio / d travel, 1/mm
    force: np.ndarray        # N, + = compressed (springs with a rate)
    wheel_rate: np.ndarray   # N/mm (springs with a rate)


class ElementModel(NamedTuple):
    """A scene's elements prepared for the compiled kernels (prepare), reused per answer."""

    mech: Mechanism
    rows: np.ndarray     # element_kernel.pack_rows of the guidance equations
    table: np.ndarray    # element_kernel.pack_elements of the elements


def prepare(scene: Scene, mech: Mechanism | None = None) -> ElementModel:
    """Prepare the scene's elements for element_values (mech: compile_scene(scene) if given)."""
    mech = mech if mech is not None else compile_scene(scene)
    elements = scene.elements
    body = np.array([e.body for e in elements]).reshape(-1, 3)
    direction = np.array([e.mount.point for e in elements]).reshape(-1, 3) - body
    springs = SpringTable(body, np.array([e.rate for e in elements]),
                          np.array([e.free_length for e in elements]),
                          direction / np.linalg.norm(direction, axis=1, keepdims=True),
                          tuple(e.force_table for e in elements))
    return ElementModel(mech, pack_rows(guidance_rows(scene, mech)),
                        pack_elements(mount_table(scene, [e.mount for e in elements]), springs))


def element_values(scene: Scene, center: ArrayLike, rotation: ArrayLike, rack: ArrayLike = 0.0,
                   jac: ArrayLike | None = None,
                   model: ElementModel | None = None) -> ElementValues:
    """
    Return the quantities of the scene's elements at n solved poses (ElementValues, (n, k)).

    center (n, 3) mm, rotation (n, 3, 3), rack mm (scalar or (n,)); jac (n, 5, 6): the
    Jacobian at the poses if the solve has it (Continuation.jacobian), else linearized here.
    model: prepare(scene), to save preparing it per call. For one answer at a time see
    values_at.
    """
    model = model if model is not None else prepare(scene)
    poses = pose_batch(model.mech, center, rotation, rack, jac)
    values = np.empty((5, len(poses.center), len(scene.elements)))
    element_kernel.elements_many(model.rows, model.table, tuple(poses), values)
    return ElementValues(*values)


def values_at(model: ElementModel, center: np.ndarray, rotation: np.ndarray, rack: float,
              jac: np.ndarray) -> np.ndarray:
    """
    Return the quantities (5, k) of one solved pose: the node's one-command path.

    Rows as ElementValues' fields: length (mm), ratio, ratio_rate (1/mm), force (N), wheel
    rate (N/mm). center (3,) mm, rotation (3, 3), rack mm and jac (5, 6) as a Solution and
    Continuation.jacobian hold them; straight to the compiled kernel (a few microseconds).
    """
    values = np.empty((5, model.table.shape[0]))
    element_kernel.elements_one(model.rows, model.table, center, rotation, rack, jac, values)
    return values


def crossing_notes(scene: Scene, travel: ArrayLike, length: ArrayLike) -> tuple[str, ...]:
    """
    Say, once per element whose ends meet or pass through each other, where (travel, mm).

    travel (n,) mm and length (n, k) mm (ElementValues.length, NaN there: element_kernel's
    MIN_LENGTH) of n solved positions, in any order (a grid's racks concatenated).
    """
    travel, length = np.asarray(travel, dtype=float), np.asarray(length, dtype=float)
    notes = []
    for j, e in enumerate(scene.elements):
        crossed = travel[np.isnan(length[:, j])]
        if len(crossed):
            notes.append(f'{scene.name}: element {e.name}: its ends meet or pass through each '
                         f'other at {len(crossed)} of {len(travel)} positions, travel '
                         f'{crossed.min():g} to {crossed.max():g} mm: its length, ratio, force '
                         'and wheel rate are NaN there (doc/elements.md)')
    return tuple(notes)


def stop_notes(scene: Scene, travel: ArrayLike, force: ArrayLike) -> tuple[str, ...]:
    """
    Say, once per stop (a spring whose force table is zero at one end), where it engages.

    travel (n,) mm and force (n, k) N (ElementValues.force) of n solved positions, in any
    order: the travel range over which the stop carries a force, or that it does not.
    """
    travel, force = np.asarray(travel, dtype=float), np.asarray(force, dtype=float)
    notes = []
    for j, e in enumerate(scene.elements):
        if not e.is_stop:
            continue
        engaged = travel[np.abs(np.nan_to_num(force[:, j])) > 0.0]
        if len(engaged):
            notes.append(f'{scene.name}: stop {e.name} engages: it carries a force from travel '
                         f'{engaged.min():g} to {engaged.max():g} mm (largest '
                         f'{np.nanmax(np.abs(force[:, j])):.6g} N)')
        elif len(travel):
            notes.append(f'{scene.name}: stop {e.name} does not engage between travel '
                         f'{travel.min():g} and {travel.max():g} mm')
    return tuple(notes)


def element_columns(scene: Scene) -> list[str]:
    """Return the table columns of the scene's elements (element_table's order, registry names)."""
    return [c for e in scene.elements for c in columns_of_element(e.name, e.has_rate)]


def element_table(scene: Scene, values: ElementValues) -> np.ndarray:
    """Return the element columns (n, len(element_columns(scene))) of ElementValues."""
    columns = []
    for j, e in enumerate(scene.elements):
        columns += [values.length[:, j], values.ratio[:, j]]
        if e.has_rate:
            columns += [values.force[:, j], values.wheel_rate[:, j]]
    return np.column_stack(columns) if columns else np.empty((len(values.length), 0))
