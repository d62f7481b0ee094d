# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage_ros.answer.health: what /diagnostics says about a corner, without ROS.

Expected behaviour is the diagnostic_updater convention the node follows: a report every
period summarising it, and a report at once for a failed command or a change of level.
"""

import math

from linkage_ros.answer.health import ERROR, Health, OK, WARN
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import Continuation
import pytest


@pytest.fixture(scope='module')
def five_link():
    return Continuation(load_scene('five_link'))


def test_a_new_corner_is_ok_and_has_counted_nothing():
    health = Health(condition_warn=1e4)
    assert (health.level, health.message, health.commands) == (OK, 'no command yet', 0)


def test_good_commands_are_counted_but_not_reported_at_once(five_link):
    health = Health(condition_warn=1e4)
    assert [health.add(five_link.solve(t)) for t in (1.0, 2.0, 3.0)] == [False] * 3
    assert (health.level, health.commands, health.failures) == (OK, 3, 0)
    assert 0 < health.residual_max <= 1e-10                         # mm, the solver's tol


def test_a_failed_command_is_reported_at_once_every_time(five_link):
    health = Health(condition_warn=1e4)
    assert [health.add(five_link.solve(t)) for t in (math.nan, math.nan)] == [True, True]
    assert (health.level, health.failures) == (ERROR, 2)
    assert 'not a finite number' in health.message


def test_the_first_good_command_after_a_failure_changes_the_level_back(five_link):
    health = Health(condition_warn=1e4)
    health.add(five_link.solve(math.inf))
    assert health.add(five_link.solve(1.0)) is True
    assert (health.level, health.message) == (OK, 'ok')


def test_crossing_condition_warn_changes_the_level_both_ways(five_link):
    design = five_link.solve(0.0).condition            # about 590 for five_link
    health = Health(condition_warn=design * 1.001)
    assert health.add(five_link.solve(0.0)) is False   # OK -> OK
    high = five_link.solve(80.0)
    assert high.condition > design * 1.001             # the condition grows towards bump
    assert health.add(high) is True and health.level == WARN
    assert health.add(five_link.solve(0.0)) is True and health.level == OK


def test_a_new_period_starts_its_counts_and_worst_values_again(five_link):
    health = Health(condition_warn=1e4)
    health.add(five_link.solve(5.0))
    health.add(five_link.solve(math.nan))
    health.reset_period()
    assert (health.commands, health.failures, health.residual_max, health.condition_max,
            health.iterations_max, health.substeps_max) == (0, 0, 0.0, 0.0, 0, 0)
    assert (health.commands_total, health.failures_total) == (2, 1)
    assert health.level == ERROR                        # the level is that of the last command


def test_a_fault_holds_error_until_cleared(five_link):
    health = Health(condition_warn=1e4)
    assert health.set_fault('recording run.mcap stopped: disk full') is True
    assert health.add(five_link.solve(1.0)) is False    # still ERROR: the fault holds
    assert (health.level, health.message) == (ERROR, 'recording run.mcap stopped: disk full')
    assert health.set_fault('') is True and health.level == OK


def test_lost_inputs_and_refused_requests_are_counted_apart_from_commands(five_link):
    health = Health(condition_warn=1e4)
    health.add(five_link.solve(10.0))
    health.lose(7)
    health.lose(2)
    health.refuse_request()
    # not commands, and no change of level: the commands that came are answered as ever
    assert (health.commands, health.failures, health.level) == (1, 0, OK)
    assert (health.lost, health.lost_total, health.refused_requests, health.refused_total) == (
        9, 9, 1, 1)
    health.reset_period()
    health.lose(1)
    assert (health.lost, health.lost_total, health.refused_requests, health.refused_total) == (
        1, 10, 0, 1)
