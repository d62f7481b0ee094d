# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
No step crosses a turning point (fold): the pose stays on the design branch in extreme cases.

Issue 23 item 11. Near a fold the other assembly branch is close and the tangent prediction
poor, so a converged pose near the prediction can still be on the other branch; there the
sign of det J_free (the Jacobian in the unknowns) differs, and the step is refused. The
expected poses come from an independent formulation (linkage_ros.bench.reference, extended
precision) or from the other path to the same point (linkage-sweep --rack: rack first at
travel 0, then travel).
"""

from pathlib import Path

from linkage_ros.bench import reference
from linkage_ros.core.base import Status
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import compile_scene, Continuation, kernel, METHODS, sweep
import numpy as np
import pytest

STRESS = Path(__file__).resolve().parents[2] / 'config' / 'stress'
SUB_TRAVEL_MM = 0.038    # five_link_submillimetre: 0.0007 mm short of its bump limit 0.03875
# chrono_hmmwv_doublewishbone_rear: combined commands along a chord of the bump limit curve
# (the limit is 566.28 mm at rack 10 mm and grows either side), found by a random search:
# before the fix each landed on the other branch, 2.6 to 27 mm from the pose of the other path.
CHORDS = [  # (travel, rack) from, (travel, rack) to (mm), max_step (mm)
    ((567.2141, -70.190), (566.6050, -32.993), 20.0),
    ((566.2290, 21.137), (566.5034, 45.619), 100.0),
    ((566.7539, -42.477), (566.4428, -19.856), 100.0),
    ((566.2954, 19.905), (566.2877, 0.734), 20.0),
    ((566.3624, 32.880), (566.2621, 5.730), 100.0),
    ((566.3774, -13.473), (566.7501, -53.175), 100.0),
    ((566.7213, 62.824), (566.4522, 40.223), 20.0),
    ((566.2782, 8.821), (566.3061, 21.508), 20.0),
]


@pytest.fixture(scope='module')
def submillimetre():
    scene = load_scene(STRESS / 'five_link_submillimetre.yaml')
    ref = reference.reference_poses(scene, [SUB_TRAVEL_MM])
    assert ref.success.all()
    return scene, np.asarray(ref.center[0], dtype=float)


@pytest.mark.parametrize('method', METHODS)
@pytest.mark.parametrize('max_step', [5.0, 0.01, 0.001, 0.0001])
def test_no_max_step_flips_the_branch_of_the_submillimetre_scene(submillimetre, method,
                                                                 max_step):
    # The issue: y 0.0319 mm with max_step 0.001 mm instead of 0.0456 mm.
    scene, expected = submillimetre
    sol = Continuation(scene, method=method, max_step=max_step).solve(SUB_TRAVEL_MM)
    assert sol.success, sol.message
    assert sol.wheel_center[1] == pytest.approx(0.0456301, abs=1e-7)
    # tol 1e-10 mm, amplified 0.0007 mm from the fold (the other branch is 0.0137 mm away)
    assert np.abs(sol.wheel_center - expected).max() <= 1e-9


def test_the_submillimetre_sweep_ends_on_the_branch_of_the_reference(submillimetre):
    scene, expected = submillimetre
    for travels in (np.linspace(0.0, SUB_TRAVEL_MM, 39), [SUB_TRAVEL_MM]):
        result = sweep(scene, travels)
        assert result.success
        assert np.abs(result.wheel_center[-1] - expected).max() <= 1e-9


@pytest.mark.parametrize('method', METHODS)
@pytest.mark.parametrize('start, end, max_step', CHORDS)
def test_a_combined_travel_and_rack_step_agrees_with_the_other_path_or_is_out_of_reach(
        start, end, max_step, method):
    scene = load_scene('chrono_hmmwv_doublewishbone_rear')
    cont = Continuation(scene, method=method, max_step=max_step)
    assert cont.solve(0.0, start[1]).success and cont.solve(start[0]).success
    sol = cont.solve(*end)
    other = sweep(scene, [end[0]], rack=end[1])        # linkage-sweep --rack
    assert other.success
    if sol.success:
        assert np.abs(sol.wheel_center - other.wheel_center[0]).max() <= 1e-6
    else:
        assert sol.status == Status.OUT_OF_REACH and cont.travel == start[0]


def test_a_step_to_the_other_side_of_a_fold_is_off_the_branch_however_near_it_lands():
    mech = compile_scene(load_scene('five_link'))
    center, rotation = mech.design_center, np.eye(3)
    # the same pose as predicted (no shift at all), det J_free of the other sign: refused
    assert kernel.on_branch(mech.equations, center, rotation, center, rotation, 1.0, 0.0, 1.0)
    assert not kernel.on_branch(mech.equations, center, rotation, center, rotation, 1.0, 0.0,
                                -1.0)
    assert not kernel.on_branch(mech.equations, center, rotation, center, rotation, 1.0, 0.0,
                                0.0)
