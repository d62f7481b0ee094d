# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""A Statics' shortcuts (core/statics/statics.py) give the answers of the long way."""

import math
from pathlib import Path

from linkage_ros.core.base import exp_so3, Status
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import Continuation
from linkage_ros.core.statics import command, forces, Load, newton, RATE_COLUMNS, \
    solve_loaded, Statics
import numpy as np
import pytest

BUSHED = str(Path(__file__).resolve().parents[1] / 'data' / 'double_wishbone_bushings.yaml')
LOAD = Load((300.0, 2000.0, -500.0), 'cp', (40.0, -20.0, 150.0))
SCENES = ('double_wishbone_bushings', 'five_link_bushings',
          'chrono_sedan_doublewishbone_bushings', 'five_link')
# Two converged Newton solves of the same equations from different starts agree to their
# stop rule (steps below 1e-11 mm times the lever) and the residual's round-off: 1e-10 mm
# and 1e-12 deg in these scenes; the bounds are 1e-9 deg, 1e-8 mm, 1e-9 of forces.
ANGLE_DEG, POSITION_MM, FORCE_REL = 1e-9, 1e-8, 1e-9


def assert_same_answer(got, want):
    """Pose to the bounds above, every pickup force to FORCE_REL of the largest."""
    assert got.status == want.status == Status.OK, (got.message, want.message)
    assert abs(got.toe_deg - want.toe_deg) < ANGLE_DEG
    assert abs(got.camber_deg - want.camber_deg) < ANGLE_DEG
    assert np.abs(got.wheel_center_mm - want.wheel_center_mm).max() < POSITION_MM
    scale = max(np.linalg.norm(f) for f in want.body_forces_n.values())
    assert abs(got.holding_force_n - want.holding_force_n) < FORCE_REL * scale
    for what in ('body_forces_n', 'body_moments_nm', 'ball_joint_forces_n'):
        for key, value in getattr(want, what).items():
            assert np.abs(getattr(got, what)[key] - value).max() < FORCE_REL * scale, key


def sine(count=60, amplitude=30.0, period=40):
    """Return travels (mm) and loads of a slow sine: a cornering load that follows it."""
    travels = [amplitude * math.sin(2 * math.pi * i / period) for i in range(count)]
    loads = [Load((200.0 * math.cos(t / 9.0), 3000.0 * t / amplitude, 0.0), 'cp',
                  (0.0, 0.0, 50.0)) for t in travels]
    return travels, loads


@pytest.mark.parametrize('name', SCENES)
def test_commands_continued_from_the_last_equilibrium_equal_fresh_solves(name):
    """A Statics along a sine (one warm Newton solve each) against solve_loaded of each."""
    scene = load_scene(name)
    statics = Statics(scene)
    for travel, load in zip(*sine()):
        warm = statics.solve(travel, load)
        assert warm.status == Status.OK
        assert_same_answer(warm, solve_loaded(scene, travel, load))


def test_a_failed_warm_step_falls_back_to_the_kinematic_pose_and_gives_the_same(monkeypatch):
    """Every warm solve made to fail: each command the long way, the same answers."""
    scene = load_scene(BUSHED)
    travels, loads = sine(count=12)
    warm = [Statics(scene).solve(t, l) for t, l in zip(travels, loads)]
    run = command.solve

    def failing(ints, reals, state, io, *work):
        if io[command.LOADED_FROM] == command.WARM:
            io[command.CODE] = command.LOADED_FAILED
            return command.LOADED_FAILED
        return run(ints, reals, state, io, *work)

    monkeypatch.setattr(command, 'solve', failing)
    statics, kinematic = Statics(scene), []
    original = statics._kinematic

    def counted(*args):
        kinematic.append(args)
        return original(*args)

    statics._kinematic = counted
    for travel, load, want in zip(travels, loads, warm):
        assert_same_answer(statics.solve(travel, load), want)
    assert len(kinematic) == len(travels)   # each command took the long way


@pytest.mark.parametrize('at', ['cp', 'wc'])
def test_commands_along_a_sine_take_the_long_way_only_at_the_first(at):
    """
    Each command within command.WARM_MM of the last continues from it (one compiled call).

    A load at the wheel centre needs no zero-load equilibrium: before, its commands asked for
    one near enough, found the one of the first command left behind, and went the long way.
    """
    scene = load_scene(BUSHED)
    statics = Statics(scene)
    travels, loads = sine(count=80)   # 4.7 mm steps at most, 30 mm from the first
    for travel, load in zip(travels, loads):
        got = statics.solve(travel, Load(load.force_n, at, load.moment_nm))
        assert got.status == Status.OK, got.message
    assert statics.long_ways == 1
    assert_same_answer(got, solve_loaded(scene, travels[-1],
                                         Load(loads[-1].force_n, at, loads[-1].moment_nm)))


