# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
solve: how a scene is solved.

The mechanism compiled from a scene (mechanism.py), the compiled kernels (kernel.py,
jacobian_kernel.py, element_kernel.py, body_kernel.py), the state vector, pose Newton, the
paper's method, arc length, continuation and the sweep (kinematics.py). Imports base and model.
"""

from . import paper_method   # the paper's 8 equations as functions, for those who time them
from .continuation import MIN_STEP
from .kinematics import (Continuation, METHODS, Settings, Solution, Sweep, sweep, travel_count,
                         travel_range)
from .mechanism import (compile_scene, design_condition, design_jacobian, equation_table,
                        geometry_of, is_singular, length_errors, lengthened, linearize, Mechanism,
                        radii, SINGULAR_CONDITION)
from .pose_newton import tangent

__all__ = ['compile_scene', 'Continuation', 'design_condition', 'design_jacobian',
           'equation_table', 'geometry_of', 'is_singular', 'length_errors', 'lengthened',
           'linearize', 'Mechanism', 'METHODS', 'MIN_STEP', 'paper_method', 'radii', 'Settings',
           'SINGULAR_CONDITION', 'Solution', 'Sweep', 'sweep', 'tangent', 'travel_count',
           'travel_range']
