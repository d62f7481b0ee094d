# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

import math

import pytest


def test_a_50_mm_bump_lifts_the_wheel_and_gives_negative_camber(suspension_node, send_travel):
    suspension_node(scene='five_link', method='fast')
    answer = send_travel(0.05, timeout=5.0)                     # m, + = bump
    assert answer.pose.pose.position.z == pytest.approx(0.30 + 0.05)   # design centre 0.30 m
    assert -math.radians(3.0) < answer.camber < 0.0             # rad, wheel top inboard


def test_a_travel_beyond_the_bump_limit_gets_no_pose_but_the_reason(suspension_node,
                                                                    send_travel):
    suspension_node(scene='five_link')
    answer = send_travel(0.5)                                   # five_link stops at 0.387 m
    assert answer.pose is None and 'out of reach' in answer.diagnostics.message
