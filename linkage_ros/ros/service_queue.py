# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A service that answers every request, in order, and refuses what it cannot hold: never silence.

    queue = RequestQueue(node, kind, name, answer, refuse, depth)
        answer(request, response) -> response       the service's answer (must not raise)
        refuse(request, response, why) -> response  its REFUSED answer (must not raise)
    queue.service                                   the rclpy Service
    queue.close(why)                                refuse every request still waiting

Why: a service's requests wait in DDS until the executor takes them. In a keep-last history
of depth qos_depth, a burst of more than that (or one that comes while the node is busy, or
not yet scheduled) drops the oldest there, unanswered and unseen, and their clients wait for
ever (2000 requests at once against the default depth of 1000: about 900 never answered,
measured across processes, and still 600 to 800 with a queue that drains DDS at once: the
burst is in before the node runs). So the service's history is keep-all (SERVICE_QOS): DDS
drops no request (one it has no room for stays with the client's writer, reliable flow
control), and the queue takes every request waiting in DDS whenever it runs (at each request
the executor hands it, after each answer, and on a timer while any wait), holds at most
depth of them itself (qos_depth), answers them in their order of arrival, and refuses the
ones beyond at once ('overloaded': REFUSED): every request has an answer, and the memory the
node holds stays bounded. It answers CHUNK requests at a time and then gives the executor
back, a timer going on with the rest: the node's topics are answered under a flood of
requests too. (The responses share the keep-all history; a client that takes none of them
can make a response wait for the writer's room, at most the writer's blocking time, then
count as undelivered.)

The executor hands each request it takes to take(), then the response take() returned, with
the request's header, to the service's send_response: send_response is replaced (as
ros/runtime.py does for the parameter services) so that the header joins its request in the
queue, whose answers are then sent by the queue. A response that cannot be sent (its client
gone) is counted (undelivered), never raised: the executor calls send_response outside its
guard of the callback, so an exception there would end the node.
"""

from __future__ import annotations

from collections import deque
from typing import Callable, TYPE_CHECKING

from rclpy.clock import Clock, ClockType
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

if TYPE_CHECKING:
    from rclpy.node import Node

CHUNK = 16         # requests answered before the executor runs the node's other callbacks
AGAIN = 1e-4       # s: the timer that goes on with the requests still waiting (steady clock)
# the service's QoS: reliable, keep all (DDS drops no request; see the module), volatile
SERVICE_QOS = QoSProfile(history=HistoryPolicy.KEEP_ALL, reliability=ReliabilityPolicy.RELIABLE,
                         durability=DurabilityPolicy.VOLATILE)


class RequestQueue:
    """A service of node answered in order, its overflow refused (module docstring)."""

    def __init__(self, node: Node, kind: type, name: str,
                 answer: Callable[[object, object], object],
                 refuse: Callable[[object, object, str], object], depth: int) -> None:
        """Serve name on node; depth: the most requests held waiting (qos_depth)."""
        self.kind, self.answer, self.refuse = kind, answer, refuse
        self.limit = depth
        self.waiting = deque()     # [request, response, header] in order of arrival
        self.handed = None         # the entry take() made, until its header comes
        self.undelivered = 0       # responses that could not be sent
        self.closed = ''           # why requests are refused from now on, once closed
        self._pumping = False
        self.service = node.create_service(kind, name, self.take, qos_profile=SERVICE_QOS)
        self._send = self.service.send_response
        self.service.send_response = self._send_response
        # steady time: it goes on under simulated time too, whatever /clock does
        self.timer = node.create_timer(AGAIN, self.pump,
                                       clock=Clock(clock_type=ClockType.STEADY_TIME))
        self.timer.cancel()

    def take(self, request, response):
        """Queue a request the executor took; its answer is sent once its header comes."""
        if self.closed:
            return self.refuse(request, response, self.closed)
        if len(self.waiting) >= self.limit:
            return self.refuse(request, response, self._overloaded())
        self.handed = [request, response, None]
        self.waiting.append(self.handed)
        return response

    def _send_response(self, response, header) -> None:
        """Take the header of the request queued (then pump), or send an answer (send_response)."""
        handed, self.handed = self.handed, None
        if handed is not None and response is handed[1]:
            handed[2] = header
            self.pump()
        else:
            self._deliver(response, header)

    def pump(self) -> None:
        """Take what waits in DDS, answer up to CHUNK requests in order; the timer goes on."""
        if self._pumping:
            return
        self._pumping = True
        try:
            self.timer.cancel()
            self._drain()
            for _ in range(CHUNK):
                if not self.waiting or self.waiting[0][2] is None:
                    break
                request, response, header = self.waiting.popleft()
                self._deliver(self._answered(request, response), header)
                self._drain()
            if self.waiting:
                self.timer.reset()
        except Exception:  # noqa: B902 (a timer or service destroyed under it: node stopping)
            pass
        finally:
            self._pumping = False

    def _answered(self, request, response):
        """Return the answer to a request; one that raised is REFUSED, naming the error."""
        try:
            return self.answer(request, response)
        except Exception as exc:  # noqa: B902 (no exception may leave the executor's call)
            text = ' '.join(str(exc).split())[:300]
            return self.refuse(request, self.kind.Response(),
                               f'internal error ({type(exc).__name__}: {text})')

    def _drain(self) -> None:
        """Take the requests waiting in DDS into the queue (refusing those beyond it)."""
        service = self.service
        for _ in range(self.limit):
            try:
                with service.handle:
                    request, header = service.handle.service_take_request(self.kind.Request)
            except Exception:  # noqa: B902 (the service is gone: nothing more to take)
                return
            if request is None:
                return
            if self.closed or len(self.waiting) >= self.limit:
                why = self.closed or self._overloaded()
                self._deliver(self.refuse(request, self.kind.Response(), why), header)
            else:
                self.waiting.append([request, self.kind.Response(), header])

    def _overloaded(self) -> str:
        return (f'overloaded: {len(self.waiting)} requests are waiting, the most this service '
                'holds (qos_depth); send it again once answers come back')

    def _deliver(self, response, header) -> None:
        """Send a response; one that cannot be sent (its client gone) is counted."""
        try:
            self._send(response, header)
        except Exception:  # noqa: B902 (never out of the executor's send_response)
            self.undelivered += 1

    def close(self, why: str) -> None:
        """
        Refuse every request still waiting (with why), and every one after (the node stops).

        Once: a second call (the node destroyed twice, its timer gone) does nothing.
        """
        if self.closed:
            return
        self.closed = why
        try:
            self.timer.cancel()
        except Exception:  # noqa: B902 (the timer is destroyed already: nothing to cancel)
            pass
        self._drain()
        while self.waiting:
            request, response, header = self.waiting.popleft()
            if header is not None:
                self._deliver(self.refuse(request, response, why), header)
