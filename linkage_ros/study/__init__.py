# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Design studies of a suspension corner, loaded only when asked for (linkage-study).

    sensitivity.py   exact d(quantity)/d(hardpoint) by the implicit function theorem
    tolerance.py     hardpoint tolerance stack-up: first order and Monte Carlo
    fit.py           hardpoints fitted to target curves by bounded least squares
    executor.py      batches on the local cores or on a Dask cluster, results in order

The numerical pieces: jets.py (forward-mode derivatives), hardpoints.py (points by name,
moved designs), equations.py and quantities.py (the mechanism and its quantities as
functions of the hardpoints), variant_kernel.py (a compiled solve batched over variants).
"""
