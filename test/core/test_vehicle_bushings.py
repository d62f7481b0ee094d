# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""demo_vehicle_bushings (issue 37 item 4): demo_vehicle with bushings at every corner."""

from dataclasses import asdict

from linkage_ros.core.base import Status
from linkage_ros.core.model import load_vehicle
from linkage_ros.core.statics import Load, Statics
from linkage_ros.core.vehicle import setup_sheet
import numpy as np
import pytest

BUSHED, PLAIN = load_vehicle('demo_vehicle_bushings'), load_vehicle('demo_vehicle')
MIRROR = np.array([1.0, -1.0, 1.0])   # y -> -y: the right corner is the left mirrored


def test_it_is_demo_vehicle_with_the_bushed_scenes_at_every_corner():
    assert list(BUSHED.corners) == list(PLAIN.corners)
    names = {name: scene.source.rsplit('/', 1)[-1] for name, scene in BUSHED.corners.items()}
    assert names == {'front_left': 'double_wishbone_bushings.yaml',
                     'front_right': 'double_wishbone_bushings.yaml',
                     'rear_left': 'five_link_bushings.yaml',
                     'rear_right': 'five_link_bushings.yaml'}
    for name, scene in BUSHED.corners.items():
        assert scene.has_bushings, name
        np.testing.assert_array_equal(scene.points, PLAIN.corners[name].points)
    assert BUSHED.joints == PLAIN.joints and BUSHED.mass == PLAIN.mass
    axles = [asdict(v.axles) for v in (BUSHED, PLAIN)]
    assert [a.pop('source') for a in axles] == [BUSHED.source, PLAIN.source]
    assert same(*axles)   # the anti-roll bar included
    assert BUSHED.axles.axles['front'].anti_roll_bar is not None


def same(a, b) -> bool:
    """Tell whether two nests of dicts, sequences and arrays hold equal values."""
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, np.ndarray):
        return np.array_equal(a, b)
    return a == b


def test_its_setup_sheet_is_demo_vehicle_s_digit_for_digit():
    """The kinematics do not read the bushings: the same hardpoints give the same sheet."""
    bushed, plain = setup_sheet(BUSHED), setup_sheet(PLAIN)
    assert bushed.status == plain.status == Status.OK
    assert bushed.rows == plain.rows   # the same arithmetic on the same numbers: equal


@pytest.mark.parametrize('axle', ['front', 'rear'])
def test_a_right_corner_answers_the_mirror_image_of_its_left_one(axle):
    """
    Under the mirrored wrench (Fy, Mx, Mz negated) the right corner mirrors the left one.

    The same camber, toe and holding force, the wheel centre and every pickup force mirrored
    in y (forces: y negated; couples, axial vectors: x and z negated), to the solves'
    round-off: 1e-9 of the largest force, 1e-9 mm, 1e-9 deg.
    """
    force, moment = np.array([300.0, 2000.0, -500.0]), np.array([20.0, 30.0, 50.0])
    left = Statics(BUSHED.corners[f'{axle}_left']).solve(
        10.0, Load(tuple(force), 'cp', tuple(moment)))
    right = Statics(BUSHED.corners[f'{axle}_right']).solve(
        10.0, Load(tuple(force * MIRROR), 'cp', tuple(-moment * MIRROR)))
    assert left.status == right.status == Status.OK
    assert right.toe_deg == pytest.approx(left.toe_deg, abs=1e-9)
    assert right.camber_deg == pytest.approx(left.camber_deg, abs=1e-9)
    np.testing.assert_allclose(right.wheel_center_mm, left.wheel_center_mm * MIRROR, atol=1e-9)
    scale = max(np.abs(f).max() for f in left.body_forces_n.values())
    assert right.holding_force_n == pytest.approx(left.holding_force_n, abs=1e-9 * scale)
    assert list(right.body_forces_n) == list(left.body_forces_n)
    for name, f in left.body_forces_n.items():
        np.testing.assert_allclose(right.body_forces_n[name], f * MIRROR, atol=1e-9 * scale)
    for name, m in left.body_moments_nm.items():
        np.testing.assert_allclose(right.body_moments_nm[name], -m * MIRROR,
                                   atol=1e-9 * scale)
