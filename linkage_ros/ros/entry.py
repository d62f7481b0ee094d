# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The suspension_node process: its command line, its start, its signals and its stop.

    main(args) -> exit status   --help, the mistakes (one line, status 2), the first compile
                                of the kernels, then the node until SIGINT or SIGTERM (0)
    lifecycle_main(args)        the same for suspension_lifecycle_node (ros/lifecycle.py), which
                                also ends once shut down through change_state (status 0)
    run(node, signals) -> 0     spin a node until SIGINT or SIGTERM, then stop it cleanly

Stopping: SIGINT and SIGTERM are Python handlers of this module (rclpy's are not installed: it
would shut the context down from its own thread, under a callback that is publishing). Before
the node spins, a signal raises Stopped where the start is (the wait for the kernels' compile
included) and the process ends with status 0. Once it spins, a signal only stops the node
taking commands: the command in hand is finished, every queued one is dropped, the executor
stops within POLL s, the recordings are closed and the status is 0, whatever was queued.
"""

from __future__ import annotations

import functools
from pathlib import Path
import signal
import sys
from typing import TYPE_CHECKING

import rclpy
from rclpy.exceptions import ParameterException
from rclpy.executors import ExternalShutdownException
from rclpy.experimental import EventsExecutor
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy
from rclpy.signals import SignalHandlerOptions

from .node import SuspensionNode
from .parameters import help_lines
from ..cli import held_stderr, program
from ..core import warmup
from ..core.base import LinkageError

if TYPE_CHECKING:
    from rclpy.node import Node

PROG = 'suspension_node'
LIFECYCLE_PROG = 'suspension_lifecycle_node'
POLL = 0.1    # s: the longest the executor waits before it looks whether a signal came
# rclpy's exception for ROS arguments it does not know (a class of its C extension).
UNKNOWN_ROS_ARGS = getattr(_rclpy, 'UnknownROSArgsError', ())

HELP = """usage: {prog} [--help] [--ros-args -p NAME:=VALUE ... --params-file FILE]

{about}

