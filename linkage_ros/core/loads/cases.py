# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Load cases: the body's accelerations in g, and a corner's own tyre load where one is given.

    cases:
      braking:  {vertical_g: 1.0, longitudinal_g: -1.0}
      pothole:  {vertical_g: 1.0,
                 corners: {front_left: {vertical_g: 3.0, longitudinal_g: -1.0, at: wc}}}
      kerb:     {vertical_g: 1.0,
                 corners: {front_left: {force_n: [0, -8000, 9000], moment_nm: [0, 0, 0],
                                        at: cp}}}

A case's accelerations (g = 9.80665 m/s^2, vehicle frame): longitudinal_g (+ = speeding up,
- = braking), lateral_g (+ = towards the left: a left turn), vertical_g (the load factor: the
tyres carry vertical_g x the weight; 1 at rest). A corner entry replaces that corner's tyre
load: in multiples of its static tyre load (vertical_g, longitudinal_g, lateral_g; at: wc or
cp, where its longitudinal force acts) or as a wrench (force_n N, moment_nm N m about the
point, at: cp or wc, as linkage-kc --load). Every number has a range (RANGES); a mistake
raises SceneError naming the file and the field. The built-in cases are data:
config/loads/cases.yaml (doc/loads.md gives their sources).
"""

from __future__ import annotations

from dataclasses import dataclass, field
import re
from typing import TYPE_CHECKING

from ..base.finite import is_finite_number
from ..model.bundled import config_dir
from ..model.fields import Fields
from ..model.yaml_file import read_yaml

if TYPE_CHECKING:
    from os import PathLike

G_KEYS = ('longitudinal_g', 'lateral_g', 'vertical_g')
CASE_KEYS = G_KEYS + ('corners',)
CORNER_G_KEYS = G_KEYS + ('at',)
CORNER_WRENCH_KEYS = ('force_n', 'moment_nm', 'at')
PLACES = ('cp', 'wc')
# The stated ranges (doc/loads.md): (low, high, inclusive low); a value outside is a mistake.
RANGES = {
    'longitudinal_g': (-5.0, 5.0), 'lateral_g': (-5.0, 5.0), 'vertical_g': (0.0, 10.0),
    'corner_g': (-20.0, 20.0), 'corner_vertical_g': (0.0, 20.0),
    'force_n': (-1e6, 1e6), 'moment_nm': (-1e5, 1e5),
}
MAX_CASES = 1000   # cases per file: about a second of solving each
NAME = re.compile(r'[A-Za-z0-9][A-Za-z0-9_-]{0,63}')   # whole: fullmatch
BUILT_IN = 'cases.yaml'


@dataclass(frozen=True)
class CornerLoad:
    """A corner's own tyre load: multiples of its static load (g) or a wrench (N, N m)."""

    at: str = 'cp'                        # where the (longitudinal) force acts: cp | wc
    g: tuple | None = None                # (longitudinal, lateral, vertical) in g, or None
    force_n: tuple = (0.0, 0.0, 0.0)      # the wrench form (g None)
    moment_nm: tuple = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class LoadCase:
    """One load case: the body's accelerations (g) and the corners given their own load."""

    name: str
    longitudinal_g: float = 0.0
    lateral_g: float = 0.0
    vertical_g: float = 1.0
    corners: dict = field(default_factory=dict)   # corner key -> CornerLoad

    @property
    def accelerations_g(self) -> tuple[float, float, float]:
        """Return (longitudinal, lateral, vertical) in g."""
        return self.longitudinal_g, self.lateral_g, self.vertical_g


def built_in_cases() -> dict[str, LoadCase]:
    """Return the built-in cases (config/loads/cases.yaml), by name, in the file's order."""
    return read_cases(config_dir() / 'loads' / BUILT_IN)


def read_cases(path: str | PathLike) -> dict[str, LoadCase]:
    """Read a cases file; SceneError names the file and the field of a mistake."""
    data = read_yaml(path, 'cases')
    return parse_cases(str(path), data)


def parse_cases(source: str, data: object) -> dict[str, LoadCase]:
    """Return the cases of a cases file's data (a mapping with `cases`), by name."""
    check = Fields(source)
    if not isinstance(data, dict):
        check.fail('cases', 'expected a mapping with cases: {NAME: {vertical_g: ...}, ...}')
    check.keys(data, ('name', 'cases'))
    cases = data.get('cases')
    if not isinstance(cases, dict) or not cases:
        check.fail('cases', 'expected a mapping of case names to {longitudinal_g, lateral_g, '
                   'vertical_g, corners}, at least one')
    if len(cases) > MAX_CASES:
        check.fail('cases', f'{len(cases)} cases: at most {MAX_CASES} in one file')
    return {str(name): _case(check, name, spec) for name, spec in cases.items()}


