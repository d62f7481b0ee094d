# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Chrono::Vehicle JSON files read as Chrono reads them, and the values in them checked.

Chrono parses its files with RapidJSON and kParseCommentsFlag: `//` and `/* */` comments
are allowed, NaN and Infinity are not, nor are trailing commas. A file larger than
MAX_BYTES or nested deeper than MAX_DEPTH is refused before it is parsed (Chrono's own
suspension files are a few kB, three levels deep). Every problem is a ChronoError (a
LinkageError) naming the file, the field and what is wrong: one line for the programs.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
import stat
from typing import Any

import numpy as np

from ..core.base import (LENGTH_LIMIT_MM, LinkageError, MM_PER_M,
                         within_length_limit)

MAX_BYTES = 10 * 1024 * 1024   # ten megabytes: thousands of times a real suspension file
MAX_DEPTH = 32                 # brackets open at once


class ChronoError(LinkageError):
    """A Chrono file that cannot be read or mapped: where, and what is wrong."""


def read_chrono(path: str | Path) -> dict:
    """
    Read a Chrono JSON file (comments allowed) and return its top-level object.

    Only a regular file is read: a FIFO, a device or a folder is refused before a byte is
    read (opened without blocking, then looked at), so that nothing waits on a writer.
    """
    path = Path(path)
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except (OSError, ValueError) as exc:   # ValueError: a NUL in the name
        raise ChronoError(path, f'cannot read ({getattr(exc, "strerror", None) or exc})') \
            from None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise ChronoError(path, 'not a regular file (a FIFO, device or folder): a Chrono '
                              'file is read from a regular file only')
        with os.fdopen(fd, 'rb', closefd=False) as stream:
            raw = stream.read(MAX_BYTES + 1)
    except OSError as exc:
        raise ChronoError(path, f'cannot read ({exc.strerror})') from None
    finally:
        os.close(fd)
    if len(raw) > MAX_BYTES:
        raise ChronoError(path, f'larger than {MAX_BYTES // (1024 * 1024)} MB: not a Chrono '
                          'suspension or vehicle file (those are a few kB)')
    try:
        text = raw.decode('utf-8')
    except UnicodeDecodeError as exc:
        raise ChronoError(path, f'not UTF-8 text (byte {exc.start}): not a JSON file') from None
    return parse_chrono(text, str(path))


def parse_chrono(text: str, where: str = '<json>') -> dict:
    """
    Parse Chrono JSON text (RapidJSON with comments) into its top-level object.

    As RapidJSON (chrono_thirdparty/rapidjson reader.h, document.h) does: a number beyond
    the range of a double is an error (kParseErrorNumberTooBig), and so is one whose positive
    exponent exceeds 308 plus its fraction digits; an integer beyond 64 bits is a double; of
    a key given twice in one object the first counts (GenericValue::FindMember walks the
    members in order). A string with a lone UTF-16 surrogate is refused (RapidJSON's
    kParseErrorStringUnicodeSurrogateInvalid).
    """
    plain = strip_comments(text, where)

    def refuse(name):
        raise ChronoError(where, f'{name} is not a JSON number (RapidJSON refuses it)')

    def number(token, value):
        if not math.isfinite(value) or _exponent_too_big(token):
            raise ChronoError(where, f'the number {token[:20]}{"..." if len(token) > 20 else ""}'
                              f' ({len(token)} characters) is beyond the range of a double '
                              '(RapidJSON: "Number too big to be stored in double")')
        return value

    def integer(token):   # RapidJSON keeps 64 bits, else a double (and never int(4301 digits))
        if len(token.lstrip('-')) <= 20 and -2 ** 63 <= int(token) <= 2 ** 64 - 1:
            return int(token)
        return number(token, float(token))

    try:
        data = json.loads(plain, parse_constant=refuse, parse_int=integer,
                          parse_float=lambda token: number(token, float(token)),
                          object_pairs_hook=_first)
    except json.JSONDecodeError as exc:
        raise ChronoError(where, f'not JSON: {exc.msg} at line {exc.lineno} column '
                          f'{exc.colno}') from None
    except RecursionError:
        raise ChronoError(where, 'nested too deeply: not a Chrono file') from None
    if not isinstance(data, dict):
        raise ChronoError(where, 'expected a JSON object {...} at the top')
    _no_surrogates(data, where)
    return data


def _first(pairs: list) -> dict:
    """Return an object's members, the first of each key kept (as RapidJSON finds them)."""
    out = {}
    for key, value in pairs:
        out.setdefault(key, value)
    return out


def _exponent_too_big(token: str) -> bool:
    """
    Whether RapidJSON refuses token for its exponent (reader.h ParseNumber, 64-bit build).

    It refuses a positive exponent beyond 308 + expFrac, the fraction digits it took into
    the significand, even where the value is in range (0e999): digits while the significand
    is at most 2^53 - 1, then while it has fewer than 17 significant digits (the first one
    of the integer part not counted); none after an integer part beyond 64 bits.
    """
    mantissa, _, exponent = token.lower().partition('e')
    if not exponent or exponent.startswith('-'):
        return False
    whole, _, fraction = mantissa.lstrip('-').partition('.')
    limit = 2 ** 63 if token.startswith('-') else 2 ** 64 - 1
    taken = 0
    if len(whole) <= 20 and int(whole) <= limit:
        significand = int(whole)
        digits = len(whole) - 1 if significand else 0
        rest = iter(fraction)
        for d in rest:   # the 64-bit significand's fast path
            if significand > 2 ** 53 - 1:
                rest = iter(fraction[taken:])
                break
            significand = significand * 10 + int(d)
            taken += 1
            digits += 1 if significand else 0
        else:
            rest = iter(())
        positive = significand > 0
        for d in rest:   # the double's, up to 17 significant digits
            if digits >= 17:
                break
            positive = positive or d != '0'
            taken += 1
            digits += 1 if positive else 0
    return int(exponent.lstrip('+') or '0') > 308 + taken


