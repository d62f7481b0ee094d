"""
axle: two corners of a vehicle solved together.

Heave and roll, roll centre, anti quantities (axle.py) and the anti-roll bar's values
(anti_roll_bar.py, loaded only for an axle with a bar, so not from here). Imports every layer
below.
"""

from .axle import (ackermann, ACKERMANN_MIN_STEER, Axle, axle_of, axle_quantities, AxleResult,
                   height_above_ground, roll_centre, roll_centre_of_poses, slopes, solve_axle,
                   wheel_travels)

__all__ = ['ackermann', 'ACKERMANN_MIN_STEER', 'Axle', 'axle_of', 'axle_quantities', 'AxleResult',
           'height_above_ground', 'roll_centre', 'roll_centre_of_poses', 'slopes', 'solve_axle',
           'wheel_travels']
