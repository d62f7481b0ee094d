# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A contact wrench beyond the stated bound is refused by the node, which goes on (issue 36, 1).

Before: force.y = 1.7e308 N on contact_wrench (or 1e307 N on every axis, or a moment of 1e308
N m) was taken, and the next travel raised LinAlgError out of the callback: the node exited.
Now every component beyond core.base.FORCE_LIMIT_N or MOMENT_LIMIT_NM is refused in one line
(an ERROR naming /contact_wrench and the component, counted in failures_total), the last good
wrench is kept, and the next travel is answered at it: on a scene with bushings, on a rigid
scene with statics:=true and on a vehicle's corner, over any magnitude a float holds on any
axis and sign (hypothesis, through the subscription's own callback as the executor calls it),
over real DDS, and through the solve service's use_wrench (REFUSED, counted).
"""

import math

from hypothesis import example, given, HealthCheck, settings, strategies as st
from linkage_ros.answer.cdr import float64_cdr, wrench_stamped_cdr
from linkage_ros.core.base import FORCE_LIMIT_N, MOMENT_LIMIT_NM, Status
from linkage_ros.ros import solve_service
from linkage_ros.ros.testing import spin_until
import pytest
from test_node_statics import assert_pose_is, bushing_scene, Core, FORCE, MOMENT, Wrenches
import yaml

AXES = ['force.x', 'force.y', 'force.z', 'moment.x', 'moment.y', 'moment.z']
MAGNITUDES = (st.floats(min_value=0.0, max_value=1.7e308) | st.floats(0.0, 2e7)
              | st.sampled_from([5e-324, 1e6, 1e7, 1.0000001e7, 1e150, 1e307, 1.7e308]))
FUZZ = settings(deadline=None, database=None, max_examples=40,
                suppress_health_check=[HealthCheck.function_scoped_fixture,
                                       HealthCheck.too_slow])
Solve = solve_service.solve_type()


def wrench_with(axis, value):
    values = [0.0] * 6
    values[AXES.index(axis)] = value
    return tuple(values[:3]), tuple(values[3:])


def vehicle_file(tmp_path):
    """Write a vehicle of two bushed double wishbones (front_left, front_right)."""
    scene = bushing_scene(tmp_path)
    path = tmp_path / 'vehicle.yaml'
    path.write_text(yaml.safe_dump({
        'name': 'bushed', 'units': 'mm', 'corners': {
            'front_left': {'scene': str(scene), 'offset': [1400.0, 0.0, 0.0]},
            'front_right': {'scene': str(scene), 'offset': [1400.0, 0.0, 0.0],
                            'mirror': True}}}))
    return path


def callback(node, topic):
    """Return the callback of node's subscription of topic (its Inbox), as the executor has it."""
    (subscription,) = [s for s in node.subscriptions if s.topic_name == topic]
    return subscription.callback


@pytest.fixture(params=['bushings', 'rigid statics', 'vehicle'])
def statics_node(request, suspension_node, tmp_path):
    """Return (node, corner prefix) of a node with statics on, of each kind."""
    if request.param == 'bushings':
        return suspension_node(scene=str(bushing_scene(tmp_path)), diagnostic_period=3600.0), ''
    if request.param == 'rigid statics':
        return suspension_node(scene='double_wishbone', statics=True,
                               diagnostic_period=3600.0), ''
    return (suspension_node(vehicle=str(vehicle_file(tmp_path)), diagnostic_period=3600.0),
            'front_left/')


@FUZZ
@given(axis=st.sampled_from(AXES), magnitude=MAGNITUDES, sign=st.sampled_from([1.0, -1.0]))
@example(axis='force.y', magnitude=1.7e308, sign=1.0)
@example(axis='moment.z', magnitude=1e308, sign=1.0)
def test_a_wrench_beyond_the_bound_is_refused_and_the_next_travel_answered(
        statics_node, axis, magnitude, sign):
    node, prefix = statics_node
    corner = node.corners[prefix.rstrip('/')]
    take_wrench = callback(node, f'/{prefix}contact_wrench')
    take_travel = callback(node, f'/{prefix}wheel_travel')
    corner.statics.set_wrench((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    failures = corner.health.failures_total
    force, moment = wrench_with(axis, sign * magnitude)
    take_wrench((wrench_stamped_cdr((1, 0), 'base_link', force, moment),
                 {'publication_sequence_number': None}))
    limit = FORCE_LIMIT_N if axis.startswith('force') else MOMENT_LIMIT_NM
    if magnitude <= limit:
        assert (corner.statics.force, corner.statics.moment) == (force, moment)
        assert corner.health.failures_total == failures
    else:
        said = corner.health.refused
        assert said.startswith(f'/{prefix}contact_wrench: ') and f'{axis} ' in said, said
        assert 'beyond the bound' in said and '\n' not in said
        assert corner.health.failures_total == failures + 1
        assert (corner.statics.force, corner.statics.moment) == ((0.0,) * 3, (0.0,) * 3)
    # the next travel is answered: a loaded pose, or a load not carried (no pose), and
    # never an exception (the Inbox would have made it an internal error)
    take_travel((float64_cdr(0.01), {'publication_sequence_number': None}))
    last = corner.health.last
    assert 'internal error' not in corner.health.message
    assert last.status in (Status.OK, Status.NOT_CARRIED), last.message


def test_a_huge_wrench_over_dds_is_an_error_and_the_last_good_wrench_answers(
        suspension_node, probe, tmp_path):
    from diagnostic_msgs.msg import DiagnosticStatus
    node = suspension_node(scene=str(bushing_scene(tmp_path)), diagnostic_period=3600.0)
    scene, wrenches = node.corners[''].scene, Wrenches(probe, node)
    wrenches.send(FORCE, MOMENT)
    before = len(probe.statuses)
    wrenches.send((0.0, 1.7e308, 0.0), (0.0, 0.0, 0.0))
    assert spin_until(probe.executor, lambda: len(probe.statuses) > before)
    status = probe.statuses[before]
    assert status.level == DiagnosticStatus.ERROR
    assert status.message.startswith('/contact_wrench: ')
    assert 'force.y 1.7e+308 N is beyond the bound of 1e+07 N' in status.message
    assert_pose_is(probe.ask(0.01), Core(scene).answer(10.0, FORCE, MOMENT))


@pytest.mark.skipif(Solve is None, reason='linkage_ros_interfaces is not built here')
@pytest.mark.parametrize('force, moment, said', [
    ((0.0, 1.7e308, 0.0), (0.0, 0.0, 0.0), 'force.y 1.7e+308 N is beyond the bound'),
    ((1e307, 1e307, 1e307), (0.0, 0.0, 0.0), 'force.x 1e+307 N is beyond the bound'),
    ((0.0, 0.0, 0.0), (0.0, 0.0, 1e308), 'moment.z 1e+308 N m is beyond the bound'),
    ((0.0, 0.0, 0.0), (math.nan, 0.0, 0.0), 'moment.x nan N m is not finite'),
])
def test_a_solve_request_with_a_huge_wrench_is_refused_and_counted(
        ros_context, executor, suspension_node, force, moment, said):
    from geometry_msgs.msg import Wrench
    import rclpy
    node = suspension_node(scene='five_link_bushings', diagnostic_period=3600.0)
    client_node = rclpy.create_node('client', context=ros_context)
    client = client_node.create_client(Solve, 'solve')
    executor.add_node(client_node)
    assert spin_until(executor, client.service_is_ready, 20.0)

    def call(**fields):
        future = client.call_async(Solve.Request(**fields))
        assert spin_until(executor, future.done, 20.0)
        return future.result()

    wrench = Wrench()
    (wrench.force.x, wrench.force.y, wrench.force.z) = force
    (wrench.torque.x, wrench.torque.y, wrench.torque.z) = moment
    answer = call(travel=0.01, wrench=wrench, use_wrench=True)
    assert answer.status == Solve.Response.REFUSED
    assert answer.status_text.startswith('REFUSED: ') and said in answer.status_text
    assert math.isnan(answer.pose.position.z)
    health = node.corners[''].health
    assert (health.refused_total, health.failures_total) == (1, 1)
    assert health.refused.startswith('/solve: ') and said in health.refused
    assert node.corners[''].statics.force == (0.0, 0.0, 0.0)
    assert call(travel=0.01).status == Status.OK       # and it answers on