def test_rates_continued_from_the_last_equilibrium_equal_fresh_ones():
    scene = load_scene(BUSHED)
    statics = Statics(scene)
    for travel in (0.0, 2.0, 4.5, 3.0, -1.0):
        warm, fresh = statics.rates(travel), Statics(scene).rates(travel)
        for key, value in fresh.rates.items():
            assert warm.rates[key] == pytest.approx(value, rel=1e-9, abs=1e-12), key
        assert np.abs(warm.matrix_si - fresh.matrix_si).max() <= 1e-9 * np.abs(
            fresh.matrix_si).max()


def test_rates_asked_again_at_the_same_travel_solve_nothing_and_are_a_copy():
    statics = Statics(load_scene(BUSHED))
    first = statics.rates(15.0)
    first.rates['toe_per_fx_wc_deg_per_kN'] = 99.0   # the caller's to change
    first.matrix[0, 0] = 99.0
    again = statics.rates(15.0)
    assert statics._io[command.ZERO_ITERATIONS] == 0   # the zero-load state kept as it was
    expected = Statics(load_scene(BUSHED)).rates(15.0)
    assert again.rates == pytest.approx(expected.rates, rel=1e-12)
    assert np.abs(again.matrix - expected.matrix).max() <= 1e-12 * np.abs(expected.matrix).max()


def test_the_compiled_rates_write_the_layout_a_compliance_reads():
    """command.rates writes one value per rate column, then the matrix, the matrix in SI."""
    assert command.MATRIX == len(RATE_COLUMNS)
    assert (command.MATRIX_SI, command.RATES_SIZE) == (command.MATRIX + 36, command.MATRIX + 72)
    got = Statics(load_scene(BUSHED)).rates(5.0)
    # the SI matrix from the table's: mm -> m and deg -> rad per kN -> per N (exact scalings
    # of the same numbers: a few ulp)
    scale = np.array([1e-6] * 3 + [math.radians(1.0) * 1e-3] * 3)[:, None]
    assert np.allclose(got.matrix * scale, got.matrix_si, rtol=1e-14, atol=0.0)
    assert got.rates['toe_per_fy_cp_deg_per_kN'] == got.values[0]


def test_a_statics_keeps_nothing_in_the_frozen_scene():
    """Only what the kinematics derive (a Mechanism, points) is there, as without statics."""
    scene = load_scene(BUSHED)
    Continuation(scene).solve(10.0)
    before = set(scene.__dict__)
    statics = Statics(scene)
    statics.solve(10.0, LOAD)
    statics.rates(12.0)
    solve_loaded(scene, 5.0, LOAD)
    assert set(scene.__dict__) == before


def test_newton_stops_when_its_next_step_is_predicted_below_round_off():
    """Steps 0.711, 1.77e-3, 3.0e-9 mm (a zero-load solve): the next, ~9e-21, is not taken."""
    tol = 1e-11 * 216.0   # TOL_STEP times the lever
    assert not newton.converged(0.711, 0.0, tol)            # the first step: no prediction
    assert not newton.converged(1.77e-3, 0.711, tol)        # next ~1e-8: still to be taken
    assert newton.converged(3.0e-9, 1.77e-3, tol)
    assert newton.converged(1e-9, 0.0, tol)                 # below the tolerance itself


def test_newton_after_a_chord_step_stops_when_the_next_is_below_a_tenth_of_tolerance():
    """
    Converged: a chord step of 0.2 mm (a 1 kHz command), then 1.63e-4 mm.

    The next is predicted at 1.63e-4^3 / 0.2^2 = 1.08e-10 mm, 0.05 of the tolerance (1e-11 x
    the 216 mm lever): not taken (it moves the pose by 5e-13 rad at most). Before, it was
    (one command in five).
    """
    tol = 1e-11 * 216.0
    assert newton.converged(1.63e-4, 0.2, tol)
    assert not newton.converged(2.5e-4, 0.2, tol)   # predicted 3.9e-10: 0.18 of tol, taken


TURNS = [(4.9, True, forces.VALID), (5.1, True, forces.TURNS), (30.0, False, forces.VALID)]


@pytest.mark.parametrize('deg, across, said', TURNS)
def test_the_validity_check_names_an_arm_turned_conically_beyond_5_deg_only(deg, across, said):
    """Turned across its axis beyond 5 deg an arm is named; about its axis (torsion) not."""
    statics = Statics(load_scene(BUSHED))
    bush = next(b for b in statics.system.bushings
                if statics.system.bodies[b.body].kind == 'arm')
    axis = np.cross(bush.axis, (0.0, 0.0, 1.0)) if across else bush.axis
    axis = axis / np.linalg.norm(axis)
    out, phi = np.zeros(forces.HEAD), np.empty(3)
    forces._validity(True, exp_so3(np.radians(deg) * axis), bush.axis, 3, 0.0, 0.0, 0.0, out,
                     phi)
    assert out[forces.VALIDITY] == said
    if said == forces.TURNS:
        assert out[forces.VALIDITY_BUSHING] == 3
        assert out[forces.VALIDITY_VALUE] == pytest.approx(deg * np.linalg.norm(
            np.cross(axis, bush.axis)), rel=1e-9)
