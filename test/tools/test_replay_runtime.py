# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-replay solve of a run the node changed while it ran: rack commands, a new scene.

The recording is made in process by suspension_node (its test fixtures), and its answers are
the expected values: the replay must give what the node gave, command for command. Bags are
read back with mcap + mcap_ros2 (test_replay.decoded), not the project's reader.
"""

from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.ros.testing import ParameterClient, spin_until
from linkage_ros.tools.replay import main
import numpy as np
import pytest
from rcl_interfaces.msg import ParameterEvent
from rclpy.parameter import Parameter
from std_msgs.msg import Float64
from test_replay import by_topic, decoded, T0

# Poses are rebuilt by the same code from the same commands: only CDR's float64 round trip
# lies between (none), so 1e-12 m (1e-9 mm) is round-off with room.
ROUND_OFF_M = 1e-12
OUTPUTS = ('/wheel_carrier_pose', '/camber', '/toe')


def answers(messages):
    """Return the poses (x, y, z, qx, qy, qz, qw, in m), cambers and toes (rad) of a bag."""
    poses = [(p.pose.position.x, p.pose.position.y, p.pose.position.z, p.pose.orientation.x,
              p.pose.orientation.y, p.pose.orientation.z, p.pose.orientation.w)
             for p in by_topic(messages, '/wheel_carrier_pose')]
    return (poses, [m.data for m in by_topic(messages, '/camber')],
            [m.data for m in by_topic(messages, '/toe')])


def record_changed_run(suspension_node, probe, path):
    """
    Record a macpherson run with rack commands, then a switch to double_wishbone and more.

    Each command waits for its answer, so the node takes them in the order sent.
    """
    from linkage_ros.ros.node import QOS
    node = suspension_node(scene='macpherson', record_mcap=str(path))
    rack = probe.node.create_publisher(Float64, 'steering_rack', QOS)
    client = ParameterClient(probe)

    def command(publisher, value):
        before = len(probe.poses)
        publisher.publish(Float64(data=value))
        assert spin_until(probe.executor, lambda: len(probe.poses) > before, 20.0)

    assert spin_until(probe.executor, lambda: probe.matched() and rack.get_subscription_count()
                      > 0, 20.0)
    command(probe.travel, 0.03)
    command(rack, 0.012)
    command(probe.travel, -0.02)
    assert client.set(scene='double_wishbone') == [(True, '')]
    command(probe.travel, 0.04)
    command(rack, -0.015)
    command(rack, 0.005)
    command(probe.travel, 0.01)
    node.destroy_node()


def test_solve_replays_rack_commands_and_a_scene_change_as_the_node_answered_them(
        suspension_node, probe, tmp_path, capsys):
    recorded = tmp_path / 'run.mcap'
    record_changed_run(suspension_node, probe, recorded)
    out = tmp_path / 'replayed.mcap'
    assert main(['solve', str(recorded), '-o', str(out)]) == 0
    assert 'not replayed' not in capsys.readouterr().err
    expected, got = decoded(recorded), decoded(out)
    (poses, cambers, toes), (poses2, cambers2, toes2) = answers(expected), answers(got)
    assert len(poses) == len(poses2) == 7
    assert np.array(poses2) == pytest.approx(np.array(poses), abs=ROUND_OFF_M)
    assert cambers2 == pytest.approx(cambers, abs=ROUND_OFF_M)
    assert toes2 == pytest.approx(toes, abs=ROUND_OFF_M)
    racks = [m.data for m in by_topic(got, '/steering_rack')]
    assert racks == [0.012, -0.015, 0.005]
    # each scene's URDF in turn, and the change itself, as the node recorded them
    names = [m.data.split('name="', 2)[1].split('"')[0]
             for m in by_topic(got, '/robot_description')]
    assert names == ['macpherson', 'double_wishbone']
    (event,) = by_topic(got, '/parameter_events')
    assert [(p.name, p.value.string_value) for p in event.changed_parameters] == [
        ('scene', 'double_wishbone')]


def write_run_with_change(path, name, value, travels_before, travels_after):
    """Write a five_link run whose node changed parameter name to value between travels."""
    with McapRecorder(path) as rec:
        t = T0
        for travel in travels_before:
            t += 10**7
            rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=travel), t, t)
        t += 10**7
        event = ParameterEvent(node='/suspension_kinematics', changed_parameters=[
            Parameter(name, value=value).to_parameter_msg()])
        rec.record('/parameter_events', 'rcl_interfaces/msg/ParameterEvent', event, t, t)
        for travel in travels_after:
            t += 10**7
            rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=travel), t, t)


def test_a_scene_change_that_does_not_load_here_is_named_and_the_run_ends_there_status_1(
        tmp_path, capsys):
    bag = tmp_path / 'run.mcap'
    missing = tmp_path / 'gone' / 'scene.yaml'
    write_run_with_change(bag, 'scene', str(missing), [0.01, 0.02], [0.03, 0.04, 0.05])
    out = tmp_path / 'replayed.mcap'
    assert main(['solve', str(bag), '-o', str(out)]) == 1
    err = capsys.readouterr().err
    assert (f"the node changed its scene to '{missing}' at 1700000000.030000000 s, which "
            'does not load here') in err
    assert 'the 3 commands from then on are not replayed' in err
    got = decoded(out)
    assert [m.data for m in by_topic(got, '/wheel_travel')] == [0.01, 0.02]
    assert len(by_topic(got, '/wheel_carrier_pose')) == 2


def test_a_change_of_solver_method_is_replayed_and_reported_as_the_node_reports_it(tmp_path):
    from linkage_ros.ros.messages import status_values
    bag = tmp_path / 'run.mcap'
    write_run_with_change(bag, 'method', 'paper', [0.04, 0.05], [0.055])
    out = tmp_path / 'replayed.mcap'
    assert main(['solve', str(bag), '-o', str(out)]) == 0
    got = decoded(out)
    assert len(by_topic(got, '/wheel_carrier_pose')) == 3
    statuses = [s for m in by_topic(got, '/diagnostics') for s in m.status]
    values = status_values(statuses[-1])       # the report after the last command
    assert values['method'] == 'paper'
    assert float(values['travel_m']) == pytest.approx(0.055, abs=1e-15)


def test_joint_states_commands_that_solve_does_not_replay_are_named_and_give_status_1(
        tmp_path, capsys):
    from sensor_msgs.msg import JointState
    bag = tmp_path / 'run.mcap'
    with McapRecorder(bag) as rec:
        rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=0.01), T0, T0)
        rec.record('/joint_states', 'sensor_msgs/msg/JointState',
                   JointState(name=['travel'], position=[0.02]), T0 + 1, T0 + 1)
    assert main(['solve', str(bag), '-o', str(tmp_path / 'out.mcap')]) == 1
    assert (f'{bag}: 1 joint_states message (sensor_msgs/JointState commands) not replayed'
            in capsys.readouterr().err)


def test_with_several_nodes_events_only_suspension_kinematics_changes_are_replayed(tmp_path):
    from linkage_ros.record.mcap_reader import read_bag
    from linkage_ros.tools.replay_commands import parameter_changes
    bag = tmp_path / 'run.mcap'
    with McapRecorder(bag) as rec:
        for i, (node, value) in enumerate([('/other_node', 'paper'),
                                           ('/car/suspension_kinematics', 'fast')]):
            event = ParameterEvent(node=node, changed_parameters=[
                Parameter('method', value=value).to_parameter_msg()])
            rec.record('/parameter_events', 'rcl_interfaces/msg/ParameterEvent', event,
                       T0 + i, T0 + i)
    assert [c.values for c in parameter_changes(read_bag(bag))] == [{'method': 'fast'}]


def test_a_scene_change_after_the_last_command_is_replayed_too(tmp_path):
    bag = tmp_path / 'run.mcap'
    write_run_with_change(bag, 'scene', 'double_wishbone', [0.01, 0.02], [])
    out = tmp_path / 'replayed.mcap'
    assert main(['solve', str(bag), '-o', str(out)]) == 0
    got = decoded(out)
    names = [m.data.split('name="', 2)[1].split('"')[0]
             for m in by_topic(got, '/robot_description')]
    assert names == ['five_link', 'double_wishbone']
    assert len(by_topic(got, '/parameter_events')) == 1
