# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The loaded ride height's search (core/loads/ride_height.py, doc/loads.md): it never stalls.

Where a corner's holding force has a root within its travel block, the search finds it to
the stated tolerance; where it has none, the corner is OUT_OF_REACH at the block's end with
its holding force still pushing beyond it. The loads are the built-in cases on
demo_vehicle_loads at a fraction of their load, as linkage-bench loads scales them
(bench/loads.scaled_case). Each holding force found is checked by solving the corner afresh
(solve_corner: a Statics of its own, from the kinematic pose) at the travel and load found.
"""

from linkage_ros.bench.loads import scaled_case
from linkage_ros.core.base import Status
from linkage_ros.core.loads import built_in_cases, Loads
from linkage_ros.core.loads.corner import solve_corner
from linkage_ros.core.loads.ride_height import TOLERANCE_N
from linkage_ros.core.model import load_vehicle
import numpy as np
import pytest

VEHICLE = 'demo_vehicle_loads'
# An afresh solve reaches the same equilibrium by another path (from the kinematic pose, the
# load in increments): its equilibrium converged to a step of 1e-11 mm at the stiffest
# bushing's 1e4 N/mm leaves about 1e-7 N in the holding force (ride_height.TOLERANCE_N's
# reasoning), so the two agree to the tolerance plus that noise.
AFRESH_N = TOLERANCE_N + 5e-7


@pytest.fixture(scope='module')
def loads():
    """Return the Loads of demo_vehicle_loads (its corners' Statics made once, reused)."""
    return Loads(load_vehicle(VEHICLE))


def assert_solved(answer):
    """Assert every corner of a CaseAnswer is OK, holding nothing, also when solved afresh."""
    for name, corner in answer.corners.items():
        assert corner.status == Status.OK, (answer.case.name, name, corner.message)
        assert abs(corner.loaded.holding_force_n) <= TOLERANCE_N, (name, corner.loaded)
        afresh = solve_corner(corner.scene, corner.travel_mm, corner.load)
        assert afresh.status == Status.OK, (name, afresh.message)
        assert abs(afresh.holding_force_n) <= AFRESH_N, (name, afresh.holding_force_n)


@pytest.mark.parametrize('level', [84, 85, 86, 87])
def test_the_pothole_near_its_full_load_closes_the_front_stop_and_is_solved(loads, level):
    """
    Solve the pothole at 0.932 to 0.945 of its load: the front left closes its bump stop.

    The levels are linkage-bench loads' 100x ones (np.linspace(0.55, 1, 100)[84:88]), where
    the front axle's search (Broyden's method alone) stalled at the stop's kink, with 22 to
    65 N left to hold (issue 39 item 3); the front left's travel is about 65 mm, where its
    bump stop's force table closes.
    """
    f = np.linspace(0.55, 1.0, 100)[level]
    assert_solved(loads.solve(scaled_case(built_in_cases()['pothole'], f)))
