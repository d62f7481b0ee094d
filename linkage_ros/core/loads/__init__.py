# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
loads: load cases on a vehicle, from its tyres to every bracket (issue 39; doc/loads.md).

    Loads(vehicle).solve(case) -> CaseAnswer     the tyre loads, each corner at its loaded
                                                 ride height, the forces at every pickup
    built_in_cases(), read_cases(path)           the cases (config/loads/cases.yaml)

The cases (cases.py), what they need of a vehicle (vehicle_data.py, from the setup sheet),
the tyre loads (transfer.py), the anti-roll bar under load (bar.py), the one call into the
statics (corner.py), the loaded ride height (ride_height.py), a case solved (answer.py) and
its tables (tables.py). Imports every layer below but vary; loaded only by a program that
asks for load cases (linkage-loads, linkage-bench loads).
"""

from . import tables
from .answer import BarAnswer, CaseAnswer, CornerAnswer, Loads
from .cases import (built_in_cases, CornerLoad, describe, LoadCase, parse_cases, RANGES,
                    read_cases)
from .corner import solve_corner
from .transfer import CornerTyre, tyre_loads, TyreLoads
from .vehicle_data import LoadsVehicle, prepare, sheet_problem

__all__ = ['BarAnswer', 'built_in_cases', 'CaseAnswer', 'CornerAnswer', 'CornerLoad',
           'CornerTyre', 'describe', 'LoadCase', 'Loads', 'LoadsVehicle', 'parse_cases',
           'prepare', 'RANGES', 'read_cases', 'sheet_problem', 'solve_corner', 'tables',
           'TyreLoads', 'tyre_loads']
