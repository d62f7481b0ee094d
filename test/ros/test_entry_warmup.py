# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The node's entry (ros/entry.py) compiles the statics kernels before solving when told."""

from linkage_ros.core import warmup
from linkage_ros.ros import entry


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
