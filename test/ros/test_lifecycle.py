# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_lifecycle_node driven from another process over DDS by the standard services.

configure, activate, deactivate, activate and shutdown through <node>/change_state: the node
answers only while active (a command sent while inactive is dropped: the answers that come
are those of the commands sent while active, in order, on a reliable topic), keeps its pose
while inactive, closes its recording at shutdown and then ends with status 0. A bad scene
fails configure with its one-line reason, and the node stays unconfigured.
"""

import gc
import math
import multiprocessing

from lifecycle_msgs.msg import State, Transition
from lifecycle_msgs.srv import ChangeState, GetState
from linkage_ros.ros.lifecycle import ManagedSuspensionNode
from linkage_ros.ros.node import NODE_NAME
from linkage_ros.ros.testing import Probe, read_mcap_ros2, spin_until
from rclpy.lifecycle import TransitionCallbackReturn
from rclpy.parameter import Parameter

WAIT = 20.0   # s: cross-process discovery is ~0.04 s or ~3 s
COMPILE = 120.0   # s: a configure on a cold numba cache compiles the kernels (~20 s alone)


class Manager:
    """The lifecycle services of suspension_kinematics, called from a probe's node."""

    def __init__(self, probe):
        self.probe = probe
        self.change = probe.node.create_client(ChangeState, f'/{NODE_NAME}/change_state')
        self.get = probe.node.create_client(GetState, f'/{NODE_NAME}/get_state')

    def _call(self, client, request, timeout=WAIT):
        assert spin_until(self.probe.executor, client.service_is_ready, WAIT)
        future = client.call_async(request)
        assert spin_until(self.probe.executor, future.done, timeout)
        return future.result()

    def transition(self, label):
        """Ask for the transition label ('configure', ...); return whether it succeeded."""
        request = ChangeState.Request(transition=Transition(label=label))
        return self._call(self.change, request, COMPILE).success

    def state(self):
        return self._call(self.get, GetState.Request()).current_state.id


def answer_of(probe, travel_m):
    """Send travel_m and wait for its pose; return the pose's z (m)."""
    count = len(probe.poses)
    probe.send(travel_m)
    assert spin_until(probe.executor, lambda: len(probe.poses) > count, WAIT)
    return probe.poses[-1].pose.position.z


def test_lifecycle_node_answers_only_while_active(node_process, localhost_context,
                                                  localhost_executor, tmp_path):
    path = tmp_path / 'run.mcap'
    node = node_process('-p', f'record_mcap:={path}', script='suspension_lifecycle_node')
    probe = Probe(localhost_context, localhost_executor)
    manager = Manager(probe)
    assert manager.state() == State.PRIMARY_STATE_UNCONFIGURED
    assert manager.transition('configure')
    assert manager.state() == State.PRIMARY_STATE_INACTIVE
    assert spin_until(localhost_executor, probe.matched, WAIT)
    probe.send(0.03)                      # inactive: dropped
    assert manager.transition('activate')
    design_z = answer_of(probe, 0.0)
    first_z = answer_of(probe, 0.01)
    assert manager.transition('deactivate')
    probe.send(0.04)                      # inactive: dropped, the pose kept
    assert manager.transition('activate')
    second_z = answer_of(probe, 0.02)
    # travel is the wheel centre's z change: the answers are those of 0, 0.01 and 0.02 m only
    assert [p.pose.position.z for p in probe.poses] == [design_z, first_z, second_z]
    assert math.isclose(first_z - design_z, 0.01, abs_tol=1e-12)
    assert math.isclose(second_z - design_z, 0.02, abs_tol=1e-12)
    assert manager.transition('shutdown')
    status, _, err = node.finish(WAIT)
    assert status == 0, err
    recorded = read_mcap_ros2(path)['/wheel_carrier_pose']
    assert [m.pose.position.z for m in recorded] == [design_z, first_z, second_z]


