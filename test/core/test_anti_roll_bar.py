# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Anti-roll bars of axles: the bar's angles and twist, its ratios, its roll stiffness.

Every quantity is checked against a computation of this file's own from the vehicle file's
points and the solved wheel poses: the drop link's lower end placed by hand (on the carrier by
the pose; on an arm turned by the angle recovered from its ball joint; on a link at its
fraction), the bar's arm angle found by a generic root finder (scipy's brentq) on the drop
link's length, the ratios and the roll stiffness by central differences of those angles.
"""

import csv
import io
import math
import subprocess
import sys

from linkage_ros.core.axle import axle_of, solve_axle, wheel_travels
from linkage_ros.core.model import load_vehicle, SceneError
from linkage_ros.core.solve import sweep
from linkage_ros.tools.axle import main
import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation
import yaml

# Within the corners' travel blocks (+-80 mm) with the 4 deg of roll: s = 760 tan(4 deg) = 53 mm
HEAVE = np.array([-24.0, -10.0, 0.0, 15.0, 24.0])
ROLL = np.radians([-4.0, -1.0, 0.0, 2.5, 4.0])
H_TRAVEL = 0.01   # mm: central differences of angles held to ~1e-13 rad: error ~1e-11 rad/mm
H_TRAVEL2 = 0.5   # mm: second differences: rounding ~4e-13 rad/mm^2, O(H^2) ~1e-12
H_ROLL = 1e-3     # rad (five-point differences): the wheels move 0.76 mm
H_ROLL2 = 5e-3    # rad

CORNERS = """corners:
  fl: {scene: double_wishbone, offset: [1400, 0, 0]}
  fr: {scene: double_wishbone, offset: [1400, 0, 0], mirror: true}
  rl: {scene: five_link, offset: [-1400, 0, 0]}
  rr: {scene: five_link, offset: [-1400, 0, 0], mirror: true}
"""
# The bars of these tests (vehicle file units, mm): the demo vehicle's (on the lower arm,
# right side mirrored), one on the carriers with both sides given and not mirror images, and
# one on the five_link's lower front links (a point on a link's line).
BARS = {
    'demo_lower_arm': ('front', {
        'axis': [[1710.0, -480.0, 330.0], [1710.0, 480.0, 330.0]],
        'arm_left': [1460.0, 490.0, 330.0],
        'drop_left': {'arm': 'lower_arm', 'point': [1460.0, 500.0, 170.0]}, 'rate': 80.0}),
    'carrier_both_sides': ('front', {
        'axis': [[1600.0, 450.0, 380.0], [1590.0, -450.0, 360.0]],   # given left to right
        'arm_left': [1360.0, 600.0, 400.0], 'drop_left': {'carrier': [1370.0, 640.0, 250.0]},
        'arm_right': [1355.0, -590.0, 390.0],
        'drop_right': {'carrier': [1365.0, -630.0, 240.0]}, 'rate': 35.0}),
    'five_link_link': ('rear', {
        'axis': [[-1100.0, -500.0, 300.0], [-1100.0, 500.0, 300.0]],
        'arm_left': [-1345.0, 610.0, 310.0],
        'drop_left': {'link': 'lower_front',     # 7/9 of the way from the body end
                      'point': [-1347.222222222222, 600.0, 164.444444444444]},
        'rate': 20.0}),
}


def vehicle_file(tmp_path, axle, bar, name='car.yaml'):
    """Write a four-corner vehicle file with bar on axle (the other axle without); its path."""
    path = tmp_path / name
    axles = {'front': {'left': 'fl', 'right': 'fr'}, 'rear': {'left': 'rl', 'right': 'rr'}}
    axles[axle]['anti_roll_bar'] = bar
    path.write_text(f'name: car\nunits: mm\n{CORNERS}' + yaml.safe_dump({'axles': axles}))
    return path


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def drop_point(scene, drop, center, rotation):
    """Place the drop link's lower end (n, 3) mm at poses (n, 3), (n, 3, 3), placed by hand."""
    names = [c.name for c in scene.constraints]

    def joint(i):   # a carrier point of the constraint, moved by the pose
        return center + np.einsum('nij,j->ni', rotation, scene.constraints[i].carrier
                                  - scene.wheel_center)
    if 'carrier' in drop:
        return center + np.einsum('nij,j->ni', rotation, np.array(drop['carrier'])
                                  - scene.wheel_center)
    point = np.array(drop['point'], dtype=float)
    if 'arm' in drop:
        c = scene.constraints[names.index(drop['arm'])]
        a0, u = c.base[0], unit(c.base[1] - c.base[0])
        before = (c.carrier - a0) - ((c.carrier - a0) @ u) * u
        now = joint(names.index(drop['arm'])) - a0
        after = now - (now @ u)[:, None] * u
        angle = np.arctan2(np.cross(before, after) @ u, after @ before)
        return a0 + Rotation.from_rotvec(angle[:, None] * u).apply(point - a0)
    i = names.index(drop['link'])
    base, end = scene.constraints[i].base[0], scene.constraints[i].carrier
    fraction = np.linalg.norm(point - base) / np.linalg.norm(end - base)
    return base + fraction * (joint(i) - base)


