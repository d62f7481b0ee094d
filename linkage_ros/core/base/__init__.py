# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
base: what every layer of the core stands on.

Errors, the Status code, finiteness and size limits, the stated ranges of input numbers
(ranges.py), the memory a run may take (memory.py), geometry of points and rotations (numpy;
so3.py the compiled forms), a spring's force table (force_table.py, compiled). Imports
nothing of the core above it.
"""

from .errors import LinkageError, listed
from .finite import all_finite, is_finite_number, lost_cells, say_lost
from .force_table import table_force
from .geometry import (camber_toe, carrier_points, cross, exp_so3, M_PER_MM,
                       matrix_from_quaternion, MM_PER_M, N_MM_PER_NM_DEG, perpendicular,
                       point_velocity, quaternion_from_matrix,
                       spin_axis_of, trilaterate, unit)
from .limits import (check_position_count, FORCE_LIMIT_N, LENGTH_LIMIT_MM, MAX_POSITIONS,
                     MOMENT_LIMIT_NM, positions_needed, within_length_limit, wrench_problem)
from .memory import address_space_room, cgroup_room, memory_room, Need, refuse_if_short, Room
from .ranges import RANGE, Range, RANGES, say_ranges
from .status import Status

__all__ = ['address_space_room', 'all_finite', 'camber_toe', 'carrier_points', 'cgroup_room',
           'check_position_count', 'cross', 'exp_so3', 'FORCE_LIMIT_N', 'is_finite_number',
           'LENGTH_LIMIT_MM', 'LinkageError', 'listed', 'lost_cells', 'M_PER_MM',
           'matrix_from_quaternion', 'MAX_POSITIONS', 'memory_room', 'MM_PER_M',
           'MOMENT_LIMIT_NM', 'N_MM_PER_NM_DEG', 'Need', 'perpendicular', 'point_velocity',
           'positions_needed', 'quaternion_from_matrix', 'Range', 'RANGE', 'RANGES',
           'refuse_if_short', 'Room', 'say_lost', 'say_ranges', 'spin_axis_of', 'Status',
           'table_force', 'trilaterate', 'unit', 'within_length_limit', 'wrench_problem']
