# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The node's entry (ros/entry.py) compiles the statics kernels before solving when told.

The node tells it when a corner answers loaded poses.
"""

from linkage_ros.core import warmup
from linkage_ros.ros import entry
from linkage_ros.ros.node import SuspensionNode
import pytest
from rclpy.parameter import Parameter


def test_the_node_entry_checks_and_compiles_the_statics_kernels_only_when_told(monkeypatch):
    calls = []
    monkeypatch.setattr(warmup, 'say_if_cold', lambda prog, file=None, statics=False:
                        calls.append(('say', prog, statics)) or True)
    monkeypatch.setattr(warmup, 'compile_in_child', lambda statics=False:
                        calls.append(('compile', statics)) or True)
    entry.compile_kernels(statics=True)
    entry.compile_kernels()
    assert calls == [('say', entry.PROG, True), ('compile', True),
                     ('say', entry.PROG, False), ('compile', False)]


@pytest.mark.parametrize('scene, statics, told', [
    ('double_wishbone_bushings', False, True),   # a scene with bushings answers loaded poses
    ('double_wishbone', True, True),             # so does a rigid one with statics:=true
    ('double_wishbone', False, False)])
def test_the_node_tells_its_entry_to_compile_the_statics_kernels_when_it_solves_statics(
        ros_context, scene, statics, told):
    # The node called before_solving() without a word of statics: a node on a scene with
    # bushings compiled the statics kernels at its first loaded answer, unsaid.
    asked = []
    node = SuspensionNode(context=ros_context, before_solving=lambda **kw: asked.append(kw),
                          parameter_overrides=[Parameter('scene', value=scene),
                                               Parameter('statics', value=statics)])
    node.destroy_node()
    assert asked == [{'statics': told}]
