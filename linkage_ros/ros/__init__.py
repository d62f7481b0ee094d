# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The ROS 2 adapter.

suspension_node (entry: the process; node: owns the corners; corner: one wheel; parameters;
qos; sinks: recorders), its messages and diagnostics (messages; their ROS-free state is
linkage_ros.answer.health) and markers, and the helpers of launch-free node tests (testing; the
pytest plugin linkage_ros_pytest wraps them in fixtures).
"""