def mirror_y(point):
    return [point[0], -point[1], point[2]]


def side_of(bar, side):
    """(arm end, drop mapping) of one side as written; the right mirrored if left out."""
    if side == 'left' or 'arm_right' in bar:
        return bar[f'arm_{side}'], bar[f'drop_{side}']
    drop = {k: mirror_y(v) if k in ('carrier', 'point') else v
            for k, v in bar['drop_left'].items()}
    return mirror_y(bar['arm_left']), drop


def arm_angles(bar, side, drop):
    """Find the arm's angles (n,) rad about the bar's axis (to the left) by brentq, drop (n, 3)."""
    a0, a1 = (np.array(p, dtype=float) for p in bar['axis'])
    u = unit(a1 - a0) * np.sign((a1 - a0)[1])
    arm, design = side_of(bar, side)
    arm = np.array(arm, dtype=float)
    design = np.array(design.get('carrier', design.get('point')), dtype=float)
    length = np.linalg.norm(arm - design)

    def end(theta):
        return a0 + Rotation.from_rotvec(np.multiply.outer(theta, u)).apply(arm - a0)

    def elbow(theta, d):   # which of the two ways the link meets the arm
        e = end(theta)
        return np.sign((e - d) @ np.cross(u, e - a0))

    grid = np.linspace(-math.pi / 2, math.pi / 2, 720)   # 0 is not a grid point
    angles = []
    for d in drop:
        f = np.sum((end(grid) - d) ** 2, axis=1) - length**2
        roots = [brentq(lambda t: np.sum((end(t) - d) ** 2) - length**2, grid[i], grid[i + 1],
                        xtol=1e-15) for i in np.flatnonzero(np.sign(f[:-1]) != np.sign(f[1:]))]
        right = [t for t in roots if elbow(t, d) == elbow(0.0, design)]
        angles.append(right[0] if len(right) == 1 else math.nan)
    return np.array(angles)


def angles_by_hand(axle, bar, travel, rack=0.0):
    """Both arms' angles (n, 2) rad at wheel travels (n, 2) mm, each corner swept by the core."""
    out = []
    for k, (scene, side) in enumerate(zip(axle.scenes, ('left', 'right'))):
        solved = sweep(scene, travel[:, k], rack=rack)
        assert solved.success
        out.append(arm_angles(bar, side, drop_point(scene, side_of(bar, side)[1],
                                                    solved.wheel_center, solved.rotation)))
    return np.column_stack(out)


@pytest.fixture(params=list(BARS))
def case(request, tmp_path):
    """(Axle with the bar, the bar's mapping as written) of each bar of BARS."""
    axle_name, bar = BARS[request.param]
    return axle_of(load_vehicle(vehicle_file(tmp_path, axle_name, bar)), axle_name), bar


def test_the_arm_angles_are_the_drop_links_length_solved_by_a_root_finder(case):
    axle, bar = case
    heave, roll = (a.ravel() for a in np.meshgrid(HEAVE, ROLL, indexing='ij'))
    rack = 8.0 if axle.steered else 0.0     # a steered corner's carrier turns under the rack
    result = solve_axle(axle, heave, roll, rack)
    assert result.success
    expected = np.concatenate([angles_by_hand(axle, bar, result.travel[i:i + 1], rack)
                               for i in range(len(heave))])
    assert np.isfinite(expected).all() and np.abs(expected).max() > 0.05   # the arms turned
    assert np.abs(result.bar.angle - expected).max() < 1e-10
    assert np.abs(result.bar.twist - (expected[:, 0] - expected[:, 1])).max() < 1e-10


