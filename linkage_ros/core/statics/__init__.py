# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
statics: a corner under load, with bushings (issue 29; STATICS_SPEC.md).

    solve_loaded(scene, travel_mm, load, rack_mm) -> Loaded    the loaded pose and forces
    compliance(scene, travel_mm, rack_mm) -> Compliance         the rates and the 6x6 matrix

The equilibrium is Newton on the Lagrange (KKT) system with exact derivatives (system.py,
rotation.py, newton.py), continuing from the kinematic pose of solve; the rates come from the
same factorised system at the zero-load equilibrium. Imports base, model, solve and measure;
read only by scenes and programs that ask for statics.
"""

from .compliance import Compliance, compliance, RATE_COLUMNS
from .loaded import Load, Loaded, solve_loaded

__all__ = ['Compliance', 'compliance', 'Load', 'Loaded', 'RATE_COLUMNS', 'solve_loaded']
