# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Chrono's names of bodies, links and springs as scene names: ROS name tokens, both ways.

A scene's constraint and element names become topics, frames and URDF names, so the import
makes each a ROS name token ([A-Za-z][A-Za-z0-9_]*, no "__", at most MAX_TOKEN characters):
the runs of ASCII letters and digits joined by "_" ("lower-arm" -> lower_arm,
"unterer_Querlenker_ü" -> unterer_Querlenker, "9arm" -> x_9arm), a number appended where
two would meet. The Chrono name is kept beside it as x_chrono_name, and the export writes
it back, so that --like finds each body, link and spring of its original by name.
"""

from __future__ import annotations

import re

from .reader import ChronoError

MAX_TOKEN = 64   # characters: a topic (<corner>/pickup/<name>) stays far below DDS's 256
KEEP = 'x_chrono_name'


def token(name: str) -> str:
    """Return a ROS name token for name (the same for the same name)."""
    text = '_'.join(re.findall(r'[A-Za-z0-9]+', str(name)))
    if not text[:1].isalpha():
        text = 'x_' + text if text else 'x'
    return text[:MAX_TOKEN].rstrip('_')


class Tokens:
    """Tokens for the names of one list (constraints or elements), each given once."""

    def __init__(self) -> None:
        self.taken: set[str] = set()

    def __call__(self, name: str) -> str:
        """Return name's token, with _2, _3, ... where it is taken already."""
        base = token(name)
        out, k = base, 2
        while out in self.taken:
            out = f'{base[:MAX_TOKEN - 6]}_{k}'
            k += 1
        self.taken.add(out)
        return out


def named(item: dict, name: str, tokens: Tokens) -> dict:
    """Give a scene item (a constraint or an element) name's token, keeping name if it differs."""
    item['name'] = tokens(name)
    if item['name'] != name:
        item[KEEP] = name
    return item


def body_name(value) -> str:
    """Return the body name of a Chrono body identifier ("Name" or ["Name", "Left"])."""
    if isinstance(value, list) and value and isinstance(value[0], str):
        return value[0]
    if isinstance(value, str):
        return value
    raise ChronoError('body identifier', f'expected a name or [name, side], got {value!r}')
