# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The robot description (URDF) of a scene or a vehicle, for RViz, Foxglove and Rerun.

    robot_description({'': scene}, frame_id='base_link', name='five_link') -> URDF text
    robot_description({'front_left/': scene, ...}, 'base_link', 'demo_vehicle')

One URDF link per body of linkage_ros.core.measure.bodies (carrier, wheel, each link, arm and strut
of every corner), named as its TF frame, under the root link frame_id. URDF describes trees,
not the closed loops of a suspension: every body hangs from the root by a `floating` joint
(its origin the body's design frame), so that a viewer places it by the /tf the node
publishes; the wheel is `fixed` to its carrier (its transform is on /tf_static too). Simple
visual geometry in m, in each body's frame: cylinders for links, arms, struts and the
carrier's arms from the wheel centre to its joints, spheres at the joints, a wheel disc of
the scene's wheel_radius (none where the scene gives none). Sizes follow each corner's reach
(the farthest hardpoint from its wheel centre), so that any scale of mechanism is drawn alike.

ROS-free: linkage-urdf and the node write the same text.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING
import xml.etree.ElementTree as ElementTree

import numpy as np

from ..core.base import M_PER_MM
from ..core.measure import Bodies, corner_bodies, frame_along

if TYPE_CHECKING:
    from ..core.model import Scene

LINK_RADIUS = 0.018     # of the corner's reach: links, arms and the carrier's arms
JOINT_RADIUS = 0.035    # of the reach: the spheres at the joints
STRUT_RADIUS = 0.04     # of the reach
WHEEL_WIDTH = 0.6       # of the wheel radius: a disc about as wide as a road tyre
# name: rgba
MATERIALS = {'linkage_link': (0.27, 0.51, 0.86, 1.0), 'linkage_joint': (0.86, 0.27, 0.27, 1.0),
             'linkage_carrier': (0.95, 0.6, 0.1, 1.0), 'linkage_strut': (0.5, 0.5, 0.55, 1.0),
             'linkage_wheel': (0.15, 0.15, 0.15, 0.45)}


def robot_description(scenes: dict[str, Scene], frame_id: str = 'base_link',
                      name: str = 'linkage') -> str:
    """
    Return the URDF (XML text) of corners {frame prefix: Scene} under the root frame_id.

    The prefix of a node of one scene is '', of a vehicle's corner 'front_left/' (the same
    as its TF frames and topics). name: the robot's name (the scene's or the vehicle's).
    """
    robot = ElementTree.Element('robot', name=name)
    for material, rgba in MATERIALS.items():
        element = ElementTree.SubElement(robot, 'material', name=material)
        ElementTree.SubElement(element, 'color', rgba=_numbers(rgba))
    ElementTree.SubElement(robot, 'link', name=frame_id)
    for prefix, scene in scenes.items():
        _corner(robot, corner_bodies(scene, prefix, taken=(frame_id,)), frame_id)
    ElementTree.indent(robot)
    return ElementTree.tostring(robot, encoding='unicode', xml_declaration=True) + '\n'


def _corner(robot, bodies: Bodies, root: str) -> None:
    """Add one corner's bodies (links with their visuals) and joints to the robot element."""
    scene = bodies.scene
    points = [scene.spin_axis_point] + [c.carrier for c in scene.constraints] + [
        b for c in scene.constraints for b in c.base]
    reach = max(float(np.linalg.norm(p - scene.wheel_center)) for p in points) * M_PER_MM
    link_r, joint_r = LINK_RADIUS * reach, JOINT_RADIUS * reach
    for i, (body, kind) in enumerate(zip(bodies.names, bodies.kinds)):
        origin, rotation = bodies.origins[i], bodies.rotations[i]

        def local(point, origin=origin, rotation=rotation):
            return rotation.T @ ((np.asarray(point) - origin) * M_PER_MM)

        link = ElementTree.SubElement(robot, 'link', name=body)
        if kind == 'carrier':
            for c in scene.constraints:
                _cylinder(link, local(scene.wheel_center), local(c.carrier), link_r,
                          'linkage_carrier')
                _sphere(link, local(c.carrier), joint_r, 'linkage_joint')
        else:
            c = scene.constraints[i - 1]
            if kind == 'strut':
                _cylinder(link, local(c.base[0]), local(c.carrier), STRUT_RADIUS * reach,
                          'linkage_strut')
            else:
                for base in c.base:
                    _cylinder(link, local(base), local(c.carrier), link_r, 'linkage_link')
                if kind == 'arm':
                    _cylinder(link, local(c.base[0]), local(c.base[1]), link_r, 'linkage_link')
            for base in c.base:
                _sphere(link, local(base), joint_r, 'linkage_joint')
        _joint(robot, f'{body}_joint', 'floating', root, body, origin * M_PER_MM, rotation)
    wheel = ElementTree.SubElement(robot, 'link', name=bodies.wheel)
    if scene.wheel_radius > 0:
        radius = scene.wheel_radius * M_PER_MM
        _visual(wheel, np.zeros(3), np.eye(3), 'cylinder', 'linkage_wheel', radius=radius,
                length=WHEEL_WIDTH * radius)
    _joint(robot, f'{bodies.wheel}_joint', 'fixed', bodies.carrier, bodies.wheel, np.zeros(3),
           bodies.wheel_rotation)


def _joint(robot, name, kind, parent, child, xyz, rotation):
    joint = ElementTree.SubElement(robot, 'joint', name=name, type=kind)
    ElementTree.SubElement(joint, 'parent', link=parent)
    ElementTree.SubElement(joint, 'child', link=child)
    ElementTree.SubElement(joint, 'origin', xyz=_numbers(xyz), rpy=_numbers(rpy(rotation)))


def _cylinder(link, start, end, radius, material):
    """Add a cylinder from start to end (m, in the link's frame)."""
    axis = end - start
    length = float(np.linalg.norm(axis))
    if length > 0:
        _visual(link, (start + end) / 2, frame_along(axis), 'cylinder', material,
                radius=radius, length=length)


def _sphere(link, center, radius, material):
    _visual(link, center, np.eye(3), 'sphere', material, radius=radius)


def _visual(link, xyz, rotation, shape, material, **size):
    visual = ElementTree.SubElement(link, 'visual')
    ElementTree.SubElement(visual, 'origin', xyz=_numbers(xyz), rpy=_numbers(rpy(rotation)))
    geometry = ElementTree.SubElement(visual, 'geometry')
    ElementTree.SubElement(geometry, shape, **{k: _numbers([v]) for k, v in size.items()})
    ElementTree.SubElement(visual, 'material', name=material)


def rpy(rotation: np.ndarray) -> tuple[float, float, float]:
    """
    Return URDF's roll, pitch, yaw (rad) of a rotation matrix: R = Rz(yaw) Ry(pitch) Rx(roll).

    Yaw and pitch from R's first column (atan2 both: exact to rounding at any pitch), then
    roll from what is left, Ry(pitch)^T Rz(yaw)^T R = Rx(roll): at pitch +-90 deg (gimbal
    lock), where yaw and roll trade off, the roll taken is the one that goes with the yaw.
    """
    r = np.asarray(rotation, dtype=float)
    yaw = math.atan2(r[1, 0], r[0, 0])
    pitch = math.atan2(-r[2, 0], math.hypot(r[0, 0], r[1, 0]))
    rest = rotation_of_rpy(0.0, pitch, yaw).T @ r
    return math.atan2(rest[2, 1], rest[1, 1]), pitch, yaw


def rotation_of_rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Return the rotation matrix of URDF's roll, pitch, yaw (the inverse of rpy)."""
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
            @ np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
            @ np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]]))


def _numbers(values) -> str:
    """Say numbers as URDF writes them: space-separated, 12 significant digits (m: 1e-12)."""
    return ' '.join(f'{float(v):.12g}' for v in values)
