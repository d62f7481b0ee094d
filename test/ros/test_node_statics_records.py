# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node's statics in its recordings, and its cost to a node without it.

The MCAP holds contact_wrench (what came in) and every pickup/<name> (what went out), read
back by mcap-ros2-support; linkage-rerun draws them as arrows; a scene without bushings and
without parameter statics imports none of the statics code.
"""

import subprocess
import sys

from linkage_ros.answer.pickups import pickup_points
from linkage_ros.ros.node import QOS
from linkage_ros.ros.testing import read_mcap_ros2, spin_until
import numpy as np
import pytest
from rerun.chunk import RrdReader
from test_node_statics import bushing_scene, FORCE, MOMENT, Wrenches

STATICS_MODULES = ('linkage_ros.core.statics', 'linkage_ros.answer.pickups',
                   'linkage_ros.core.model.bushing')


def _one_wrench(suspension_node, probe, scene_path, **params):
    """Start the node on the bushing scene, send FORCE, MOMENT at 20 mm; (node, Wrenches)."""
    node = suspension_node(scene=str(scene_path), diagnostic_period=3600.0, **params)
    wrenches = Wrenches(probe, node)
    wrenches.send(FORCE, MOMENT)
    probe.ask(0.02)
    return node, wrenches


def test_the_mcap_holds_the_contact_wrench_and_every_pickup_topic(suspension_node, probe,
                                                                  tmp_path):
    path = tmp_path / 'run.mcap'
    node, wrenches = _one_wrench(suspension_node, probe, bushing_scene(tmp_path),
                                 record_mcap=str(path))
    sent = wrenches.last()
    names = list(pickup_points(node.corners[''].scene))
    node.destroy_node()
    topics = read_mcap_ros2(path)
    (contact,) = topics['/contact_wrench']
    assert contact.header.frame_id == 'base_link'
    assert [contact.wrench.force.x, contact.wrench.force.y, contact.wrench.force.z] == \
        list(FORCE)
    assert [contact.wrench.torque.z] == [MOMENT[2]]
    for name in names:
        (recorded,) = topics[f'/pickup/{name}']
        live = sent[name]
        assert recorded.header.frame_id == live.header.frame_id
        assert [recorded.wrench.force.x, recorded.wrench.force.y, recorded.wrench.force.z] == \
            [live.wrench.force.x, live.wrench.force.y, live.wrench.force.z]


def test_linkage_rerun_draws_the_recorded_forces_as_arrows(suspension_node, probe, tmp_path):
    from linkage_ros.record.rerun_draw import FORCE_SCALE
    from linkage_ros.tools.rerun_convert import main
    scene_path = bushing_scene(tmp_path)
    path = tmp_path / 'run.mcap'
    node, wrenches = _one_wrench(suspension_node, probe, scene_path, record_mcap=str(path))
    sent = wrenches.last()
    node.destroy_node()
    out = tmp_path / 'run.rrd'
    assert main([str(path), '-o', str(out), '--scene', str(scene_path)]) == 0
    reader = RrdReader(str(out))
    vectors = {}
    for chunk in reader.stream(store=reader.recordings()[0]):
        if chunk.entity_path.startswith('/suspension/forces/') and not chunk.is_static:
            batch = chunk.to_record_batch()
            vectors[chunk.entity_path] = batch.column('Arrows3D:vectors').to_pylist()[-1][0]
    assert vectors['/suspension/forces/contact'] == pytest.approx(
        np.array(FORCE) * FORCE_SCALE, rel=1e-6)      # float32 in the .rrd
    for name, msg in sent.items():
        force = [msg.wrench.force.x, msg.wrench.force.y, msg.wrench.force.z]
        assert vectors[f'/suspension/forces/pickup/{name}'] == pytest.approx(
            np.array(force) * FORCE_SCALE, rel=1e-6, abs=1e-3)


def test_the_node_mirror_to_rerun_draws_the_forces_too(suspension_node, probe, tmp_path):
    out = tmp_path / 'live.rrd'
    node, wrenches = _one_wrench(suspension_node, probe, bushing_scene(tmp_path),
                                 rerun_rrd=str(out))
    wrenches.last()
    node.destroy_node()
    reader = RrdReader(str(out))
    drawn = {chunk.entity_path for chunk in reader.stream(store=reader.recordings()[0])
             if chunk.entity_path.startswith('/suspension/forces/') and not chunk.is_static}
    assert drawn == {'/suspension/forces/contact', *(
        f'/suspension/forces/pickup/{name}' for name in wrenches.pickups)}


def test_a_scene_without_bushings_imports_no_statics_code(domain_id):
    code = f"""
import sys
from linkage_ros.ros.node import SuspensionNode
from linkage_ros.ros.testing import init_context
from rclpy.parameter import Parameter
context = init_context({domain_id})
node = SuspensionNode(context=context, parameter_overrides=[
    Parameter('scene', value='double_wishbone')])
node.corners[''].answer(20.0, None, (1, 0), lambda: 'x')
topics = [name for name, _ in node.get_topic_names_and_types()]
node.destroy_node()
print([m for m in sys.modules if m.startswith({STATICS_MODULES!r})])
print(any('contact_wrench' in t or '/pickup/' in t for t in topics))
"""
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split('\n')[:2] == ['[]', 'False']


def test_a_statics_node_without_a_wheel_radius_is_refused_in_one_line(suspension_node,
                                                                      tmp_path):
    import yaml
    from linkage_ros.core.base import LinkageError
    path = bushing_scene(tmp_path)
    data = yaml.safe_load(path.read_text())
    del data['wheel_radius']
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(LinkageError, match='statics needs wheel_radius') as caught:
        suspension_node(scene=str(path))
    assert '\n' not in str(caught.value)


def test_a_wrench_to_a_corner_whose_new_scene_has_no_statics_is_refused(
        suspension_node, probe, tmp_path):
    from linkage_ros.ros.testing import ParameterClient
    node = suspension_node(scene=str(bushing_scene(tmp_path)), diagnostic_period=3600.0)
    wrenches = Wrenches(probe, node)
    assert ParameterClient(probe).set(scene='double_wishbone') == [(True, '')]
    corner = node.corners['']
    assert corner.statics is None
    before = corner.health.failures_total
    pub = probe.node.create_publisher(type(wrenches.pub.msg_type()), 'contact_wrench', QOS)
    assert spin_until(probe.executor, lambda: pub.get_subscription_count() > 0)
    pub.publish(pub.msg_type())
    assert spin_until(probe.executor, lambda: corner.health.failures_total > before)
    assert 'no bushings and parameter statics is false' in corner.health.refused


def test_a_new_scene_with_bushings_and_no_wheel_radius_is_refused_while_running(
        suspension_node, probe, tmp_path):
    import yaml
    from linkage_ros.ros.testing import ParameterClient
    path = bushing_scene(tmp_path)
    data = yaml.safe_load(path.read_text())
    del data['wheel_radius']
    path.write_text(yaml.safe_dump(data))
    suspension_node(scene='double_wishbone', diagnostic_period=3600.0)
    ((ok, reason),) = ParameterClient(probe).set(scene=str(path))
    assert not ok
    assert reason.startswith('scene: scene double_wishbone') and \
        'statics needs wheel_radius' in reason
    assert probe.ask(0.01).pose is not None     # the old scene answers on
