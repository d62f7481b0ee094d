# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The carrier's exact velocity and acceleration per travel (core/measure/motion.py).

Checked against central differences of solved poses, and the guidance rows it reads against
the mechanism's own Jacobian.
"""

from linkage_ros.core.measure import (carrier_motion, guidance_rows, mount_motion, mount_table,
                                      pose_batch)
from linkage_ros.core.model import bundled_scenes, load_scene, Mount
from linkage_ros.core.solve import compile_scene, linearize, sweep
import numpy as np
import pytest

TRAVEL = np.array([-50.0, -10.0, 25.0, 60.0])
H = 0.05   # mm: second differences of joints held to ~1e-10 mm err by ~4e-8; O(H^2) ~1e-11
STEERED = [(name, rack) for name in ('five_link', 'double_wishbone', 'macpherson')
           for rack in (0.0, 6.0) if rack == 0.0 or name != 'five_link']


@pytest.mark.parametrize('name, rack', STEERED)
def test_every_joint_moves_with_the_velocity_and_acceleration_of_the_carrier(name, rack):
    scene = load_scene(name)
    mech = compile_scene(scene)
    rows = guidance_rows(scene, mech)
    minus, here, plus = (sweep(scene, TRAVEL + h, rack=rack) for h in (-H, 0.0, H))
    joints = mount_table(scene, [Mount('carrier', c.carrier) for c in scene.constraints])
    moving = mount_motion(rows, joints, pose_batch(mech, here.wheel_center, here.rotation, rack))
    for j in range(len(scene.constraints)):
        position, velocity, acceleration = (m[:, j] for m in moving)
        assert position == pytest.approx(here.joints[:, j], abs=1e-9)
        assert velocity == pytest.approx((plus.joints[:, j] - minus.joints[:, j]) / (2 * H),
                                         abs=1e-8)
        assert acceleration == pytest.approx(
            (plus.joints[:, j] - 2 * here.joints[:, j] + minus.joints[:, j]) / H**2, abs=2e-7)


def test_travel_moves_the_wheel_centre_up_at_one_mm_per_mm_with_no_vertical_acceleration():
    scene = load_scene('five_link')
    mech = compile_scene(scene)
    here = sweep(scene, TRAVEL)
    motion = carrier_motion(guidance_rows(scene, mech),
                            pose_batch(mech, here.wheel_center, here.rotation))
    assert np.all(motion.velocity[:, 2] == 1.0) and np.all(motion.acceleration[:, 2] == 0.0)


@pytest.mark.parametrize('name', bundled_scenes())
def test_guidance_rows_rebuild_the_mechanisms_jacobian(name):
    # Row i of the Jacobian: sphere (d / l, r x d / l), line (-n, n x (T - C) - r x n).
    scene = load_scene(name)
    mech = compile_scene(scene)
    rows = guidance_rows(scene, mech)
    result = sweep(scene, [-30.0, 30.0], rack=4.0 if mech.steered else 0.0)
    _, jac = linearize(mech, result.wheel_center, result.rotation, result.rack)
    rack = np.array([0.0, result.rack, 0.0])
    for n, (center, rotation) in enumerate(zip(result.wheel_center, result.rotation)):
        for i in range(5):
            r = rotation @ rows.offset[i]
            if rows.line[i]:
                normal = rotation @ rows.normal[i]
                row = np.concatenate((-normal, np.cross(normal, rows.base[i] - center - r)
                                      - np.cross(r, normal)))
            else:
                d = center + r - rows.base[i] - rows.steer[i] * rack
                row = np.concatenate((d, np.cross(r, d))) / rows.length[i]
            assert row == pytest.approx(jac[n, i], abs=1e-12)
