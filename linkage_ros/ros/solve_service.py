# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The <corner>/solve service: one command, one answer, for simulators that step in lockstep.

    services = serve_corners(node, corners)   # {corner name: SolveAnswers}; {} without the
                                              # interface package (said once on the log)

linkage_ros_interfaces/srv/Solve (config/interfaces/linkage_ros_interfaces, built by
linkage-tf2-msgs): request corner, travel (m), rack (m), wrench and use_wrench; response the
pose (geometry_msgs/Pose: wheel centre in m in frame_id, carrier rotation relative to design),
camber and toe (rad), status (linkage_ros.core.base.Status, or REFUSED), status_text, residual
(m) and iterations.

A request is answered by the corner itself (ros/corner.Corner.answer, its Responder): it is
solved from the corner's last good pose, moves it, and publishes the same answer on the
corner's topics (the pose, camber, toe and the extras turned on), so that recordings and TF see
every step. The response's pose, camber and toe are read back from the very CDR bytes published
(cdr.pose_of, cdr.float64_of): a service answer and the topic answer to the same command are
equal, bit for bit. With parameter angles false, camber and toe are not published but still
answered (the solution's own, the same floats). A request with use_wrench sets the corner's
contact wrench (the tyre's force and moment at the contact patch, vehicle frame), as a
contact_wrench message does, and is answered with the loaded pose: it needs statics on (a scene
with bushings, or parameter statics). A request the solver cannot take (a corner of another
name, a wrench on a corner without statics, not finite or beyond the bound
core.base.FORCE_LIMIT_N and MOMENT_LIMIT_NM, a node that is not active, more requests waiting
than qos_depth) is refused with status REFUSED and no pose (NaN), the corner untouched, and
counted in its /diagnostics (refused, refused_total; a bad wrench is also an ERROR, as on
contact_wrench); a command that cannot be solved (NaN travel, out of reach, a load not carried)
has its Status and no pose, as on the topics. Never an exception, and never silence: every
request is answered, in order (ros/service_queue.py).

A request taken (not refused) is an input like the topics' commands: recorded, at receipt, on
the service's name (<corner>/solve) as the request itself (type
linkage_ros_interfaces/srv/Solve_Request, its schema the request half of Solve.srv), its
receipt time the answer's stamp; linkage-replay solve answers it again (doc/recording.md).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .corner import BAD_WRENCH
from .service_queue import RequestQueue
from ..answer.cdr import float64_of, pose_of, SOLVE_REQUEST, to_cdr
from ..answer.protocol import wrench_problem
from ..core.base import M_PER_MM, MM_PER_M

if TYPE_CHECKING:
    from rclpy.node import Node

    from .corner import Corner

NOT_ACTIVE = 'the node is not active: it answers no command now'
REFUSED = 'refused request'   # the console's kind of a REFUSED answer (throttled as one)
MISSING = ('linkage_ros_interfaces cannot be imported (it has no wheel on the package index): '
           'no <corner>/solve service; `linkage-tf2-msgs` builds it into this environment '
           '(needs a C/C++ compiler and the Python headers)')


def solve_type():
    """Return the Solve service class, or None where linkage_ros_interfaces is not built."""
    try:
        from linkage_ros_interfaces.srv import Solve
    except ImportError:
        return None
    return Solve


def serve_corners(node: Node, corners: dict[str, Corner]) -> dict:
    """
    Serve <corner>/solve for each of corners on node; {corner name: SolveAnswers}.

    node is the corners' Outlet (ros/node.py): its taking_commands says whether it answers
    now, its clock stamps the answer. Without the interface package: none, said once.
    """
    kind = solve_type()
    if kind is None:
        if not getattr(node, '_said_solve', False):
            node.get_logger().warning(MISSING)
            node._said_solve = True
        return {}
    return {name: SolveAnswers(node, name, corner, kind) for name, corner in corners.items()}


class SolveAnswers:
    """
    The answers of one corner's solve service; service: its rclpy Service.

    Every request is answered, in order (ros/service_queue.RequestQueue): at most qos_depth
    wait, and one beyond them is REFUSED at once ('overloaded'), never dropped unanswered.
    Every REFUSED answer is counted in the corner's /diagnostics (refused, refused_total).
    """

    def __init__(self, node: Node, name: str, corner: Corner, kind: type) -> None:
        self.node, self.corner = node, corner
        self.topic = node.resolve_service_name(corner.prefix + 'solve')
        # the names a request may give: the corner's, or '' and the scene's for one scene
        self.names = {name} if name else {'', corner.scene.name}
        self._said = None      # the refusal the corner has said on the console already
        self.queue = RequestQueue(node, kind, corner.prefix + 'solve', self.solve,
                                  self.refuse, node.qos.depth)
        self.service = self.queue.service

    def solve(self, request, response):
        """Answer one request (never raises: a bad one is a status and its text)."""
        why = self._refusal(request)
        if why:
            return self.refuse(request, response, why, said=why is self._said)
        # an input like the topics' commands: recorded at receipt, on the service's name, as
        # the request itself (linkage-replay solve answers it again); its time stamps the answer
        stamp = self.node.received(self.topic, SOLVE_REQUEST, to_cdr(request))
        if stamp is None:
            return self.refuse(request, response, NOT_ACTIVE)
        # as the topics read a command (messages.command_mm): the same float, bit for bit
        travel_mm, rack_mm = request.travel * MM_PER_M, request.rack * MM_PER_M
        if request.use_wrench:   # as a contact_wrench message would: kept for what follows
            self.corner.statics.set_wrench(*wrench_parts(request.wrench))
        if not self.corner.scene.steered and rack_mm == 0.0:
            rack_mm = None    # no rack link: the rack stays where it is (none)
        reply = self.corner.answer(travel_mm, rack_mm, stamp, lambda: self._sent(request))
        return fill(response, reply)

    def refuse(self, request, response, why: str, said: bool = False):
        """
        Answer REFUSED with why, no pose; count it in the corner's diagnostics.

        said: the console has said why already (a bad wrench, the corner's own ERROR).
        """
        self.corner.health.refuse_request()
        if not said:
            self.node.bad_command(self.topic, REFUSED, why)
        return refused(response, why)

    def _refusal(self, request) -> str:
        """Say why a request is not solved at all, or ''."""
        corner = self.corner
        if request.corner not in self.names:
            return (f'no corner {request.corner!r} here: this is the solve service of '
                    f'{" or ".join(repr(n) for n in sorted(self.names))}')
        if not self.node.taking_commands:
            return NOT_ACTIVE
        if request.use_wrench:
            if corner.statics is None:
                return (f'scene {corner.scene.name} has no bushings and parameter statics is '
                        'false: use_wrench moves nothing')
            force, torque = wrench_parts(request.wrench)
            problem = wrench_problem(corner.frame_id, force, torque, corner.frame_id)
            if problem:     # an ERROR of the corner, as on its contact_wrench topic
                corner.refuse(self.topic, problem, BAD_WRENCH)
                self._said = problem
                return problem
        return ''

    def _sent(self, request) -> str:
        """Say what was asked, for the console and diagnostics of a failed command."""
        return (f'{self.corner.prefix}solve travel {request.travel!r} m, rack '
                f'{request.rack!r} m')

    def close(self, why: str = 'the node is stopping') -> None:
        """Refuse every request still waiting, and every one after."""
        self.queue.close(why)


def wrench_parts(wrench) -> tuple[tuple, tuple]:
    """Return (force, torque) of a geometry_msgs/Wrench as triples of floats (N, N m)."""
    f, t = wrench.force, wrench.torque
    return (f.x, f.y, f.z), (t.x, t.y, t.z)


def fill(response, reply):
    """Fill response from a Responder Reply: its published bytes, or NaN and the Status."""
    solution = reply.solution
    pose = response.pose
    outputs = {name: data for name, _, data in reply.outputs}
    if solution.success:
        (x, y, z), (qx, qy, qz, qw) = pose_of(outputs['wheel_carrier_pose'])
        # with parameter angles false no camber or toe is published: the solution's own
        # floats, which a Float64's CDR holds unchanged (8 bytes, the same bits)
        response.camber = float64_of(outputs['camber']) if 'camber' in outputs \
            else solution.camber
        response.toe = float64_of(outputs['toe']) if 'toe' in outputs else solution.toe
    else:
        x = y = z = qx = qy = qz = qw = response.camber = response.toe = math.nan
    pose.position.x, pose.position.y, pose.position.z = x, y, z
    pose.orientation.x, pose.orientation.y = qx, qy
    pose.orientation.z, pose.orientation.w = qz, qw
    response.status = int(solution.status)
    response.status_text = 'OK' if solution.success else (
        f'{solution.status.name}: {solution.message}')
    response.residual = solution.residual * M_PER_MM
    response.iterations = int(solution.iterations)
    return response


def refused(response, why: str):
    """Fill response for a request that was not solved: REFUSED, no pose (NaN)."""
    pose = response.pose
    pose.position.x = pose.position.y = pose.position.z = math.nan
    pose.orientation.x = pose.orientation.y = pose.orientation.z = math.nan
    pose.orientation.w = response.camber = response.toe = response.residual = math.nan
    response.status = response.REFUSED
    response.status_text = f'REFUSED: {why}'
    response.iterations = 0
    return response