def test_the_ratios_to_each_wheels_travel_are_central_differences(case):
    axle, bar = case
    travel = np.column_stack((HEAVE, HEAVE[::-1] * 0.5))
    result = solve_axle(axle, 0.5 * travel.sum(1), np.arctan(
        (travel[:, 1] - travel[:, 0]) / axle.design_track))   # the same wheel travels
    assert np.abs(result.travel - travel).max() < 1e-9
    plus, minus = (angles_by_hand(axle, bar, travel + h) for h in (H_TRAVEL, -H_TRAVEL))
    rate = (plus - minus) / (2 * H_TRAVEL)
    assert np.abs(result.bar.angle_rate - rate).max() < 1e-9
    assert np.abs(result.bar.ratio_travel - rate * [1, -1]).max() < 1e-9
    plus2, mid, minus2 = (angles_by_hand(axle, bar, travel + h)
                          for h in (H_TRAVEL2, 0.0, -H_TRAVEL2))
    rate2 = (plus2 - 2 * mid + minus2) / H_TRAVEL2**2
    assert np.abs(result.bar.angle_rate2 - rate2).max() < 1e-9


def twist_in_roll(axle, bar, heave, roll):
    """Return the twist (n,) rad at heave (mm) and roll (n,) rad, the angles by hand."""
    travel = np.column_stack(wheel_travels(axle, np.full_like(roll, heave), roll))
    angles = angles_by_hand(axle, bar, travel)
    return angles[:, 0] - angles[:, 1]


@pytest.mark.parametrize('heave', [-20.0, 0.0, 25.0])
def test_the_ratio_to_roll_and_the_roll_stiffness_are_central_differences(case, heave):
    axle, bar = case
    result = solve_axle(axle, heave, ROLL)
    # Five-point differences (error O(h^4)) of the twist and of the bar's energy
    # V = k_rad twist^2 / 2 in roll: the ratio, the roll moment dV/dphi and the roll
    # stiffness d2V/dphi2, per degree.
    twist = {j: twist_in_roll(axle, bar, heave, ROLL + j * H_ROLL) for j in (-2, -1, 1, 2)}
    ratio = (twist[-2] - 8 * twist[-1] + 8 * twist[1] - twist[2]) / (12 * H_ROLL)
    assert result.bar.ratio_roll == pytest.approx(ratio, rel=1e-9)
    k_rad = bar['rate'] * 180.0 / math.pi    # N m/rad
    energy = {j: 0.5 * k_rad * t**2 for j, t in twist.items()}
    moment = (energy[-2] - 8 * energy[-1] + 8 * energy[1] - energy[2]) / (12 * H_ROLL)
    energy = {j: 0.5 * k_rad * twist_in_roll(axle, bar, heave, ROLL + j * H_ROLL2) ** 2
              for j in (-2, -1, 0, 1, 2)}
    stiffness = (-energy[-2] + 16 * energy[-1] - 30 * energy[0] + 16 * energy[1]
                 - energy[2]) / (12 * H_ROLL2**2) * math.pi / 180.0
    assert result.bar.roll_moment == pytest.approx(moment, rel=1e-8, abs=1e-6)
    assert result.bar.roll_stiffness == pytest.approx(stiffness, rel=1e-6)
    assert result.bar.torque == pytest.approx(bar['rate'] * np.degrees(result.bar.twist))


def test_a_symmetric_bar_does_not_twist_in_heave_and_its_wheels_ratios_are_opposite():
    axle = axle_of(load_vehicle('demo_vehicle'), 'front')
    result = solve_axle(axle, np.linspace(-80.0, 80.0, 17))
    assert np.abs(result.bar.angle[:, 0]).max() > 0.15      # 8.6 deg at 80 mm
    assert np.abs(result.bar.twist).max() < 1e-12
    assert np.abs(result.bar.ratio_travel[:, 0] + result.bar.ratio_travel[:, 1]).max() < 1e-12


