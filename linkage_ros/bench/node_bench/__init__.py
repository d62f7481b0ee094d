# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench node: speed on the paths users take, side by side with what it must beat.

cli (the program: its help, options and sections), the sections (solver: core and sweep;
start; latency; vehicle; callback), the bare references (echo), the driver that sends
commands and times the answers (driver), the processes under test (processes) and the
tables printed (tables).
"""

from .cli import main

__all__ = ['main']