def test_lifecycle_node_with_a_bad_scene_fails_configure_with_its_reason(
        node_process, localhost_context, localhost_executor, tmp_path):
    missing = tmp_path / 'no_such_scene.yaml'
    node = node_process('-p', f'scene:={missing}', script='suspension_lifecycle_node')
    probe = Probe(localhost_context, localhost_executor)
    manager = Manager(probe)
    assert not manager.transition('configure')
    assert manager.state() == State.PRIMARY_STATE_UNCONFIGURED
    status, _, err = node.stop()
    assert status == 0, err
    failed = [line for line in err.splitlines() if 'configure failed' in line]
    assert len(failed) == 1 and failed[0].startswith('[ERROR]')
    assert failed[0].endswith(f'configure failed: {missing}: file: cannot read (No such file '
                              'or directory)')
    assert 'Traceback' not in err


def entity_names(node):
    return sorted([*(p.topic_name for p in node.publishers),
                   *(s.topic_name for s in node.subscriptions),
                   *(s.srv_name for s in node.services)])


def test_cleanup_releases_what_configure_made_and_configure_works_again(
        ros_context, tmp_path):
    path = tmp_path / 'run.mcap'
    node = ManagedSuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('record_mcap', value=str(path))])
    try:
        unconfigured = entity_names(node)
        assert '/wheel_travel' not in unconfigured
        assert node.trigger_configure() == TransitionCallbackReturn.SUCCESS
        assert {'/wheel_travel', '/wheel_carrier_pose'} <= set(entity_names(node))
        assert node.trigger_cleanup() == TransitionCallbackReturn.SUCCESS
        assert entity_names(node) == unconfigured
        # closed: a whole file that reads back, with what configure sent and no answer
        assert sorted(read_mcap_ros2(path)) == ['/robot_description', '/tf_static']
        assert node.trigger_configure() == TransitionCallbackReturn.SUCCESS
    finally:
        node.destroy_node()


def test_configure_after_cleanup_makes_a_vehicle_s_roll_centres_anew(ros_context):
    # cleanup destroys the roll-centre publishers with the corners: configure again makes
    # them again, listening to the new corners (parameter roll_centres, on by default)
    node = ManagedSuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('vehicle', value='demo_vehicle'), Parameter('tf', value=False)])
    try:
        for _ in range(2):
            assert node.trigger_configure() == TransitionCallbackReturn.SUCCESS
            assert {'/front/roll_centre', '/rear/roll_centre'} <= set(entity_names(node))
            front = node.roll_centres.axles[0]
            assert front.corners == (node.corners['front_left'], node.corners['front_right'])
            assert len(node.corners['front_left'].listeners) == 1
            assert node.trigger_cleanup() == TransitionCallbackReturn.SUCCESS
            assert '/front/roll_centre' not in entity_names(node)
    finally:
        node.destroy_node()


def test_each_transition_is_one_line_on_the_log(ros_context, capfd):
    node = ManagedSuspensionNode(context=ros_context)
    try:
        for trigger in (node.trigger_configure, node.trigger_activate, node.trigger_deactivate,
                        node.trigger_cleanup, node.trigger_configure, node.trigger_shutdown):
            assert trigger() == TransitionCallbackReturn.SUCCESS
    finally:
        node.destroy_node()
    said = [line.split(']: ', 1)[1] for line in capfd.readouterr().err.splitlines()
            if '[INFO]' in line and ']: transition ' in line]
    assert said == ['transition configure: unconfigured -> inactive',
                    'transition activate: inactive -> active',
                    'transition deactivate: active -> inactive',
                    'transition cleanup: inactive -> unconfigured',
                    'transition configure: unconfigured -> inactive',
                    'transition shutdown: inactive -> finalized']


def test_a_parameter_change_while_configured_is_refused_saying_why(ros_context):
    node = ManagedSuspensionNode(context=ros_context)
    try:
        assert node.set_parameters([Parameter('method', value='paper')])[0].successful
        assert node.trigger_configure() == TransitionCallbackReturn.SUCCESS
        result = node.set_parameters([Parameter('method', value='fast')])[0]
        assert (result.successful, result.reason) == (False, (
            'the parameters are read at configure: cleanup, set them, then configure again'))
        assert node.corners[''].method == 'paper'
    finally:
        node.destroy_node()


