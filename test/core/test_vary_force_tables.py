# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A stop (a spring with a force table) in core/vary: its force as linkage-sweep gives it.

The corner of demo_vehicle_loads (config/vehicles/demo_vehicle_loads/front.yaml) has a bump
and a rebound stop: force tables, no rate. The study's quantities (vary.outputs) gave their
force as rate x deflection, NaN for a table; linkage-sweep (Element.spring_at) interpolates
the table. The independent path: linkage-sweep's table of the scene (tools/sweep.py), and
central differences of it for scenes moved in the file's data and loaded again.
"""

from pathlib import Path

from linkage_ros.core.model import parse_scene
from linkage_ros.core.solve import sweep
from linkage_ros.core.vary import load_design, scene_data_with, sensitivities
from linkage_ros.tools.sweep import header, table as sweep_table
import numpy as np
import pytest

FRONT = str(Path(__file__).resolve().parents[2] / 'config' / 'vehicles' / 'demo_vehicle_loads'
            / 'front.yaml')
# -72 mm: the rebound stop 12 mm into its table; 0: both stops free; 47 mm: the bump stop
# about 12 mm in. Each away from the tables' rows (5 mm apart), where the force has a kink.
TRAVELS = np.array([-72.0, 0.0, 47.0])
STOPS = ('bump_stop_force_N', 'rebound_stop_force_N')
SOLVE_TOL = 1e-12   # the sweeps' tolerance, mm (as test_vary_sensitivity)


def table_columns(scene, names):
    """Return linkage-sweep's columns names (n, q) of a scene at TRAVELS."""
    result = sweep(scene, TRAVELS, tol=SOLVE_TOL)
    assert result.success, result.message
    columns = header(scene, False, scene)
    values = sweep_table(result, scene, False, scene)
    return np.stack([values[:, columns.index(n)] for n in names], axis=1)


def test_a_stop_s_force_is_its_force_table_s_as_linkage_sweep_gives_it():
    design = load_design(FRONT)
    exact = sensitivities(design.scene, TRAVELS)
    assert exact.success and set(STOPS) <= set(exact.quantities)
    mine = exact.nominal[:, [exact.quantities.index(n) for n in STOPS]]
    sweep_values = table_columns(design.scene, STOPS)
    # engaged where the travels were chosen (the table's forces are 1e3 to 2.5e4 N)
    assert sweep_values[0, 1] < -1000.0 and sweep_values[2, 0] > 1000.0
    assert sweep_values[1, 0] == sweep_values[1, 1] == 0.0
    # the same table at the same lengths; the lengths agree to the solves' 1e-12 mm, times
    # the tables' steepest slope (2200 N/mm): 1e-8 N at most
    np.testing.assert_allclose(mine, sweep_values, rtol=0.0, atol=1e-8)


@pytest.mark.parametrize('point', ['lower_arm.carrier', 'wheel_center'])
def test_a_stop_s_force_sensitivity_is_the_central_difference_of_the_sweep_s(point):
    """
    d(stop force)/d(hardpoint) against central differences of moved scenes' sweeps.

    4th-order differences at h = 0.01 mm (truncation h^4 times a 5th derivative of a force
    linear in the lengths: below 1e-9), rounding 1e-8 N / h: 1e-6 N/mm; the bound 1e-6 of
    the largest derivative (about 1e3 N/mm) plus 1e-5 N/mm.
    """
    design = load_design(FRONT)
    exact = sensitivities(design.scene, TRAVELS)
    k = exact.points.index(point)
    q = [exact.quantities.index(n) for n in STOPS]
    h = 0.01
    for axis in range(3):
        moved = []
        for m in (-2, -1, 1, 2):
            values = design.values.copy()
            values[k, axis] += m * h
            scene = parse_scene(scene_data_with(design, values), source=design.scene.source)
            moved.append(table_columns(scene, STOPS))
        estimate = (moved[0] - 8 * moved[1] + 8 * moved[2] - moved[3]) / (12 * h)
        derivative = exact.derivative[:, q, k, axis]
        assert np.all(np.isfinite(derivative))
        bound = 1e-6 * np.abs(exact.derivative[:, q]).max() + 1e-5
        np.testing.assert_allclose(derivative, estimate, rtol=0.0, atol=bound)
