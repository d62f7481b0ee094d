# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Field readers of scene and vehicle files: each value checked, each mistake named by its field.

A mistake raises SceneError(file, field, problem), the field written as a path into the file
('constraints[2] (lower_front).base'). A key the file format does not know is refused with
the closest known key suggested ('unknown key wheel_centre (did you mean wheel_center?)'),
so that a misspelt key is not reported as the right one missing.
"""

from __future__ import annotations

import difflib
import re
from typing import Any, TYPE_CHECKING
import unicodedata

import numpy as np

from .yaml_file import SceneError
from ..base.finite import is_finite_number
from ..base.limits import LENGTH_LIMIT_MM, within_length_limit
from ..base.ranges import DOC as RANGES_DOC, RANGE, shown

if TYPE_CHECKING:
    from collections.abc import Collection

# Keys any mapping of a scene or vehicle file may hold, kept and ignored by the solver; and
# the prefix of a user's own keys (x_supplier: ...).
FREE_KEYS = ('description', 'source', 'notes')
OWN_KEY_PREFIX = 'x_'
PLAIN_KEY = re.compile(r'^[A-Za-z_][A-Za-z0-9_-]*$')   # named as it is; others by repr
# A name that becomes part of a topic, a TF frame, a URDF link or joint name or a Foxglove
# path (a constraint's: pickup/<name>_base, <corner>/<name>; an element's: <name>_body; a
# vehicle's corner's: the namespace <corner>/) is a ROS name token (the ROS 2 topic and
# service names design; rclpy's validate_full_topic_name and validate_node_name accept what
# it makes): a letter, then letters, digits and _, without __ (ROS reserves it) and not
# ending in _ (the names made of it append _base, _axis0, ...: no __ in them either), at most
# NAME_TOKEN_MAX characters: the longest topic of two such names, /<corner>/pickup/<name>_
# centre, is 144 characters, within rmw's 247 for a fully qualified topic with 103 to spare
# for the node's namespace. ASCII only: a topic holds no other letter.
NAME_TOKEN = re.compile(r'^[A-Za-z][A-Za-z0-9_]*$')
NAME_TOKEN_MAX = 64
NAME_TOKEN_RULE = (f'a ROS name token: a letter, then letters, digits and _, without __ or a '
                   f'trailing _, at most {NAME_TOKEN_MAX} characters')


class Fields:
    """Field readers that raise SceneError with the file and field named."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.scale = 1.0   # mm per scene unit, once units is read

    def fail(self, field_name: str, problem: str):
        """Raise SceneError for field_name of this file."""
        raise SceneError(self.source, field_name, problem)

    def keys(self, data: dict, known: Collection[str], where: str = '',
             free: Collection[str] = FREE_KEYS) -> None:
        """
        Refuse a key of data that is neither known nor free (nor x_...), naming it.

        where: the field path of data ('' for the top level, 'carrier', ...).
        """
        for key in data:
            if key in known or key in free or (isinstance(key, str)
                                               and key.startswith(OWN_KEY_PREFIX)):
                continue
            said = key if isinstance(key, str) and PLAIN_KEY.match(key) else shown(key)
            name = f'{where}.{said}' if where else said
            close = difflib.get_close_matches(str(key), [str(k) for k in known], n=1)
            hint = (f'did you mean {close[0]}?' if close else
                    f'known: {", ".join(known)}; also allowed: {", ".join(free)}, '
                    f'{OWN_KEY_PREFIX}...')
            self.fail(name, f'unknown key ({hint})')

    def length(self, value: float, where: str, what: str) -> None:
        """Refuse a finite number whose length in mm is beyond LENGTH_LIMIT_MM."""
        if not within_length_limit(value, self.scale):
            self.fail(where, f'{what} {shown(value)} is beyond {LENGTH_LIMIT_MM:g} mm in '
                      'magnitude (a typo? lengths this large leave no precision for '
                      'millimetres)')

    def _get(self, data, key, where):
        if key not in data or data[key] is None:
            self.fail(where, 'missing (required)')
        return data[key]

    def mapping(self, data: dict, key: str, where: str | None = None) -> dict:
        """Return data[key], a mapping."""
        where = where or key
        value = self._get(data, key, where)
        if not isinstance(value, dict):
            self.fail(where, f'expected a mapping, got {type(value).__name__}')
        return value

    def sequence(self, data: dict, key: str) -> list:
        """Return data[key], a list."""
        value = self._get(data, key, key)
        if not isinstance(value, list):
            self.fail(key, f'expected a list, got {type(value).__name__}')
        return value

    def choice(self, data: dict, key: str, options: tuple, where: str | None = None) -> Any:
        """Return data[key], one of options."""
        where = where or key
        value = self._get(data, key, where)
        if not isinstance(value, (str, int, float)) or value not in options:
            self.fail(where, f'unknown value {shown(value)} (expected one of: '
                      f'{", ".join(options)})')
        return value

    def text(self, data: dict, key: str, default: str = '', where: str | None = None) -> str:
        """Return data[key] as text, a number written as text; default if absent."""
        value = data.get(key)
        if value is None:
            return default
        if isinstance(value, bool) or not isinstance(value, (str, int, float)):
            self.fail(where or key, f'expected text, got {type(value).__name__}')
        return str(value)

    def name(self, data: dict, key: str, default: str = '', where: str | None = None) -> str:
        """
        Return the text data[key], refused if no frame may have it; default if absent or ''.

        A scene's, a constraint's or a vehicle's name becomes TF frame names, URDF names and
        diagnostic names: name_problem says what is refused.
        """
        value = self.text(data, key, default, where)
        problem = name_problem(value) if value != '' else ''   # '': the default applies
        if problem:
            self.fail(where or key, problem)
        return value

    def token(self, data: dict, key: str, where: str) -> str:
        """
        Return data[key], a name that topics and frames are made of (token_problem); required.

        A mistake names the file, the field, the name given and the rule, on one line.
        """
        value = data.get(key)
        if value is None:
            self.fail(where, f'missing (required): give a name, {NAME_TOKEN_RULE}')
        if not isinstance(value, str):
            self.fail(where, f'expected a name, {NAME_TOKEN_RULE}; got {value!r}')
        problem = token_problem(value)
        if problem:
            self.fail(where, problem)
        return value

    def number(self, data: dict, key: str, where: str, default: float | None = None,
               minimum: float | None = None, length: bool = True) -> float:
        """Return data[key], a finite number: a length within the limit unless not length."""
        if data.get(key) is None:
            if default is None:
                self.fail(where, 'missing (required)')
            return default
        value = data[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(where, f'expected a number, got {shown(value)}')
        if not is_finite_number(value):
            self.fail(where, f'must be finite, got {shown(value)}')
        if minimum is not None and value < minimum:
            self.fail(where, f'must be at least {minimum:g}, got {shown(value)}')
        if length:
            self.length(value, where, 'value')
        return float(value)

    def ranged(self, data: dict, key: str, where: str, kind: str,
               default: float | None = None) -> float:
        """
        Return data[key], a finite number within its stated range, in the core's units.

        kind: the row of base.ranges.RANGE (its unit scales with the file's units: a rate per
        mm or per m, a length in mm or m); default if absent or null (None: required). Out of
        range: SceneError saying the value as given, its unit and the range in the file's.
        """
        if data.get(key) is None and default is not None:
            return default
        stated, raw = RANGE[kind], data.get(key)
        if isinstance(raw, int) and not isinstance(raw, bool):   # beyond the floats: outside
            problem = stated.problem(raw, self.scale)
            if problem:
                self.fail(where, f'{problem} ({RANGES_DOC})')
        value = self.number(data, key, where, length=False)
        problem = stated.problem(raw, self.scale)
        if problem:
            self.fail(where, f'{problem} ({RANGES_DOC})')
        return value * self.scale ** stated.length_power

    def point(self, data: dict, key: str, where: str) -> np.ndarray:
        """Return data[key], a point [x, y, z] in the file's units, (3,)."""
        return self.vector(self._get(data, key, where), where)

    def vector(self, value: Any, where: str) -> np.ndarray:
        """Return value, a point [x, y, z] in the file's units, (3,)."""
        if not isinstance(value, (list, tuple)):
            self.fail(where, f'expected a point [x, y, z], got {shown(value)}')
        if len(value) != 3:
            self.fail(where, f'expected 3 coordinates [x, y, z], got {len(value)}')
        for v in value:
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                self.fail(where, f'coordinate {shown(v)} is not a number')
            if not is_finite_number(v):
                self.fail(where, f'coordinate {shown(v)} is not finite')
            self.length(v, where, 'coordinate')
        return np.array(value, dtype=float)


def token_problem(name: object) -> str:
    """
    Say why name cannot be a name that topics and frames are made of ('' if it can).

    The rule is NAME_TOKEN_RULE (see NAME_TOKEN). One line naming the name (its first 80
    characters, by repr) and the rule.
    """
    if not isinstance(name, str):
        return f'expected a name, {NAME_TOKEN_RULE}; got {type(name).__name__} {name!r:.80}'
    said = repr(name) if len(name) <= 80 else f'{name[:80]!r}... ({len(name)} characters)'
    other = sorted({c for c in name if not (c.isascii() and (c.isalnum() or c == '_'))})
    why = ('empty' if not name else
           f'it holds {", ".join(f"U+{ord(c):04X}" for c in other[:8])}' if other else
           'it does not start with a letter' if not name[0].isalpha() else
           'it holds __' if '__' in name else
           'it ends in _' if name.endswith('_') else
           f'{len(name)} characters' if len(name) > NAME_TOKEN_MAX else '')
    if not why:
        return ''
    return f'{said} is not {NAME_TOKEN_RULE} ({why})'


def name_problem(name: str) -> str:
    """
    Say why text cannot be a name of frames, URDF elements and topics; '' if it can.

    Refused: an empty name; a control, format, private-use or unassigned character (NUL,
    U+0001, U+FFFE: XML cannot hold them, and C strings end at a NUL); a leading '/' (tf2
    refuses a frame named so). The characters are said by their code points.
    """
    if not name.strip():
        return 'empty: give a name'
    bad = sorted({c for c in name if unicodedata.category(c)[0] == 'C'})
    if bad:
        said = ', '.join(f'U+{ord(c):04X}' for c in bad)
        return (f'{name!r} holds {said}: a name may not hold control or unassigned characters '
                '(they break the URDF, which is XML, and the frame names)')
    if name.startswith('/'):
        return f'{name!r} starts with /, which tf2 refuses in a frame name'
    return ''