def collect_garbage():
    gc.collect()


def test_a_destroyed_node_leaves_nothing_that_crashes_a_forked_child(ros_context):
    # rclpy left the lifecycle state machine to the garbage collector: collected in a child
    # forked later (flake8's process pool in the same pytest run) it crashed the child, and
    # the pool waited for it for ever.
    ManagedSuspensionNode(context=ros_context).destroy_node()
    child = multiprocessing.get_context('fork').Process(target=collect_garbage)
    child.start()
    child.join(WAIT)
    assert child.exitcode == 0


def carrier_heights_mm(rrd):
    """Return the z (mm) of every carrier pose a .rrd holds, as rerun-sdk's reader reads it."""
    from rerun.chunk import RrdReader
    reader = RrdReader(str(rrd))
    (recording,) = reader.recordings()
    heights = []
    for chunk in reader.stream(store=recording):
        if chunk.entity_path == '/suspension/carrier' and not chunk.is_static:
            column = chunk.to_record_batch().column('Transform3D:translation').to_pylist()
            heights += [row[0][2] for row in column]
    return heights


def test_configure_after_cleanup_keeps_the_first_recording_and_starts_a_numbered_one(
        node_process, localhost_context, localhost_executor, tmp_path):
    # Configure after cleanup emptied record_mcap: of 150 answers the file held the last 50.
    # The first file is kept whole, the second configure records into run_1.mcap (.rrd
    # alike), and every command and answer is in one of them, read back by mcap-ros2-support
    # (MCAP) and rerun-sdk's RrdReader (Rerun).
    mcap, rrd = tmp_path / 'run.mcap', tmp_path / 'run.rrd'
    node = node_process('-p', f'record_mcap:={mcap}', '-p', f'rerun_rrd:={rrd}',
                        script='suspension_lifecycle_node')
    probe = Probe(localhost_context, localhost_executor)
    manager = Manager(probe)
    first = [(i - 50) * 0.0004 for i in range(100)]       # m: -20 .. 19.6 mm
    second = [(j + 0.5) * 0.0004 - 0.01 for j in range(50)]   # m: none equal to a first
    heights = []
    for travels, last in ((first, 'cleanup'), (second, 'shutdown')):
        assert manager.transition('configure')
        assert manager.transition('activate')
        assert spin_until(localhost_executor, probe.matched, WAIT)
        heights += [answer_of(probe, travel) for travel in travels]
        if last == 'cleanup':
            assert manager.transition('deactivate')
        assert manager.transition(last)
    status, _, err = node.finish(WAIT)
    assert status == 0, err
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        'run.mcap', 'run.rrd', 'run_1.mcap', 'run_1.rrd']
    for name, parameter in (('run_1.mcap', 'record_mcap'), ('run_1.rrd', 'rerun_rrd')):
        said = [line for line in err.splitlines() if f'this one goes to {tmp_path / name}' in line]
        assert len(said) == 1 and said[0].startswith('[WARN]'), err
        assert f'{parameter}: {tmp_path / name.replace("_1", "")} holds an earlier ' \
               'recording of this process, kept whole' in said[0]
    for path, travels, answers in ((mcap, first, heights[:100]),
                                   (tmp_path / 'run_1.mcap', second, heights[100:])):
        topics = read_mcap_ros2(path)
        assert [m.data for m in topics['/wheel_travel']] == travels
        assert [m.pose.position.z for m in topics['/wheel_carrier_pose']] == answers
    # Rerun stores the pose in float32 mm: 1 ulp of 300 mm is 3e-5 mm.
    for path, answers in ((rrd, heights[:100]), (tmp_path / 'run_1.rrd', heights[100:])):
        drawn = carrier_heights_mm(path)
        assert len(drawn) == len(answers)
        assert all(math.isclose(d, a * 1000.0, abs_tol=1e-4) for d, a in zip(drawn, answers))
