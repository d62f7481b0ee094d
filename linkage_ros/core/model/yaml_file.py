# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Reading a scene or vehicle file: plain YAML data, within bounds, or one line that says why not.

A file is refused, with SceneError naming the file and where in it, when it is
- larger than FILE_LIMIT_BYTES (a scene is a few KB; parsing 100 MB of YAML takes minutes);
- not UTF-8 text, or not YAML (the line, the column and the problem; never the file echoed);
- holding more than VALUES_LIMIT values once its aliases are expanded: anchors and aliases
  (`&p`, `*p`) are allowed for sharing a point or a block, but a chain of aliases that
  multiply (a "billion laughs" in 2 KB) is refused while it is read, before anything is
  built from it; a recursive alias is refused too;
- nested deeper than DEPTH_LIMIT levels;
- tagged with anything but plain data (`!!python/object`, `!!binary`, `!!set`, `!mine`);
- giving one key twice in a mapping (YAML would keep the last silently).
Dates are not converted (`2024-01-01` stays text): a scene has no dates, and an invalid one
(`2001-13-45`) would otherwise fail deep inside the YAML library. A number with an exponent
is a number, as in YAML 1.2, also without a point or a sign after the e (`1e-3`, `-1.0e9`),
which PyYAML's YAML 1.1 reads as text.
"""

from __future__ import annotations

import os
from pathlib import Path
import re
import stat
from typing import Any, TYPE_CHECKING

import yaml

from ..base.errors import LinkageError

if TYPE_CHECKING:
    from os import PathLike

FILE_LIMIT_BYTES = 1_000_000
VALUES_LIMIT = 100_000
DEPTH_LIMIT = 100

_CORE = 'tag:yaml.org,2002:'
# The tags of plain data: what a scene or vehicle file may hold.
PLAIN_TAGS = {_CORE + t for t in ('str', 'int', 'float', 'bool', 'null', 'seq', 'map', 'merge')}
PLAIN_TAGS.add('!')   # the non-specific tag of a quoted scalar

_Base = yaml.CSafeLoader if yaml.__with_libyaml__ else yaml.SafeLoader


class SceneError(LinkageError):
    """A scene or vehicle file is malformed; the message names the file, field and problem."""

    def __init__(self, source: str | PathLike, field_name: str, problem: str) -> None:
        super().__init__(f'{source}: {field_name}', problem)
        self.source, self.field = str(source), field_name


class _Refused(yaml.MarkedYAMLError):
    """Valid YAML that these files may not hold; its problem is said as it is."""


class _PlainLoader(_Base):
    """A safe YAML loader without dates, refusing a key given twice in a mapping."""

    yaml_implicit_resolvers = {
        first: [(tag, regexp) for tag, regexp in resolvers if tag != _CORE + 'timestamp']
        for first, resolvers in _Base.yaml_implicit_resolvers.items()}

    def construct_mapping(self, node, deep=False):
        """Build a mapping, refusing a key given twice (merged keys may be overridden)."""
        seen = {}
        for key_node, _ in node.value:
            if isinstance(key_node, yaml.ScalarNode) and key_node.tag != _CORE + 'merge':
                key = (key_node.tag, key_node.value)
                if key in seen:
                    raise _Refused(
                        None, None, f'key {key_node.value!r} given twice (first on line '
                        f'{seen[key].line + 1})', key_node.start_mark)
                seen[key] = key_node.start_mark
        return super().construct_mapping(node, deep)


# 1e-3, -2E5, -1.0e9, .5e3: floats (after the int and float resolvers, which take every
# other number; YAML 1.1's wants a sign in the exponent and reads -1.0e9 as text).
_PlainLoader.add_implicit_resolver(
    _CORE + 'float',
    re.compile(r'^[-+]?(?:[0-9][0-9_]*(?:\.[0-9_]*)?|\.[0-9][0-9_]*)[eE][-+]?[0-9]+$'),
    list('-+.0123456789'))


def read_yaml(path: str | PathLike, what: str = 'scene') -> Any:
    """
    Return the data of a YAML file (what: 'scene' or 'vehicle', for the messages).

    Raises SceneError(path, field, problem): field 'file' for the file as a whole, 'line L,
    column C' (from 1) for a place in it.
    """
    path = Path(path)
    try:
        with open_regular(path) as stream:
            raw = stream.read(FILE_LIMIT_BYTES + 1)
    except OSError as exc:
        raise SceneError(path, 'file', f'cannot read ({exc.strerror or exc})') from None
    if len(raw) > FILE_LIMIT_BYTES:
        size = _size_of(path)
        raise SceneError(path, 'file', f'{size} bytes, over the limit of {FILE_LIMIT_BYTES:,} '
                         f'bytes for a {what} file (a {what} file is a few KB)')
    try:
        text = raw.decode('utf-8')
    except UnicodeDecodeError as exc:
        raise SceneError(path, 'file', f'not UTF-8 text ({exc})') from None
    return parse_yaml(text, path)


def open_regular(path: str | PathLike):
    """
    Open a regular file for reading in binary, or raise SceneError(path, 'file', why not).

    Opened without blocking (O_NONBLOCK) and checked on the open descriptor: a FIFO, a
    device or a socket named as a scene would otherwise block the reader (and a node's
    executor) until something writes to it, or forever. OSError as open raises it.
    """
    descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, 'O_CLOEXEC', 0))
    try:
        mode = os.fstat(descriptor).st_mode
        if not stat.S_ISREG(mode):
            raise SceneError(path, 'file', f'not a regular file ({_file_kind(mode)}): give '
                             'a YAML file')
        os.set_blocking(descriptor, True)
        return os.fdopen(descriptor, 'rb')
    except BaseException:
        os.close(descriptor)
        raise


def _file_kind(mode):
    kinds = ((stat.S_ISDIR, 'a folder'), (stat.S_ISFIFO, 'a FIFO'), (stat.S_ISSOCK, 'a socket'),
             (stat.S_ISCHR, 'a character device'), (stat.S_ISBLK, 'a block device'))
    return next((said for test, said in kinds if test(mode)), 'not a file')


def parse_yaml(text: str, where: str | PathLike) -> Any:
    """
    Return the data of YAML text with read_yaml's bounds (values, depth, plain tags only).

    where names the text in errors (a file, or a recording's stored scene); the text's length
    is the caller's to bound (read_yaml reads at most FILE_LIMIT_BYTES). Raises SceneError.
    """
    try:
        _check_events(text)
        return yaml.load(text, Loader=_PlainLoader)   # noqa: S506 (_PlainLoader is safe)
    except yaml.MarkedYAMLError as exc:
        raise _located(where, exc) from None
    except (yaml.YAMLError, ValueError, RecursionError) as exc:
        raise SceneError(where, 'file', f'not valid YAML ({_one_line(str(exc))})') from None


def _size_of(path):
    """Say the size of a file too large to read ('more than N' where it cannot be told)."""
    try:
        return f'{path.stat().st_size:,}'
    except OSError:
        return f'more than {FILE_LIMIT_BYTES:,}'


def _check_events(text):
    """
    Walk the YAML events of text, refusing what read_yaml refuses before it is built.

    The values each anchor stands for are counted as its block closes, so that an alias
    adds them without expanding anything: memory stays that of the deepest open block.
    """
    values = {}        # anchor -> how many values it stands for
    open_blocks = []   # [count, anchor, event] of each open sequence or mapping
    total, aliased = 0, False
    for event in yaml.parse(text, Loader=_Base):
        if isinstance(event, (yaml.ScalarEvent, yaml.CollectionStartEvent)):
            _check_tag(event)
        if isinstance(event, yaml.CollectionStartEvent):
            if len(open_blocks) >= DEPTH_LIMIT:
                _refuse(event, f'nested deeper than {DEPTH_LIMIT} levels')
            open_blocks.append([1, event.anchor, event])
            continue
        if isinstance(event, yaml.ScalarEvent):
            count, anchor = 1, event.anchor
        elif isinstance(event, yaml.AliasEvent):
            if event.anchor not in values:
                recursive = any(block[1] == event.anchor for block in open_blocks)
                _refuse(event, f'the alias *{event.anchor} ' + (
                    'is inside its own anchor (a recursive structure)' if recursive
                    else 'names no anchor before it'))
            count, anchor, aliased = values[event.anchor], None, True
        elif isinstance(event, yaml.CollectionEndEvent):
            count, anchor, _ = open_blocks.pop()
        else:
            continue
        if anchor is not None:
            values[anchor] = count
        if open_blocks:
            open_blocks[-1][0] += count
        total += count if not open_blocks else 0
        if open_blocks and open_blocks[0][0] > VALUES_LIMIT or total > VALUES_LIMIT:
            _refuse(event, (f'its aliases expand it to more than {VALUES_LIMIT:,} values '
                            '(a chain of aliases that multiply?)') if aliased else
                    f'more than {VALUES_LIMIT:,} values (a scene holds a few hundred)')


def _check_tag(event):
    tag = event.tag
    if tag is not None and tag not in PLAIN_TAGS:
        shown = '!!' + tag[len(_CORE):] if tag.startswith(_CORE) else tag
        _refuse(event, f'the tag {shown} is refused: these files hold plain data (mappings, '
                'lists, numbers, text, true/false, null)')


def _refuse(event, problem):
    raise _Refused(problem=problem, problem_mark=event.start_mark)


def _located(path, exc):
    """Return the SceneError of a YAML error with a place: 'line L, column C: problem'."""
    mark = exc.problem_mark or exc.context_mark
    where = f'line {mark.line + 1}, column {mark.column + 1}' if mark else 'file'
    problem = _one_line(exc.problem or '')
    if not isinstance(exc, _Refused):
        context = _one_line(exc.context or '')
        if context and exc.context_mark and exc.problem_mark \
                and exc.context_mark.line != exc.problem_mark.line:
            context += f' (from line {exc.context_mark.line + 1})'
        said = [context, problem]
        problem = 'not valid YAML: ' + ', '.join(s for s in said if s)
    return SceneError(path, where, problem)


def _one_line(text):
    return ' '.join(str(text).split())
