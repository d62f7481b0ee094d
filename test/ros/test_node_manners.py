# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node as a first-time user meets it: --help, mistakes, and bad commands.

Each mistake gets one line on stderr naming it and exit status 2 before ROS answers anything;
a bad command is said on the console once per kind (not a number, out of reach), with the
value in the unit it was sent in.
"""

import math
from pathlib import Path
import signal
import subprocess

from linkage_ros.core.model import load_scene
from linkage_ros.ros.node import PARAMETERS
from linkage_ros.ros.testing import connect, node_script, Probe, spin_until
import pytest


def run_node(*args, timeout=60):
    """Run the suspension_node console script to its end; (status, stdout, stderr)."""
    done = subprocess.run([str(node_script()), *args], capture_output=True, text=True,
                          timeout=timeout)
    return done.returncode, done.stdout, done.stderr


def test_help_lists_every_parameter_with_its_default_topics_and_exit_statuses():
    status, out, err = run_node('--help')
    assert status == 0 and err == ''
    for name, spec in PARAMETERS.items():
        assert f'  {name} ' in out and repr(spec.default) in out
        assert spec.low is None or f'({spec.range_text()})' in ' '.join(out.split())
    for topic in ('wheel_travel', 'wheel_carrier_pose', 'camber', 'toe', '/diagnostics'):
        assert topic in out
    assert 'example:' in out and 'exit status: 0' in out and '2 a mistake' in out


@pytest.mark.parametrize('args, says', [
    (['--ros-args', '-p', 'sceen:=macpherson'],
     'parameter sceen: not a parameter of suspension_node (did you mean scene?'),
    (['--ros-args', '-p', 'record_mcap:=/no/such/folder/run.mcap'],
     'record_mcap: cannot write /no/such/folder/run.mcap: no folder /no/such/folder'),
    (['--ros-args', '-p', 'rerun_rrd:=/'], 'rerun_rrd: / is a folder, not a file'),
    (['--ros-args', '-p', 'record_mcap:=/dev/full'],
     'record_mcap: /dev/full: cannot write (No space left on device)'),
    (['--ros-args', '-p', 'rerun_rrd:=/dev/full'],   # once a traceback from rerun-sdk
     'rerun_rrd: /dev/full: cannot write ('),
    (['--ros-args', '-p', 'max_step_mm:=-1.0'],
     'max_step_mm: must be from 0.001 to 1000 mm, got -1.0'),
    # Each numeric parameter has a range (issue 23): 1e-7 mm never answered, 1e300 s was an
    # OverflowError traceback, 1e-9 s flooded /diagnostics.
    (['--ros-args', '-p', 'max_step_mm:=1e-7'],
     'max_step_mm: must be from 0.001 to 1000 mm, got 1e-07'),
    (['--ros-args', '-p', 'diagnostic_period:=1e300'],
     'diagnostic_period: must be from 0.01 to 86400 s, got 1e+300'),
    (['--ros-args', '-p', 'diagnostic_period:=1e-9'],
     'diagnostic_period: must be from 0.01 to 86400 s, got 1e-09'),
    (['--ros-args', '-p', 'condition_warn:=0.5'], 'condition_warn: must be from 1 to 1e+15'),
    (['--ros-args', '-p', 'qos_depth:=0'], 'qos_depth: must be from 1 to 100000 messages, got 0'),
    (['--ros-args', '-p', 'qos_depth:=10.5'], 'qos_depth: expected an integer, got 10.5'),
    (['--ros-args', '-p', 'alignment:=yes please'],
     "alignment: expected true or false, got 'yes please'"),
    (['--ros-args', '-p', 'scene:=no_such_scene'], 'scene: no such file, and not a bundled scene'),
    (['scene:=five_link'], "unknown argument 'scene:=five_link': parameters go after --ros-args"),
    # These three were tracebacks from rclpy.init, after a line of rcl's own:
    (['--ros-args', '--params-file', '/no/such/params.yaml'],
     '--params-file /no/such/params.yaml: no such file'),
    (['--ros-args', '--bogus'], "--ros-args: unknown ROS arguments ['--bogus']"),
    (['--ros-args', '-p', 'scene'],
     "--ros-args: Couldn't parse parameter override rule: '-p scene'"),
])
def test_a_mistake_is_one_line_and_status_2(args, says):
    status, out, err = run_node(*args)
    assert status == 2 and out == ''
    assert err.startswith('suspension_node: ') and err.count('\n') == 1, err
    assert says in err


@pytest.mark.parametrize('output, other, says', [
    ('record_mcap', 'rerun_rrd', 'record_mcap: run.yaml is also rerun_rrd; give each output '
     'its own file'),
    ('record_mcap', 'scene', 'record_mcap: run.yaml is the scene file; give another file name'),
    ('rerun_rrd', 'scene', 'rerun_rrd: run.yaml is the scene file; give another file name'),
    ('rerun_rrd', 'vehicle', 'rerun_rrd: run.yaml is the vehicle file; give another file name'),
])
def test_an_output_that_is_an_input_or_the_other_output_is_refused_untouched(
        tmp_path, monkeypatch, output, other, says):
    from linkage_ros.core.model import load_vehicle
    monkeypatch.chdir(tmp_path)
    # run.yaml: a copy of a bundled scene or vehicle file (or nothing yet, for two outputs),
    # named once relatively and once by its absolute path: compared resolved, one file.
    source = {'scene': load_scene('five_link').source,
              'vehicle': load_vehicle('demo_vehicle').source}.get(other)
    path = tmp_path / 'run.yaml'
    if source:
        path.write_text(Path(source).read_text())
    status, out, err = run_node('--ros-args', '-p', f'{output}:=run.yaml', '-p',
                                f'{other}:={path}')
    assert (status, out, err) == (2, '', f'suspension_node: {says}\n')
    assert (path.read_text() if source else path.exists()) == (
        Path(source).read_text() if source else False)


def test_rcl_problem_reads_the_problem_out_of_rcls_error_text():
    # The one place that reads rcl's wording: pinned against the installed rcl here.
    import rclpy
    from linkage_ros.ros.entry import rcl_problem
    context = rclpy.context.Context()
    with pytest.raises(RuntimeError) as raised:
        rclpy.init(context=context, args=['x', '--ros-args', '-p', 'scene'])
    assert str(raised.value).startswith('failed to initialize rcl: ')
    problem = rcl_problem(str(raised.value))
    assert problem.startswith("Couldn't parse parameter override rule: '-p scene'")
    assert ', at /' not in problem and '\n' not in problem
    assert rcl_problem('another\nform') == 'another form'


def test_a_params_file_that_is_not_yaml_is_one_line_and_status_2(tmp_path):
    params = tmp_path / 'params.yaml'
    params.write_text('x: [\n')
    status, out, err = run_node('--ros-args', '--params-file', str(params))
    assert (status, out) == (2, '')
    assert err == (f"suspension_node: --ros-args: Couldn't parse params file: '--params-file "
                   f"{params}'. Error: Sequences can only be values and not keys in params. "
                   'Error at line 1\n')


def test_a_bad_command_is_said_on_the_console_once_per_kind_with_its_unit(
        node_process, localhost_context, localhost_executor):
    process = node_process('-p', 'diagnostic_period:=3600.0')
    probe = Probe(localhost_context, localhost_executor)
    connect(localhost_executor, probe)
    probe.send(math.nan, math.nan, 0.5, 1e308, 0.5, math.inf, 0.01)
    assert spin_until(localhost_executor, lambda: len(probe.poses) >= 2 and sum(
        s.level == b'\x02' for s in probe.statuses) == 6, 20.0)
    status, _, err = process.stop(signal.SIGINT)
    assert status == 0
    said = [line for line in err.splitlines() if 'ERROR' in line]
    # Two kinds, each said once (the repeats within the throttle period are held back):
    assert len(said) == 2, said
    assert '/wheel_travel nan m: travel nan mm is not a finite number' in said[0]
    assert '/wheel_travel 0.5 m: travel 500 mm is out of reach' in said[1]
    # /diagnostics reports every one, with the value as it was sent:
    errors = [s.message for s in probe.statuses if s.level == b'\x02']
    # 1e308 m is finite but beyond the float range in mm, the core's unit: the value as sent,
    # with its unit, and the range of a length it is outside (issue 36, item 12)
    assert errors[3] == ('/wheel_travel 1e+308 m: travel outside -1e+09 to 1e+09 m (-1e+12 to '
                         '1e+12 mm), the range of a length: not a finite number of mm')
    assert errors[5].startswith('/wheel_travel inf m: ')
