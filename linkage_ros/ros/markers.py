# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
visualization_msgs/MarkerArray of one solved position: links and joints, pure, no DDS.

Imported by the node only when its parameter markers is true. Two markers, in frame_id and m:

    ns 'links'  (id 0) LINE_LIST: per constraint, base -> carrier joint (sphere: link, line:
                strut), and base[0] -> joint -> base[1] for an arm (circle), as line pairs
    ns 'joints' (id 1) SPHERE_LIST: the carrier joints, in the scene's constraint order

Carrier joints are M + R (b0 - M0) (wheel centre M, rotation R relative to design, design
joint b0 and centre M0): core.base.geometry.carrier_points, drawn as
core.model.scene.link_polylines.
"""

from builtin_interfaces.msg import Time
from geometry_msgs.msg import Point
import numpy as np
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray

from ..core.base import carrier_points, M_PER_MM
from ..core.model import link_polylines

LINE_WIDTH = 0.004     # of the scene size: thin lines that stay visible at any scene scale
JOINT_SIZE = 0.015     # sphere diameter, of the scene size
LINK_COLOR = ColorRGBA(r=0.27, g=0.51, b=0.86, a=1.0)
JOINT_COLOR = ColorRGBA(r=0.86, g=0.27, b=0.27, a=1.0)


def link_segments(scene, joints):
    """
    Return line-list point pairs (k, 3) mm of the links, arms and struts for joints (m, 3) mm.

    A pair goes from each body point of a polyline (core.model.scene.link_polylines: its ends) to
    its joint (the second point).
    """
    pairs = []
    for line in link_polylines(scene, joints):
        pairs += [(base, line[1]) for base in (line[0], *line[2:])]
    return np.array(pairs).reshape(-1, 3)


def marker_array(scene, solution, stamp, frame_id):
    """Return the links and joints of a solved position as a MarkerArray (m, in frame_id)."""
    joints = carrier_points(scene.carrier_offsets, solution.wheel_center, solution.rotation)
    size = scene.size * M_PER_MM
    links = _marker('links', 0, Marker.LINE_LIST, link_segments(scene, joints), stamp,
                    frame_id, LINK_COLOR)
    links.scale.x = LINE_WIDTH * size
    spheres = _marker('joints', 1, Marker.SPHERE_LIST, joints, stamp, frame_id, JOINT_COLOR)
    spheres.scale.x = spheres.scale.y = spheres.scale.z = JOINT_SIZE * size
    return MarkerArray(markers=[links, spheres])


def markers_builder(scene, frame_id):
    """Return build(solution, stamp (sec, nanosec)) -> marker_array: the markers output."""
    def build(solution, stamp):
        return marker_array(scene, solution, Time(sec=stamp[0], nanosec=stamp[1]), frame_id)

    return build


def marker_points(marker):
    """Return a marker's points as a (k, 3) array in m, for its readers."""
    return np.array([[p.x, p.y, p.z] for p in marker.points]).reshape(-1, 3)


def _marker(ns, marker_id, kind, points_mm, stamp, frame_id, color):
    marker = Marker(ns=ns, id=marker_id, type=kind, action=Marker.ADD, color=color)
    marker.header.stamp = stamp
    marker.header.frame_id = frame_id
    marker.pose.orientation.w = 1.0
    marker.points = [Point(x=float(x), y=float(y), z=float(z))
                     for x, y, z in np.asarray(points_mm) * M_PER_MM]
    return marker
