"""
Force elements of a corner: springs, dampers and plain lengths, with their motion ratios.

A scene may list elements, each between a body point and a point on the moving side
(mounts.py: on the carrier, on an arm, on a link's line, or along a strut):

    elements:
      - {name: damper, type: damper, body: [x, y, z], arm: lower_arm, point: [x, y, z]}
      - {name: spring, type: spring, body: [x, y, z], arm: lower_arm, point: [x, y, z],
         rate: 35.0, free_length: 320.0}
      - {name: strut, type: damper, along: strut}

Coordinates, free_length and rate are in the scene's units (rate in N per unit of length:
N/mm in a mm scene, N/m in an m scene); everything is mm and N/mm once loaded.

At every solved position each element has (element_values):
    length L (mm); ratio = dL/dz (mm/mm, z = wheel travel, + = bump; negative where the
    element shortens in bump); ratio_rate = d ratio/dz (1/mm); and, for a spring with a rate
    k and a free length L0, its force F = k (L0 - L) (N, + = compressed: pushing its ends
    apart) and the wheel rate dW/dz = k ratio^2 - F ratio_rate (N/mm), W = -F ratio being the
    vertical wheel load it carries (virtual work). With the installation ratio MR = -ratio
    this is the textbook k MR^2 + F dMR/dz.
ratio and ratio_rate are exact (the implicit function theorem to second order, motion.py),
computed compiled (element_kernel.py): a few microseconds per answer.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math
import re
from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from .motion import guidance_rows, pose_batch
from .mounts import KINDS, Mount, mount_table, parse_mount
from ..solve import element_kernel
from ..solve.element_kernel import pack_elements, pack_rows, SpringTable
from ..solve.mechanism import compile_scene, Mechanism

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Constraint, Scene

TYPES = ('spring', 'damper', 'length')
KEYS = ('name', 'type', 'body', 'point', 'rate', 'free_length') + tuple(KINDS)
NAME = re.compile(r'^[A-Za-z][A-Za-z0-9_]*$')   # becomes the start of table column names


@dataclass(frozen=True)
class Element:
    """A spring, damper or length between a body point and a mount. mm, N/mm."""

    name: str
    type: str             # noqa: A003 (the scene files' key)
    body: np.ndarray      # (3,) body point, vehicle frame, design position
    mount: Mount          # the moving-side point
    rate: float = math.nan          # N/mm (springs; NaN if not given)
    free_length: float = math.nan   # mm (springs; NaN if not given)

    @property
    def has_rate(self) -> bool:
        """Whether force and wheel rate are defined (a spring with rate and free_length)."""
        return not math.isnan(self.rate)

    def transformed(self, flip: ArrayLike, offset: ArrayLike) -> Element:
        """Return the element with every point p at p * flip + offset (mirror, translate)."""
        return replace(self, body=self.body * flip + offset,
                       mount=self.mount.transformed(flip, offset))


class ElementValues(NamedTuple):
    """Quantities of k elements at n positions, arrays (n, k); NaN where undefined."""

    length: np.ndarray       # mm
    ratio: np.ndarray        # d length / d travel, mm/mm
    ratio_rate: np.ndarray   # d ratio / d travel, 1/mm
    force: np.ndarray        # N, + = compressed (springs with a rate)
    wheel_rate: np.ndarray   # N/mm (springs with a rate)


def parse_elements(check, items: object,
                   constraints: tuple[Constraint, ...]) -> tuple[Element, ...]:
    """
    Read and validate a scene file's elements list (None: no elements).

    check is the scene parser's field reader (fields.Fields), so a mistake
    raises SceneError naming the file and the field.
    """
    if items is None:
        return ()
    if not isinstance(items, list):
        check.fail('elements', f'expected a list of elements, got {type(items).__name__}')
    elements = tuple(_parse_element(check, item, i, constraints) for i, item in enumerate(items))
    names = [e.name for e in elements]
    for i, name in enumerate(names):
        if name in names[:i]:
            check.fail(f'elements[{i}] ({name}).name', 'used twice: names make the table '
                       'columns, so each element needs its own')
    return elements


def _parse_element(check, item, index, constraints):
    where = f'elements[{index}]'
    if not isinstance(item, dict):
        check.fail(where, 'expected a mapping {name, type, body, and carrier, arm + point, '
                   'link + point or along}')
    name = item.get('name')
    if not isinstance(name, str) or not NAME.match(name):
        check.fail(f'{where}.name', f'expected a name of letters, digits and _ starting with a '
                   f'letter (it starts the table columns), got {name!r}')
    where = f'elements[{index}] ({name})'
    check.keys(item, KEYS, where)   # free keys (description, notes, x_...) pass
    kind = check.choice(item, 'type', TYPES, f'{where}.type')
    scale = check.scale
    mount, body = parse_mount(item, constraints, where, scale,
                              lambda key, field: check.point(item, key, field), check.fail)
    if body is None:
        body = check.point(item, 'body', f'{where}.body') * scale
    if np.linalg.norm(mount.point - body) <= 1e-9 * max(1.0, float(np.abs(body).max())):
        check.fail(where, 'the body point and the moving point coincide at design: an element '
                   'of zero length has no direction')
    rate, free_length = _spring(check, item, where, kind)
    return Element(name=name, type=kind, body=body, mount=mount, rate=rate,
                   free_length=free_length)


def _spring(check, item, where, kind):
    """Return (rate N/mm, free_length mm) of a spring, NaN, NaN if not given."""
    given = [key for key in ('rate', 'free_length') if item.get(key) is not None]
    if not given:
        return math.nan, math.nan
    if kind != 'spring':
        check.fail(f'{where}.{given[0]}', f'only a spring has a rate and a free length (this '
                   f'is a {kind})')
    if len(given) == 1:
        missing = ({'rate', 'free_length'} - set(given)).pop()
        check.fail(f'{where}.{missing}', 'missing: rate and free_length go together (the '
                   'force needs both)')
    unit = 'mm' if check.scale == 1.0 else 'm'
    values = []
    for key in given:
        value = check.number(item, key, f'{where}.{key}')
        if not value > 0:
            what = f'N/{unit}, a stiffness' if key == 'rate' else f'{unit}, a length'
            check.fail(f'{where}.{key}', f'must be positive ({what}), got {value!r}')
        values.append(value)
    return values[0] / check.scale, values[1] * check.scale


class ElementModel(NamedTuple):
    """A scene's elements prepared for the compiled kernels (prepare), reused per answer."""

    mech: Mechanism
    rows: np.ndarray     # element_kernel.pack_rows of the guidance equations
    table: np.ndarray    # element_kernel.pack_elements of the elements


def prepare(scene: Scene, mech: Mechanism | None = None) -> ElementModel:
    """Prepare the scene's elements for element_values (mech: compile_scene(scene) if given)."""
    mech = mech if mech is not None else compile_scene(scene)
    elements = scene.elements
    springs = SpringTable(np.array([e.body for e in elements]).reshape(-1, 3),
                          np.array([e.rate for e in elements]),
                          np.array([e.free_length for e in elements]))
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


def element_columns(scene: Scene) -> list[str]:
    """Return the table columns of the scene's elements (element_table's order)."""
    columns = []
    for e in scene.elements:
        columns += [f'{e.name}_length_mm', f'{e.name}_ratio']
        if e.has_rate:
            columns += [f'{e.name}_force_N', f'{e.name}_wheel_rate_N_per_mm']
    return columns


def element_table(scene: Scene, values: ElementValues) -> np.ndarray:
    """Return the element columns (n, len(element_columns(scene))) of ElementValues."""
    columns = []
    for j, e in enumerate(scene.elements):
        columns += [values.length[:, j], values.ratio[:, j]]
        if e.has_rate:
            columns += [values.force[:, j], values.wheel_rate[:, j]]
    return np.column_stack(columns) if columns else np.empty((len(values.length), 0))
