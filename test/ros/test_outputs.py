# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The outputs of an answered command: one declared table (protocol.OUTPUTS), one list per answer.

The Responder builds every output a scene and the switches turn on, in the table's order
(outputs_of); suspension_node publishes that list as it is (recorded in publishing order, read
back by mcap + mcap_ros2), and linkage-replay writes the same list.
"""

from linkage_ros.answer.cdr import float64_of, from_cdr
from linkage_ros.answer.frames import CornerFrames
from linkage_ros.answer.protocol import OUTPUTS, outputs_of, Responder
from linkage_ros.core.measure import alignment, element_values
from linkage_ros.core.model import load_scene
from linkage_ros.ros import messages
from linkage_ros.ros.testing import spin_until
from linkage_ros.tools.replay_commands import Command
from linkage_ros.tools.replay_solve import solve_commands
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
import numpy as np
import pytest

EVERY = ['wheel_carrier_pose', 'camber', 'toe', 'alignment', 'markers', 'elements', '/tf']


def responder(scene):
    return Responder(scene, method='fast', max_step_mm=5.0, condition_warn=1e4,
                     frame_id='base_link', status_name='s', period_ns=10**9,
                     builders=messages.BUILDERS)


def test_the_outputs_of_a_scene_and_its_switches_come_from_one_table_in_its_order():
    five_link, plain = load_scene('five_link'), load_scene('chrono_generic_multilink')
    assert [o.name for o in OUTPUTS] == [*EVERY, 'pickup']   # pickup: with statics only
    on = {'alignment': True, 'markers': True, 'tf': True}
    assert [o.name for o in outputs_of(five_link, on)] == EVERY
    # chrono_generic_multilink declares no elements; switches off give the answer alone
    assert [o.name for o in outputs_of(plain, on)] == [n for n in EVERY if n != 'elements']
    assert [o.name for o in outputs_of(plain, {})] == EVERY[:3]
    assert [o.name for o in outputs_of(five_link, {'tf': True})] == [
        *EVERY[:3], 'elements', '/tf']


def test_a_responder_builds_every_output_turned_on_in_the_tables_order():
    scene = load_scene('five_link')
    corner = responder(scene)
    frames = CornerFrames(scene, 'base_link', '')
    corner.set_outputs(alignment=True, markers=True, frames=frames)
    assert [o.name for o in corner.outputs] == EVERY
    reply = corner.answer(30.0, None, (4, 5))
    solution = reply.solution
    assert [(n, t) for n, t, _ in reply.outputs] == [(o.name, o.type_name) for o in OUTPUTS
                                                     if o.when != 'pickups']
    out = {name: data for name, _, data in reply.outputs}
    pose = from_cdr('geometry_msgs/msg/PoseStamped', out['wheel_carrier_pose'])
    position = pose.pose.position
    assert [position.x, position.y, position.z] == pytest.approx(
        solution.wheel_center / 1000.0, abs=1e-15)
    assert float64_of(out['camber']) == solution.camber
    assert float64_of(out['toe']) == solution.toe
    values = messages.alignment_values(out['alignment'])
    expected = alignment(scene, corner.solver.mech, solution.wheel_center, solution.rotation)
    gain = expected.camber_gain[0] * 1000.0        # rad/mm to rad/m
    assert values['camber_gain_rad_per_m'] == pytest.approx(gain, rel=1e-12)
    assert [m.ns for m in out['markers'].markers] == ['links', 'joints']
    elements = from_cdr('sensor_msgs/msg/JointState', out['elements'])
    lengths = element_values(scene, solution.wheel_center[None], solution.rotation[None])
    expected_m = lengths.length[0] / 1000.0
    assert np.array(elements.position) == pytest.approx(expected_m, abs=1e-12)
    assert out['/tf'] == frames.tf_cdr(solution, (4, 5))
    # turned off again: the answer alone, and the elements the scene declares
    corner.set_outputs(alignment=False, markers=False, frames=None)
    assert [n for n, _, _ in corner.answer(20.0, None, (6, 0)).outputs] == [
        *EVERY[:3], 'elements']


def test_a_failed_command_has_no_output_whatever_is_turned_on():
    corner = responder(load_scene('five_link'))
    corner.set_outputs(alignment=True, markers=True,
                       frames=CornerFrames(corner.scene, 'base_link', ''))
    assert corner.answer(5000.0, None, (1, 0)).outputs == []


class Collect:
    """A replay sink that keeps (topic, type name) in the order recorded."""

    def __init__(self):
        self.rows = []

    def record(self, topic, type_name, data, log_time, publish_time):
        self.rows.append((topic, type_name))


def test_replay_writes_the_responders_list_after_each_command():
    scene = load_scene('five_link')
    sink = Collect()
    commands = [Command(10**9 * (k + 1), 10**9 * (k + 1), 0.01 * (k + 1)) for k in range(2)]
    assert solve_commands(commands, scene, 'fast', [sink]) == 0
    names = ['/' + n.lstrip('/') for n in EVERY if n not in ('alignment', 'markers')]
    answered = [t for t, _ in sink.rows if t in names]
    assert answered == names * 2
    types = {o.name.lstrip('/'): o.type_name for o in OUTPUTS}
    assert all(kind == types[t.lstrip('/')] for t, kind in sink.rows if t in names)


def test_the_node_publishes_the_responders_list_in_its_order(suspension_node, executor,
                                                             probe, tmp_path):
    path = tmp_path / 'run.mcap'
    node = suspension_node(record_mcap=str(path), alignment=True, markers=True, tf=True)
    probe.send(0.02, -0.01)
    assert spin_until(executor, lambda: len(probe.poses) == 2)
    node.destroy_node()
    with open(path, 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        topics = [c.topic for _, c, _ in reader.iter_messages(log_time_order=False)]
    names = ['/' + n.lstrip('/') for n in EVERY]
    assert [t for t in topics if t in names] == names * 2


def test_with_statics_the_pickups_follow_the_extras_each_in_its_static_frame():
    from linkage_ros.answer.cdr import transforms_of, wrench_of
    from linkage_ros.answer.frames import static_cdr
    from linkage_ros.answer.pickups import pickup_points
    scene = load_scene('double_wishbone')
    corner = Responder(scene, method='fast', max_step_mm=5.0, condition_warn=1e4,
                       frame_id='base_link', status_name='s', period_ns=10**9, statics=True,
                       prefix='front_left/')
    frames = CornerFrames(scene, 'base_link', 'front_left/', corner.statics.frame_points())
    corner.set_outputs(frames=frames)
    points = pickup_points(scene)
    assert [o.name for o in corner.outputs] == [*EVERY[:3], 'elements', '/tf', 'pickup']
    reply = corner.answer(30.0, None, (4, 5))
    names = [n for n, _, _ in reply.outputs]
    assert names == [*EVERY[:3], 'elements', '/tf', *(f'pickup/{p}' for p in points)]
    static = {child: (parent, translation, q) for _, parent, child, translation, q
              in transforms_of(static_cdr([frames], (0, 0)))}
    out = {n: d for n, _, d in reply.outputs}
    for name, point in points.items():
        frame_id, _, _ = wrench_of(out[f'pickup/{name}'])
        assert frame_id == f'front_left/pickup/{name}'
        parent, translation, q = static[frame_id]
        assert parent == 'base_link' and tuple(q) == (0.0, 0.0, 0.0, 1.0)
        assert translation == pytest.approx(point / 1000.0, abs=1e-15)
    # without the frames (tf off), the wrenches name the vehicle frame
    corner.set_outputs(frames=None)
    reply = corner.answer(30.0, None, (4, 6))
    assert {wrench_of(d)[0] for n, _, d in reply.outputs if n.startswith('pickup/')} == {
        'base_link'}
