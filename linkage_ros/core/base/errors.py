# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The one base class of the errors linkage_ros raises for bad input.

Bad input is a scene or vehicle file, a parameter, a recording or a bag. The error is a
ValueError whose message names where the problem is and what it is, built from the
offending value, in one line of bounded length: a list of offenders is its first few and a
count (listed), and a where or problem too long is cut in the middle (bounded).
"""


from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Sequence
    from os import PathLike


# The longest where and problem of an error line (characters): a line names the first few
# offenders and counts the rest (listed); a name or a path longer than this is cut in the middle.
WHERE_LIMIT = 400
PROBLEM_LIMIT = 800
LISTED = 4   # the items an error line names before it counts the rest


class LinkageError(ValueError):
    """Bad input: where (a file, a field, a parameter) and what is wrong with it."""

    def __init__(self, where: str | PathLike, problem: str) -> None:
        self.where, self.problem = str(where), str(problem)
        super().__init__(f'{bounded(self.where, WHERE_LIMIT)}: '
                         f'{bounded(self.problem, PROBLEM_LIMIT)}')


def bounded(text: str, limit: int) -> str:
    """Return text, or its two ends and how much was left out between, if over limit."""
    if len(text) <= limit:
        return text
    keep = limit - 40
    return (f'{text[:keep * 2 // 3]}... ({len(text) - keep:,} characters left out) ...'
            f'{text[len(text) - keep // 3:]}')


def listed(items: Sequence[object], first: int = LISTED) -> str:
    """Return the first items joined by ', ' and the count of the rest: 'a, b, c, d and 9 more'."""
    items = [str(i) for i in items]
    if len(items) <= first + 1:
        return ', '.join(items)
    return f'{", ".join(items[:first])} and {len(items) - first} more'
