# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
statics: a corner under load, with bushings (issue 29; doc/kc.md).

    Statics(scene).solve(travel_mm, load, rack_mm) -> Loaded   command after command
    Statics(scene).rates(travel_mm, rack_mm) -> Compliance      the rates and the 6x6 matrix
    solve_loaded(scene, travel_mm, load, rack_mm) -> Loaded    one solve (a Statics of its own)
    compliance(scene, travel_mm, rack_mm) -> Compliance         likewise

The equilibrium is Newton on the Lagrange (KKT) system with the exact derivative of its
residual (kernel.py, rotation.py, newton.py), the KKT system reduced and solved along its
structure (kkt.py); the rates come from the same system at the zero-load equilibrium; the
pickup forces from the multipliers and energies (forces.py): all compiled, one call per
command (command.py). A Statics goes on from its last equilibrium, the kinematic pose of
solve where it has none (statics.py). Imports base, model, solve and measure; read only by
scenes and programs that ask for statics.
"""

from . import kernels   # the compiled kernels, by module, for the benchmarks
from .compliance import Compliance, RATE_COLUMNS
from .loaded import Load, Loaded
from .statics import compliance, solve_loaded, Statics

__all__ = ['Compliance', 'compliance', 'kernels', 'Load', 'Loaded', 'RATE_COLUMNS',
           'solve_loaded', 'Statics']
