"""
measure: what is measured from a solution.

Alignment and the instantaneous steer axis, the geometric kingpin, the carrier's motion to
second order, mounts' motion, element values (length, ratio, force, wheel rate) and the bodies'
poses. Imports base, model and solve.
"""

from .alignment import Alignment, alignment, contact_patch
from .bodies import Bodies, body_poses, corner_bodies, frame_along
from .elements import (element_columns, element_table, element_values, ElementModel, ElementValues,
                       prepare, values_at)
from .kingpin import geometric_kingpin, GeometricKingpin, kingpin_points
from .motion import carrier_motion, guidance_rows, pose_batch
from .mounts import mount_motion, mount_table

__all__ = ['Alignment', 'alignment', 'Bodies', 'body_poses', 'carrier_motion', 'contact_patch',
           'corner_bodies', 'element_columns', 'element_table', 'element_values', 'ElementModel',
           'ElementValues', 'frame_along', 'geometric_kingpin', 'GeometricKingpin',
           'guidance_rows', 'kingpin_points', 'mount_motion', 'mount_table', 'pose_batch',
           'prepare', 'values_at']
