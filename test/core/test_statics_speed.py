# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The statics' shortcuts (core/statics/loaded.py) give the answers of the long way."""

import importlib
from pathlib import Path

from linkage_ros.core.model import load_scene
from linkage_ros.core.statics import compliance, kernel, Load, loaded, solve_loaded
from linkage_ros.core.statics.forces import item_places
from linkage_ros.core.statics.system import Item, position
import numpy as np
import pytest

BUSHED = str(Path(__file__).resolve().parents[1] / 'data' / 'double_wishbone_bushings.yaml')
LOAD = Load((300.0, 2000.0, -500.0), 'cp', (40.0, -20.0, 150.0))


def test_a_zero_load_state_continued_from_the_last_one_equals_the_one_from_kinematics(
        monkeypatch):
    """Continued from travel 10 mm, the state at 12 mm needs no arm poses from kinematics."""
    cold_scene, warm_scene = load_scene(BUSHED), load_scene(BUSHED)
    cold = compliance(cold_scene, 12.0), solve_loaded(cold_scene, 12.0, LOAD)
    compliance(warm_scene, 10.0)

    def refused(*args):
        raise AssertionError('the kinematic start was taken')

    monkeypatch.setattr(loaded, 'initial_pose', refused)
    warm = compliance(warm_scene, 12.0), solve_loaded(warm_scene, 12.0, LOAD)
    for key, value in cold[0].rates.items():
        assert warm[0].rates[key] == pytest.approx(value, rel=1e-9, abs=1e-12), key
    assert np.abs(warm[1].wheel_center_mm - cold[1].wheel_center_mm).max() < 1e-9
    scale = max(np.linalg.norm(f) for f in cold[1].body_forces_n.values())
    for key, force in cold[1].body_forces_n.items():
        assert np.abs(warm[1].body_forces_n[key] - force).max() < 1e-9 * scale, key


def test_the_compiled_item_places_are_where_the_system_puts_each_item():
    """pickup_forces reads the places kernel.places writes; system.position is the check."""
    scene = load_scene('five_link')   # a spring on a link: weighted moving items
    base = loaded.unloaded(scene, 20.0)
    at = item_places(base.system, base.model, base.eq.pose)
    system, pose = base.system, base.eq.pose
    m = len(system.constraints)
    for i, (_, _, items, _) in enumerate(system.constraints):
        for a, item in enumerate(items):
            assert np.abs(at[i, a] - position(system, pose, item)[0]).max() < 1e-12
    for s, (_, end, moving) in enumerate(system.springs):
        for a, item in enumerate([end] + [it for _, it in moving]):
            assert np.abs(at[m + s, a] - position(system, pose, item)[0]).max() < 1e-12
    first = m + len(system.springs)
    for b, bush in enumerate(system.bushings):
        place = position(system, pose, Item(bush.body, bush.x0))[0]
        assert np.abs(at[first + b, 0] - place).max() < 1e-12
    assert np.abs(at[-1, 0] - position(system, pose, system.load_item)[0]).max() < 1e-12
    by_numpy = item_places(system, None, pose)   # the numpy path's places: the same
    assert np.array_equal(np.isnan(by_numpy), np.isnan(at))
    assert np.nanmax(np.abs(by_numpy - at)) < 1e-12


def test_rates_asked_again_at_the_same_state_are_not_solved_again_and_are_a_copy(monkeypatch):
    scene = load_scene(BUSHED)
    first = compliance(scene, 15.0)
    first.rates['toe_per_fx_wc_deg_per_kn'] = 99.0   # the caller's to change
    first.matrix[0, 0] = 99.0

    def refused(*args):
        raise AssertionError('the rates were solved again')

    monkeypatch.setattr(importlib.import_module('linkage_ros.core.statics.compliance'),
                        '_rates', refused)
    again = compliance(scene, 15.0)
    fresh = load_scene(BUSHED)
    monkeypatch.undo()
    expected = compliance(fresh, 15.0)
    assert again.rates == expected.rates   # same code path on the same input: exactly equal
    assert np.array_equal(again.matrix, expected.matrix)


def test_newton_stops_when_its_next_step_is_predicted_below_round_off():
    """Steps 0.711, 1.77e-3, 3.0e-9 mm (a zero-load solve): the next, ~9e-21, is not taken."""
    tol = 1e-11 * 216.0   # TOL_STEP times the lever
    assert not kernel.converged(0.711, 0.0, tol)            # the first step: no prediction
    assert not kernel.converged(1.77e-3, 0.711, tol)        # next ~1e-8: still to be taken
    assert kernel.converged(3.0e-9, 1.77e-3, tol)
    assert kernel.converged(1e-9, 0.0, tol)                 # below the tolerance itself


def _turned(rotation, axis, deg):
    """Return rotation turned by deg about the unit axis (3,) (Rodrigues)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    a = np.radians(deg)
    return (np.eye(3) + np.sin(a) * k + (1.0 - np.cos(a)) * k @ k) @ rotation


TURNS = [(4.9, True, ''), (5.1, True, 'conically'), (30.0, False, '')]


@pytest.mark.parametrize('deg, across, said', TURNS)
def test_the_validity_check_names_an_arm_turned_conically_beyond_5_deg_only(
        deg, across, said):
    """Turned across its axis beyond 5 deg an arm is named; about its axis (torsion) not."""
    scene = load_scene(BUSHED)
    base = loaded.unloaded(scene, 0.0)
    bush = next(b for b in base.system.bushings if base.system.bodies[b.body].kind == 'arm')
    axis = np.cross(bush.axis, (0.0, 0.0, 1.0)) if across else bush.axis
    axis = axis / np.linalg.norm(axis)
    r = base.eq.pose.r.copy()
    r[bush.body] = _turned(r[bush.body], axis, deg)
    eq = base.eq._replace(pose=base.eq.pose._replace(r=r))
    at = item_places(base.system, base.model, base.eq.pose)
    message = loaded._beyond_validity(base.system, eq, at)
    assert (said in message) if said else message == ''
    if said:
        assert message.startswith(f'bushing {bush.key} turns ')
