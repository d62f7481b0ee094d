# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Continuation's guards: substeps bounded, limits remembered, settings and commands checked.

A bound on the substeps of a command, travel limits remembered per rack, settings checked,
commands of any real number type. Issue 23 item 3 (max_step_mm:=1e-7 never answered) and its
weak spot "out-of-reach commands are expensive" (7 ms each, limits found again every time).
"""

import math
from pathlib import Path

from linkage_ros.core.base import LinkageError, Status
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import Continuation, METHODS, sweep
import numpy as np
import pytest

STRESS = Path(__file__).resolve().parents[2] / 'config' / 'stress'
# trailing_arm_toggle: the bump travel ends with the arm vertical (test_stability)
TOGGLE_LIMIT_MM = -100.0 + math.hypot(150.0, 400.0) - 300.0
FIVE_LINK_BUMP_MM = 387.469      # five_link's bump limit (test_stability, README)


# --- a bound on the substeps ----------------------------------------------------------------

@pytest.mark.parametrize('method', METHODS)
def test_a_command_needing_more_substeps_than_max_substeps_is_refused_at_once(method):
    # 1 mm at max_step 1e-7 mm is 1e7 substeps: more than the default max_substeps 10 000.
    cont = Continuation(load_scene('five_link'), method=method, max_step=1e-7)
    sol = cont.solve(1.0)
    assert not sol.success and sol.status == Status.SUBSTEP_LIMIT
    assert 'needs 10000000 substeps of max_step 1e-07 mm' in sol.message
    assert 'max_substeps 10000' in sol.message and sol.substeps == 0
    assert cont.travel == 0.0                           # nothing was walked
    small = cont.solve(5e-6)          # 50 substeps, within the bound (51: float64 rounding of
    assert small.success and small.substeps in (50, 51)   # the distance walked leaves 1e-21)


@pytest.mark.parametrize('method', METHODS)
def test_max_substeps_counts_the_substeps_tried_and_a_walk_that_runs_out_is_refused(method):
    # Near the toggle substeps fail and are halved: 50 are tried to 0.001 mm before the fold
    # with the defaults; with 20 allowed the walk stops, says where, and keeps no pose.
    scene = load_scene(STRESS / 'trailing_arm_toggle.yaml')
    target = TOGGLE_LIMIT_MM - 0.001
    assert Continuation(scene, method=method).solve(target).success
    cont = Continuation(scene, method=method, max_substeps=20)
    sol = cont.solve(target)
    assert not sol.success and sol.status == Status.SUBSTEP_LIMIT
    assert 'not reached within max_substeps 20 substeps' in sol.message
    assert 0 < sol.substeps < 20 and cont.travel == 0.0


def test_a_sweep_whose_walk_needs_too_many_substeps_ends_with_the_status():
    result = sweep(load_scene('five_link'), [0.0, 1.0], max_step=1e-7)
    assert not result.success and result.status == Status.SUBSTEP_LIMIT
    assert len(result.travel) == 1


# --- travel limits remembered per rack ------------------------------------------------------

@pytest.mark.parametrize('method', METHODS)
def test_a_command_beyond_a_known_limit_is_refused_with_the_same_status_and_message(method):
    cont = Continuation(load_scene('five_link'), method=method)
    cont.solve(10.0)
    first = cont.solve(500.0)
    assert first.status == Status.OUT_OF_REACH and first.substeps > 0
    assert cont.limits[0.0][1] == pytest.approx(FIVE_LINK_BUMP_MM, abs=1e-3)
    again = cont.solve(500.0)
    assert again.status == Status.OUT_OF_REACH and again.message == first.message
    assert again.substeps == 0 and again.reachable == first.reachable
    farther = cont.solve(1e4)
    assert farther.status == Status.OUT_OF_REACH and f'{cont.limits[0.0][1]:.3f}' in \
        farther.message
    assert cont.travel == 10.0


def test_a_known_limit_refuses_nothing_within_it_and_each_side_is_found_on_its_own():
    cont = Continuation(load_scene('five_link'))
    cont.solve(500.0)
    assert cont.limits[0.0][0] == -math.inf           # the rebound limit is not known yet
    near = cont.solve(FIVE_LINK_BUMP_MM - 0.02)
    assert near.success and near.residual <= 1e-9
    below = cont.solve(-300.0)
    assert below.status == Status.OUT_OF_REACH and 'rebound limit' in below.message
    assert cont.limits[0.0][0] == pytest.approx(below.reachable[0])


def test_a_known_limit_refuses_from_memory_only_beyond_how_closely_it_is_located():
    cont = Continuation(load_scene('five_link'))
    limit = cont.solve(500.0).reachable[1]
    assert 'located to 0.01 mm' in cont.solve(500.0).message
    within = cont.solve(limit + 0.005)           # not refused from memory: walked again
    assert within.status == Status.OUT_OF_REACH and within.substeps > 0
    assert cont.solve(limit + 0.02).substeps == 0


def test_limits_are_kept_per_rack_and_forgotten_by_reset():
    scene = load_scene('double_wishbone')               # its tie rod is steered by the rack
    cont = Continuation(scene)
    found = cont.solve(1000.0)
    assert found.status == Status.OUT_OF_REACH
    assert cont.solve(0.0, 20.0).success
    assert cont.limits[20.0] == [-math.inf, math.inf]   # a new rack: nothing known there
    at_rack = cont.solve(1000.0)
    assert at_rack.status == Status.OUT_OF_REACH and at_rack.substeps > 0
    assert cont.limits[20.0][1] != cont.limits[0.0][1]
    assert cont.solve(0.0, 0.0).success
    assert cont.solve(1000.0).message.endswith(found.message.split(';')[1])
    cont.reset()
    assert cont.limits == {0.0: [-math.inf, math.inf]}


# --- settings and commands ------------------------------------------------------------------

@pytest.mark.parametrize('name, value', [('max_step', 0.0), ('max_step', math.nan),
                                         ('min_step', -1.0), ('tol', math.inf),
                                         ('max_substeps', 0), ('max_iter', 2.5),
                                         ('knot_step', 0.0), ('method', 'newton')])
def test_a_bad_setting_is_a_linkage_error_naming_it(name, value):
    with pytest.raises(LinkageError, match=name):
        Continuation(load_scene('five_link'), **{name: value})


def test_mechanism_sized_defaults_follow_the_carrier_and_given_values_are_kept():
    # The carrier levers: five_link 221 mm (scale 1), its 1e-4 copy 0.0221 mm.
    big = Continuation(load_scene('five_link')).settings
    small = Continuation(load_scene(STRESS / 'five_link_submillimetre.yaml')).settings
    assert (big.min_step, big.knot_step, big.knot_tol) == (0.005, 40.0, 1e-6)
    assert small.min_step == pytest.approx(0.005 * 0.0221 / 100.0, rel=1e-3)
    assert small.knot_step == pytest.approx(40.0 * 0.0221 / 100.0, rel=1e-3)
    given = Continuation(load_scene(STRESS / 'five_link_submillimetre.yaml'), min_step=0.002)
    assert given.settings.min_step == 0.002


@pytest.mark.parametrize('travel', [np.int64(20), np.float32(20.0), 20, np.float64(20.0)])
def test_a_command_of_any_real_number_type_is_solved(travel):
    sol = Continuation(load_scene('double_wishbone')).solve(travel, np.int64(0))
    assert sol.success and sol.travel == 20.0


@pytest.mark.parametrize('travel', [True, '20', None, 10**400])
def test_a_command_that_is_not_a_finite_real_number_is_refused(travel):
    sol = Continuation(load_scene('five_link')).solve(travel)
    assert not sol.success and sol.status == Status.NOT_FINITE
