# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-replay solve of a run driven through the <corner>/solve service.

The node records each request it takes as an input (linkage_ros_interfaces/srv/Solve_Request
on <corner>/solve, at receipt); a replay answers it again, travel and rack at once and its
wrench taken, and must give the node's answers bit for bit: the same code
(protocol.Responder) on the same recorded floats.
"""

from linkage_ros.ros import solve_service
from linkage_ros.ros.testing import spin_until
from linkage_ros.tools.replay import main
import pytest
from test_replay import decoded
from test_replay_statics import answers

Solve = solve_service.solve_type()
pytestmark = pytest.mark.skipif(Solve is None, reason=(
    'linkage_ros_interfaces is not built here (linkage-tf2-msgs builds it)'))
WAIT = 20.0
# (travel m, rack m, wrench (fx, fy, fz, tz) N and N m or None), in the order sent
STEERED = [(0.02, 0.0, None), (0.03, 0.012, None), (-0.02, -0.01, None), (0.0, 0.005, None)]
LOADED = [(0.01, 0.0, None), (0.02, 0.0, (-1500.0, 3000.0, 2500.0, 40.0)),
          (-0.015, 0.0, None), (0.005, 0.0, (800.0, -2000.0, 3500.0, -25.0))]


def record_service_run(ros_context, executor, suspension_node, scene, requests, path):
    """Record a run of the requests to solve, each waiting for its answer; return these."""
    import rclpy
    node = suspension_node(scene=scene, record_mcap=str(path), diagnostic_period=3600.0)
    client_node = rclpy.create_node('client', context=ros_context)
    client = client_node.create_client(Solve, 'solve')
    executor.add_node(client_node)
    assert spin_until(executor, client.service_is_ready, WAIT)
    served = []
    for travel, rack, wrench in requests:
        request = Solve.Request(travel=travel, rack=rack, use_wrench=wrench is not None)
        if wrench is not None:
            w = request.wrench
            w.force.x, w.force.y, w.force.z, w.torque.z = wrench
        future = client.call_async(request)
        assert spin_until(executor, future.done, WAIT)
        served.append(future.result())
    executor.remove_node(client_node)
    client_node.destroy_node()
    node.destroy_node()     # the recording is finished
    return served


@pytest.mark.parametrize('scene, requests', [('macpherson', STEERED),
                                             ('five_link_bushings', LOADED)])
def test_a_service_driven_run_replays_to_the_node_s_answers_bit_for_bit(
        ros_context, executor, suspension_node, tmp_path, scene, requests):
    from linkage_ros.core.base import Status
    recorded = tmp_path / 'run.mcap'
    served = record_service_run(ros_context, executor, suspension_node, scene, requests,
                                recorded)
    assert [a.status for a in served] == [Status.OK] * len(requests)
    out = tmp_path / 'replayed.mcap'
    assert main(['solve', str(recorded), '-o', str(out), '--scene', scene]) == 0
    expected, got = answers(recorded), answers(out)
    assert len(expected['/wheel_carrier_pose']) == len(requests)
    assert got == expected     # exact: the same code on the same recorded floats
    poses = [p[1:] for p in got['/wheel_carrier_pose']]
    assert poses == [(a.pose.position.x, a.pose.position.y, a.pose.position.z,
                      a.pose.orientation.x, a.pose.orientation.y, a.pose.orientation.z,
                      a.pose.orientation.w) for a in served]


def test_the_recording_holds_each_request_at_its_answer_s_time(
        ros_context, executor, suspension_node, tmp_path):
    recorded = tmp_path / 'run.mcap'
    record_service_run(ros_context, executor, suspension_node, 'macpherson', STEERED,
                       recorded)
    messages = decoded(recorded)
    requests = [(t, m) for topic, t, m in messages if topic == '/solve']
    assert [(m.travel, m.rack) for _, m in requests] == [(r[0], r[1]) for r in STEERED]
    stamps = [m.header.stamp.sec * 10**9 + m.header.stamp.nanosec
              for topic, _, m in messages if topic == '/wheel_carrier_pose']
    assert stamps == [t for t, _ in requests]
