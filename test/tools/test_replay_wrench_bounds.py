# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-replay solve of a recording that holds a wrench beyond the bound (issue 36, item 1).

Before: a contact_wrench of 1.7e308 N in a recording was taken, and the next travel raised
LinAlgError: a traceback, and a partial output file. Now the replay refuses it as the node
does (an ERROR on /diagnostics naming /contact_wrench and the component; the last good
wrench kept), refuses a recorded solve request whose wrench is beyond it (the node would have
answered REFUSED and recorded nothing), answers every travel, and finishes: status 0, a whole
file read back by mcap's own reader.
"""

from linkage_ros.answer.cdr import wrench_stamped_cdr
from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.ros import solve_service
from linkage_ros.tools.replay import main
import pytest
from test_replay import decoded, T0

SCENE = 'five_link_bushings'
ERROR = 2      # diagnostic_msgs/DiagnosticStatus ERROR, as mcap_ros2 decodes a byte
TRAVELS = [0.01, 0.02, -0.01]
Solve = solve_service.solve_type()


def write_run(path, huge_request=False):
    """Write a recording: a huge wrench, then travels (and a solve request with a huge one)."""
    from std_msgs.msg import Float64
    with McapRecorder(path) as rec:
        rec.record('/contact_wrench', 'geometry_msgs/msg/WrenchStamped', wrench_stamped_cdr(
            (1, 0), 'base_link', (0.0, 1.7e308, 0.0), (0.0, 0.0, 0.0)), T0 - 2, T0 - 2)
        if huge_request:
            from geometry_msgs.msg import Wrench
            wrench = Wrench()
            wrench.torque.z = 1e308
            rec.record('/solve', 'linkage_ros_interfaces/srv/Solve_Request', Solve.Request(
                travel=0.03, wrench=wrench, use_wrench=True), T0 - 1, T0 - 1)
        for i, value in enumerate(TRAVELS):
            rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=value),
                       T0 + i * 10**7, T0 + i * 10**7)


def errors(path):
    return [s.message for t, _, m in decoded(path) if t == '/diagnostics'
            for s in m.status if s.level == ERROR]


def test_a_recorded_huge_contact_wrench_is_refused_and_the_replay_finishes(tmp_path):
    recorded, out = tmp_path / 'run.mcap', tmp_path / 'replayed.mcap'
    write_run(recorded)
    assert main(['solve', str(recorded), '-o', str(out), '--scene', SCENE]) == 0
    messages = decoded(out)     # mcap's reader: a whole file
    poses = [m for t, _, m in messages if t == '/wheel_carrier_pose']
    assert len(poses) == len(TRAVELS)
    (error,) = errors(out)
    assert error.startswith('/contact_wrench: ')
    assert 'force.y 1.7e+308 N is beyond the bound of 1e+07 N' in error


@pytest.mark.skipif(Solve is None, reason='linkage_ros_interfaces is not built here')
def test_a_recorded_solve_request_with_a_huge_wrench_is_refused_as_the_node_does(tmp_path):
    recorded, out = tmp_path / 'run.mcap', tmp_path / 'replayed.mcap'
    write_run(recorded, huge_request=True)
    assert main(['solve', str(recorded), '-o', str(out), '--scene', SCENE]) == 0
    messages = decoded(out)
    assert len([m for t, _, m in messages if t == '/wheel_carrier_pose']) == len(TRAVELS)
    assert not [m for t, _, m in messages if t == '/solve']      # the node records none
    said = errors(out)
    assert len(said) == 2 and said[1].startswith('/solve: ')
    assert 'moment.z 1e+308 N m is beyond the bound of 1e+06 N m' in said[1]
