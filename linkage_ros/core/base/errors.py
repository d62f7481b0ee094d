# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The one base class of the errors linkage_ros raises for bad input.

Bad input is a scene or vehicle file, a parameter, a recording or a bag. The error is a
ValueError whose message names where the problem is and what it is, built from the
offending value.
"""


from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from os import PathLike


class LinkageError(ValueError):
    """Bad input: where (a file, a field, a parameter) and what is wrong with it."""

    def __init__(self, where: str | PathLike, problem: str) -> None:
        self.where, self.problem = str(where), str(problem)
        super().__init__(f'{where}: {problem}')
