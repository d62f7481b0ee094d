# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Load cases on a vehicle (core/loads, doc/loads.md): the checks of issue 39.

The seven built-in cases on demo_vehicle_loads, each checked against an independent route:
the vehicle's equilibrium (its masses from the vehicle file), m a h / L and the setup sheet's
lateral paths, each corner's own statics solved afresh, the holding force, the virtual work
of kinematic solves, the bar's energy.
"""

from dataclasses import replace
import math

from linkage_ros.core.base import LinkageError, Status
from linkage_ros.core.loads import built_in_cases, LoadCase, Loads, tables
from linkage_ros.core.loads.bar import bar_state, DROP_LINK
from linkage_ros.core.loads.corner import corner_load, CornerStatics, kinematic_pose, \
    solve_corner
from linkage_ros.core.loads.transfer import ground_moment
from linkage_ros.core.measure import element_values
from linkage_ros.core.model import link_fraction, load_vehicle
from linkage_ros.core.solve import Continuation
from linkage_ros.core.solve.kernel import LENGTH
from linkage_ros.core.solve.mechanism import compile_scene, COMPILED
from linkage_ros.core.statics import Load, solve_loaded
from linkage_ros.core.vehicle import G
import numpy as np
import pytest

VEHICLE = 'demo_vehicle_loads'
CASES = list(built_in_cases())


@pytest.fixture(scope='module')
def solved():
    """Solve the seven built-in cases on demo_vehicle_loads: (Loads, {case: CaseAnswer})."""
    loads = Loads(load_vehicle(VEHICLE))
    return loads, {name: loads.solve(case) for name, case in built_in_cases().items()}


def masses(vehicle, sheet):
    """Return (m kg, centre (3,) mm above the ground, sprung kg) from the vehicle file."""
    mass = vehicle.mass
    x = {a: sheet.rows[a]['axle_x_mm'] for a in ('front', 'rear')}
    heights = {a: mass.unsprung_cg_height[a] for a in ('front', 'rear')}
    total = mass.sprung + 2 * (mass.unsprung['front'] + mass.unsprung['rear'])
    moment = np.array([mass.sprung * mass.cg_x, 0.0, mass.sprung * mass.cg_height])
    for a in ('front', 'rear'):
        moment += 2 * mass.unsprung[a] * np.array([x[a], 0.0, heights[a]])
    return total, moment / total, mass.sprung


@pytest.mark.parametrize('name', CASES)
def test_the_four_tyre_wrenches_balance_the_body_in_every_case(solved, name):
    """
    Balance the body's weight and accelerations, in forces and in moments about its centre.

    Forces: the tyres carry m g (a_x, a_y, vertical_g); moments about the centre of every
    mass: zero, but for the sprung centre's shift in roll, the one term of the sheet's
    lateral transfer that is not m a h (doc/vehicle.md). The masses are the vehicle file's;
    the tyre loads act at the design contact patches (ground z as the sheet takes it). The
    case's own corner loads (the pothole) replace what the body's accelerations give: the
    balance is of the latter, and the former differ from them at those corners only.
    To 1e-9 of m g times the wheelbase: a sum of eight products of numbers near 1e4 N and
    1e3 mm, each to 1e-16, is exact to about 1e-12 of it.
    """
    loads, answers = solved
    answer, data = answers[name], loads.data
    mass, centre, sprung = masses(loads.vehicle, data.sheet)
    case = answer.case
    accel = mass * G * np.array(case.accelerations_g)
    force, moment = np.zeros(3), np.zeros(3)
    for corner, tyre in answer.tyres.derived.items():
        patch = data.patches[corner] - np.array([0.0, 0.0, data.ground_z_mm])
        force += tyre.force_n
        moment += np.cross(patch - centre, tyre.force_n) + 1000.0 * ground_moment(
            tyre, data.centres[corner], data.patches[corner])
    shift = sprung * np.cross(answer.tyres.body_shift_mm, G * np.array(case.accelerations_g))
    scale = mass * G
    assert np.abs(force - accel).max() <= 1e-9 * scale
    assert np.abs(moment - shift).max() <= 1e-9 * scale * data.wheelbase_mm
    given = {loads.corner_keys(case)[k] for k in case.corners}
    for corner, tyre in answer.tyres.corners.items():
        same = tyre is answer.tyres.derived[corner]
        assert same == (corner not in given)


def test_the_pothole_gives_the_front_left_three_times_its_static_load_and_a_rearward_one(
        solved):
    loads, answers = solved
    static, pothole = answers['static'].tyres.corners, answers['pothole'].tyres.corners
    wheel = static['front_left'].force_n[2]
    assert pothole['front_left'].force_n == pytest.approx([-wheel, 0.0, 3.0 * wheel],
                                                          rel=1e-15)
    assert pothole['front_left'].centre_n == pytest.approx([-wheel, 0.0, 0.0], rel=1e-15)
    for corner in ('front_right', 'rear_left', 'rear_right'):
        assert np.array_equal(pothole[corner].force_n, static[corner].force_n)


@pytest.mark.parametrize('name', ['braking', 'traction', 'combined'])
def test_the_longitudinal_transfer_is_m_a_h_over_l(solved, name):
    """Each axle's vertical load less its static share is -+ m g a_x h / L (Gillespie ch. 2)."""
    loads, answers = solved
    answer = answers[name]
    mass, centre, _ = masses(loads.vehicle, loads.data.sheet)
    wheelbase = loads.data.sheet.rows['vehicle']['wheelbase_mm']
    ax = answer.case.longitudinal_g
    moved = mass * G * ax * centre[2] / wheelbase
    x = {a: loads.data.sheet.rows[a]['axle_x_mm'] for a in ('front', 'rear')}
    static = {'front': mass * G * (centre[0] - x['rear']) / wheelbase,
              'rear': mass * G * (x['front'] - centre[0]) / wheelbase}
    vertical = answer.tyres.axle_vertical_n
    assert vertical['front'] == pytest.approx(static['front'] - moved, rel=1e-9)
    assert vertical['rear'] == pytest.approx(static['rear'] + moved, rel=1e-9)
    assert answer.tyres.longitudinal_transfer_n == pytest.approx(moved, rel=1e-9)


