# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
vehicle: the setup sheet of a vehicle with masses, from its axles' exact kinematics.

The elastic parts of an axle as one energy of its wheel travels, and the rates and roll
stiffness from it (elastic.py); the roll axis, roll gradient, load transfer and pitch
(balance.py, formulas on floats); the sheet (sheet.py). Imports every layer below; loaded
only by a program that asks for a setup sheet (linkage-vehicle, linkage-bench vehicle).
Formulas and sources: doc/vehicle.md.
"""

from .balance import (G, load_transfer, pitch_gradient, ride_frequency, roll_axis_height,
                      roll_gradient, Transfer)
from .elastic import (Elastic, ELASTIC_PARTS, elastic_parts, heave_rate, roll_moment,
                      roll_stiffness, series, textbook_roll_stiffness)
from .sheet import setup_sheet, SetupSheet

__all__ = ['Elastic', 'ELASTIC_PARTS', 'elastic_parts', 'G', 'heave_rate', 'load_transfer',
           'pitch_gradient', 'ride_frequency', 'roll_axis_height', 'roll_gradient',
           'roll_moment', 'roll_stiffness', 'series', 'setup_sheet', 'SetupSheet',
           'textbook_roll_stiffness', 'Transfer']
