# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The kind of a solver result, as a code beside its message (scipy's OptimizeResult.status).

Callers (the node, its diagnostics, the tools, the tests) branch on the code; the message is
for people and free to change.
"""

from enum import IntEnum


class Status(IntEnum):
    """What became of a command or a sweep. OK is 0; every other value is a failure."""

    OK = 0
    NOT_FINITE = 1     # the command (travel or rack) is not a finite number
    OUT_OF_REACH = 2   # beyond a travel limit (a turning point) of the assembly branch
    CURVE_LOST = 3     # continuation could not follow the solution curve any further
    SINGULAR = 4       # the Jacobian is singular where the command needs it
    SUBSTEP_LIMIT = 5  # the walk needs more substeps than max_substeps allows
    NO_RACK = 6        # a rack command to a scene without a steer: rack link
    NOT_CARRIED = 7    # statics: the load deflects a bushing beyond the model, or diverges
    SOLVER_ERROR = 8   # the solver raised an exception (a defect): its type and text said

    @property
    def phrase(self) -> str:
        """Say the kind in a few words, as the node's console names kinds of bad commands."""
        return self.name.lower().replace('_', ' ')