def _case(check: Fields, name: object, spec: object) -> LoadCase:
    if not isinstance(name, str) or not NAME.fullmatch(name):
        check.fail(f'cases.{_shown(name)}', 'a case name is 1 to 64 ASCII letters, digits, _ '
                   'or -, starting with a letter or a digit')
    where = f'cases.{name}'
    if not isinstance(spec, dict):
        check.fail(where, f'expected a mapping {{longitudinal_g, lateral_g, vertical_g, '
                   f'corners}}, got {spec!r}')
    check.keys(spec, CASE_KEYS, where)
    values = {key: _number(check, spec, key, f'{where}.{key}', RANGES[key],
                           1.0 if key == 'vertical_g' else 0.0)
              for key in G_KEYS}
    if not values['vertical_g'] > 0:
        check.fail(f'{where}.vertical_g', 'must be above 0 (the tyres carry vertical_g x the '
                   'weight)')
    corners = spec.get('corners') or {}
    if not isinstance(corners, dict):
        check.fail(f'{where}.corners', f'expected a mapping of corner names to their load, '
                   f'got {corners!r}')
    return LoadCase(name, **values, corners={
        str(key): _corner(check, f'{where}.corners.{_shown(key)}', key, value)
        for key, value in corners.items()})


def _shown(key: object) -> str:
    """Return a key as a field path names it: as it is if a valid name, else its repr."""
    return key if isinstance(key, str) and NAME.fullmatch(key) else repr(key)


def _corner(check: Fields, where: str, key: object, spec: object) -> CornerLoad:
    if not isinstance(key, str) or not NAME.fullmatch(key):
        check.fail(where, 'a corner is named as in the vehicle file (front_left, ...)')
    if not isinstance(spec, dict):
        check.fail(where, f'expected {{vertical_g, longitudinal_g, lateral_g, at}} or '
                   f'{{force_n, moment_nm, at}}, got {spec!r}')
    at = spec.get('at', 'cp')
    if at not in PLACES:
        check.fail(f'{where}.at', f'unknown value {at!r} (expected one of: cp, wc)')
    if any(k in spec for k in ('force_n', 'moment_nm')):
        check.keys(spec, CORNER_WRENCH_KEYS, where)
        force, moment = (_vector(check, spec, key, f'{where}.{key}', RANGES[key])
                         for key in ('force_n', 'moment_nm'))
        return CornerLoad(at, None, force, moment)
    check.keys(spec, CORNER_G_KEYS, where)
    g = tuple(_number(check, spec, key, f'{where}.{key}',
                      RANGES['corner_vertical_g' if key == 'vertical_g' else 'corner_g'],
                      1.0 if key == 'vertical_g' else 0.0) for key in G_KEYS)
    return CornerLoad(at, g)


def _number(check: Fields, spec: dict, key: str, where: str, bounds: tuple,
            default: float) -> float:
    """Return spec[key] (default if absent), a finite number within bounds (inclusive)."""
    value = check.number(spec, key, where, default=default, length=False)
    low, high = bounds
    if not low <= value <= high:
        check.fail(where, f'{value!r} is outside {low:g} to {high:g}')
    return value + 0.0   # no -0.0


def _vector(check: Fields, spec: dict, key: str, where: str, bounds: tuple) -> tuple:
    """Return spec[key] ((0, 0, 0) if absent), three finite numbers within bounds."""
    value = spec.get(key, [0.0, 0.0, 0.0])
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        check.fail(where, f'expected [x, y, z], three numbers, got {value!r}')
    low, high = bounds
    for v in value:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not is_finite_number(v):
            check.fail(where, f'{v!r} is not a finite number')
        if not low <= v <= high:
            check.fail(where, f'{v!r} is outside {low:g} to {high:g}')
    return tuple(float(v) + 0.0 for v in value)


def resolve_corner(key: str, corners, axles) -> str:
    """
    Return the vehicle corner a case's corner key names, or '' if none.

    The key is a corner name of the vehicle, or <axle>_<side> (front_left, rear_right) of its
    axles (axles: {name: AxleSpec}) where no corner has that name.
    """
    if key in corners:
        return key
    axle, _, side = key.rpartition('_')
    spec = axles.get(axle)
    return getattr(spec, side) if spec is not None and side in ('left', 'right') else ''


def describe(case: LoadCase) -> str:
    """Say a case in words for messages: 'braking (-1 g longitudinal, 1 g vertical)'."""
    parts = [f'{v:g} g {k[:-2]}' for k, v in zip(G_KEYS, case.accelerations_g)
             if v != 0.0 or k == 'vertical_g']
    said = ', '.join(parts)
    if case.corners:
        said += f'; {", ".join(case.corners)} given'
    return f'{case.name} ({said})'
