# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A spring's force table, interpolated: the one formula of the kernels and of Python (numba).

element_kernel.py compiles table_force into its kernels (base/compiled.py's one cache key
recompiles them after an edit here); model/elements.py's Element.spring_at calls the same
compiled function from Python.
"""

from .compiled import jit


@jit
def table_force(deflection, force, x):
    """
    Return a force table's (force N, stiffness dF/dx N/mm) at deflection x mm.

    deflection (n,) mm rising, force (n,) N, n >= 2. Interpolated linearly and held at the
    end values outside, as Chrono's ChFunctionInterp (no extrapolation): the stiffness is the
    slope of the table's segment at x, 0 outside.
    """
    n = deflection.shape[0]
    if x <= deflection[0]:
        return force[0], 0.0
    if x >= deflection[n - 1]:
        return force[n - 1], 0.0
    i = 1
    while deflection[i] < x:
        i += 1
    slope = (force[i] - force[i - 1]) / (deflection[i] - deflection[i - 1])
    return force[i - 1] + slope * (x - deflection[i - 1]), slope
