# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Design studies of a suspension corner, loaded only when asked for (linkage-study).

    cli.py, commands.py  the program: its options, and each study run with its progress
    tolerance.py     hardpoint tolerance stack-up: first order and Monte Carlo
    fit.py           hardpoints fitted to target curves by bounded least squares
    targets.py       the fit's targets file; fitted_scene.py the fitted design as a scene
    executor.py      batches on the local cores or on a Dask cluster, results in order
    tables.py, plots.py  what a study writes

The numerics they stand on are the core's (linkage_ros.core.vary): exact sensitivities,
the hardpoints by name and moved designs, variants of a design solved in batches.
"""