@pytest.mark.parametrize('name', ['cornering', 'combined'])
def test_the_lateral_transfer_is_the_sheets_three_paths(solved, name):
    """At vertical_g 1 the paths are the sheet's at 1 g times lateral_g (doc/vehicle.md)."""
    loads, answers = solved
    answer = answers[name]
    ay = answer.case.lateral_g
    for axle, spec in loads.data.axles.items():
        row = loads.data.sheet.rows[axle]
        got = answer.tyres.lateral[axle]
        for path in ('geometric', 'elastic', 'unsprung'):
            assert getattr(got, path) == pytest.approx(ay * row[f'load_transfer_{path}_N'],
                                                       rel=1e-9)
        left, right = (answer.tyres.corners[c].force_n[2] for c in spec.corners)
        assert right - left == pytest.approx(2.0 * ay * row['load_transfer_N'], rel=1e-9)


def balance_of(answer):
    """Return (net force, net moment about the wheel centre, scale N) of a corner's pickups."""
    loaded, load = answer.loaded, answer.load
    centre = loaded.wheel_center_mm
    body = sum(loaded.body_forces_n.values())
    moment = sum(np.cross(loaded.body_points_mm[k] - centre, f) / 1000.0
                 + loaded.body_moments_nm.get(k, 0.0) for k, f in loaded.body_forces_n.items())
    force = np.array(load.force_n) + [0.0, 0.0, loaded.holding_force_n]
    applied = np.cross(loaded.load_point_mm - centre, load.force_n) / 1000.0 + load.moment_nm
    return body - force, moment - applied, max(1.0, float(np.abs(force).max()))


