# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The alignment and marker message builders, pure: no DDS."""

from builtin_interfaces.msg import Time
from linkage_ros.core.measure import alignment
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import Continuation
from linkage_ros.ros import messages
from linkage_ros.ros.markers import marker_array, marker_points
import numpy as np
import pytest
from visualization_msgs.msg import Marker

LABELS = ['camber_gain_rad_per_m', 'bump_steer_rad_per_m', 'caster_rad',
          'kingpin_inclination_rad', 'scrub_radius_m', 'mechanical_trail_m', 'track_change_m',
          'wheelbase_change_m', 'wheel_center_lateral_shift_m',
          'wheel_center_longitudinal_shift_m', 'svic_x_m', 'svic_z_m', 'fvic_y_m', 'fvic_z_m']


@pytest.fixture(scope='module')
def steered():
    """double_wishbone solved at 25 mm bump and 8 mm rack: (continuation, solution)."""
    cont = Continuation(load_scene('double_wishbone'))
    solution = cont.solve(25.0, 8.0)
    assert solution.success
    return cont, solution


def core_alignment(cont, solution):
    return alignment(cont.scene, cont.mech, solution.wheel_center, solution.rotation,
                     solution.rack)


def test_alignment_message_names_every_field_in_si_in_a_fixed_order(steered):
    msg = messages.alignment_array(core_alignment(*steered))
    assert [d.label for d in msg.layout.dim] == LABELS
    assert len(msg.data) == len(LABELS)


def test_alignment_message_values_are_the_core_values_converted_to_si(steered):
    core = core_alignment(*steered)
    values = messages.alignment_values(messages.alignment_array(core))
    expected = [core.camber_gain[0] * 1e3, core.bump_steer[0] * 1e3, core.caster[0],
                core.kingpin_inclination[0], core.scrub_radius[0] / 1e3,
                core.mechanical_trail[0] / 1e3, core.track_change[0] / 1e3,
                core.wheelbase_change[0] / 1e3, core.lateral_shift[0] / 1e3,
                core.longitudinal_shift[0] / 1e3, core.side_view_ic[0, 0] / 1e3,
                core.side_view_ic[0, 1] / 1e3, core.front_view_ic[0, 0] / 1e3,
                core.front_view_ic[0, 1] / 1e3]
    assert [values[label] for label in LABELS] == pytest.approx(expected, rel=1e-12)
    assert np.isfinite(list(values.values())).all()


def test_alignment_message_of_a_scene_without_a_rack_link_has_no_steer_axis():
    cont = Continuation(load_scene('five_link'))
    values = messages.alignment_values(messages.alignment_array(
        core_alignment(cont, cont.solve(10.0))))
    assert np.isnan([values['caster_rad'], values['kingpin_inclination_rad']]).all()
    assert np.isfinite(values['camber_gain_rad_per_m'])


def test_marker_joints_are_the_core_joints_in_metres(steered):
    cont, solution = steered
    links, joints = marker_array(cont.scene, solution, Time(sec=3), 'chassis').markers
    assert joints.type == Marker.SPHERE_LIST and links.type == Marker.LINE_LIST
    core = np.array(list(cont.joints(solution).values())) / 1000.0
    assert marker_points(joints) == pytest.approx(core, abs=1e-12)
    assert (links.header.frame_id, links.header.stamp.sec) == ('chassis', 3)


def test_marker_links_run_from_each_base_point_to_its_joint(steered):
    cont, solution = steered
    links, _ = marker_array(cont.scene, solution, Time(), 'base_link').markers
    core = list(cont.joints(solution).values())
    expected = []
    for c, joint in zip(cont.scene.constraints, core):   # arms: both axis points
        for base in c.base:
            expected.extend((base, joint))
    assert marker_points(links) == pytest.approx(np.array(expected) / 1000.0, abs=1e-12)
