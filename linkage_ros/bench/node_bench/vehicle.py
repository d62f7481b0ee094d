# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Section vehicle of linkage-bench node: four corners against a four-corner echo node.

demo_vehicle (rigid) with one Float64 per corner per step, then one JointState per step; then
demo_vehicle_bushings (issue 37) as a simulator drives a compliant vehicle: per step a
contact_wrench per corner (a cornering load swept as a sine, the right corners' mirrored in
y), then one JointState with the four travels. Each corner of the node answers with its
loaded pose (a Statics solve per corner per step); the echo node takes the same wrenches and
echoes the travels. The bushed node runs three ways, side by side with the echo node in one
run (BUSHED_NODES): lean, as a simulator needs it (the loaded poses alone, one PoseStamped
per corner per step, the echo node's traffic: tf, pickups, angles, elements and roll_centres
false); the node's defaults (camber, toe, elements, roll centres, TF and a WrenchStamped per
pickup); and every output on (alignment and markers too). The step latency is from sending a
step (its first wrench) to the last of its four poses. cpu_us_per_step: the CPU time the
target's process used over the run (every thread: the executor's and DDS's; /proc), per step
answered. Each row ends with the 1-minute load average after its run (a shared machine: read
the ratios).
"""

import math
import os
import sys

import numpy as np

from .driver import sine
from .echo import CORNERS
from .processes import node_script, Target
from .tables import progress, table, us
from ...answer.cdr import wrench_stamped_cdr

VEHICLE = 'demo_vehicle'
BUSHED = 'demo_vehicle_bushings'
WRENCHED = 'joint_states+contact_wrench'
# The bushed node's configurations: (target name, its parameters)
BUSHED_NODES = (('node_lean', {'tf': False, 'pickups': False, 'angles': False,
                               'elements': False, 'roll_centres': False}),
                ('node_defaults', {}),
                ('node_all', {'alignment': True, 'markers': True}))


def corner_wrenches(count, frame_id='base_link'):
    """
    Return per step the four corners' contact wrenches (CDR), in CORNERS order.

    A cornering load swept once as a sine over the steps: lateral up to 3 kN, longitudinal
    200 N, vertical 4 kN, an aligning moment up to 50 N m; the right corners' mirrored in y
    (force y and moments x, z change sign).
    """
    steps = []
    for p in np.linspace(0.0, 2.0 * math.pi, count):
        force, moment = (200.0 * math.cos(p), 3000.0 * math.sin(p), 4000.0), \
            (0.0, 0.0, 50.0 * math.sin(p))
        mirrored = (force[0], -force[1], force[2]), (-moment[0], moment[1], -moment[2])
        steps.append([wrench_stamped_cdr((0, 0), frame_id,
                                         *(mirrored if c.endswith('right') else (force, moment)))
                      for c in CORNERS])
    return steps


def _run(targets, steps, args, modes, rows, medians):
    """Drive each target through each mode ((name, joint_states, wrenches)); add rows."""
    try:
        for mode, joint_states, wrenches in modes:
            for target in targets:
                target.driver.connect(joint_states, wrenches=wrenches is not None)
                cpu = target.cpu_seconds()
                sent, got, lag, values = target.driver.paced(
                    sine(steps), args.hz, joint_states, label=f'vehicle: {target.name}, {mode}',
                    wrenches=wrenches)
                cpu = (target.cpu_seconds() - cpu) / max(got, 1) * 1e6   # us a step answered
                medians[target.name, mode] = np.median(values) if len(values) else np.nan
                load = os.getloadavg()[0]
                rows.append([target.name, mode, sent, got, sent - got, lag * 1000.0,
                             us(values), us(values, 99), cpu, load])
                progress(f'vehicle: {target.name}, {mode}: {got}/{sent} steps answered, last '
                         f'{lag * 1000.0:.1f} ms after the last step, median '
                         f'{us(values):.0f} us, process CPU {cpu:.0f} us a step; load average '
                         f'{load:.2f}')
    finally:
        for target in targets:
            target.close()


def targets_of(vehicle, log_dir, domain_id, nodes=(('node', {}),)):
    """
    Return the node (vehicle:=vehicle) and the four-corner echo node, as Targets.

    nodes: (name, {parameter: value}) of each node process to run, in that order.
    """
    prefixes = tuple(f'{c}/' for c in CORNERS)
    return [*(Target(name, [node_script(), '--ros-args', '-p', f'vehicle:={vehicle}',
                            *(a for k, v in params.items()
                              for a in ('-p', f'{k}:={str(v).lower()}'))],
                     domain_id, log_dir, prefixes) for name, params in nodes),
            Target('echo', [sys.executable, '-m', 'linkage_ros.bench.node_bench',
                            '--echo-vehicle'], domain_id, log_dir, prefixes)]


def bench_vehicle(args, log_dir, domain_id):
    """Four corners at args.hz each: rigid, Float64 then JointState; bushed, with wrenches."""
    rows, medians = [], {}
    steps = int(args.hz * args.seconds * args.scale)
    _run(targets_of(VEHICLE, log_dir, domain_id), steps, args,
         [('float64_per_corner', False, None), ('joint_states', True, None)], rows, medians)
    _run(targets_of(BUSHED, log_dir, domain_id, BUSHED_NODES), steps, args,
         [(WRENCHED, True, corner_wrenches(steps))], rows, medians)
    for row in rows:
        row.append(float(medians[row[0], row[1]] / medians['echo', row[1]]))
    table(['vehicle', 'mode', 'steps', 'answered', 'lost', 'last_answer_lag_ms',
           'step_median_us', 'step_p99_us', 'cpu_us_per_step', 'load_average',
           'ratio_to_echo'], rows)
