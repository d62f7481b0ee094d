"""
The ROS 2 adapter.

suspension_node, its messages, diagnostics and markers, and the pytest plugin for
launch-free node tests.
"""
