# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
How suspension_node answers a corner's commands, without ROS: the node and linkage-replay share it.

    responder = Responder(scene, method='fast', max_step_mm=5.0, condition_warn=1e4,
                          frame_id='base_link', status_name='suspension_kinematics: five_link',
                          period_ns=10**9)
    responder.set_outputs(alignment=False, markers=False, frames=None)   # the extras turned on
    responder.set_outputs(angles=False, elements=False)    # camber, toe, elements left out
    responder.outputs                     # [Output]: what a solved command publishes, in order
    due = responder.due(now_ns)           # a periodic report due by now? (its time, or None)
    reply = responder.answer(travel_mm, rack_mm, stamp, sent)
    reply.outputs                         # [(output name, type name, CDR bytes or message)]
    reply.report                          # /diagnostics must say so at once
    new.follow(responder)                 # new settings or scene: take over its Health

One command: solved by continuation from the last good pose (Continuation); a solved command
is answered by every output of OUTPUTS that its scene and switches turn on (outputs_of), in
the table's order: wheel_carrier_pose (geometry_msgs/PoseStamped: wheel centre in m, carrier
rotation relative to design), always; camber and toe (std_msgs/Float64, rad), unless switch
angles is False; then the extras: alignment, markers, the scene's elements (unless switch
elements is False: then not computed), the corner's TF frames, all stamped with stamp. A
command that cannot be solved (NaN, infinite, out of reach) gets no answer and keeps the last
good pose. Every command is counted into the corner's Health (linkage_ros.answer.health), whose
status goes to /diagnostics at once for a failure or a change of level, and every diagnostic
period (period_ns) of the clock the caller gives: the node's timer, or a recording's timeline.
The roll centre of a vehicle's axle is not a corner's output: it needs both corners' poses
(ros/roll_centres.py listens to both).