@pytest.mark.parametrize('name', CASES)
def test_every_corners_pickups_balance_its_tyre_load_and_hold_nothing(solved, name):
    """
    Balance each corner's load by its pickups, the holding force zero.

    The body's pickups (the bar's drop link among them) carry the corner's load: its tyre
    wrench and its unsprung mass's, as the statics took them, in force and moment; the
    holding force, left to a rig, is zero at the loaded ride height (to 1e-6 N).
    To 1e-9 of the load, beside the equilibrium's own residual (Loaded.residual, N: the
    largest unbalanced generalized force, moments over the lever; up to 5e-5 N where a stop
    has just closed, which the moment balance shows, times a lever below 1 m).
    """
    _, answers = solved
    for corner, answer in answers[name].corners.items():
        assert answer.status == Status.OK, answer.message
        assert abs(answer.loaded.holding_force_n) <= 1e-6, corner
        net_f, net_m, scale = balance_of(answer)
        left = answer.loaded.residual
        assert np.abs(net_f).max() <= 1e-9 * scale + left, (corner, net_f)
        assert np.abs(net_m).max() <= (1e-9 * scale + left) * 1.0, (corner, net_m)   # N m
        # the carrier's side: the members' forces on it balance the load too
        carrier = sum(answer.loaded.ball_joint_forces_n.values())
        load = np.array(answer.load.force_n) + [0.0, 0.0, answer.loaded.holding_force_n]
        assert np.abs(carrier + load).max() <= 1e-9 * scale


def close(a, b, scale):
    """Assert a == b to 1e-9 relative, 1e-9 of scale where near zero."""
    assert np.allclose(a, b, rtol=1e-9, atol=1e-9 * scale), (a, b)


def test_each_corner_s_statics_is_made_once_and_serves_every_case(solved):
    """One CornerStatics per corner, kept by the Loads, made at the first case's first solve."""
    loads, _ = solved
    kept = dict(loads.statics)
    assert sorted(kept) == sorted(loads.vehicle.corners)
    loads.solve(built_in_cases()['braking'])
    assert all(loads.statics[c] is kept[c] for c in kept)


def test_a_drop_link_written_in_place_is_the_scene_with_that_drop_link():
    """
    Solve a barred corner for drop links that change between solves: as each one's own scene.

    CornerStatics writes the drop link's end E and force into one Statics' arrays; each
    answer equals solve_corner on the scene with that drop link (bar.drop_element), solved
    alone, to 1e-9 relative (both converge to 1e-11 mm: 1e-7 N at 1e4 N/mm). Ends 20 mm
    apart and forces of both signs, so that a stale E or force would show.
    """
    vehicle = load_vehicle(VEHICLE)
    scene = vehicle.corners['front_left']
    side = vehicle.axles.axles['front'].anti_roll_bar.sides[0]
    statics = CornerStatics(scene, side)
    load = Load((0.0, 2000.0, 4000.0), 'cp', (0.0, 0.0, 0.0))
    for travel, shift, tension in ((0.0, 0.0, 800.0), (10.0, 20.0, -1500.0),
                                   (-5.0, -20.0, 300.0)):
        end = side.arm_end + np.array([0.0, 0.0, shift])
        got = statics.solve(travel, load, end, tension)
        alone = solve_corner(statics.with_drop(end, tension), travel, load)
        assert got.status == alone.status == Status.OK
        assert alone.spring_forces_n[DROP_LINK] == pytest.approx(-tension, rel=1e-12)
        scale = max(abs(f) for f in load.force_n)
        close(got.wheel_center_mm, alone.wheel_center_mm, 1000.0)
        close(got.holding_force_n, alone.holding_force_n, scale)
        for key, force in alone.body_forces_n.items():
            close(got.body_forces_n[key], force, scale)


@pytest.mark.parametrize('name', CASES)
def test_each_corner_is_its_statics_solved_afresh_at_the_travel_found(solved, name):
    """
    Solve each corner afresh at the travel found: the same answer.

    A new copy of the corner (no kept equilibrium to start from) solved at the travel found
    with the load it was given gives the same answer: every force to 1e-9 relative (the
    equilibria converge to steps of 1e-11 mm: 1e-7 N at 1e4 N/mm, below 1e-9 of 1e4 N).
    """
    _, answers = solved
    for corner, answer in answers[name].corners.items():
        fresh = solve_loaded(replace(answer.scene), answer.travel_mm, answer.load)
        got, scale = answer.loaded, max(abs(f) for f in answer.load.force_n)
        assert fresh.status == Status.OK
        close([fresh.camber_deg, fresh.toe_deg], [got.camber_deg, got.toe_deg], 1.0)
        close(fresh.wheel_center_mm, got.wheel_center_mm, 1000.0)
        close(fresh.holding_force_n, got.holding_force_n, scale)
        for field in ('link_forces_n', 'spring_forces_n', 'body_forces_n',
                      'ball_joint_forces_n', 'body_moments_nm'):
            a, b = getattr(fresh, field), getattr(got, field)
            assert a.keys() == b.keys()
            for key in a:
                close(a[key], b[key], scale)


