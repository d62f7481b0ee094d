# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
measure: what is measured from a solution.

Alignment and the instantaneous steer axis, the geometric kingpin, the carrier's motion to
second order, mounts' motion, element values (length, ratio, force, wheel rate) and the bodies'
poses; the registry of quantities (quantities: every quantity an output names, with its
unit and sign). Imports base, model and solve.
"""

from . import quantities
from .alignment import Alignment, alignment, contact_patch, patch_offset
from .bodies import Bodies, body_poses, corner_bodies, frame_along
from .elements import (crossing_notes, element_columns, element_table, element_values,
                       ElementModel, ElementValues, prepare, stop_notes, values_at)
from .kingpin import geometric_kingpin, GeometricKingpin, kingpin_points
from .motion import carrier_motion, guidance_rows, pose_batch
from .mounts import mount_motion, mount_table
from .quantities import columns, columns_of_element, quantity, title, TOPICS

__all__ = ['Alignment', 'alignment', 'Bodies', 'body_poses', 'carrier_motion', 'columns',
           'columns_of_element', 'contact_patch', 'corner_bodies', 'crossing_notes',
           'element_columns', 'element_table', 'element_values', 'ElementModel', 'ElementValues',
           'frame_along', 'geometric_kingpin', 'GeometricKingpin', 'guidance_rows',
           'kingpin_points', 'mount_motion', 'mount_table', 'patch_offset', 'pose_batch',
           'prepare', 'quantities', 'quantity', 'stop_notes', 'title', 'TOPICS', 'values_at']