def strip_comments(text: str, where: str) -> str:
    """Return text with `//` and `/* */` comments blanked, checking the nesting depth."""
    out, i, n, depth, in_string = [], 0, len(text), 0, False
    while i < n:
        c = text[i]
        if in_string:
            if c == '\\':
                out.append(text[i:i + 2])
                i += 2
                continue
            in_string = c != '"'
        elif c == '"':
            in_string = True
        elif text.startswith('//', i):
            end = text.find('\n', i)
            i = n if end < 0 else end
            continue
        elif text.startswith('/*', i):
            end = text.find('*/', i + 2)
            if end < 0:
                raise ChronoError(where, 'not JSON: a /* comment is never closed')
            out.append(' ' + '\n' * text.count('\n', i, end))   # keep the line numbers
            i = end + 2
            continue
        elif c in '[{':
            depth += 1
            if depth > MAX_DEPTH:
                raise ChronoError(where, f'nested deeper than {MAX_DEPTH} levels: not a Chrono '
                                  'suspension or vehicle file')
        elif c in ']}':
            depth -= 1
        out.append(c)
        i += 1
    return ''.join(out)


def _no_surrogates(value: Any, where: str) -> None:
    """Refuse a string (key or value) with a lone UTF-16 surrogate, as RapidJSON does."""
    stack = [value]
    while stack:
        item = stack.pop()
        texts = list(item) if isinstance(item, dict) else [item] if isinstance(item, str) else []
        for text in texts:
            try:
                text.encode('utf-8')
            except UnicodeEncodeError:
                raise ChronoError(where, f'the string {text[:40]!r} has a lone UTF-16 '
                                  'surrogate (RapidJSON refuses it)') from None
        if isinstance(item, dict):
            stack.extend(item.values())
        elif isinstance(item, list):
            stack.extend(item)


class Fields:
    """Typed access to one JSON object of a Chrono file: each miss is a ChronoError."""

    def __init__(self, where: str, data: Any, path: str = '') -> None:
        self.where, self.data, self.path = where, data, path
        if not isinstance(data, dict):
            raise ChronoError(where, f'{path or "file"}: expected an object {{...}}, got '
                              f'{_kind(data)}')

    def _field(self, key: str) -> str:
        return f'"{key}"' if not self.path else f'{self.path} / "{key}"'

    def has(self, key: str) -> bool:
        """Whether the object has key."""
        return key in self.data

    def raw(self, key: str) -> Any:
        """Return the value of key, or fail naming it as missing."""
        if key not in self.data:
            raise ChronoError(self.where, f'{self._field(key)}: missing')
        return self.data[key]

    def sub(self, key: str) -> Fields:
        """Return the object under key."""
        return Fields(self.where, self.raw(key), self._field(key))

    def number(self, key: str, default: float | None = None) -> float:
        """Return the finite number under key (a bool or a string is refused)."""
        if default is not None and key not in self.data:
            return default
        return _number(self.where, self._field(key), self.raw(key))

    def text(self, key: str) -> str:
        """Return a string."""
        value = self.raw(key)
        if not isinstance(value, str):
            raise ChronoError(self.where, f'{self._field(key)}: expected a string, got '
                              f'{_kind(value)}')
        return value

    def vector(self, key: str, size: int = 3) -> np.ndarray:
        """Return an array of size finite numbers (a point in m, or a quaternion)."""
        value = self.raw(key)
        if not isinstance(value, list) or len(value) != size:
            raise ChronoError(self.where, f'{self._field(key)}: expected {size} numbers '
                              f'[...], got {_kind(value)}')
        out = np.array([_number(self.where, f'{self._field(key)}[{i}]', v)
                        for i, v in enumerate(value)])
        if size == 3 and not all(within_length_limit(float(v), MM_PER_M) for v in out):
            raise ChronoError(self.where, f'{self._field(key)}: {value} m is beyond '
                              f'{LENGTH_LIMIT_MM / MM_PER_M:g} m (a point in a suspension '
                              'file is metres)')
        return out

    def table(self, key: str) -> np.ndarray:
        """Return a curve [[x, y], ...] as an (n, 2) array of finite numbers."""
        value = self.raw(key)
        if not isinstance(value, list) or not all(isinstance(r, list) and len(r) == 2
                                                  for r in value):
            raise ChronoError(self.where, f'{self._field(key)}: expected rows [x, y]')
        return np.array([[_number(self.where, f'{self._field(key)}[{i}]', v) for v in row]
                         for i, row in enumerate(value)]).reshape(-1, 2)

    def objects(self, key: str) -> list[Fields]:
        """Return the objects of the array under key (none if the key is absent)."""
        value = self.data.get(key, [])
        if not isinstance(value, list):
            raise ChronoError(self.where, f'{self._field(key)}: expected an array [...]')
        return [Fields(self.where, v, f'{self._field(key)}[{i}]') for i, v in enumerate(value)]


def _number(where: str, field: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ChronoError(where, f'{field}: expected a number, got {_kind(value)}')
    value = float(value)
    if not math.isfinite(value):
        raise ChronoError(where, f'{field}: {value} is not a finite number')
    return value


def _kind(value: Any) -> str:
    if isinstance(value, str):
        return f'the string {value[:40]!r}'
    return {dict: 'an object', list: 'an array', bool: 'a boolean',
            type(None): 'null'}.get(type(value), type(value).__name__)
