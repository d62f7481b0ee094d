# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
One roll centre: the axle table, suspension_node and the maps compute it by one formula.

The three callers (core.axle.solve_axle's table, the node's roll_centre_of_states per answer,
tools/map_grid's axle map) give the same roll centre at the same wheel travels, and no module
of the package but core/axle/roll_centre.py writes the roll-centre geometry again, nor any
but measure/alignment.patch_offset the contact patch (a second copy of a formula is a defect).
"""

import ast
from pathlib import Path

import linkage_ros
from linkage_ros.core.axle import axle_of, patch_motion, roll_centre, roll_centre_of_poses, \
    roll_centre_of_states, solve_axle
from linkage_ros.core.model import load_vehicle
from linkage_ros.core.solve import Continuation, jacobian_kernel, linearize
from linkage_ros.tools.map_grid import axle_grid_map
import numpy as np
import pytest

PACKAGE = Path(linkage_ros.__file__).parent
# Where the formulas live: every function of the roll-centre module, and the contact patch's.
HOMES = {('core/axle/roll_centre.py', None), ('core/base/patch.py', 'patch_offset')}


def test_the_axle_table_the_node_and_the_map_give_one_roll_centre_at_the_same_travels():
    axle = axle_of(load_vehicle('demo_vehicle'), 'front')
    travels = np.array([-40.0, -15.0, 0.0, 20.0, 45.0])
    grid = axle_grid_map(axle, travels)
    assert not grid.unreached
    found = {name: grid.values[:, :, grid.quantities.index(name)].ravel()
             for name in ('roll_centre_y_mm', 'roll_centre_z_mm')}
    left, right = (a.ravel() for a in np.meshgrid(travels, travels, indexing='ij'))
    table = solve_axle(axle, (left + right) / 2, np.arctan((right - left) / axle.design_track))
    assert table.success and np.allclose(table.travel, np.column_stack((left, right)),
                                         rtol=0, atol=1e-9)
    node = []
    for center, rotation in zip(table.wheel_center, table.rotation):
        jac = np.array([linearize(m, center[k][None], rotation[k][None], np.zeros(1))[1][0]
                        for k, m in enumerate(axle.mechanisms)])
        node.append(roll_centre_of_poses([s.wheel_radius for s in axle.scenes],
                                         [m.spin_axis for m in axle.mechanisms], center,
                                         rotation, jac))
    node = np.array(node)
    # Each pose is solved by its own continuation (the map per wheel, the table per axle) to
    # the Newton tolerance; what is left is round-off of mm-sized values, far below 1e-9 mm.
    for k, name in enumerate(('roll_centre_y_mm', 'roll_centre_z_mm')):
        assert found[name] == pytest.approx(table.roll_centre[:, k], rel=1e-9, abs=1e-9)
        assert node[:, 1 + k] == pytest.approx(table.roll_centre[:, k], rel=1e-9, abs=1e-9)
    assert node[:, 0] == pytest.approx(table.contact_patch[:, :, 0].mean(axis=1), abs=1e-9)
    assert np.ptp(table.roll_centre[:, 1]) > 1.0     # the travels move it: a real comparison


def _products(node):
    return isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult)


def _formulas(function):
    """Say which roll-centre or contact-patch formulas a function writes out."""
    names = {n.id for n in ast.walk(function) if isinstance(n, ast.Name)}
    names |= {a.arg for a in ast.walk(function) if isinstance(a, ast.arg)}
    found = set()
    for node in ast.walk(function):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Sub):
            # a 2 x 2 determinant or cross product (a b - c d) beside contact patches: the
            # front-view intersection, or a patch's velocity
            patches = any('patch' in n for n in names)
            if _products(node.left) and _products(node.right) and patches:
                found.add('intersection or velocity of contact patches')
            # the up direction square to a spin axis, 1 - a_z a_z or (0, 0, 1) - a_z a
            right = node.right
            if _products(right) and (
                    '0.0, 0.0, 1.0' in ast.unparse(node.left) or (
                        isinstance(node.left, ast.Constant) and node.left.value == 1
                        and ast.unparse(right.left) == ast.unparse(right.right))):
                found.add('contact patch')
        # omega x (patch - centre); a force's moment, patch x F, is another formula
        if (isinstance(node, ast.Call)
                and getattr(node.func, 'id', getattr(node.func, 'attr', '')) == 'cross'
                and len(node.args) == 2 and 'patch' in ast.unparse(node.args[1])):
            found.add("a contact patch's velocity")
    return found


def test_no_module_but_the_roll_centres_writes_a_roll_centre_or_contact_patch_formula():
    copies = []
    for path in sorted(PACKAGE.rglob('*.py')):
        module = path.relative_to(PACKAGE).as_posix()
        for function in ast.walk(ast.parse(path.read_text())):
            if not isinstance(function, ast.FunctionDef):
                continue
            if {(module, None), (module, function.name)} & HOMES:
                continue
            copies += [f'{module}:{function.lineno} {function.name}: {what}'
                       for what in sorted(_formulas(function))]
    assert copies == []


def test_the_formula_check_finds_a_second_copy():
    # The check above reads what it is meant to: the inlined formulas of before.
    source = """
def node(az, ax, ay, patch_y, vy, vz, by, bz):
    uz = 1.0 - az * az
    det = vy * bz - by * vz
def table(axis, omega, patch, center):
    up = np.array([0.0, 0.0, 1.0]) - axis[:, 2:3] * axis
    return cross(omega, patch - center)
"""
    found = [_formulas(f) for f in ast.parse(source).body]
    assert found == [{'contact patch', 'intersection or velocity of contact patches'},
                     {'contact patch', "a contact patch's velocity"}]


EPS = np.finfo(float).eps


@pytest.mark.parametrize('vehicle, axle_name', [('demo_vehicle_bushings', 'front'),
                                                ('demo_vehicle_bushings', 'rear'),
                                                ('demo_vehicle', 'front')])
def test_the_nodes_compiled_roll_centre_is_the_array_formulas_to_round_off(vehicle, axle_name):
    # suspension_node's roll centre is one compiled call on the two corners' kinematic states
    # (roll_centre_of_states); the axle table's is the numpy array path (patch_motion,
    # roll_centre). The same operations on the same poses: they differ by round-off only.
    # y = (a_r b_z - b_r a_z) / det (meet): each term carries some 16 roundings of eps
    # relative (contact patch 7, velocity 3, a_r 2, products and difference 3; a generous
    # count), so |error| <= 16 eps (|a_r b_z| + |b_r a_z| + |y| (|a_y b_z| + |b_y a_z|)) /
    # |det|; x, a mean of patch positions of mm, within 16 eps of their magnitudes.
    axle = axle_of(load_vehicle(vehicle), axle_name)
    solvers = [Continuation(scene) for scene in axle.scenes]
    radius = np.array([scene.wheel_radius for scene in axle.scenes])
    spin = np.array([m.spin_axis for m in axle.mechanisms])
    out, compared, moved = np.empty(3), 0, []
    for left, right in [(-50.0, 40.0), (-20.0, -20.0), (0.0, 0.0), (15.0, -35.0), (45.0, 45.0),
                        (30.0, 5.0)]:
        assert all(s.solve(t).success for s, t in zip(solvers, (left, right)))
        roll_centre_of_states(radius, spin, solvers[0].state, solvers[1].state, out)
        jac = np.array([s.jacobian for s in solvers])
        free = np.empty((2, 5))
        jacobian_kernel.slope_many(jac, free)       # (v_x, v_y, omega) per mm of travel
        patch, velocity = zip(*(patch_motion(
            s.center[None], (s.rotation @ m.spin_axis)[None], r,
            np.array([[free[k, 0], free[k, 1], 1.0]]), free[k, 2:][None])
            for k, (s, m, r) in enumerate(zip(solvers, axle.mechanisms, radius))))
        patch, velocity = np.stack(patch, axis=1), np.stack(velocity, axis=1)   # (1, 2, 3)
        y, z = roll_centre(patch, velocity)[0]
        (ay, az), (by, bz) = velocity[0, :, 1:]
        ar, br = (velocity[0, k, 1:] @ patch[0, k, 1:] for k in range(2))
        det = abs(ay * bz - by * az)
        scale = abs(ay * bz) + abs(by * az)
        tol_y = 16 * EPS * (abs(ar * bz) + abs(br * az) + abs(y) * scale) / det
        tol_z = 16 * EPS * (abs(ay * br) + abs(by * ar) + abs(z) * scale) / det
        assert out[1] == pytest.approx(y, rel=0, abs=tol_y)
        assert out[2] == pytest.approx(z, rel=0, abs=tol_z)
        x = patch[0, :, 0].mean()
        assert out[0] == pytest.approx(x, rel=0, abs=16 * EPS * np.abs(patch[0, :, 0]).sum())
        compared += 1
        moved.append(out[2])
    assert compared == 6 and np.ptp(moved) > 1.0      # the travels move it: a real comparison
