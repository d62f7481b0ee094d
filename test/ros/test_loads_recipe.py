# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A load case answered by suspension_node, as doc/loads.md's recipe asks it ('In ROS').

The core solves the case (core/loads); each corner's travel and load go to the node's
<corner>/solve service over real DDS, from another process: a rear corner (no anti-roll bar)
comes back as the core's loaded answer, to the equilibria's tolerance; a front corner (whose
bar's drop link the node's corner does not carry) is answered, its pose the corner's without
the bar at that travel.
"""

import math

from geometry_msgs.msg import Vector3, Wrench
from linkage_ros.core.base import Status
from linkage_ros.core.loads import built_in_cases, Loads
from linkage_ros.core.model import load_vehicle
from linkage_ros.core.statics import solve_loaded
from linkage_ros.ros import solve_service
from linkage_ros.ros.testing import spin_until
import pytest

Solve = solve_service.solve_type()
needs_interfaces = pytest.mark.skipif(Solve is None, reason=(
    'linkage_ros_interfaces is not built here (linkage-tf2-msgs builds it where a C/C++ '
    'compiler and the Python headers are)'))
WAIT = 60.0


def request(name, corner):
    """Return the Solve request of a corner's travel and load (SI), as doc/loads.md's."""
    force, moment = corner.load.force_n, corner.load.moment_nm
    wrench = Wrench(force=Vector3(x=force[0], y=force[1], z=force[2]),
                    torque=Vector3(x=moment[0], y=moment[1], z=moment[2]))
    return Solve.Request(corner=name, travel=corner.travel_mm / 1000.0, use_wrench=True,
                         wrench=wrench)


@needs_interfaces
def test_a_load_case_is_answered_by_the_nodes_corners_as_the_core_solves_it(
        node_process, localhost_context, localhost_executor):
    import rclpy
    answer = Loads(load_vehicle('demo_vehicle_loads')).solve(built_in_cases()['braking'])
    node_process('-p', 'vehicle:=demo_vehicle_loads', '-p', 'tf:=false')
    node = rclpy.create_node('loads_case', context=localhost_context, enable_rosout=False,
                             start_parameter_services=False)
    localhost_executor.add_node(node)
    clients = {name: node.create_client(Solve, f'/{name}/solve') for name in answer.corners}
    assert spin_until(localhost_executor,
                      lambda: all(c.service_is_ready() for c in clients.values()), WAIT)
    served = {}
    for name, corner in answer.corners.items():
        future = clients[name].call_async(request(name, corner))
        assert spin_until(localhost_executor, future.done, WAIT)
        served[name] = future.result()
    for name in ('rear_left', 'rear_right'):
        got, core = served[name], answer.corners[name].loaded
        assert got.status == Status.OK, got.status_text
        # the same equilibrium: converged to steps of 1e-11 mm, here in m
        assert [got.pose.position.x, got.pose.position.y, got.pose.position.z] == \
            pytest.approx(core.wheel_center_mm / 1000.0, abs=1e-12)
        assert math.degrees(got.toe) == pytest.approx(core.toe_deg, abs=1e-9)
        assert math.degrees(got.camber) == pytest.approx(core.camber_deg, abs=1e-9)
    for name in ('front_left', 'front_right'):
        corner = answer.corners[name]
        got = served[name]
        assert got.status == Status.OK, got.status_text
        # the node's corner has no drop link: the vehicle's corner scene, the same load
        alone = solve_loaded(load_vehicle('demo_vehicle_loads').corners[name],
                             corner.travel_mm, corner.load)
        assert math.degrees(got.toe) == pytest.approx(alone.toe_deg, abs=1e-9)
