# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
What a corner answers to a command, ROS-free: shared by the node and linkage-replay.

protocol (Responder: one corner's solver, answers and reports; OUTPUTS: every message a command
produces, in publishing order), health (what /diagnostics says of a corner), cdr (ROS 2
messages as CDR bytes, built and read in place), frames (a corner's TF frames), elements (the
elements topic), pickups (statics: the loaded answer and each body pickup's force),
robot_description (the URDF of a scene or vehicle). Imports the core only: never rclpy or a
message package.
"""
