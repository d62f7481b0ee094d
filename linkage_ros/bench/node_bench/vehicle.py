# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Section vehicle of linkage-bench node: four corners against a four-corner echo node."""

import sys

import numpy as np

from .driver import sine
from .echo import CORNERS
from .processes import node_script, Target
from .tables import progress, table, us

VEHICLE = 'demo_vehicle'


def bench_vehicle(args, log_dir, domain_id):
    """Four corners at args.hz each: Float64 per corner, then one JointState per step."""
    prefixes = tuple(f'{c}/' for c in CORNERS)
    targets = [Target('node', [node_script(), '--ros-args', '-p', f'vehicle:={VEHICLE}'],
                      domain_id, log_dir, prefixes),
               Target('echo', [sys.executable, '-m', 'linkage_ros.bench.node_bench',
                               '--echo-vehicle'], domain_id, log_dir, prefixes)]
    rows, medians = [], {}
    try:
        steps = int(args.hz * args.seconds * args.scale)
        for joint_states in (False, True):
            mode = 'joint_states' if joint_states else 'float64_per_corner'
            for target in targets:
                target.driver.connect(joint_states)
                sent, got, lag, values = target.driver.paced(
                    sine(steps), args.hz, joint_states, label=f'vehicle: {target.name}, {mode}')
                medians[target.name, mode] = np.median(values) if len(values) else np.nan
                rows.append([target.name, mode, sent, got, sent - got, lag * 1000.0,
                             us(values), us(values, 99)])
                progress(f'vehicle: {target.name}, {mode}: {got}/{sent} steps answered, last '
                         f'{lag * 1000.0:.1f} ms after the last step')
    finally:
        for target in targets:
            target.close()
    for row in rows:
        row.append(float(medians[row[0], row[1]] / medians['echo', row[1]]))
    table(['vehicle', 'mode', 'steps', 'answered', 'lost', 'last_answer_lag_ms',
           'step_median_us', 'step_p99_us', 'ratio_to_echo'], rows)
