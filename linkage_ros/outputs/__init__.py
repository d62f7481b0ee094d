# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
outputs: what the programs write, checked before any work and written whole or in place.

The guard (guard.py) refuses, before any work, an output that is an input (by path, link or
hard link), another output, a folder, a disk, or a file or device that cannot be written; the
whole-file writer (whole.py) writes a file whole beside it and renames it, and a device or a
FIFO in place, never replacing it; the table writer (table.py) writes every program's tables
with one rule for numbers, NaN and infinity (doc/tables.md). Imports core.base only.
"""

from .guard import check_output, check_outputs, output_folder, output_problem, same_file
from .table import cell, is_parquet, write_csv, write_table, Written
from .whole import in_place, save_figure, whole_file

__all__ = ['cell', 'check_output', 'check_outputs', 'in_place', 'is_parquet', 'output_folder',
           'output_problem', 'same_file', 'save_figure', 'whole_file', 'write_csv',
           'write_table', 'Written']
