# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The robot description (URDF) of a scene or vehicle, and linkage-urdf.

Read with xml.etree (and, as a second reader, Rerun's URDF loader). The decisive check places
every drawn body by the /tf of a solved pose and finds its cylinders' ends on the solved
hardpoints: the URDF and the TF frames agree on every body.
"""

from pathlib import Path
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

from linkage_ros.answer.cdr import transforms_of
from linkage_ros.answer.frames import CornerFrames, static_cdr
from linkage_ros.answer.robot_description import robot_description, rotation_of_rpy, rpy
from linkage_ros.core.model import load_scene, load_vehicle
from linkage_ros.core.solve import Continuation
import numpy as np
import pytest

URDF = Path(sys.executable).parent / 'linkage-urdf'


def rotation(q):
    """Return the rotation matrix of a unit quaternion (x, y, z, w)."""
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def numbers(text):
    return np.array([float(v) for v in text.split()])


def cylinder_ends(robot):
    """Return {link name: [(end, end)]} of every cylinder, in m, in its link's frame."""
    ends = {}
    for link in robot.iter('link'):
        for visual in link.iter('visual'):
            cylinder = visual.find('geometry/cylinder')
            if cylinder is None:
                continue
            origin = visual.find('origin')
            center, turn = numbers(origin.get('xyz')), rotation_of_rpy(*numbers(origin.get('rpy')))
            half = turn[:, 2] * float(cylinder.get('length')) / 2
            ends.setdefault(link.get('name'), []).append((center - half, center + half))
    return ends


@pytest.mark.parametrize('scene_name', ['five_link', 'double_wishbone', 'macpherson'])
def test_a_link_per_body_each_floating_from_the_root_and_the_wheel_fixed(scene_name):
    scene = load_scene(scene_name)
    robot = ElementTree.fromstring(robot_description({'': scene}, 'base_link', scene.name))
    links = [link.get('name') for link in robot.iter('link')]
    assert links[0] == 'base_link'
    assert sorted(links[1:]) == sorted(['wheel_carrier', 'wheel',
                                        *[c.name for c in scene.constraints]])
    joints = {j.find('child').get('link'): (j.get('type'), j.find('parent').get('link'))
              for j in robot.iter('joint')}
    assert joints.pop('wheel') == ('fixed', 'wheel_carrier')
    assert set(joints.values()) == {('floating', 'base_link')}
    assert len(joints) == len(links) - 2
    (disc,) = robot.find("link[@name='wheel']").iter('cylinder')
    assert float(disc.get('radius')) == pytest.approx(scene.wheel_radius / 1000.0, abs=1e-12)


@pytest.mark.parametrize('scene_name,travel,rack', [
    ('five_link', 55.0, None), ('double_wishbone', -40.0, 15.0), ('macpherson', 30.0, -10.0)])
def test_the_bodies_placed_by_tf_at_a_pose_end_on_the_solved_hardpoints(scene_name, travel,
                                                                        rack):
    # Each link, arm and the carrier's arms are cylinders between joints: placed by the
    # frames of a solved pose, their ends must be the solved carrier joints, the body points
    # (the tie rod's moved by the rack) or the wheel centre, to 1e-9 m. A strut (a tube that
    # slides) ends at its top mount and on its line through the carrier joint.
    scene = load_scene(scene_name)
    cont = Continuation(scene)
    solution = cont.solve(travel, rack)
    assert solution.success
    frames = CornerFrames(scene)
    tf = {child: (np.array(t), rotation(q)) for _, _, child, t, q in
          transforms_of(frames.tf_cdr(solution, (0, 0)))}
    ((_, carrier, wheel, t, q),) = transforms_of(static_cdr([frames], (0, 0)))
    tf[wheel] = (tf[carrier][0] + tf[carrier][1] @ t, tf[carrier][1] @ rotation(q))
    hardpoints = [solution.wheel_center] + list(cont.joints(solution).values()) + [
        b + [0.0, solution.rack if c.steer == 'rack' else 0.0, 0.0]
        for c in scene.constraints for b in c.base]
    hardpoints = np.array(hardpoints) / 1000.0
    robot = ElementTree.fromstring(robot_description({'': scene}))
    placed = 0
    for link, ends in cylinder_ends(robot).items():
        origin, turn = tf[link]
        for end in ends:
            if link == 'strut':      # test_a_strut_is_drawn_from_its_top_mount_...
                continue
            if link == 'wheel':      # the disc: about the wheel centre, along the spin axis
                a, b = (origin + turn @ e for e in end)
                spin = solution.rotation @ (scene.wheel_center - scene.spin_axis_point)
                assert (a + b) / 2 == pytest.approx(solution.wheel_center / 1000.0, abs=1e-12)
                assert np.linalg.norm(np.cross(b - a, spin)) < 1e-12
                continue
            for point in (origin + turn @ e for e in end):
                assert np.min(np.linalg.norm(hardpoints - point, axis=1)) < 1e-9, link
                placed += 1
    assert placed >= 2 * len(scene.constraints)


def test_a_strut_is_drawn_from_its_top_mount_along_the_line_through_its_carrier_joint():
    scene = load_scene('macpherson')
    (strut,) = [c for c in scene.constraints if c.type == 'line']
    cont = Continuation(scene)
    solution = cont.solve(45.0)
    joints = dict(zip([c.name for c in scene.constraints], cont.joints(solution).values()))
    joint = joints[strut.name] / 1000.0
    tf = {child: (np.array(t), rotation(q)) for _, _, child, t, q in
          transforms_of(CornerFrames(scene).tf_cdr(solution, (0, 0)))}
    origin, turn = tf[strut.name]
    (ends,) = cylinder_ends(ElementTree.fromstring(robot_description({'': scene})))[strut.name]
    top, bottom = (origin + turn @ e for e in ends)
    assert top == pytest.approx(strut.base[0] / 1000.0, abs=1e-12)
    line = (bottom - top) / np.linalg.norm(bottom - top)
    assert np.linalg.norm(np.cross(joint - top, line)) < 1e-9


def test_a_vehicle_has_every_corner_under_its_name_and_one_root():
    vehicle = load_vehicle('demo_vehicle')
    scenes = {f'{name}/': scene for name, scene in vehicle.corners.items()}
    robot = ElementTree.fromstring(robot_description(scenes, 'chassis', vehicle.name))
    links = [link.get('name') for link in robot.iter('link')]
    assert robot.get('name') == 'demo_vehicle' and links[0] == 'chassis'
    assert len(links) == 1 + sum(2 + len(s.constraints) for s in vehicle.corners.values())
    assert {name.split('/')[0] for name in links[1:]} == set(vehicle.corners)
    assert len(set(links)) == len(links)


def test_rpy_gives_back_the_rotation_even_at_gimbal_lock():
    from scipy.spatial.transform import Rotation
    turns = list(Rotation.random(200, random_state=1).as_matrix())
    turns += [Rotation.from_euler('xyz', [0.3, s * np.pi / 2, -1.1]).as_matrix()
              for s in (1, -1)]
    for turn in turns:
        assert rotation_of_rpy(*rpy(turn)) == pytest.approx(turn, abs=1e-12)


def test_rerun_urdf_loader_reads_every_link_and_joint(tmp_path):
    # A second, independent URDF reader (Rerun's, written in Rust).
    import rerun as rr
    path = tmp_path / 'double_wishbone.urdf'
    scene = load_scene('double_wishbone')
    path.write_text(robot_description({'': scene}, 'base_link', 'double_wishbone'))
    tree = rr.urdf.UrdfTree.from_file_path(path)
    assert tree.name == 'double_wishbone' and tree.root_link().name == 'base_link'
    joints = {j.child_link: j.joint_type for j in tree.joints()}
    assert joints == {'wheel_carrier': 'floating', 'upper_arm': 'floating',
                      'lower_arm': 'floating', 'tie_rod': 'floating', 'wheel': 'fixed'}


def test_linkage_urdf_writes_what_the_node_publishes(tmp_path):
    out = tmp_path / 'demo.urdf'
    done = subprocess.run([str(URDF), 'demo_vehicle', '-o', str(out)], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    vehicle = load_vehicle('demo_vehicle')
    assert out.read_text() == robot_description(
        {f'{n}/': s for n, s in vehicle.corners.items()}, 'base_link', 'demo_vehicle')
    assert done.stderr == f'linkage-urdf: demo_vehicle: 25 links -> {out}\n'


@pytest.mark.parametrize('args,message', [
    (['no_such_scene', '-o', 'x.urdf'], 'linkage-urdf: no_such_scene: scene: no such file'),
    (['five_link', '-o', '/no/such/folder/x.urdf'],
     'linkage-urdf: -o: cannot write /no/such/folder/x.urdf: no folder /no/such/folder'),
    (['five_link'], 'linkage-urdf: error: the following arguments are required: -o'),
])
def test_a_mistake_is_one_line_and_status_2(tmp_path, args, message):
    done = subprocess.run([str(URDF), *args], capture_output=True, text=True, timeout=120,
                          cwd=tmp_path)
    assert done.returncode == 2
    assert done.stderr.startswith(message) and done.stderr.count('\n') == 1
