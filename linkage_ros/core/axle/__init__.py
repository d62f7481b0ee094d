# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
axle: two corners of a vehicle solved together.

Heave and roll, anti quantities (axle.py), the roll centre (roll_centre.py: the one formula,
which suspension_node and the maps use too) and the anti-roll bar's values (anti_roll_bar.py,
loaded only for an axle with a bar, so not from here). Imports every layer below.
"""

from .axle import (ackermann, ACKERMANN_MIN_STEER, Axle, axle_of, axle_quantities, AxleResult,
                   slopes, solve_axle, wheel_travels)
from .roll_centre import (height_above_ground, patch_motion, roll_centre,
                          roll_centre_of_poses, roll_centre_of_states)

__all__ = ['ackermann', 'ACKERMANN_MIN_STEER', 'Axle', 'axle_of', 'axle_quantities', 'AxleResult',
           'height_above_ground', 'patch_motion', 'roll_centre', 'roll_centre_of_poses',
           'roll_centre_of_states', 'slopes',
           'solve_axle', 'wheel_travels']
