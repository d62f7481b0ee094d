# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Writers of importer.py's results: a scene YAML file and a Chrono JSON file.

The scene is written as the bundled scenes are (one flow mapping per constraint and element,
floats as Python's repr, so that reading the file back gives the very same numbers), headed
by comments that record the source file, its template and what was not imported.
"""

from __future__ import annotations

import json
import re

import yaml

PLAIN = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')


def scene_text(scene: dict, header: list) -> str:
    """Return the YAML text of a scene mapping, headed by comment lines."""
    lines = [f'# {_comment(line)}' if line else '#' for line in header]
    for key, value in scene.items():
        if key in ('constraints', 'elements'):
            lines.append(f'{key}:')
            lines += [f'  - {_flow(item)}' for item in value]
        elif isinstance(value, dict):
            lines.append(f'{key}:')
            lines += [f'  {k}: {_flow(v)}' for k, v in value.items()]
        else:
            lines.append(f'{key}: {_flow(value)}')
    return '\n'.join(lines) + '\n'


def _comment(line: str) -> str:
    """Return line fit for a comment: a line break or other unprintable character escaped."""
    return ''.join(c if c.isprintable() else json.dumps(c)[1:-1] for c in str(line))


def _flow(value) -> str:
    if isinstance(value, dict):
        return '{' + ', '.join(f'{k}: {_flow(v)}' for k, v in value.items()) + '}'
    if isinstance(value, (list, tuple)):
        return '[' + ', '.join(_flow(v) for v in value) + ']'
    if isinstance(value, bool) or value is None:
        return yaml.safe_dump(value).split('\n')[0]
    if isinstance(value, (int, float)):
        return _number(float(value))
    text = str(value)
    if PLAIN.match(text) and yaml.safe_load(text) == text:   # not true, null, ...
        return text
    return _quoted(text)


def _number(value: float) -> str:
    """
    Return a finite float as YAML reads it back, the very same number: Python's repr.

    YAML 1.1 (PyYAML) reads 1e+20 as a string: its floats need a point, so 1.0e+20.
    """
    text = repr(value)
    if 'e' in text and '.' not in text:
        mantissa, exponent = text.split('e')
        text = f'{mantissa}.0e{exponent}'
    return text


def _quoted(text: str) -> str:
    """
    Return text as a YAML double-quoted scalar, every character kept.

    JSON's escapes are YAML's, except that JSON writes a character beyond U+FFFF as two
    UTF-16 escapes, which YAML reads as two lone surrogates: those pairs become YAML's
    eight-digit escapes (backslash U).
    """
    def pair(match):
        if match.group(1) is None:
            return match.group(0)   # another escape, taken whole (an escaped backslash too)
        high, low = int(match.group(1), 16), int(match.group(2), 16)
        return f'\\U{0x10000 + ((high - 0xD800) << 10) + (low - 0xDC00):08x}'

    return SURROGATES.sub(pair, json.dumps(text))


SURROGATES = re.compile(r'\\u(d[89ab][0-9a-f]{2})\\u(d[c-f][0-9a-f]{2})|\\.')


def json_text(data: dict) -> str:
    """Return a Chrono JSON file's text (no comments: Chrono and CARLA both read it)."""
    return json.dumps(data, indent=2, allow_nan=False) + '\n'
