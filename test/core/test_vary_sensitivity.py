# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Exact hardpoint sensitivities (linkage_ros.core.vary.sensitivity) against an independent path.

The independent path is central differences of linkage-sweep's own table (sweep + table of
tools/sweep.py) for scenes whose hardpoints are moved in the scene file's data and loaded
again (hardpoints.scene_data_with and the loader, compile_scene, the batched sweep).
Nothing of the study's equations or jets is on that path.
"""

from linkage_ros.core.base import jets
from linkage_ros.core.model import bundled_scenes, load_scene, parse_scene, with_points
from linkage_ros.core.solve import compile_scene, Continuation, kernel, sweep
from linkage_ros.core.vary import load_design, scene_data_with, sensitivities, \
    sweep_column_rates, SWEEP_COLUMNS
from linkage_ros.core.vary.outputs import quantities
from linkage_ros.tools.sweep import header, table as sweep_table
import numpy as np
import pytest

SCENES = sorted(bundled_scenes())
TRAVELS = np.array([-40.0, 0.0, 35.0])
# Central differences, 4th order at h and h/2, combined by Richardson extrapolation (6th
# order). h = 0.01 mm: truncation (h^6 times a 7th derivative) is far below the bound even
# for an instant centre 1.4 km away (chrono_bmw_e90_macpherson_front's svic_x_mm, whose
# derivative is 1.4e6 mm/mm), and rounding stays small because every sweep is solved to
# 1e-12 mm (the solves' own tolerance, not 1e-10, would otherwise dominate: 1e-10 / h).
STEP, SOLVE_TOL = 0.01, 1e-12
# The bound: 1e-6 relative or 1e-9 absolute. Relative to the quantity's gradient
# at that position (its largest derivative over all coordinates): an instant centre 1e6 mm
# away has derivatives of 1e6, and its rounding (1e-16 of 1e6 mm over h) reaches 1e-8.
RELATIVE, ABSOLUTE = 1e-6, 1e-9


def moved_table(design, values, names):
    """Return the sweep table's columns names (n, q) for the design moved to values."""
    scene = parse_scene(scene_data_with(design, values), source=design.scene.source)
    result = sweep(scene, TRAVELS, tol=SOLVE_TOL)
    assert result.success, result.message
    elements = scene if scene.elements else None
    columns = header(scene, False, elements)
    values = sweep_table(result, scene, False, elements)
    return np.stack([values[:, columns.index(n)] for n in names], axis=1)


def central_difference(design, point, axis, names, h):
    """Return the 4th-order central difference of the table columns along one coordinate."""
    moved = []
    for m in (-2, -1, 1, 2):
        values = design.values.copy()
        values[point, axis] += m * h
        moved.append(moved_table(design, values, names))
    return (moved[0] - 8 * moved[1] + 8 * moved[2] - moved[3]) / (12 * h)


@pytest.mark.parametrize('name', SCENES)
def test_sensitivities_equal_central_differences_of_sweeps_for_every_coordinate(name):
    design = load_design(name)
    exact = sensitivities(design.scene, TRAVELS)
    assert exact.success and len(exact.quantities) >= 30   # sweep, alignment (+ elements)
    scale = np.abs(exact.derivative).max(axis=(2, 3))      # (n, q)
    worst = 0.0
    for k in range(len(design.names)):
        for a in range(3):
            coarse = central_difference(design, k, a, exact.quantities, STEP)
            fine = central_difference(design, k, a, exact.quantities, STEP / 2)
            estimate = (16 * fine - coarse) / 15
            derivative = exact.derivative[:, :, k, a]
            bound = RELATIVE * np.maximum(np.abs(derivative), scale) + ABSOLUTE
            worst = max(worst, float(np.max(np.abs(estimate - derivative) / bound)))
    assert worst <= 1.0, worst


def test_the_sensitivities_cover_every_hardpoint_axis_and_quantity_of_the_table():
    design = load_design('double_wishbone')
    exact = sensitivities(design.scene, [10.0])
    assert exact.points == ('upper_arm.axis0', 'upper_arm.axis1', 'upper_arm.carrier',
                            'lower_arm.axis0', 'lower_arm.axis1', 'lower_arm.carrier',
                            'tie_rod.base', 'tie_rod.carrier', 'wheel_center',
                            'spin_axis_point')
    assert exact.derivative.shape == (1, len(exact.quantities), 10, 3)
    columns = header(design.scene, False, design.scene)
    assert set(exact.quantities) <= set(columns)
    # the element table's wheel rate needs the second-order motion: not a quantity here
    assert {'damper_length_mm', 'spring_ratio', 'spring_force_N', 'toe_deg',
            'kingpin_inclination_geometric_deg'} <= set(exact.quantities)


def test_at_design_the_carrier_follows_the_wheel_centre_and_nothing_else_moves_it():
    # Travel 0 is the design position of every variant: moving any hardpoint but the wheel
    # centre leaves the carrier where it is (R = I, M = M0), moving M0 moves it as much.
    exact = sensitivities(load_scene('five_link'), [0.0], wanted=(
        'wheel_center_x_mm', 'wheel_center_y_mm', 'wheel_center_z_mm'))
    centre = exact.points.index('wheel_center')
    d = exact.derivative[0]   # (3 quantities, k, 3 axes)
    np.testing.assert_allclose(d[:, centre, :], np.eye(3), atol=1e-12)
    others = np.delete(d, centre, axis=1)
    np.testing.assert_allclose(others, 0.0, atol=1e-12)