def test_the_3g_bump_closes_every_bump_stop_and_says_so(solved):
    """The springs alone would need more travel; the stops carry the rest, and a note says."""
    _, answers = solved
    bump, static = answers['bump'], answers['static']
    notes = tables.case_notes(bump)
    for corner, answer in bump.corners.items():
        stop = answer.loaded.spring_forces_n['bump_stop']
        assert stop > 0.0 and static.corners[corner].loaded.spring_forces_n['bump_stop'] == 0.0
        assert any(n.startswith(f'bump: {corner}: bump_stop closed at travel') and
                   f'carrying {stop:.0f} N' in n for n in notes), notes
    assert not tables.case_notes(static)


def test_without_stops_the_3g_bump_is_out_of_reach_at_the_travel_limit():
    vehicle = load_vehicle(VEHICLE)
    corners = {name: replace(scene, elements=tuple(e for e in scene.elements if not e.is_stop))
               for name, scene in vehicle.corners.items()}
    answer = Loads(replace(vehicle, corners=corners)).solve(built_in_cases()['bump'])
    for corner in ('front_left', 'rear_left'):
        got = answer.corners[corner]
        assert got.status == Status.OUT_OF_REACH
        assert 'reaches its upper travel limit (80 mm)' in got.message
        assert 'cannot carry the load within its travel' in got.message


def test_the_drop_links_do_the_work_of_the_bars_energy(solved):
    """
    Do by each drop link what the bar's energy loses, per mm of its corner's travel.

    Each drop link's force on its corner, along the link at its lower end D, does per mm of
    that corner's travel what the bar's energy k twist^2 / 2 loses: -dV/dz (central
    differences of the twist and of D over +-1e-3 mm of kinematic solves: the h^2 error,
    1e-7 of the rates, and the poses' 1e-11 mm over 2e-3 mm stay below 1e-6 relative).
    """
    loads, answers = solved
    axle, bar = loads.axles['front'], loads.data.axles['front'].bar
    travels = [answers['cornering'].corners[c].travel_mm for c in ('front_left', 'front_right')]
    kin = [Continuation(s) for s in axle.scenes]

    def state(z):
        poses = [kinematic_pose(s, k.solve(t)) for s, k, t in zip(axle.scenes, kin, z)]
        return bar_state(axle, bar, np.array([p.centre for p in poses]),
                         np.array([p.rotation for p in poses]))

    here, h = state(travels), 1e-3
    k = bar.rate * 180.0 / math.pi * 1000.0   # N mm/rad
    for side in (0, 1):
        step = np.eye(2)[side] * h
        up, down = state(travels + step), state(travels - step)
        d_energy = 0.5 * k * (up.twist_rad ** 2 - down.twist_rad ** 2) / (2 * h)   # N
        d_drop = (up.drops[side] - down.drops[side]) / (2 * h)
        pull = here.ends[side] - here.drops[side]   # tension pulls D towards E
        work = here.tension_n[side] * pull @ d_drop / np.linalg.norm(pull)
        assert work == pytest.approx(-d_energy, rel=1e-6)


def rigid(vehicle):
    """Return the vehicle with every bushing taken out of its corners."""
    corners = {n: replace(s, constraints=tuple(replace(c, bushing=None) for c in s.constraints))
               for n, s in vehicle.corners.items()}
    return replace(vehicle, corners=corners)


def with_length(scene, row, delta):
    """Return a copy of scene whose kinematic equation row is delta mm longer."""
    mech = compile_scene(scene)
    equations = mech.equations.copy()
    equations[row, LENGTH] += delta
    copy = replace(scene)
    copy.__dict__[COMPILED] = replace(mech, equations=equations)
    return copy


