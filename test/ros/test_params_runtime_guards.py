# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node's SetParameters under hostile or careless requests (issue 27, items 2-8).

A request is taken whole or refused whole with its reason; no request stops, blocks or
silently resets the node. In process, over DDS in one Context, with the probe's client.
"""

import math
import os
from pathlib import Path
import threading

from diagnostic_msgs.msg import DiagnosticStatus
from linkage_ros.core.base import LinkageError
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import Continuation
from linkage_ros.ros.messages import status_values
from linkage_ros.ros.node import QOS, SuspensionNode
from linkage_ros.ros.testing import ParameterClient, spin_until
import pytest
from rcl_interfaces.srv import SetParameters
from rclpy.parameter import Parameter
from std_msgs.msg import Float64
from test_params_runtime import assert_answers

SINGULAR = Path(__file__).resolve().parents[1] / 'data' / 'five_link_singular.yaml'


@pytest.fixture
def client(probe):
    return ParameterClient(probe)


def test_a_scene_name_too_long_for_the_file_system_is_refused_with_the_reason(
        suspension_node, probe, client):
    node = suspension_node()
    ((ok, reason),) = client.set(scene='x' * 5000 + '.yaml')
    assert not ok and 'File name too long' in reason and '(5005 characters)' in reason
    assert node.get_parameter('scene').value == 'five_link'
    assert_answers(probe, 'five_link', [0.02])          # the node goes on


def test_a_scene_path_that_is_a_fifo_is_refused_at_once(suspension_node, probe, client,
                                                        tmp_path):
    node = suspension_node()
    fifo = tmp_path / 'scene.yaml'
    os.mkfifo(fifo)              # nobody writes to it: opened plainly, it blocks for good
    ((ok, reason),) = client.set(scene=str(fifo))
    assert not ok
    assert reason == f'{fifo}: file: not a regular file (a FIFO): give a YAML file'
    assert node.get_parameter('scene').value == 'five_link'
    assert_answers(probe, 'five_link', [0.02])


def test_a_lower_max_step_mm_keeps_the_pose_held(suspension_node, probe, client):
    # 350 mm from design at 0.001 mm is 350 001 substeps, beyond max_substeps: a walk back
    # from design would fail; the pose held is kept instead.
    node = suspension_node(diagnostic_period=3600.0)
    assert probe.ask(0.35).pose is not None
    assert client.set(max_step_mm=0.001) == [(True, '')]
    solver = node.corners[''].solver
    assert solver.settings.max_step == 0.001 and solver.travel == pytest.approx(350.0, abs=1e-9)
    answer = probe.ask(0.3500005)                       # 0.0005 mm on: one substep
    assert answer.pose is not None
    expected = Continuation(load_scene('five_link')).solve(350.0005)
    assert answer.pose.pose.position.z == pytest.approx(expected.wheel_center[2] / 1000.0,
                                                        abs=1e-9)


def test_a_request_with_one_refused_parameter_sets_none_of_them(suspension_node, probe,
                                                                client, tmp_path):
    node = suspension_node()
    missing = tmp_path / 'missing.yaml'
    results = client.set(max_step_mm=2.0, scene=str(missing))
    assert [ok for ok, _ in results] == [False, False]
    assert all(reason.startswith(f'{missing}: file: cannot read') for _, reason in results)
    assert node.get_parameter('max_step_mm').value == 5.0
    assert node.corners[''].solver.settings.max_step == 5.0
    assert client.set(max_step_mm=2.0, diagnostic_period=2.0) == [(True, '')] * 2
    assert node.corners[''].solver.settings.max_step == 2.0


def test_an_unknown_parameter_is_refused_by_its_name(suspension_node, client):
    node = suspension_node()
    results = client.set(max_step=2.0, max_step_mm=3.0)
    assert [ok for ok, _ in results] == [False, False]
    assert results[0][1].startswith('max_step: not a parameter of suspension_node (did you '
                                    'mean max_step_mm?')
    assert node.get_parameter('max_step_mm').value == 5.0


@pytest.mark.parametrize('frame_id,problem', [
    ('', 'empty: give a name'),
    ('/base_link', "'/base_link' starts with /, which tf2 refuses in a frame name"),
    ('base\x00link', "'base\\x00link' holds U+0000: a name may not hold control"),
])
def test_a_frame_id_no_frame_may_have_is_refused_at_start(ros_context, frame_id, problem):
    with pytest.raises(LinkageError) as raised:
        SuspensionNode(context=ros_context, parameter_overrides=[
            Parameter('frame_id', value=frame_id)])
    assert str(raised.value).startswith(f'frame_id: {problem}')


def test_a_singular_scene_set_while_running_is_warned_of_as_at_start(suspension_node, client,
                                                                     capfd):
    suspension_node()
    capfd.readouterr()
    assert client.set(scene=str(SINGULAR)) == [(True, '')]
    warned = [line for line in capfd.readouterr().err.splitlines() if '[WARN]' in line]
    assert len(warned) == 1
    assert warned[0].endswith(f'[suspension_kinematics]: {load_scene(SINGULAR).warnings[0]}')


def test_a_rack_command_to_a_scene_without_a_rack_is_refused_after_a_switch(
        suspension_node, probe, client):
    suspension_node(scene='macpherson', diagnostic_period=3600.0)
    assert client.set(scene='five_link') == [(True, '')]
    rack = probe.node.create_publisher(Float64, 'steering_rack', QOS)
    assert spin_until(probe.executor, lambda: rack.get_subscription_count() > 0)
    before_poses, before = len(probe.poses), len(probe.statuses)
    rack.publish(Float64(data=0.01))
    assert spin_until(probe.executor, lambda: any(
        s.level == DiagnosticStatus.ERROR for s in probe.statuses[before:]))
    error = next(s for s in probe.statuses[before:] if s.level == DiagnosticStatus.ERROR)
    assert 'scene five_link has no steer: rack link' in error.message
    assert len(probe.poses) == before_poses
    assert math.isclose(float(status_values(error)['travel_m']), 0.0, abs_tol=1e-12)


def test_commands_are_answered_while_a_new_scene_loads_and_the_request_waits_for_it(
        suspension_node, probe, client, monkeypatch):
    # The loader is held until the test lets it go: a large scene (0.5 MB took 1-4 s) that
    # loaded on the executor would hold every command back as long.
    import linkage_ros.core.model as scenes
    load, release = scenes.load_scene, threading.Event()

    def held_load(name):
        release.wait(60.0)
        return load(name)

    monkeypatch.setattr(scenes, 'load_scene', held_load)
    node = suspension_node()
    assert spin_until(probe.executor, client.client.service_is_ready)
    request = SetParameters.Request(parameters=[
        Parameter('scene', value='macpherson').to_parameter_msg()])
    future = client.client.call_async(request)
    answer = probe.ask(0.02, timeout=30.0)              # answered with the scene held
    assert answer.pose is not None and not future.done()
    assert node.get_parameter('scene').value == 'five_link'
    release.set()
    assert spin_until(probe.executor, future.done, 20.0)
    assert [(r.successful, r.reason) for r in future.result().results] == [(True, '')]
    assert node.get_parameter('scene').value == 'macpherson'
    assert_answers(probe, 'macpherson', [0.03])


def test_a_scene_that_fails_to_load_in_the_background_refuses_the_whole_request(
        suspension_node, client, tmp_path):
    node = suspension_node()
    bad = tmp_path / 'bad.yaml'
    bad.write_text('name: [unclosed\n')
    results = client.set(scene=str(bad), max_step_mm=2.0)
    assert [ok for ok, _ in results] == [False, False]
    assert results[0][1].startswith(f'{bad}: line ')
    assert node.get_parameter('max_step_mm').value == 5.0


def test_a_scene_is_switched_under_sim_time_with_no_clock_published(suspension_node, client):
    # The wait for the loaded scene runs on the steady clock: a node clock stopped at 0 (sim
    # time, no /clock yet) must not hold the answer back.
    node = suspension_node(use_sim_time=True)
    assert client.set(scene='macpherson') == [(True, '')]
    assert node.corners[''].scene.name == 'macpherson'


def test_set_parameters_atomically_names_an_unknown_parameter_and_sets_nothing(
        suspension_node, probe):
    from rcl_interfaces.srv import SetParametersAtomically
    node = suspension_node()
    atomic = probe.node.create_client(SetParametersAtomically,
                                      '/suspension_kinematics/set_parameters_atomically')
    assert spin_until(probe.executor, atomic.service_is_ready, 20.0)
    future = atomic.call_async(SetParametersAtomically.Request(parameters=[
        Parameter('max_step_mm', value=2.0).to_parameter_msg(),
        Parameter('sceen', value='macpherson').to_parameter_msg()]))
    assert spin_until(probe.executor, future.done, 20.0)
    result = future.result().result
    assert not result.successful
    assert result.reason.startswith('sceen: not a parameter of suspension_node (did you mean '
                                    'scene?')
    assert node.get_parameter('max_step_mm').value == 5.0
