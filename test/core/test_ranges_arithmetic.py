# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Within the stated ranges the arithmetic stays finite (issue 36, items 2 and 11).

Numbers drawn across their whole stated ranges (doc/scenes.md#ranges), the ends included,
give: statics whose answers are finite or a status, never an exception or an overflow; a
setup sheet whose every cell is finite, but where the body falls over in roll (K <= m_s g d,
checked here from the sheet's own cells); a spring whose force and wheel rate are finite.
"""

from dataclasses import replace
import math

from hypothesis import example, given, HealthCheck, settings, strategies as st
from linkage_ros.core.base import Status
from linkage_ros.core.model import load_scene, load_vehicle
from linkage_ros.core.statics import compliance, Load, solve_loaded
import numpy as np
from test_ranges import ANGULAR, FORCE, HEIGHT, MASS, RATE, spring_with, vehicle_with

SLOW = settings(deadline=None, database=None, max_examples=25,
                suppress_health_check=[HealthCheck.too_slow])


def across(low, high):
    """Numbers across [low, high], log-uniform, the two ends often."""
    return st.sampled_from([low, high]) | st.floats(math.log10(low), math.log10(high)).map(
        lambda e: min(max(10.0 ** e, low), high))


@SLOW
@given(name=st.sampled_from(['double_wishbone_bushings', 'five_link_bushings',
                             'chrono_sedan_doublewishbone_bushings']),
       rates=st.lists(st.tuples(across(*RATE), across(*RATE), across(*ANGULAR),
                                across(*ANGULAR)), min_size=5, max_size=5))
@example(name='double_wishbone_bushings', rates=[(RATE[1], RATE[0], ANGULAR[1], ANGULAR[0])] * 5)
@example(name='five_link_bushings', rates=[(RATE[0], RATE[1], ANGULAR[0], ANGULAR[1])] * 5)
def test_statics_across_the_ranges_of_bushing_rates_is_finite_or_a_status(name, rates):
    scene = load_scene(name)
    constraints = []
    for c, (axial, radial, torsion, conical) in zip(scene.constraints, rates):
        if c.bushing is not None:
            angular = {'torsion': torsion, 'conical': conical} if c.type == 'circle' else {}
            c = replace(c, bushing=replace(c.bushing, axial=axial, radial=radial, **angular))
        constraints.append(c)
    scene = replace(scene, constraints=tuple(constraints))
    loaded = solve_loaded(scene, 0.0, Load((0.0, 4000.0, 0.0), at='cp'))
    assert loaded.status in (Status.OK, Status.NOT_CARRIED), loaded.message
    if loaded.status == Status.OK:
        assert np.isfinite([loaded.camber_deg, loaded.toe_deg, loaded.holding_force_n]).all()
        assert all(np.isfinite(f).all() for f in loaded.body_forces_n.values())
    rates_at = compliance(scene, travel_mm=0.0)
    assert rates_at.status in (Status.OK, Status.NOT_CARRIED), rates_at.message
    if rates_at.status == Status.OK:
        assert np.isfinite(list(rates_at.rates.values())).all()
        assert np.isfinite(rates_at.matrix).all()


@SLOW
@given(sprung=across(*MASS), unsprung=st.sampled_from([0.0]) | across(*MASS),
       share=across(1e-3, 1.0 - 1e-3), tyre=across(*RATE), bar=across(*ANGULAR),
       height=across(*HEIGHT))
@example(sprung=MASS[1], unsprung=MASS[1], share=1e-3, tyre=RATE[0], bar=ANGULAR[0],
         height=HEIGHT[1])
@example(sprung=MASS[0], unsprung=0.0, share=1.0 - 1e-3, tyre=RATE[1], bar=ANGULAR[1],
         height=HEIGHT[0])
def test_the_setup_sheet_across_the_ranges_is_finite_but_where_the_body_falls_over(
        sprung, unsprung, share, tyre, bar, height):
    from linkage_ros.core.vehicle import setup_sheet

    def put(data):
        data['mass'].update(sprung=sprung, front_share=share,
                            unsprung={'front': unsprung, 'rear': unsprung},
                            unsprung_cg_height={'front': height, 'rear': height})
        data['tyre_rate'] = {'front': tyre, 'rear': tyre}
        data['axles']['front']['anti_roll_bar']['rate'] = bar
        data['cg_height'] = height

    sheet = setup_sheet(load_vehicle(vehicle_with(put)))
    vehicle = sheet.rows['vehicle']
    # the body falls over where K <= m_s g d (balance.roll_gradient), K per rad
    stiffness = vehicle['roll_stiffness_Nm_per_deg'] * 180.0 / math.pi
    overturning = sprung * 9.80665 * vehicle['roll_moment_arm_mm'] / 1000.0
    falls = stiffness <= overturning * (1.0 + 1e-12)   # the sheet's own rounding either side
    undefined = {('vehicle', 'roll_gradient_deg_per_g'), ('vehicle', 'lltd_front_pct')} | {
        (axle, f'load_transfer{k}_N') for axle in ('front', 'rear') for k in ('_elastic', '')}
    for axle, row in sheet.rows.items():
        for column, value in row.items():
            if falls and (axle, column) in undefined:
                continue
            assert math.isfinite(value), (axle, column, value, falls)


@SLOW
@given(rate=across(*RATE))
@example(rate=RATE[1])
def test_a_spring_rate_across_its_range_gives_a_finite_force_and_wheel_rate(rate):
    from linkage_ros.core.measure import element_values
    from linkage_ros.core.model import parse_scene
    from linkage_ros.core.solve import sweep
    scene = parse_scene(spring_with(rate=rate), 'scene.yaml')
    result = sweep(scene, [-60.0, 0.0, 60.0])
    values = element_values(scene, result.wheel_center, result.rotation)
    spring = 1   # elements[1]; elements[0] is a damper, without a force
    assert np.isfinite(values.force[:, spring]).all()
    assert np.isfinite(values.wheel_rate[:, spring]).all()


@SLOW
@given(force=st.sampled_from([FORCE]) | across(1e-3, FORCE), run=across(FORCE / RATE[1], 1e3))
@example(force=FORCE, run=FORCE / RATE[1])   # the largest force at the steepest slope
def test_a_force_table_across_its_ranges_gives_a_finite_force_and_wheel_rate(force, run):
    from linkage_ros.core.measure import element_values
    from linkage_ros.core.model import parse_scene
    from linkage_ros.core.solve import sweep
    # from -force to +force over 2 run mm about the free length: every travel on the table
    rows = [[-run, -force], [run, force]]
    scene = parse_scene(spring_with(rate=None, force_table=rows), 'scene.yaml')
    result = sweep(scene, [-60.0, -1e-3, 0.0, 1e-3, 60.0])
    values = element_values(scene, result.wheel_center, result.rotation)
    spring = 1   # elements[1]; elements[0] is a damper, without a force
    assert np.isfinite(values.force[:, spring]).all()
    assert np.isfinite(values.wheel_rate[:, spring]).all()
    assert np.abs(values.force[:, spring]).max() <= force


def test_the_bounds_these_tests_draw_from_are_the_tables():
    from linkage_ros.core.base import RANGE
    for key, bounds in (('bushing_rate', RATE), ('bushing_angular_rate', ANGULAR),
                        ('spring_rate', RATE), ('tyre_rate', RATE), ('bar_rate', ANGULAR),
                        ('sprung_mass', MASS), ('unsprung_mass', MASS), ('height', HEIGHT)):
        assert (RANGE[key].low, RANGE[key].high) == bounds, key
    assert RANGE['force_table_force'].high == FORCE
    assert RANGE['force_table_slope'].high == RATE[1]
