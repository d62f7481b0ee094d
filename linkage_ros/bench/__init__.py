# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Benchmarks and their references.

The extended-precision reference, the peer solvers, and linkage-bench (cli.py: a subcommand per
benchmark: accuracy, node, soak, sweep, axle, map, study, replay).
"""
