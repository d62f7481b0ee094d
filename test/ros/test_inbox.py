# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The node's input callbacks (ros/inbox.py): losses told by sequence numbers, no exception out.

SequenceGaps counts, from the publication sequence numbers of the messages received, how many
of each publisher's were lost between them: for one publisher, exactly the numbers missing
between its first and its last received (hypothesis over any subset dropped); for publishers
numbered apart, each its own. An Inbox takes the message info as rclpy's executors hand it
(one (data, info) pair: rclpy 7.1.6's EventsExecutor; or two arguments: its Python
executors), declares two arguments so that rclpy hands it the info at all, and turns an
exception of its take into failed(exc).
"""

import inspect

from hypothesis import given, settings, strategies as st
from linkage_ros.ros.inbox import Inbox, SequenceGaps
import pytest


@settings(deadline=None, database=None, max_examples=300)
@given(total=st.integers(1, 400), data=st.data())
def test_one_publisher_s_losses_are_the_numbers_missing_between_those_received(total, data):
    kept = sorted(data.draw(st.sets(st.integers(1, total), min_size=1)))
    gaps = SequenceGaps()
    counted = sum(gaps.add(n) for n in kept)
    assert counted == (kept[-1] - kept[0] + 1) - len(kept)


def test_two_publishers_numbered_apart_are_counted_each_its_own():
    # a publisher at 1000 and one just started, interleaved; 1003 and 5, 6 lost
    gaps = SequenceGaps()
    received = [1000, 1, 1001, 2, 1002, 3, 1004, 4, 7]
    assert [gaps.add(n) for n in received] == [0, 0, 0, 0, 0, 0, 1, 0, 2]


def test_a_publisher_that_restarts_numbering_is_a_new_one_not_a_loss():
    gaps = SequenceGaps()
    assert [gaps.add(n) for n in (1, 2, 3, 1, 2, 3, 5)] == [0, 0, 0, 0, 0, 0, 1]


class Taken:
    """What an Inbox handed over: data taken, losses counted, exceptions."""

    def __init__(self, fail_on=None):
        self.data, self.lost, self.failed, self.fail_on = [], [], [], fail_on

    def take(self, data):
        if data == self.fail_on:
            raise ZeroDivisionError('in take')
        self.data.append(data)

    def inbox(self):
        return Inbox(self.take, self.lost.append, self.failed.append)


def test_an_inbox_takes_the_pair_as_one_argument_or_two_and_counts_the_gap():
    taken = Taken()
    inbox = taken.inbox()
    inbox((b'a', {'publication_sequence_number': 1}))      # EventsExecutor (rclpy 7.1.6)
    inbox(b'b', {'publication_sequence_number': 4})        # rclpy's Python executors
    inbox(b'c')                                             # an executor that gives no info
    assert (taken.data, taken.lost, taken.failed) == ([b'a', b'b', b'c'], [2], [])


def test_an_exception_of_take_goes_to_failed_and_not_out():
    taken = Taken(fail_on=b'bad')
    inbox = taken.inbox()
    inbox((b'bad', {'publication_sequence_number': 1}))
    inbox((b'good', {'publication_sequence_number': 2}))
    assert taken.data == [b'good']
    assert [type(e) for e in taken.failed] == [ZeroDivisionError]


def test_an_inbox_declares_two_arguments_so_that_rclpy_hands_it_the_info():
    # rclpy (Subscription.callback) binds one argument first, then two
    signature = inspect.signature(Taken().inbox())
    with pytest.raises(TypeError):
        signature.bind(object())
    signature.bind(object(), object())