def potential(scene, travel, load, x0, reference):
    """
    Return -(the load's work) + the springs' energy, N mm, at the kinematic pose at travel.

    The load's point x0 is carrier-fixed (its design-frame position) and its couple works
    through the carrier's turn from reference (the unperturbed pose: centre, rotation).
    """
    solution = Continuation(scene).solve(travel)
    assert solution.success
    centre, rotation = np.array(solution.wheel_center), np.array(solution.rotation)
    mech = compile_scene(scene)
    point = centre + rotation @ (x0 - mech.design_center)
    turn = rotation @ reference[1].T
    angle = np.arccos(np.clip((np.trace(turn) - 1.0) / 2.0, -1.0, 1.0))
    axis = np.array([turn[2, 1] - turn[1, 2], turn[0, 2] - turn[2, 0], turn[1, 0] - turn[0, 1]])
    theta = axis * (angle / (2.0 * np.sin(angle))) if angle > 1e-300 else 0.5 * axis
    work = np.array(load.force_n) @ (point - reference[2]) + 1000.0 * np.array(
        load.moment_nm) @ theta
    values = element_values(scene, centre[None], rotation[None])
    energy = sum(e.spring_at(float(values.length[0, j]))[2]
                 for j, e in enumerate(scene.elements) if e.has_rate)
    return energy - work


@pytest.mark.parametrize('corner', ['front_left', 'rear_left'])
def test_a_rigid_corners_link_forces_are_the_virtual_work_of_kinematic_solves(corner):
    """
    Give a rigid corner's link and joint forces as the virtual work of kinematic solves.

    Without bushings, each kinematic equation's force (a link's tension, an arm's two
    pivot-to-ball rows) is minus the derivative of the potential -(load's work) + springs'
    energy with respect to that row's length, the travel held: central differences of
    kinematic solves with the length +-1e-3 mm. Error: h^2 / 6 of the third derivative (about
    F / l^2, 0.1 N/mm^2) is 1e-8 N; the potential, taken from the unperturbed pose, is exact
    to about 1e-9 N mm (the poses' 1e-12 mm x 1e4 N), 1e-6 N over 2h: 1e-9 of 1e3 N. Then
    a link's force on the body at its base is that tension along it, and each carrier joint's
    force is the sum of its rows' (checked to 1e-6 relative).
    """
    loads = Loads(rigid(load_vehicle(VEHICLE)))
    answer = loads.solve(built_in_cases()['combined']).corners[corner]
    assert answer.status == Status.OK
    scene, loaded, load = answer.scene, answer.loaded, answer.load
    mech = compile_scene(scene)
    x0 = mech.design_center + answer.loaded.rotation.T @ (loaded.load_point_mm
                                                          - loaded.wheel_center_mm)
    reference = (loaded.wheel_center_mm, loaded.rotation, loaded.load_point_mm)
    h = 1e-3
    rows = {}
    for row in range(5):
        up, down = (potential(with_length(scene, row, s * h), answer.travel_mm, load, x0,
                              reference) for s in (1.0, -1.0))
        rows[row] = -(up - down) / (2 * h)   # + = tension
    scale = max(abs(f) for f in load.force_n)
    carrier = {}
    for row, point in enumerate(mech.equation_point):
        con = scene.constraints[int(point)]
        joint = loaded.wheel_center_mm + loaded.rotation @ (con.carrier - mech.design_center)
        base = mech.equations[row, 4:7]
        pull = (base - joint) / np.linalg.norm(base - joint)   # tension pulls to the base
        carrier[con.name] = carrier.get(con.name, 0.0) + rows[row] * pull
        carried = [link_fraction(e, scene.constraints) for e in scene.elements
                   if e.mount.kind == 'link' and e.mount.constraint == int(point)
                   and e.has_rate]
        if con.type == 'sphere' and carried:
            # a link that carries springs or stops at P, a fraction t from its body end B:
            # the segment B-P holds the body end's tension, P-C the carrier end's, and a
            # row length change dl stretches them by t dl and (1 - t) dl
            t = carried[0]
            assert all(f == t for f in carried)   # one point on the link here
            forces = loaded.link_forces_n
            both = (t * forces[f'{con.name}_body_end']
                    + (1 - t) * forces[f'{con.name}_carrier_end'])
            assert both == pytest.approx(rows[row], rel=1e-6, abs=1e-6 * scale)
        elif con.type == 'sphere':
            assert loaded.link_forces_n[con.name] == pytest.approx(rows[row], rel=1e-6,
                                                                   abs=1e-6 * scale)
            assert loaded.body_forces_n[f'{con.name}_base'] == pytest.approx(
                -rows[row] * pull, rel=1e-6, abs=1e-6 * scale)
    for name, force in carrier.items():
        # a member that carries a spring, a stop or a drop link passes part of it to the
        # carrier beside its rows' forces (the statics' split, doc/kc.md): not a row's alone
        own = [e for e in scene.elements if e.mount.kind in ('link', 'arm')
               and scene.constraints[e.mount.constraint].name == name]
        if not own:
            assert loaded.ball_joint_forces_n[name] == pytest.approx(force, rel=1e-6,
                                                                     abs=1e-6 * scale)