def test_the_right_side_left_out_is_the_left_mirrored_in_y(tmp_path):
    _, bar = BARS['demo_lower_arm']
    given = dict(bar, arm_right=[1460.0, -490.0, 330.0],
                 drop_right={'arm': 'lower_arm', 'point': [1460.0, -500.0, 170.0]})
    mirrored = axle_of(load_vehicle(vehicle_file(tmp_path, 'front', bar, 'a.yaml')), 'front')
    explicit = axle_of(load_vehicle(vehicle_file(tmp_path, 'front', given, 'b.yaml')), 'front')
    assert mirrored.anti_roll_bar.mirrored and not explicit.anti_roll_bar.mirrored
    a, b = mirrored.anti_roll_bar.right, explicit.anti_roll_bar.right
    assert (a.arm_end.tolist(), a.mount.point.tolist(), a.mount.constraint, a.link_length) == (
        b.arm_end.tolist(), b.mount.point.tolist(), b.mount.constraint, b.link_length)
    assert a.arm_end.tolist() == [1460.0, -490.0, 330.0]


def test_the_demo_vehicles_front_bar_is_in_its_vehicle_file():
    vehicle = load_vehicle('demo_vehicle')
    bar = axle_of(vehicle, 'front').anti_roll_bar
    assert bar.rate == 80.0 and bar.axis.tolist() == [0.0, 1.0, 0.0]
    assert axle_of(vehicle, 'rear').anti_roll_bar is None
    assert solve_axle(axle_of(vehicle, 'rear'), 0.0).bar is None


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, list(csv.DictReader(io.StringIO(out))), out, err


def test_linkage_axle_writes_the_bars_columns_in_deg_and_n_m(capsys):
    code, rows, _, _ = run(capsys, '--heave', '10', '--roll=-3:3:1.5')
    assert code == 0
    axle = axle_of(load_vehicle('demo_vehicle'), 'front')
    bar = solve_axle(axle, 10.0, np.radians(np.arange(-3.0, 3.1, 1.5))).bar
    expected = {
        'arb_left_angle_deg': np.degrees(bar.angle[:, 0]),
        'arb_right_angle_deg': np.degrees(bar.angle[:, 1]),
        'arb_twist_deg': np.degrees(bar.twist), 'arb_ratio_deg_per_deg_roll': bar.ratio_roll,
        'arb_ratio_left_deg_per_mm': np.degrees(bar.ratio_travel[:, 0]),
        'arb_ratio_right_deg_per_mm': np.degrees(bar.ratio_travel[:, 1]),
        'arb_torque_Nm': bar.torque, 'arb_roll_moment_Nm': bar.roll_moment,
        'arb_roll_stiffness_Nm_per_deg': bar.roll_stiffness}
    for column, values in expected.items():
        got = [float(row[column]) for row in rows]
        assert got == pytest.approx(values, rel=1e-9, abs=1e-12), column
    # Plausible for a front bar: about 3.3 deg of twist per deg of roll, 860 N m/deg (these
    # numbers pin the demo vehicle's bar: a change of its geometry shows here).
    assert float(rows[2]['arb_ratio_deg_per_deg_roll']) == pytest.approx(-3.27633, abs=1e-5)
    assert float(rows[2]['arb_roll_stiffness_Nm_per_deg']) == pytest.approx(858.748, abs=1e-3)


def test_a_bar_without_a_rate_has_no_torque_or_stiffness_columns(capsys, tmp_path):
    _, bar = BARS['demo_lower_arm']
    path = vehicle_file(tmp_path, 'front', {k: v for k, v in bar.items() if k != 'rate'})
    code, _, out, _ = run(capsys, str(path), '--heave', '0')
    assert code == 0 and out.splitlines()[0].endswith(
        'arb_twist_deg,arb_ratio_deg_per_deg_roll,arb_ratio_left_deg_per_mm,'
        'arb_ratio_right_deg_per_mm')


