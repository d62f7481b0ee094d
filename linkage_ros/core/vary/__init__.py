# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
vary: how a solution varies with the design, exactly, and many designs solved at once.

The hardpoints of a scene by name and the scene they describe once moved (hardpoints.py); the
mechanism's equations (equations.py) and the measured quantities (outputs.py) as jets of the
hardpoints; exact sensitivities by the implicit function theorem (sensitivity.py, with its
compiled form pose_kernel.py); variants of a design solved in batches (variants.py over
variant_kernel.py, compiled); bushing rates as variables and the compliance rates as outputs
(bushings.py, over statics). What linkage-study's sensitivity, tolerance and fit stand on.
Imports base, model, solve, measure and statics.
"""

from .bushings import (bushing_names, bushing_values, compliance_of, compliance_rates,
                       rate_names, with_bushings)
from .hardpoints import (AXES, coordinate_names, Design, link_fractions, load_design,
                         scene_data_with, scene_with)
from .outputs import ALIGNMENT_COLUMNS, element_names, SWEEP_COLUMNS
from .sensitivity import (available, check_quantities, did_you_mean, length_rates,
                          pose_derivative, rows, sensitivities, Sensitivity, sweep_column_rates)
from .variants import controls_of, design_starts, poses, QUANTITIES, solve_variants

__all__ = ['ALIGNMENT_COLUMNS', 'available', 'AXES', 'bushing_names', 'bushing_values',
           'check_quantities', 'compliance_of', 'compliance_rates', 'controls_of',
           'coordinate_names', 'Design', 'design_starts', 'did_you_mean', 'element_names',
           'length_rates', 'link_fractions', 'load_design', 'pose_derivative', 'poses',
           'QUANTITIES', 'rate_names', 'rows', 'scene_data_with', 'scene_with', 'Sensitivity',
           'sensitivities', 'solve_variants', 'SWEEP_COLUMNS', 'sweep_column_rates',
           'with_bushings']
