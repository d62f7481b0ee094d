# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Section step of linkage-bench node: one bushed vehicle step in process (no DDS).

vehicle:=demo_vehicle_bushings, its callbacks called directly as the executor would call
them for one step of the vehicle section: a contact_wrench per corner (vehicle.
corner_wrenches), then one JointState with the four travels (the same slow sine). Timed per
step (wall clock, perf_counter), in each configuration of the vehicle section
(vehicle.BUSHED_NODES: lean, the node's defaults, every output on), one node after the other
in this process, with discovery OFF (no subscriber: a publish costs its rclpy call only).
What it leaves out is what DDS adds: the executor's five callbacks a step and the
subscribers' deliveries.
"""

import os
import time

import numpy as np
import rclpy

from .driver import sine
from .echo import CORNERS
from .tables import progress, table, us
from .vehicle import BUSHED, BUSHED_NODES, corner_wrenches
from ...answer.cdr import joint_state_cdr
from ...ros.isolation import init_context

WARMUP = 50      # steps not counted: the first answers build what later ones reuse


def joint_states(travels_m):
    """Return per step the CDR of one JointState with every corner's travel (m)."""
    names = [f'{corner}_travel' for corner in CORNERS]
    return [joint_state_cdr(divmod(k * 1_000_000, 1_000_000_000), '', names, [float(t)] * 4)
            for k, t in enumerate(travels_m)]


def bench_step(args):
    """Time one bushed vehicle step in process in each configuration; print the table."""
    from rclpy.parameter import Parameter

    from ...ros.node import SuspensionNode
    count = int(args.count * args.scale)
    travels = sine(count + WARMUP)
    wrenches, states = corner_wrenches(len(travels)), joint_states(travels)
    context = init_context(args.domain_id, 'OFF')      # no subscriber, and none outside
    rows, base = [], None
    try:
        for name, params in BUSHED_NODES:
            node = SuspensionNode(context=context, parameter_overrides=[
                Parameter('vehicle', value=BUSHED),
                *(Parameter(k, value=v) for k, v in params.items())])
            corners = [node.corners[c] for c in CORNERS]
            times = []
            for k, (wrench, state) in enumerate(zip(wrenches, states)):
                start = time.perf_counter()
                for corner, data in zip(corners, wrench):
                    corner.on_wrench(data)
                node.on_vehicle_joint_states(state)
                if k >= WARMUP:
                    times.append(time.perf_counter() - start)
            failed = sum(c.health.failures_total for c in corners)
            node.destroy_node()
            base = base or np.median(times)
            load = os.getloadavg()[0]
            rows.append((name, len(times), us(times), float(np.mean(times) * 1e6),
                         float(np.median(times) / base), failed, load))
            progress(f'step: {name}: median {us(times):.0f} us; load average {load:.2f}')
    finally:
        rclpy.try_shutdown(context=context)
    table(['step', 'steps', 'median_us', 'mean_us', 'ratio_to_lean', 'failures',
           'load_average'], rows)
