# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The work a program's arguments ask for, as its benchmark takes it (one rule for all)."""

from __future__ import annotations

from types import ModuleType
from typing import Any, Callable

from ..cli import fail, warn
from ..core.base import LinkageError
from ..core.warmup import compile_if_cold


def asked(program: ModuleType, args: Any, warnings_of: Callable[[Any], list],
          statics: bool = False) -> Any:
    """
    Return program's request for its parsed args, as the program makes it, or an exit status.

    program: a tools module with PROG and request(args) (linkage-sweep's, ...); args: what its
    parse_args(argv) returned. A mistake is its one line and status 2 (an int returned); else
    the request's warnings (warnings_of(request)) are said and the kernels compiled (statics:
    those of the statics too) before any timing.
    """
    try:
        request = program.request(args)
    except LinkageError as exc:
        return fail(program.PROG, exc)
    warn(program.PROG, warnings_of(request))
    compile_if_cold(program.PROG, statics=statics)
    return request
