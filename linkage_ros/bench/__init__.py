# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Benchmarks and their references.

The extended-precision reference, the peer solvers, and linkage-bench (cli.py: a subcommand per
benchmark, each a module here: accuracy, node, soak, sweep, axle, map, vehicle (sheet.py),
study, replay, kc, chrono). All timing of the package is here; the programs of tools/ give
the benchmarks their parse_args and request, never a clock.
"""
