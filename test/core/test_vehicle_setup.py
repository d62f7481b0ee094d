# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The setup sheet's rates, roll stiffness, roll gradient and load transfer (core/vehicle).

Each checked against an independent route: the elastic energy's central differences, the
wheel load's central difference, a published worked example, and the moment balance.
"""

import csv
import math

from linkage_ros.core.axle import axle_of, solve_axle
from linkage_ros.core.measure import element_values
from linkage_ros.core.model import load_vehicle, vehicle_dir
from linkage_ros.core.vehicle import (elastic_parts, G, load_transfer, roll_gradient,
                                      roll_moment, roll_stiffness, series, setup_sheet)
import numpy as np
import pytest

VEHICLES = sorted(p.stem for p in vehicle_dir().glob('*.yaml'))
NMM_PER_RAD_TO_NM_PER_DEG = math.pi / 180.0 / 1000.0


def energy(axle, roll):
    """Return the springs' and the bar's stored work, N mm, at rolls phi (rad)."""
    result = solve_axle(axle, 0.0, roll)
    assert result.success, result.message
    return sum(p.energy for p in elastic_parts(axle, result).values())


@pytest.mark.parametrize('name', VEHICLES)
@pytest.mark.parametrize('axle_name', ['front', 'rear'])
@pytest.mark.parametrize('roll_deg', [0.0, 2.0])
def test_roll_stiffness_is_the_second_difference_of_the_elastic_energy_over_roll(
        name, axle_name, roll_deg):
    axle = axle_of(load_vehicle(name), axle_name)
    phi = math.radians(roll_deg)
    result = solve_axle(axle, 0.0, phi)
    exact = sum(roll_stiffness(p, axle.design_track, result.roll)
                for p in elastic_parts(axle, result).values())[0]

    def second_difference(h):
        v = energy(axle, phi + np.array([-h, 0.0, h]))
        return (v[0] - 2.0 * v[1] + v[2]) / h ** 2 * NMM_PER_RAD_TO_NM_PER_DEG

    # Richardson: the h^2 error term (about 1.6e-6 relative at h = 1e-3 rad) cancels; the
    # round-off of V (poses to 1e-10 mm) over h^2 stays near 1e-8 relative at h = 5e-4 rad
    estimate = (4.0 * second_difference(5e-4) - second_difference(1e-3)) / 3.0
    assert estimate == pytest.approx(exact, rel=1e-6)


@pytest.mark.parametrize('axle_name', ['front', 'rear'])
def test_roll_stiffness_is_the_derivative_of_the_roll_moment_and_that_of_the_energy(axle_name):
    axle = axle_of(load_vehicle('demo_vehicle'), axle_name)
    phi, h = math.radians(2.0), 1e-4
    result = solve_axle(axle, 0.0, phi + np.array([-h, 0.0, h]))
    parts = elastic_parts(axle, result).values()
    moment = sum(roll_moment(p, axle.design_track, result.roll) for p in parts)   # N mm
    stiffness = sum(roll_stiffness(p, axle.design_track, result.roll) for p in parts)
    energy = sum(p.energy for p in parts)
    # central differences: error h^2 / 6 of the third derivative, about 1e-9 relative here
    assert moment[1] == pytest.approx((energy[2] - energy[0]) / (2.0 * h), rel=1e-7)
    assert stiffness[1] == pytest.approx((moment[2] - moment[0]) / (2.0 * h)
                                         * NMM_PER_RAD_TO_NM_PER_DEG, rel=1e-7)


def test_the_bars_energy_hessian_gives_the_bars_own_roll_stiffness():
    axle = axle_of(load_vehicle('demo_vehicle'), 'front')
    result = solve_axle(axle, 0.0, np.radians(np.linspace(-3.0, 3.0, 7)))
    part = elastic_parts(axle, result)['bar']
    np.testing.assert_allclose(roll_stiffness(part, axle.design_track, result.roll),
                               result.bar.roll_stiffness, rtol=1e-12)


@pytest.mark.parametrize('axle_name', ['front', 'rear'])
def test_ride_rate_is_the_wheel_loads_difference_over_travel_in_series_with_the_tyre(
        axle_name):
    vehicle = load_vehicle('demo_vehicle')
    axle = axle_of(vehicle, axle_name)
    h = 1e-3
    result = solve_axle(axle, np.array([-h, h]))
    scene = axle.left
    values = element_values(scene, result.wheel_center[:, 0], result.rotation[:, 0])
    load = sum(-values.force[:, j] * values.ratio[:, j]
               for j, e in enumerate(scene.elements) if e.has_rate)   # N, virtual work
    wheel_rate = (load[1] - load[0]) / (2.0 * h)
    tyre = vehicle.mass.tyre_rate[axle_name]
    row = setup_sheet(vehicle).rows[axle_name]
    assert row['ride_rate_N_per_mm'] == pytest.approx(series(wheel_rate, tyre), rel=1e-7)
    assert row['ride_rate_N_per_mm'] == pytest.approx(wheel_rate * tyre / (wheel_rate + tyre),
                                                      rel=1e-7)


# Barton and Fieldhouse, Automotive Chassis Engineering (Springer, 2018), sec. 3.6, worked
# example p. 173-174: m_s = 1280 kg, 54 % on the front axle, roll moment arm d = 0.365 m,
# total roll stiffness k_s = 28650 N m/rad, roll centres 0.07 m (front) and 0.32 m (rear),
# tracks 1.46 m, unsprung 140 kg at 0.28 m (front) and 180 kg at 0.30 m (rear), 0.6 g.
# The book gives k_phi = 0.0194 rad/(m s^-2) = 10.9 deg/g, and the load transfers 195 N and
# 760 N (sprung, through the roll centres), 158 N and 218 N (unsprung), 1556 N and 671 N
# (through the roll stiffness) at 0.6 g; it takes g = 9.81 and 57.3 deg/rad.
BOOK_G = 9.81


def test_roll_gradient_reproduces_barton_and_fieldhouses_worked_example():
    gradient = roll_gradient(1280.0, 0.365, 28650.0, g=BOOK_G)
    assert gradient == pytest.approx(0.0194, abs=5e-5)            # the book's 3 figures
    assert gradient * 57.3 * BOOK_G == pytest.approx(10.9, abs=0.05)


def test_load_transfer_paths_reproduce_barton_and_fieldhouses_worked_example():
    accel = 0.6 * BOOK_G
    roll = roll_gradient(1280.0, 0.365, 28650.0, g=BOOK_G) * accel
    front = load_transfer(accel, 1280.0 * 0.54, 0.07, 0.0, roll, 140.0, 0.28, 1.46)
    rear = load_transfer(accel, 1280.0 * 0.46, 0.32, 0.0, roll, 180.0, 0.30, 1.46)
    assert (front.geometric, rear.geometric) == pytest.approx((195.0, 760.0), abs=1.0)
    assert (front.unsprung, rear.unsprung) == pytest.approx((158.0, 218.0), abs=1.0)
    # the book splits k_s front to rear without stating the split: their elastic sum
    elastic = load_transfer(accel, 0.0, 0.0, 28650.0, roll, 0.0, 0.0, 1.46).elastic
    assert elastic == pytest.approx(1556.0 + 671.0, rel=0.01)      # rounding of phi


def test_the_three_paths_sum_to_the_overturning_moment_over_the_tracks():
    vehicle = load_vehicle('demo_vehicle')
    sheet = setup_sheet(vehicle)
    mass, car = vehicle.mass, sheet.rows['vehicle']
    heights = mass.unsprung_cg_height
    # m a h at 1 g (N m): the sprung and the four unsprung masses at their heights
    moment = G * (mass.sprung * mass.cg_height + 2.0 * sum(
        mass.unsprung[a] * heights[a] for a in ('front', 'rear'))) / 1000.0
    roll = math.radians(car['roll_gradient_deg_per_g'])
    moment += mass.sprung * G * car['roll_moment_arm_mm'] / 1000.0 * roll   # cg shifted d phi
    paths = sum(sheet.rows[a]['track_mm'] / 1000.0 * (
        sheet.rows[a]['load_transfer_geometric_N'] + sheet.rows[a]['load_transfer_elastic_N']
        + sheet.rows[a]['load_transfer_unsprung_N']) for a in ('front', 'rear'))
    assert paths == pytest.approx(moment, rel=1e-12)
    assert car['lltd_front_pct'] == pytest.approx(100.0 * sheet.rows['front']['load_transfer_N']
                                                  / (sheet.rows['front']['load_transfer_N']
                                                     + sheet.rows['rear']['load_transfer_N']),
                                                  rel=1e-12)


def test_the_roll_axis_passes_through_both_roll_centres_under_the_cg():
    vehicle = load_vehicle('demo_vehicle')
    rows = setup_sheet(vehicle).rows
    front, rear, car = rows['front'], rows['rear'], rows['vehicle']
    share = (car['cg_x_mm'] - rear['axle_x_mm']) / (front['axle_x_mm'] - rear['axle_x_mm'])
    axis = rear['roll_centre_height_mm'] + share * (front['roll_centre_height_mm']
                                                    - rear['roll_centre_height_mm'])
    assert car['roll_axis_height_at_cg_mm'] == pytest.approx(axis, rel=1e-12)
    assert car['roll_moment_arm_mm'] == pytest.approx(car['cg_height_mm'] - axis, rel=1e-12)
    assert front['sprung_mass_kg'] == pytest.approx(0.54 * 1280.0, rel=1e-12)


def test_the_textbook_roll_stiffness_is_within_a_percent_of_the_exact_one_at_design():
    # the springs' preload term -F dMR/dz is what 0.5 k MR^2 t^2 leaves out; the bar agrees
    rows = setup_sheet(load_vehicle('demo_vehicle')).rows
    for axle in ('front', 'rear'):
        exact, book = (rows[axle][f'roll_stiffness{k}_Nm_per_deg'] for k in ('', '_textbook'))
        assert book != exact
        assert book == pytest.approx(exact, rel=0.01)


def test_the_pitch_centre_lies_on_both_axles_side_view_force_lines():
    vehicle = load_vehicle('demo_vehicle')
    sheet = setup_sheet(vehicle)
    car = sheet.rows['vehicle']
    for case in ('braking', 'drive'):
        for s in sheet.axles.values():
            patch = case == 'braking' and s.axle.brakes == 'outboard'
            point = (s.design.contact_patch if patch else s.design.wheel_center)[0, 0]
            velocity = (s.design.patch_velocity if patch else s.design.center_velocity)[0, 0]
            ground = s.design.contact_patch[0, :, 2].mean()
            centre = np.array([car[f'pitch_centre_{case}_x_mm'],
                               car[f'pitch_centre_{case}_height_mm'] + ground])
            offset = centre - point[[0, 2]]
            # square to the point's side-view velocity: the line of the force it passes
            cosine = offset @ velocity[[0, 2]] / np.linalg.norm(offset) / np.linalg.norm(
                velocity[[0, 2]])
            assert abs(cosine) < 1e-9


def test_the_pitch_gradient_under_braking_adds_springs_less_anti_and_tyres():
    vehicle = load_vehicle('demo_vehicle')
    rows = setup_sheet(vehicle).rows
    mass = vehicle.mass
    height = (mass.sprung * mass.cg_height + 2.0 * sum(
        mass.unsprung[a] * mass.unsprung_cg_height[a] for a in ('front', 'rear'))) / mass.total
    wheelbase = rows['vehicle']['wheelbase_mm']
    transfer = mass.total * G * height / wheelbase                   # N at 1 g
    anti = {'front': rows['front']['anti_dive_pct'], 'rear': rows['rear']['anti_lift_pct']}
    dive = sum(transfer * ((1.0 - anti[a] / 100.0) / (2.0 * rows[a]['wheel_rate_N_per_mm'])
                           + 1.0 / (2.0 * rows[a]['tyre_rate_N_per_mm']))
               for a in ('front', 'rear'))                            # mm
    assert rows['vehicle']['pitch_gradient_braking_deg_per_g'] == pytest.approx(
        math.degrees(dive / wheelbase), rel=1e-12)


def test_the_steering_ratio_is_the_mean_steers_slope_at_rack_0():
    vehicle = load_vehicle('demo_vehicle')
    axle = axle_of(vehicle, 'front')
    h = 0.01   # mm: the slope of the solves themselves, to h^2 (about 1e-8 relative)
    result = solve_axle(axle, 0.0, 0.0, np.array([-h, h]))
    slope = math.degrees(result.mean_steer[1] - result.mean_steer[0]) / (2.0 * h)
    # the sheet's table has 1 mm steps: its second-order difference is off by h^2 f''' / 6
    assert setup_sheet(vehicle).rows['front']['steering_ratio_deg_per_mm'] == pytest.approx(
        slope, rel=1e-4)


def test_the_pitch_gradients_follow_from_the_numbers_the_sheet_prints(tmp_path):
    # The sheet printed cg_height_mm (550, the sprung mass's) but took the whole car's
    # centre (498 mm) for the pitch gradient: it did not follow from what it printed.
    from linkage_ros.tools.vehicle import main
    path = tmp_path / 'sheet.csv'
    assert main(['demo_vehicle', '-o', str(path)]) == 0
    with open(path, newline='') as stream:
        rows = {row['axle']: row for row in csv.DictReader(stream)}

    def number(axle, column):
        return float(rows[axle][column] or 0.0)   # empty: not this axle's (no share, 0 %)
    # printed to 10 significant digits: each number to 5e-10 relative, the result to 1e-8
    car = rows['vehicle']
    wheelbase = float(car['wheelbase_mm'])
    transfer = float(car['mass_kg']) * G * float(car['cg_height_total_mm']) / wheelbase
    for case, antis, sign in (('braking', ('anti_dive_pct', 'anti_lift_pct'), 1.0),
                              ('drive', ('anti_lift_pct', 'anti_squat_pct'), -1.0)):
        pitch = sum(transfer * ((1.0 - number(a, anti) / 100.0)
                                / (2.0 * number(a, 'wheel_rate_N_per_mm'))
                                + 1.0 / (2.0 * number(a, 'tyre_rate_N_per_mm')))
                    for a, anti in zip(('front', 'rear'), antis)) / wheelbase
        assert float(car[f'pitch_gradient_{case}_deg_per_g']) == pytest.approx(
            sign * math.degrees(pitch), rel=1e-8)
    # the whole car's centre, from the printed masses (the file's unsprung heights)
    heights = load_vehicle('demo_vehicle').mass.unsprung_cg_height
    whole = (float(car['sprung_mass_kg']) * float(car['cg_height_mm']) + sum(
        number(a, 'unsprung_mass_kg') * heights[a] for a in ('front', 'rear'))) \
        / float(car['mass_kg'])
    assert float(car['cg_height_total_mm']) == pytest.approx(whole, rel=1e-9)