def test_braking_needs_shares_that_sum_to_one(tmp_path):
    vehicle = load_vehicle(VEHICLE)
    axles = vehicle.axles
    front = replace(axles.axles['front'], brake_share=0.5)
    odd = replace(vehicle, axles=replace(axles, axles={**axles.axles, 'front': front}))
    loads = Loads(odd)
    with pytest.raises(LinkageError, match=r'brake_share: a case with longitudinal_g -1 needs '
                       r'brake shares that sum to 1 \(front 0.5 \+ rear 0.4 = 0.9\)'):
        loads.solve(built_in_cases()['braking'])
    assert loads.solve(built_in_cases()['traction']).status == Status.OK


def test_a_wheel_that_lifts_off_leaves_its_axle_unsolved_and_says_so():
    """demo_vehicle's front carries 76 % of the transfer: its inner wheel lifts at 1 g."""
    loads = Loads(load_vehicle('demo_vehicle'))
    answer = loads.solve(LoadCase('turn', lateral_g=1.0))
    front = answer.corners['front_left']
    assert front.status == Status.NOT_CARRIED and front.loaded is None
    assert front.tyre.force_n[2] < 0
    assert 'a wheel lifts off' in front.message and 'front_left (-15.9' in front.message
    assert answer.corners['front_right'].status == Status.NOT_CARRIED


def test_the_corner_load_moves_the_longitudinal_force_of_a_shaft_to_the_wheel_centre(solved):
    """Traction (a driven rear axle): force at the patch plus the couple (wc - cp) x F_x."""
    _, answers = solved
    answer = answers['traction'].corners['rear_left']
    tyre, pose = answer.tyre, answer.pose
    assert tyre.shaft and tyre.centre_n[0] == tyre.force_n[0] > 0
    load = corner_load(tyre, pose, 0.0)
    centre_only = np.cross(pose.centre - pose.patch, tyre.centre_n) / 1000.0
    unsprung = np.cross(pose.centre - pose.patch, tyre.unsprung_n) / 1000.0
    assert np.allclose(load.moment_nm, centre_only + unsprung, rtol=1e-14, atol=1e-9)
    assert load.at == 'cp'
    assert ground_moment(tyre, pose.centre, pose.patch) == pytest.approx([0.0, 0.0, 0.0])


def test_the_tables_name_only_registry_quantities(solved):
    from linkage_ros.core.measure import quantities
    for columns in tables.TABLES.values():
        assert [c for c in columns if not quantities.known(c)] == []
    _, answers = solved
    rows = tables.pickup_rows(answers['cornering'])
    ends = {(r[1], r[2], r[3]) for r in rows}
    assert ('front_left', 'lower_arm_axis0', 'body') in ends
    assert ('front_left', 'lower_arm_carrier', 'carrier') in ends
    assert ('front_left', DROP_LINK, 'bar') in ends
    assert ('front', 'arb_axis1', 'body') in ends
    assert ('rear_right', 'tie_rod_base', 'body') in ends
