# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage_ros_pytest, the pytest plugin: its fixtures in use, and what it leaves alone."""

from importlib.metadata import entry_points
import os
from pathlib import Path
import shutil
import subprocess
import sys

from diagnostic_msgs.msg import DiagnosticStatus
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import sweep
import linkage_ros_pytest
import numpy as np
import pytest

EXAMPLE = Path(__file__).resolve().parent / 'test_plugin_example.py'
REPO = Path(__file__).resolve().parents[2]


def plugin_args():
    """-p linkage_ros_pytest unless an installed linkage_ros registers it (pytest11)."""
    installed = any(e.value == 'linkage_ros_pytest' for e in entry_points(group='pytest11'))
    return [] if installed else ['-p', 'linkage_ros_pytest']


def test_the_readme_example_passes_under_plain_pytest_outside_this_project(tmp_path):
    shutil.copy(EXAMPLE, tmp_path / 'test_example.py')
    (tmp_path / 'test_plain.py').write_text(
        'def test_a_test_without_its_fixtures_sets_up_nothing(request):\n'
        "    assert request.fixturenames == ['request']\n")
    result = subprocess.run(
        [sys.executable, '-m', 'pytest', '-q', '-p', 'no:cacheprovider', *plugin_args()],
        cwd=tmp_path, capture_output=True, text=True, timeout=120,
        env=dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST'))
    assert result.returncode == 0, result.stdout + result.stderr
    assert '3 passed' in result.stdout   # the example's two tests and test_plain's one


def test_the_helpers_import_without_pytest():
    script = ("import sys; sys.modules['pytest'] = None\n"
              'import linkage_ros, linkage_ros.ros.testing\n'
              'print(linkage_ros.ros.testing.Probe.__name__)\n')
    result = subprocess.run([sys.executable, '-c', script], capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ['Probe']


def test_importing_the_plugin_loads_neither_rclpy_nor_numpy():
    script = ('import sys, linkage_ros_pytest\n'
              "print(sorted(m for m in ('rclpy', 'numpy', 'scipy') if m in sys.modules))\n")
    result = subprocess.run([sys.executable, '-c', script], capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == '[]'


def test_the_plugin_defines_no_hooks():
    assert [name for name in vars(linkage_ros_pytest) if name.startswith('pytest_')] == []


def test_a_run_from_the_repository_leaves_the_package_s_assertions_alone(tmp_path):
    # pytest rewrites the assertions of the outermost package of a pytest11 plugin module; with
    # the plugin inside linkage_ros, every run from a checkout (python -m pytest puts it on
    # sys.path) rewrote and recompiled the whole package on its first import of each module
    (tmp_path / 'test_loader.py').write_text(
        'from _pytest.assertion.rewrite import AssertionRewritingHook\n'
        'import linkage_ros.core.model.scene as scene\n\n\n'
        'def test_the_package_is_imported_as_it_is():\n'
        '    assert not isinstance(scene.__loader__, AssertionRewritingHook)\n')
    result = subprocess.run(
        [sys.executable, '-m', 'pytest', '-q', '-p', 'no:cacheprovider', *plugin_args(),
         str(tmp_path / 'test_loader.py')], cwd=REPO, capture_output=True, text=True,
        timeout=120, env=dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST'))
    assert result.returncode == 0, result.stdout + result.stderr


def test_send_travel_returns_no_pose_and_the_error_for_a_travel_out_of_reach(
        suspension_node, send_travel):
    suspension_node()
    answer = send_travel(1.0)
    assert (answer.pose, answer.camber, answer.toe) == (None, None, None)
    assert answer.diagnostics.level == DiagnosticStatus.ERROR
    assert 'out of reach' in answer.diagnostics.message


def test_send_travel_answers_follow_their_commands(suspension_node, send_travel):
    suspension_node(scene='double_wishbone')
    travels = [0.02, -0.03, 0.0]
    answers = [send_travel(t) for t in travels]
    expected = sweep(load_scene('double_wishbone'), np.array(travels) * 1000.0)
    assert [a.pose.pose.position.z for a in answers] == pytest.approx(
        list(expected.wheel_center[:, 2] / 1000.0), abs=1e-12)
    assert [a.camber for a in answers] == pytest.approx(list(expected.camber), abs=1e-12)
    assert [a.diagnostics for a in answers] == [None] * 3    # solved: nothing said at once


def test_send_travel_without_a_node_times_out_naming_the_problem(send_travel):
    with pytest.raises(TimeoutError, match='no suspension_node matched wheel_travel'):
        send_travel(0.01, timeout=0.2)