def test_the_compiled_table_holds_the_scenes_hardpoint_table_exactly():
    # One compile, from Scene.points by Scene.layout: the body points are copied and the
    # carrier points are one subtraction (the same IEEE operation on the same input here).
    for name in SCENES:
        scene = load_scene(name)
        points, layout, eqs = scene.points, scene.layout, compile_scene(scene).equations
        np.testing.assert_array_equal(eqs[:, kernel.BASE:kernel.BASE + 3],
                                      points[layout.base], err_msg=name)
        np.testing.assert_array_equal(eqs[:, kernel.POINT:kernel.POINT + 3],
                                      points[layout.carrier] - points[layout.center],
                                      err_msg=name)
        spheres = ~layout.line
        np.testing.assert_allclose(   # a length: a root of a sum, 1e-15 relative
            eqs[spheres, kernel.LENGTH],
            np.linalg.norm(points[layout.carrier] - points[layout.base], axis=1)[spheres],
            rtol=1e-14, err_msg=name)


def test_the_hardpoint_table_holds_the_scenes_points_by_name():
    for name in SCENES:
        scene = load_scene(name)
        row = dict(zip(scene.point_names, scene.points))
        np.testing.assert_array_equal(row['wheel_center'], scene.wheel_center)
        np.testing.assert_array_equal(row['spin_axis_point'], scene.spin_axis_point)
        for c in scene.constraints:
            np.testing.assert_array_equal(row[f'{c.name}.carrier'], c.carrier)
            ends = ('axis0', 'axis1') if c.type == 'circle' else ('base',)
            np.testing.assert_array_equal([row[f'{c.name}.{e}'] for e in ends], c.base)


@pytest.mark.parametrize('name', SCENES)
def test_a_moved_design_is_the_scene_its_moved_file_would_load(name):
    # with_points moves the Scene itself (no file); the fitted-scene route writes the moved
    # file data and loads it. Same points, spin axis, third point and element points, to
    # the rounding of a scene's metres (1e-9 mm); a static camber/toe scene re-derives its
    # spin axis point along the same axis, so the axis is compared, not the point.
    design = load_design(name)
    moved = design.values + np.random.default_rng(1).normal(0.0, 0.5, design.values.shape)
    moved[design.index('wheel_center')] = design.values[design.index('wheel_center')]
    moved[design.index('spin_axis_point')] = design.values[design.index('spin_axis_point')]
    direct = with_points(design.scene, moved)
    loaded = parse_scene(scene_data_with(design, moved), source=design.scene.source)
    np.testing.assert_allclose(direct.points[:-1], loaded.points[:-1], rtol=0, atol=1e-9)
    axes = [(s.wheel_center - s.spin_axis_point) / np.linalg.norm(
        s.wheel_center - s.spin_axis_point) for s in (direct, loaded)]
    np.testing.assert_allclose(axes[0], axes[1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(direct.third_point, loaded.third_point, rtol=0, atol=1e-9)
    assert len(direct.elements) == len(loaded.elements)
    for a, b in zip(direct.elements, loaded.elements):
        np.testing.assert_allclose(a.body, b.body, rtol=0, atol=1e-9)
        np.testing.assert_allclose(a.mount.point, b.mount.point, rtol=0, atol=1e-9)


def test_the_quantities_written_on_hardpoints_reproduce_linkage_sweeps_table():
    for name in SCENES:
        scene = load_scene(name)
        rack = 2.0 if compile_scene(scene).steered else 0.0
        result = sweep(scene, TRAVELS, rack=rack)
        elements = scene if scene.elements else None
        columns = header(scene, True, elements)
        expected = sweep_table(result, scene, True, elements)
        got = quantities(scene, scene.points, result.wheel_center, result.rotation,
                         rack)
        for quantity, values in got.items():
            reference = expected[:, columns.index(quantity)]
            np.testing.assert_allclose(values, reference, rtol=1e-12, atol=1e-12,
                                       err_msg=f'{name} {quantity}')


def test_a_jet_carries_the_derivative_of_a_linear_solve():
    # d(A^-1 b)/dp against central differences of numpy's own solve
    rng = np.random.default_rng(5)
    a0, b0 = rng.normal(size=(4, 4)) + 4 * np.eye(4), rng.normal(size=4)
    p = jets.seed(np.concatenate([a0.ravel(), b0]))
    x = jets.solve(jets.Jet(p.v[:16].reshape(4, 4), p.g[:16].reshape(4, 4, 20)), p[16:])
    h = 1e-6
    for i in range(20):
        step = np.zeros(20)
        step[i] = h
        plus, minus = p.v + step, p.v - step
        fd = (np.linalg.solve(plus[:16].reshape(4, 4), plus[16:])
              - np.linalg.solve(minus[:16].reshape(4, 4), minus[16:])) / (2 * h)
        np.testing.assert_allclose(x.g[:, i], fd, rtol=1e-7, atol=1e-9)


@pytest.mark.parametrize('name', SCENES)
def test_the_compiled_closed_forms_equal_the_jets_for_the_sweep_columns(name):
    # Two formulations of one derivative: jets carried through the equations (checked above
    # against central differences) and the closed forms of pose_kernel.py written out per
    # row. They differ only by rounding (1e-15 of derivatives of order 1 on every scene).
    scene = load_scene(name)
    jets_way = sensitivities(scene, TRAVELS, wanted=SWEEP_COLUMNS)
    assert jets_way.success, jets_way.message
    walk = Continuation(scene)
    poses = [walk.solve(float(t)) for t in TRAVELS]
    compiled = sweep_column_rates(scene, np.array([p.wheel_center for p in poses]),
                                  np.array([p.rotation for p in poses]))
    assert compiled.shape == jets_way.derivative.shape
    scale = np.abs(jets_way.derivative).max()
    np.testing.assert_allclose(compiled, jets_way.derivative, rtol=0, atol=1e-12 * scale)
