# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
What /diagnostics says about one corner, kept the way diagnostic_updater keeps it.

A Health counts the commands a corner answers and remembers the worst of the period
(residual, condition number, Newton iterations, substeps), and counts what never became a
command: inputs lost in a flood (a subscription's queue overflowed) and solve requests
answered REFUSED. The node publishes its status
every diagnostic period and resets the period, and publishes at once when a command fails or
the level changes. ROS-free: messages.health_status turns it into a DiagnosticStatus.

Level (the diagnostic_msgs values): ERROR if a fault holds (a recording that stopped, say) or
the last command failed or did not decode, WARN if the last pose is near a singular position
(Jacobian condition number above condition_warn), OK otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..core.solve import Solution

OK, WARN, ERROR = 0, 1, 2


@dataclass
class Health:
    """The diagnostic state of one corner. Lengths in mm."""

    condition_warn: float          # condition number above which a pose is WARN
    level: int = OK
    message: str = 'no command yet'
    last: Solution | None = None   # the Solution of the last command
    sent: str = ''                 # the last command as it was sent, if it failed
    fault: str = ''                # a fault outside the solver (sets ERROR while it holds)
    refused: str = ''              # why the last command could not be read, if it could not
    commands_total: int = 0        # since start
    failures_total: int = 0
    lost_total: int = 0            # inputs lost before the node took them (a queue overflowed)
    refused_total: int = 0         # solve requests answered REFUSED
    # The period since the last report:
    commands: int = 0
    failures: int = 0
    residual_max: float = 0.0      # mm, over the solved commands
    condition_max: float = 0.0
    iterations_max: int = 0
    substeps_max: int = 0
    lost: int = 0
    refused_requests: int = 0

    def add(self, solution: Solution, sent: str = '') -> bool:
        """
        Count one answered command (a kinematics Solution).

        sent: the command as it was sent (e.g. '/wheel_travel 0.5 m'), which the message about
        a failure starts with. Returns True if /diagnostics should say so at once: the command
        failed, or the level changed.
        """
        self.commands += 1
        self.commands_total += 1
        self.last, self.sent, self.refused = solution, sent, ''
        if solution.success:
            # max() would drop a NaN; a residual or condition that is NaN must show.
            if not solution.residual <= self.residual_max:
                self.residual_max = solution.residual
            if not solution.condition <= self.condition_max:
                self.condition_max = solution.condition
            self.iterations_max = max(self.iterations_max, solution.iterations)
            self.substeps_max = max(self.substeps_max, solution.substeps)
        else:
            self.failures += 1
            self.failures_total += 1
        level = self.level
        self.level, self.message = self._assess()
        return not solution.success or self.level != level

    def refuse(self, why: str) -> bool:
        """
        Count one command whose bytes could not be read (why says so); return True.

        It is a failure, ERROR at once, with no Solution: the last one (and the values the
        status gives of it) stays.
        """
        self.commands += 1
        self.commands_total += 1
        self.failures += 1
        self.failures_total += 1
        self.refused = why
        self.level, self.message = self._assess()
        return True

    def lose(self, count: int) -> None:
        """
        Count inputs lost before the node took them (a subscription's queue overflowed).

        Counted apart from the commands: they were never answered, and the level is not
        changed (the commands that did come are answered as ever).
        """
        self.lost += count
        self.lost_total += count

    def refuse_request(self) -> None:
        """Count a solve request answered REFUSED (the solver never saw it)."""
        self.refused_requests += 1
        self.refused_total += 1

    def set_fault(self, fault: str) -> bool:
        """Hold a fault (a non-empty text) or clear it (''); return True if the level changed."""
        level, self.fault = self.level, fault
        self.level, self.message = self._assess()
        return self.level != level

    def reset_period(self) -> None:
        """Start a new period: the counts and the worst values start again."""
        self.commands = self.failures = self.iterations_max = self.substeps_max = 0
        self.lost = self.refused_requests = 0
        self.residual_max = self.condition_max = 0.0

    def _assess(self):
        solution = self.last
        if self.fault:
            return ERROR, self.fault
        if self.refused:
            return ERROR, self.refused
        if solution is None:
            return OK, 'no command yet'
        if not solution.success:
            return ERROR, f'{self.sent}: {solution.message}' if self.sent else solution.message
        if not solution.condition <= self.condition_warn:
            return WARN, (f'near a singular position: Jacobian condition number '
                          f'{solution.condition:.3g} above {self.condition_warn:.3g}')
        return OK, 'ok'