parameters (-p NAME:=VALUE after --ros-args, or a params file under /**: ros__parameters:):
{parameters}
topics (relative names; a vehicle puts each corner's under its name, e.g. front_left/; all
reliable, keep-last qos_depth):
  in   wheel_travel        std_msgs/Float64           m, + = bump
  in   steering_rack       std_msgs/Float64           m, + = rack to the left (scenes with a
                                                      steer: rack link)
  in   joint_states        sensor_msgs/JointState     travel_joint's position, m (and the
                                                      joints a vehicle file names)
  out  wheel_carrier_pose  geometry_msgs/PoseStamped  wheel centre (m) in frame_id, rotation
                                                      relative to design
  out  camber, toe         std_msgs/Float64           rad, + = top outboard, + = toe-in
  out  /diagnostics        diagnostic_msgs/DiagnosticArray  every diagnostic_period, and at
                                                      once for a bad command or a new level;
                                                      one status per corner, named '<node's
                                                      full name>: <scene or corner>'
  out  alignment, markers  Float64MultiArray, MarkerArray (when turned on)
  out  elements            sensor_msgs/JointState     the scene's elements: length (m), motion
                                                      ratio (scenes with elements)
  in   contact_wrench      geometry_msgs/WrenchStamped  the tyre's force (N) and moment (N m)
                                                      at the contact patch, in frame_id, each
                                                      component within 1e7 N and 1e6 N m (with
                                                      statics: a scene with bushings, or
                                                      -p statics:=true); answers are then the
                                                      loaded pose at the last one
  out  pickup/<name>       geometry_msgs/WrenchStamped  with statics, per answer: the force (N)
                                                      on the body at each pickup and a
                                                      bushing's couple (N m); name
                                                      <link>_base, <arm>_axis0, <arm>_axis1,
                                                      <arm>_centre, <strut>_top or
                                                      <spring>_body; in frame
                                                      <prefix>pickup/<name> (with tf)
  out  /tf, /tf_static     tf2_msgs/TFMessage         the bodies' frames per answer; the wheel
                                                      and pickup frames (parameter tf)
  out  robot_description   std_msgs/String            the URDF (parameter tf)
  out  <axle>/roll_centre  geometry_msgs/PointStamped  a vehicle axle's roll centre (m,
                                                      frame_id; vehicle files with axles)
  in   /clock              rosgraph_msgs/Clock        with use_sim_time: the node clock
  srv  solve               linkage_ros_interfaces/    one command, one answer (travel, rack,
       srv/Solve                                      optional wrench in; pose, camber, toe,
                                                      status out), equal to the topic answer
                                                      (where linkage-tf2-msgs built it)

The first start after an install compiles the numerical kernels (about 20 s, said once; a
Ctrl-C stops it at once); later starts load them.

example:
  ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST {prog} \\
      --ros-args -p scene:=macpherson -p record_mcap:=run.mcap
{example}
exit status: 0 stopped by Ctrl-C (SIGINT) or SIGTERM, at any time: the command in hand is
               finished, queued ones are dropped, recordings are closed;{shutdown}
             2 a mistake: unknown parameter, bad value, bad scene or vehicle file, an output
               file that cannot be written or that is an input, a missing optional package
               (one line on stderr)
"""


ABOUT = 'Wheel travel in; wheel-carrier pose, camber, toe and solver health out (ROS 2, SI units).'

LIFECYCLE_ABOUT = """suspension_node as a managed (lifecycle) node. It starts unconfigured; drive
it with the standard <node>/change_state service (ros2 lifecycle set /suspension_kinematics
configure, activate, deactivate, cleanup, shutdown): configure parses the scene or vehicle,
compiles the kernels and creates the topics (a bad scene fails it, with its reason on the
log); it answers only while active; cleanup closes the recordings (the next configure
records into run_1.mcap, never over them); shutdown closes the recordings and ends the
process (status 0). Each transition is one line on the log. Parameters are read at
configure. Otherwise as suspension_node:"""

LIFECYCLE_EXAMPLE = """  ros2 lifecycle set /suspension_kinematics configure
      (then activate; ros2 needs a full ROS install: from Python, doc/node.md's manage.py)
"""


def help_text(managed: bool = False) -> str:
    """
    Return the text of --help: the parameters with defaults and ranges.

    managed: suspension_lifecycle_node's, which names it and says what its transitions do.
    """
    return HELP.format(
        prog=LIFECYCLE_PROG if managed else PROG, parameters='\n'.join(help_lines()),
        about=LIFECYCLE_ABOUT if managed else ABOUT,
        example=LIFECYCLE_EXAMPLE if managed else '',
        shutdown='\n               or shut down through change_state: recordings closed;'
        if managed else '')


class Stopped(BaseException):
    """A SIGINT or SIGTERM came before the node was spinning: the start stops where it is."""


class Signals:
    """
    SIGINT and SIGTERM as a request to stop.

    requested turns True at the first. Until a node is given (spinning), the first signal
    raises Stopped; then each only stops the node taking commands, and the spin loop ends.
    """

    def __init__(self) -> None:
        self.requested = False
        self.node = None

    def install(self) -> None:
        for number in (signal.SIGINT, signal.SIGTERM):
            signal.signal(number, self._handle)

    def spinning(self, node: Node) -> None:
        """Stop raising: from now on a signal stops node taking commands."""
        self.node = node
        self.install()     # again: an executor may have put handlers of its own

    def _handle(self, number, frame):
        first = not self.requested
        self.requested = True
        if self.node is not None:
            if hasattr(self.node, 'stop_taking_commands'):
                self.node.stop_taking_commands()
        elif first:    # a second signal must not break the cleaning up of the first
            raise Stopped(number)


def lifecycle_main(args: list[str] | None = None) -> int:
    """Run suspension_lifecycle_node: the managed node (ros/lifecycle.py); as main."""
    return main(args, managed=True)


@program(PROG)
def main(args: list[str] | None = None, managed: bool = False) -> int:
    """Run suspension_node: 0 when stopped by SIGINT or SIGTERM, 2 for a mistake."""
    prog = LIFECYCLE_PROG if managed else PROG
    argv = sys.argv[1:] if args is None else list(args)
    own = argv[:argv.index('--ros-args')] if '--ros-args' in argv else argv
    if {'-h', '--help'} & set(own):          # before ROS starts
        print(help_text(managed), end='')
        return 0
    if own:
        print(f'{prog}: unknown argument {own[0]!r}: parameters go after --ros-args, '
              f'as -p name:=value (see {prog} --help)', file=sys.stderr)
        return 2
    # A file-size limit (ulimit -f) would kill the process at the limit: make it an error of
    # the write instead, which stops the recording and is reported, while the node goes on.
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    signals = Signals()
    signals.install()
    node = None
    try:
        init_ros(argv)
        if managed:
            from .lifecycle import ManagedSuspensionNode
            node = ManagedSuspensionNode(before_solving=functools.partial(
                compile_kernels, prog=LIFECYCLE_PROG))
        else:
            node = SuspensionNode(before_solving=compile_kernels)
        return run(node, signals)
    except Stopped:
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
        return 0
    except (ValueError, OSError, ImportError, ParameterException) as exc:
        # LinkageError (a ValueError): its message names the file, field or parameter.
        print(f'{prog}: {exc}', file=sys.stderr)
        rclpy.try_shutdown()
        return 2


def compile_kernels(statics: bool = False, prog: str = PROG) -> None:
    """
    Compile the kernels in a child process if numba's cache lacks them, saying so once.

    statics: the statics kernels too (a scene with bushings, or statics asked for:
    warmup.wants_statics), so that the first loaded answer does not compile them. prog: the
    program that says so (suspension_node or suspension_lifecycle_node).
    """
    if warmup.say_if_cold(prog, statics=statics):
        warmup.compile_in_child(statics)


def init_ros(argv: list[str]) -> None:
    """
    Start rclpy with the user's arguments; a mistake in them is one LinkageError.

    A params file that is not there, one rcl cannot parse, a bad -p rule, an unknown ROS
    argument: rclpy raises after rcl logged a line of its own, which is held back (and shown
    if rclpy starts after all). rclpy's signal handlers are not installed (see the module).
    """
    for option, value in zip(argv, argv[1:]):
        if option == '--params-file' and not Path(value).is_file():
            raise LinkageError(f'--params-file {value}', 'no such file')
    with held_stderr():
        try:
            rclpy.init(args=[PROG, *argv], signal_handler_options=SignalHandlerOptions.NO)
        except UNKNOWN_ROS_ARGS as exc:
            raise LinkageError('--ros-args', f'unknown ROS arguments {exc} (see {PROG} '
                               '--help)') from None
        except RuntimeError as exc:   # rclpy's RCLError: rcl could not parse the arguments
            raise LinkageError('--ros-args', rcl_problem(str(exc))) from None


def rcl_problem(text: str) -> str:
    """
    Return the problem rcl found in the ROS arguments, from the text of rclpy's error.

    rcl says "failed to initialize rcl: <problem>, at <source file>:<line>". This is the one
    place that reads rcl's wording, and test_node_manners pins it against the installed rcl;
    a text of another form is given whole, on one line.
    """
    text = ' '.join(text.split(', at /')[0].split())
    prefix = 'failed to initialize rcl: '
    return text[len(prefix):] if text.startswith(prefix) else text


def run(node: Node, signals: Signals | None = None) -> int:
    """
    Spin node until SIGINT or SIGTERM, then destroy it and shut its context down; return 0.

    signals: the process's Signals, if installed already (a new one is installed otherwise).
    The loop looks at signals.requested at least every POLL s: a Python signal handler runs
    only when the executor gives the main thread back.
    """
    if signals is None:
        signals = Signals()
    executor = EventsExecutor(context=node.context)
    signals.spinning(node)
    try:
        executor.add_node(node)
        # Finite timeouts on purpose too: with rclpy 7.1.6, EventsExecutor.spin_once()
        # without one busy-waits holding the GIL and never runs a callback.
        while not signals.requested and node.context.ok() \
                and not getattr(node, 'finished', False):   # a managed node shut down
            executor.spin_once(timeout_sec=POLL)
    except ExternalShutdownException:    # the context was shut down by someone else
        pass
    finally:
        if hasattr(node, 'stop_taking_commands'):
            node.stop_taking_commands()
        executor.shutdown()
        node.destroy_node()
        rclpy.try_shutdown(context=node.context)
        del executor
        signals.install()    # the executor's end may have reset handlers of its own
    return 0