def test_a_drop_link_that_cannot_close_is_nan_there_with_status_1(capsys, tmp_path):
    # A 30 mm arm: the lower arm's point moves 40 mm at 80 mm of bump; the arm cannot follow.
    bar = {'axis': [[1490.0, -480.0, 330.0], [1490.0, 480.0, 330.0]],
           'arm_left': [1460.0, 490.0, 330.0],
           'drop_left': {'arm': 'lower_arm', 'point': [1460.0, 500.0, 170.0]}}
    path = vehicle_file(tmp_path, 'front', bar)
    code, rows, _, err = run(capsys, str(path), '--heave=0:80:20')
    assert code == 1
    angle = [float(row['arb_left_angle_deg']) for row in rows]
    assert abs(angle[0]) < 1e-9 and math.isnan(angle[-1])
    assert "front axle: the anti-roll bar's drop links cannot close at" in err


BAD = {
    'no such arm': ({'drop_left': {'arm': 'middle_arm', 'point': [1460.0, 500.0, 170.0]}},
                    'axles.front.anti_roll_bar.drop_left.arm',
                    "no arm (circle) named 'middle_arm' in the scene (its arms: upper_arm, "
                    'lower_arm) (the left corner, fl)'),
    'arm_right alone': ({'arm_right': [1460.0, -490.0, 330.0]},
                        'axles.front.anti_roll_bar.drop_right',
                        'missing: give arm_right and drop_right together'),
    'negative rate': ({'rate': -5.0}, 'axles.front.anti_roll_bar.rate',
                      '-5.0 N m/deg is outside 0.001 to 1e+10 N m/deg'),
    'axis along x': ({'axis': [[1710.0, 0.0, 330.0], [1500.0, 0.0, 330.0]]},
                     'axles.front.anti_roll_bar.axis', 'runs across the car'),
    'arm end on the axis': ({'arm_left': [1710.0, 490.0, 330.0]},
                            'axles.front.anti_roll_bar.arm_left', 'an arm needs a lever'),
    'dead centre': ({'arm_left': [1460.0, 490.0, 170.0]},
                    'axles.front.anti_roll_bar.drop_left', 'dead centre'),
    'off the link': ({'drop_left': {'link': 'tie_rod', 'point': [1300.0, 500.0, 260.0]}},
                     'axles.front.anti_roll_bar.drop_left.point', 'off the line of link'),

    'unknown key': ({'arm_lenght': 250}, 'axles.front.anti_roll_bar.arm_lenght',
                    'unknown key'),
}


@pytest.mark.parametrize('change', list(BAD))
def test_a_bad_bar_is_one_line_naming_the_file_and_the_key_with_status_2(
        capsys, tmp_path, change):
    values, key, says = BAD[change]
    path = vehicle_file(tmp_path, 'front', {**BARS['demo_lower_arm'][1], **values})
    with pytest.raises(SceneError) as error:
        load_vehicle(path)
    assert error.value.field == key and says in error.value.problem, error.value
    code, _, out, err = run(capsys, str(path))
    assert (code, out) == (2, '')
    assert err == f'linkage-axle: {path}: {key}: {error.value.problem}\n'


def test_a_vehicle_whose_axles_have_no_bar_imports_no_bar_code(tmp_path):
    path = tmp_path / 'car.yaml'
    path.write_text(f'name: car\n{CORNERS}axles:\n  front: {{left: fl, right: fr}}\n')
    code = ('import sys\nfrom linkage_ros.core.axle import axle_of, solve_axle\n'
            'from linkage_ros.core.model import load_vehicle\n'
            f"result = solve_axle(axle_of(load_vehicle({str(path)!r}), 'front'), 0.0)\n"
            "print(result.bar, [m for m in sys.modules if m.endswith('anti_roll_bar')])\n")
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True)
    assert (done.returncode, done.stdout) == (0, 'None []\n'), done.stderr


def test_a_mirrored_side_that_does_not_fit_its_corner_says_it_was_mirrored(tmp_path):
    path = vehicle_file(tmp_path, 'front', BARS['demo_lower_arm'][1])
    path.write_text(path.read_text().replace(   # a five_link on the right: no lower_arm
        'fr: {scene: double_wishbone', 'fr: {scene: five_link'))
    with pytest.raises(SceneError) as error:
        load_vehicle(path)
    assert error.value.field == 'axles.front.anti_roll_bar.drop_right.arm'
    assert error.value.problem == (
        "no arm (circle) named 'lower_arm' in the scene (its arms: none) (the right corner, "
        'fr; mirrored from arm_left and drop_left)')
