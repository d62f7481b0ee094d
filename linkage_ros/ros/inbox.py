# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The callback of each input subscription of suspension_node: losses counted, no exception out.

    subscription(node, kind, topic, Inbox(take, lost, failed), qos, raw=True)

Inbox(take, lost, failed) is given each message (CDR bytes) with its rmw message info and
    - counts the messages lost before it (SequenceGaps over the publication sequence numbers
      rmw gives: a reliable keep-last queue that overflows in a flood drops the oldest, a
      best-effort one drops any) and hands the count to lost(n);
    - hands the message to take(data);
    - turns any exception of either into failed(exc): none leaves the callback, which would
      end the executor's spin and the node with it.

Why sequence numbers: Fast DDS (2.14, rmw_fastrtps 8.4) raises no message-lost event when a
subscription's history overflows (reliable or best effort, in one process or across two:
measured), so the gaps in the numbers that each publisher gives its messages are what shows
a loss. rclpy gives a callback that takes two arguments the message info with each message
(publication_sequence_number among its fields); rclpy 7.1.6's EventsExecutor, the node's,
passes the pair as one argument instead (a two-argument function then raises SystemError in
the executor), its Python executors as two: an Inbox declares two arguments and takes either.
rclpy 7.1 gives no publisher gid, so the numbers of several publishers on one topic are told
apart by continuity (SequenceGaps): exact for one publisher per topic (a simulator's command
stream); with several, a publisher matched late, or one restarted beside one that is gone,
can have its numbers counted against another's. What a publisher sent before the first of its
messages that the node takes is not counted: a publisher that ran before the node matched it
numbered messages that were never sent to it.
"""

from __future__ import annotations

import inspect
from typing import Callable

# The publishers of one topic whose numbering SequenceGaps follows at most (a restarted
# publisher numbers from 1 again: the oldest follower is dropped).
MAX_PUBLISHERS = 16
_TWO = inspect.Signature([inspect.Parameter(name, inspect.Parameter.POSITIONAL_ONLY)
                          for name in ('data', 'info')])


class SequenceGaps:
    """
    Messages lost between those received, told by their publication sequence numbers.

    add(number) -> how many messages of that publisher were lost just before this one.
    Each publisher numbers its messages 1, 2, 3, ... in the order it sends them, and a
    subscription receives each publisher's in that order, with gaps where some were lost. A
    number continues the publisher whose last number is the largest below it; a number that
    continues none (the first of a publisher, or one matched late) starts a publisher, and
    what it sent before is not counted: it was not sent to this subscription.
    """

    def __init__(self) -> None:
        self.lasts: list[int] = []    # the last number of each publisher, most recent first

    def add(self, number: int) -> int:
        """Take the number of a message received; return the messages lost just before it."""
        best = -1
        for i, last in enumerate(self.lasts):
            if last < number and (best < 0 or last > self.lasts[best]):
                best = i
        if best < 0:
            self.lasts.insert(0, number)
            del self.lasts[MAX_PUBLISHERS:]
            return 0
        lost = number - self.lasts[best] - 1
        del self.lasts[best]
        self.lasts.insert(0, number)
        return lost


class Inbox:
    """One input subscription's callback (module docstring)."""

    __signature__ = _TWO      # what rclpy reads to hand it the message info

    def __init__(self, take: Callable[[bytes], None], lost: Callable[[int], None],
                 failed: Callable[[BaseException], None]) -> None:
        self.take, self.lost, self.failed = take, lost, failed
        self.gaps = SequenceGaps()

    def __call__(self, *args) -> None:
        """Take (data, info) as one argument or two (see the module); never raises."""
        try:
            data, info = args if len(args) == 2 else _pair(args[0])
            number = info.get('publication_sequence_number') if isinstance(info, dict) \
                else None
            if isinstance(number, int) and number > 0:
                lost = self.gaps.add(number)
                if lost:
                    self.lost(lost)
            self.take(data)
        except Exception as exc:  # noqa: B902 (no exception may leave a ROS callback)
            try:
                self.failed(exc)
            except Exception:  # noqa: B902 (the failure's own report failed: the node goes on)
                pass


def _pair(given):
    """Return (data, info) of what the executor handed over as one argument."""
    if isinstance(given, tuple) and len(given) == 2:
        return given
    return given, None    # a message alone (an executor that gives no info)