With statics on (wants_statics: a scene with bushings, or statics=True), a solved command is
answered with the loaded pose at the last contact wrench (responder.statics.set_wrench;
answer/pickups.CornerStatics, which alone imports the statics core) in place of the kinematic
one, then with every body pickup's force (pickup/<name>, after the extras; switch pickups,
on unless set False: off, the forces are neither read nor built); a load the
linkage cannot carry is a failed command (Status.NOT_CARRIED), with no answer. No exception
of a solve leaves answer(): the statics' is NOT_CARRIED, the kinematics' (or an output
builder's) Status.SOLVER_ERROR, after which the corner restarts from its design position;
either names the exception in one line.
wrench_problem says why a contact wrench is refused (another frame, not finite, beyond the
bound core.base.FORCE_LIMIT_N or MOMENT_LIMIT_NM), statics_problem why a scene cannot
have statics.

ROS-free: this module imports the core, cdr (the answer's CDR bytes) and the Health logic,
never rclpy or a message package. The elements' JointState and the TF frames are CDR bytes
(answer/elements.py, answer/frames.py, themselves ROS-free); the alignment and markers outputs
are rclpy messages, so their makers come from the caller (builders=: the node hands
ros/messages.BUILDERS, which import ros/messages.py and ros/markers.py once turned on).
A DiagnosticStatus is built from responder.health by linkage_ros.ros.messages.health_status.
"""

from __future__ import annotations

from typing import Any, Callable, NamedTuple, TYPE_CHECKING

from .cdr import float64_cdr, pose_stamped_cdr
from .health import Health
from ..core.base import LinkageError, M_PER_MM, Status
from ..core.base import wrench_problem as bounded_wrench_problem
from ..core.solve import Continuation, Solution
from ..core.warmup import wants_statics

if TYPE_CHECKING:
    from .frames import CornerFrames
    from ..core.model import Scene

SOLVED = 'solved'       # Output.when of the output of every solved command: the pose
ANGLES = 'angles'       # Output.when of camber and toe: on unless switch angles is False


class Output(NamedTuple):
    """One output of an answered command: its topic, its type and what turns it on."""

    name: str           # relative to the corner's namespace, or absolute ('/tf')
    type_name: str      # the ROS 2 type
    # SOLVED: always; 'elements': a scene with elements, unless switched off; else the
    # switch (angles, pickups: on unless False)
    when: str
    content: str        # what it holds


# Every output of a solved command, in publishing order: the pose first (what a controller
# waits for, and all a simulator may need), then camber and toe, then the extras. Read by the
# node (ros/corner.py: its publishers and topic list), linkage-replay (tools/replay_solve.py)
# and the Responder.
OUTPUTS = (
    Output('wheel_carrier_pose', 'geometry_msgs/msg/PoseStamped', SOLVED,
           'wheel centre (m, frame_id), carrier rotation relative to design'),
    Output('camber', 'std_msgs/msg/Float64', ANGLES, 'rad, + = top outboard'),
    Output('toe', 'std_msgs/msg/Float64', ANGLES, 'rad, + = toe-in'),
    Output('alignment', 'std_msgs/msg/Float64MultiArray', 'alignment',
           'the alignment set in SI (ros/messages.alignment_array)'),
    Output('markers', 'visualization_msgs/msg/MarkerArray', 'markers',
           'links and joints (ros/markers.py)'),
    Output('elements', 'sensor_msgs/msg/JointState', 'elements',
           "the scene's elements: lengths (m) and motion ratios (answer/elements.py)"),
    Output('/tf', 'tf2_msgs/msg/TFMessage', 'tf',
           "the frames of the corner's bodies (answer/frames.py)"),
    Output('pickup', 'geometry_msgs/msg/WrenchStamped', 'pickups',
           "each body pickup's force on the body, N, one topic pickup/<name> each "
           '(answer/pickups.py)'),
)
# The input of a corner with statics on: the tyre's wrench at the contact patch.
CONTACT_WRENCH = 'contact_wrench'
WRENCH_TYPE = 'geometry_msgs/msg/WrenchStamped'
# output name: ROS 2 type, of the answer proper (answer_outputs): the pose, camber and toe
ANSWER_TYPES = {o.name: o.type_name for o in OUTPUTS if o.when in (SOLVED, ANGLES)}


def wrench_problem(frame_id: str, force: tuple, torque: tuple, vehicle_frame: str) -> str:
    """
    Say why a contact wrench cannot be taken ('' if it can), on one line.

    Another frame than the vehicle's, or a component not finite or beyond the stated bound
    (core.base.wrench_problem: FORCE_LIMIT_N, MOMENT_LIMIT_NM). The last good wrench is kept.
    """
    if frame_id != vehicle_frame:
        return (f'frame_id {frame_id!r} is not the vehicle frame {vehicle_frame!r} (the '
                'contact wrench is taken in the vehicle frame only)')
    problem = bounded_wrench_problem(force, torque)
    if problem:
        return (f'force {list(force)} N, torque {list(torque)} N m: {problem} (the last good '
                'wrench is kept)')
    return ''


def statics_problem(scene: Scene, switch: bool) -> str:
    """Say why a corner of scene cannot answer loaded poses though statics is on, or ''."""
    if wants_statics(scene, switch) and not scene.wheel_radius > 0:
        return (f'scene {scene.name} ({scene.source}): statics needs wheel_radius: the '
                'contact wrench acts at the contact patch')
    return ''


def outputs_of(scene: Scene, switches: dict[str, Any]) -> list[Output]:
    """
    Return the outputs a solved command of scene publishes, in publishing order.

    switches: {'alignment': bool, 'markers': bool, 'tf': bool, 'statics': bool, 'pickups':
    bool, 'angles': bool, 'elements': bool} (the node's parameters of those names; a missing
    one is off, but for pickups, angles and elements, which are on unless False). elements:
    only for a scene with elements; statics: also on for a scene with bushings
    (wants_statics); pickups (the pickup/<name> forces): only with statics; angles: camber
    and toe. The pose (SOLVED) is always on.
    """
    statics = wants_statics(scene, switches.get('statics'))
    on = {**switches, SOLVED: True, ANGLES: switches.get(ANGLES, True) is not False,
          'elements': bool(scene.elements) and switches.get('elements', True) is not False,
          'statics': statics, 'pickups': statics and switches.get('pickups', True) is not False}
    return [output for output in OUTPUTS if on.get(output.when)]


def answer_outputs(solution: Solution, stamp: tuple[int, int], frame_id: str,
                   angles: bool = True) -> list[tuple[str, str, bytes]]:
    """
    Return the messages answering a solved command: [(output name, type name, CDR bytes)].

    In publishing order, the pose first (what a controller waits for): wheel_carrier_pose
    (geometry_msgs/PoseStamped: the wheel centre in m in frame_id, the carrier's rotation
    relative to design as a unit quaternion, so that design reads (0, 0, 0, 1)), then, with
    angles (the node's parameter of that name), camber and toe (std_msgs/Float64, rad), at
    stamp (sec, nanosec). Names are relative to the corner's namespace. A solution without a
    pose raises ValueError saying why it has none.
    """
    if not solution.success:
        raise ValueError(f'no pose for travel {solution.travel!r} mm: {solution.message}')
    x, y, z = solution.wheel_center.tolist()
    pose = ('wheel_carrier_pose', ANSWER_TYPES['wheel_carrier_pose'], pose_stamped_cdr(
        stamp, frame_id, (x * M_PER_MM, y * M_PER_MM, z * M_PER_MM),
        solution.quaternion.tolist()))
    if not angles:
        return [pose]
    return [pose, ('camber', ANSWER_TYPES['camber'], float64_cdr(solution.camber)),
            ('toe', ANSWER_TYPES['toe'], float64_cdr(solution.toe))]


def extra_builder(name: str, responder: Responder) -> Callable[[Solution, tuple], Any]:
    """
    Return build(solution, stamp) of the extra output name for responder's corner.

    The elements and TF outputs are built here (CDR bytes, answer/elements.py and frames.py);
    alignment and markers are rclpy messages, so the caller hands their makers to the
    Responder (builders: the node's ros/messages.BUILDERS), and nothing here imports ROS.
    """
    if name in responder.builders:
        return responder.builders[name](responder)
    if name == 'elements':
        from .elements import elements_builder
        solver = responder.solver
        return elements_builder(responder.scene, solver.mech, responder.frame_id,
                                lambda: solver.jacobian)
    if name == '/tf':
        return responder.frames.tf_cdr
    if name == 'pickup':
        return None    # built with the loaded pose (Responder.answer, answer/pickups.py)
    if name in ('alignment', 'markers'):
        raise ValueError(f'output {name!r} is an rclpy message: its maker comes from the '
                         'caller (Responder builders=, the node gives ros/messages.BUILDERS)')
    raise ValueError(f'no output {name!r} (outputs: {", ".join(o.name for o in OUTPUTS)})')


class Reply(NamedTuple):
    """
    What answering one command gives.

    solution: the core's Solution (mm, rad; status says why it failed). outputs: [(output
    name, type name, CDR bytes or rclpy message)] in publishing order (Responder.outputs: the
    pose first, a controller waits for it), empty for a command that was not solved. sent:
    what was sent, for a failed command ('/wheel_travel 0.5 m'), else ''. report:
    /diagnostics must say so at once (the command failed, or the level changed).
    """

    solution: Solution
    outputs: list
    sent: str
    report: bool


class Responder:
    """
    One corner of suspension_node: its solver, its answers, its Health and report times.

    Lengths of commands in mm (the core's unit), times in ns of the caller's clock.
    """

    def __init__(self, scene: Scene, *, method: str, max_step_mm: float,
                 condition_warn: float, frame_id: str, status_name: str,
                 period_ns: int, start_ns: int | None = None, statics: bool = False,
                 prefix: str = '', builders: dict | None = None) -> None:
        """
        Make the corner's solver and Health.

        status_name: the DiagnosticStatus name ('suspension_kinematics: five_link').
        period_ns: the diagnostic period; start_ns: when its first period starts (the node:
        its clock at start), or None for the time of the first call of due(). statics: answer
        the loaded pose at the last contact wrench (wants_statics; answer/pickups.CornerStatics,
        whose set_wrench takes it), with the pickups' forces; prefix: the corner's TF
        prefix ('' or 'front_left/'), which names its pickups' frames. builders: {output name:
        make(responder) -> build(solution, stamp)} of the outputs whose messages are rclpy's
        (alignment, markers: the node's ros/messages.BUILDERS), called once one is turned on.
        """
        self.scene, self.method, self.frame_id = scene, method, frame_id
        self.builders = dict(builders or {})
        self.status_name, self.condition_warn = status_name, condition_warn
        self.solver = Continuation(scene, method=method, max_step=max_step_mm)
        self.health = Health(condition_warn)
        self.period = int(period_ns)
        if self.period <= 0:
            raise ValueError(f'period_ns must be above 0, got {period_ns!r}')
        self._next = None if start_ns is None else int(start_ns) + self.period
        self.switches = {'alignment': False, 'markers': False, 'pickups': True,
                         ANGLES: True, 'elements': True}
        self.frames: CornerFrames | None = None
        self.statics = None
        if wants_statics(scene, statics):   # the statics core is imported only here
            if statics_problem(scene, statics):
                raise LinkageError('statics', statics_problem(scene, statics))
            from .pickups import CornerStatics
            self.statics = CornerStatics(scene, frame_id, prefix, self.solver)
        self.outputs: list[Output] = []
        self._extras: list[tuple[str, str, Callable]] = []
        self.set_outputs()

    def set_outputs(self, alignment: bool | None = None, markers: bool | None = None,
                    frames: CornerFrames | None | bool = False,
                    pickups: bool | None = None, angles: bool | None = None,
                    elements: bool | None = None) -> None:
        """
        Turn the outputs other than the pose on or off (None, or frames False: as they are).

        alignment, markers, pickups, angles, elements: the node's parameters of those names
        (pickups: with statics, each pickup's force; off, they are neither read nor built;
        angles: camber and toe; elements: a scene's elements, off: not computed); frames: the
        corner's TF frames (ros/tf.CornerFrames, in the corner's namespace), or None for no
        /tf. The scene's elements are published only for a scene with elements.
        """
        for name, value in (('alignment', alignment), ('markers', markers),
                            ('pickups', pickups), (ANGLES, angles), ('elements', elements)):
            if value is not None:
                self.switches[name] = bool(value)
        if frames is not False:
            self.frames = frames
        self.outputs = outputs_of(self.scene, {**self.switches, 'tf': self.frames is not None,
                                               'statics': self.statics is not None})
        self._extras = [(o.name, o.type_name, extra_builder(o.name, self))
                        for o in self.outputs if o.when not in (SOLVED, ANGLES, 'pickups')]
        self._pickups = any(o.when == 'pickups' for o in self.outputs)
        self._angles = any(o.when == ANGLES for o in self.outputs)
        if self.statics is not None:   # pickups in their TF frames where /tf_static has them
            self.statics.use_frames(bool(getattr(self.frames, 'pickups', False)))

    def answer(self, travel_mm: float | None, rack_mm: float | None,
               stamp: tuple[int, int], sent: str | Callable[[], str] = '') -> Reply:
        """
        Solve one command and build its answer; count it into the Health.

        travel_mm, rack_mm: the command (None = unchanged: a rack command is solved at the
        last travel). stamp: (sec, nanosec) of the answer. sent: what was sent where ('/
        wheel_travel 0.5 m'), or a function that says it, called only for a failed command;
        a failure's status message starts with it.
        """
        if rack_mm is not None and not self.scene.steered:
            return self._no_rack(sent() if callable(sent) else sent)
        travel = self.solver.travel if travel_mm is None else travel_mm
        try:
            solution, outputs = self._solve(travel, rack_mm, stamp)
        except Exception as exc:  # noqa: B902 (no exception of a solve may leave an answer)
            solution, outputs = self._raised(travel, rack_mm, exc, Status.SOLVER_ERROR), []
        said = '' if solution.success else (sent() if callable(sent) else sent)
        return Reply(solution, outputs, said, self.health.add(solution, said))

    def _solve(self, travel: float, rack_mm: float | None,
               stamp: tuple[int, int]) -> tuple[Solution, list]:
        """Return (the Solution of a command, its outputs: [] unless solved)."""
        solution = self.solver.solve(travel, rack_mm)
        pickups = []
        if solution.success and self.statics is not None:   # the loaded pose in its place
            try:
                solution, pickups = self.statics.load(solution, stamp, self._pickups)
            except Exception as exc:  # noqa: B902 (a statics solve that raises: not carried)
                return self._raised(travel, rack_mm, exc, Status.NOT_CARRIED), []
        if not solution.success:
            return solution, []
        outputs = answer_outputs(solution, stamp, self.frame_id, self._angles)
        for name, type_name, build in self._extras:
            outputs.append((name, type_name, build(solution, stamp)))
        return solution, outputs + pickups

    def _raised(self, travel: float, rack_mm: float | None, exc: Exception,
                status: Status) -> Solution:
        """
        Return the failed Solution of a command whose solve raised exc: no pose.

        A statics solve that raises is a load not carried (NOT_CARRIED): the kinematic pose
        it started from stands. Any other is a defect (SOLVER_ERROR), after which the state
        the walk left is not trusted: the corner goes back to its design position (on the
        design branch, as every pose is), which the message says. The message names the
        exception, on one line.
        """
        text = ' '.join(str(exc).split())[:300]
        said = f'({type(exc).__name__}: {text}): no pose'
        solver = self.solver
        if self.statics is not None:   # its last equilibrium is not trusted either
            try:
                self.statics.reset()
            except Exception:  # noqa: B902 (the answer is said; the next starts anew)
                pass
        if status == Status.NOT_CARRIED:
            message = f'the statics solve failed {said}'
        else:
            message = f'the solver failed {said}; the corner restarts from its design position'
            try:
                solver.reset()
            except Exception:  # noqa: B902 (the answer is said; the next command walks anew)
                pass
        return Solution(travel=travel, success=False, message=message,
                        reachable=tuple(solver.reachable),
                        rack=solver.rack if rack_mm is None else rack_mm, status=status)

    def _no_rack(self, said: str) -> Reply:
        """Refuse a rack command to a scene without a steer: rack link: ERROR, no pose."""
        why = (f'scene {self.scene.name} has no steer: rack link: a rack command moves '
               'nothing (no pose)')
        solver = self.solver
        solution = Solution(travel=solver.travel, success=False, message=why,
                            reachable=tuple(solver.reachable), rack=solver.rack,
                            status=Status.NO_RACK)
        self.health.refuse(f'{said}: {why}' if said else why)
        return Reply(solution, [], said, True)

    def follow(self, old: Responder) -> None:
        """
        Take over from old, the corner's Responder until a change of its parameters.

        What the node's corner (ros/corner.Corner.configure and set_scene) and linkage-replay
        do on a change of parameters: one home.

        Its extra outputs stay as old had them (the frames: old's, until set_outputs gives those of
        a new scene). Its Health goes on counting (with this condition_warn), and its report times
        (a period started keeps its end). The same scene: this solver takes over the pose old holds
        (its state and the travel limits found: Continuation.take_pose), not walked again from
        design, which new settings might not manage (a max_step_mm too short for the way back).
        Another scene: the corner restarts from its design position, and the Health says so in its
        message.
        """
        health = self.health = old.health
        health.condition_warn = self.condition_warn
        self._next = old._next
        # its extras too: the frames are old's until the caller gives those of a new scene
        self.switches = dict(old.switches)
        if self.statics is not None:     # the last contact wrench holds on
            self.statics.take(old.statics)
        self.set_outputs(frames=old.frames)
        if self.scene is old.scene:
            self.solver.take_pose(old.solver)
            return
        health.last, health.sent, health.refused = None, '', ''
        health.set_fault(health.fault)           # the level and message of no command yet
        if not health.fault:
            health.message = (f'scene changed to {self.scene.name} ({self.scene.source}): '
                              'continuation restarts from its design position')

    def restart_period(self, period_ns: int, now_ns: int) -> None:
        """Count report periods of period_ns from now_ns on (a new diagnostic_period)."""
        self.period = int(period_ns)
        self._next = int(now_ns) + self.period

    def due(self, now_ns: int) -> int | None:
        """
        Return the time (ns) of the periodic report due by now_ns, or None if none is.

        Periods are counted from start_ns (or from the first call), as the node's timer
        counts them from its start. The report due is the first period end not reported yet;
        the next is then the first period end after now_ns: periods that a gap in the
        commands (or a jump of the clock) passed over give one report, not one each. The
        caller sends the status with that stamp and then starts a new period
        (health.reset_period()).
        """
        if self._next is None:
            self._next = int(now_ns) + self.period
            return None
        if now_ns < self._next:
            return None
        due = self._next
        self._next += self.period * ((int(now_ns) - self._next) // self.period + 1)
        return due
