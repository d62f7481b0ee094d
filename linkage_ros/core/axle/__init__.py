"""axle: see linkage_ros/core/__init__.py for the layers."""
