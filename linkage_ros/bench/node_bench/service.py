# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Sections service and lifecycle of linkage-bench node: the solve service, configure's time.

service    one suspension_node process, asked alternately by topic (wheel_travel in,
           wheel_carrier_pose back) and by its solve service (linkage_ros_interfaces/srv/
           Solve), one command when the previous is answered (ping-pong), in alternating
           rounds; the round trip of each and their ratio (goal: service <= 2x topic)
lifecycle  suspension_lifecycle_node: the time of change_state configure (parse the scene,
           load or compile the kernels, create the topics): cold (numba's cache empty: the
           kernels compiled), the first of a new process (loaded from the cache) and again
           after a cleanup in the same process
"""

import tempfile
import time

import numpy as np

from .driver import sine
from .processes import node_script, Target
from .tables import progress, table, us
from ...ros.node import QOS
from ...ros.solve_service import solve_type


def bench_service(args, log_dir, domain_id):
    """Time the node's round trip by topic and by its solve service, in alternating rounds."""
    kind = solve_type()
    if kind is None:
        progress('service: skipped: linkage_ros_interfaces is not built here (linkage-tf2-msgs '
                 'builds it where a C/C++ compiler and the Python headers are)')
        return
    target = Target('node', [node_script(), '--ros-args', '-p', f'scene:={args.scene}'],
                    domain_id, log_dir)
    try:
        driver = target.driver
        client = driver.node.create_client(kind, 'solve', qos_profile=QOS)
        driver.connect()
        if not driver.spin_until(client.service_is_ready, 20.0):
            raise RuntimeError('the node under test serves no solve service')

        def call(travel):
            start = time.perf_counter()
            future = client.call_async(kind.Request(travel=float(travel)))
            if not driver.spin_until(future.done, 5.0):
                raise RuntimeError('no answer from the solve service within 5 s')
            return time.perf_counter() - start

        for travel in sine(args.warmup):
            call(travel)
        driver.ping_pong(sine(args.warmup))
        count, rounds = max(4, args.count // 4 * args.scale), 4
        times = {'topic': [], 'service': []}
        for r in range(rounds):
            chunk = sine(count // rounds)
            times['topic'] += list(driver.ping_pong(chunk))
            times['service'] += [call(travel) for travel in chunk]
            progress(f'service: round {r + 1}/{rounds}')
    finally:
        target.close()
    topic = np.median(times['topic'])
    table(['service', 'round_trips', 'median_us', 'p99_us', 'ratio_to_topic'],
          [(name, len(values), us(values), us(values, 99), float(np.median(values) / topic))
           for name, values in times.items()])


def bench_lifecycle(args, log_dir, domain_id):
    """
    Time change_state configure: cold, a new process's first, and after cleanup.

    cold: numba's cache empty (the kernels compiled in configure), one process, not with
    --quick; first: the
    first configure of each of --starts new processes (the kernels loaded from the cache);
    again: three configures after a cleanup in each of those processes.
    """
    times = {'cold': [], 'first': [], 'again': []}
    if args.quick:     # a smoke run: no compile
        del times['cold']
    else:
        with tempfile.TemporaryDirectory() as empty:
            configures(args, log_dir, domain_id, 'cold', {'NUMBA_CACHE_DIR': empty},
                       times['cold'])
    for start in range(args.starts):
        configures(args, log_dir, domain_id, str(start), {}, times['first'], times['again'])
        progress(f'lifecycle: process {start + 1}/{args.starts}')
    table(['lifecycle', 'configures', 'median_ms', 'max_ms'],
          [(f'configure {case}', len(values), float(np.median(values) * 1e3),
            float(max(values) * 1e3)) for case, values in times.items()])


def configures(args, log_dir, domain_id, name, env, first, again=None):
    """Start suspension_lifecycle_node; time its first configure, then 3 after cleanup."""
    from lifecycle_msgs.msg import Transition
    from lifecycle_msgs.srv import ChangeState

    from ...ros.node import NODE_NAME
    script = str(node_script()).replace('suspension_node', 'suspension_lifecycle_node')
    target = Target(f'lifecycle_{name}', [script, '--ros-args', '-p', f'scene:={args.scene}'],
                    domain_id, log_dir, env=env)
    try:
        driver = target.driver
        client = driver.node.create_client(ChangeState, f'{NODE_NAME}/change_state')
        if not driver.spin_until(client.service_is_ready, 20.0):
            raise RuntimeError('suspension_lifecycle_node serves no change_state')

        def change(label):
            began = time.perf_counter()
            future = client.call_async(ChangeState.Request(transition=Transition(label=label)))
            if not driver.spin_until(future.done, 300.0) or not future.result().success:
                raise RuntimeError(f'{label} failed')
            return time.perf_counter() - began

        first.append(change('configure'))
        for _ in range(3 if again is not None else 0):
            change('cleanup')
            again.append(change('configure'))
    finally:
        target.close()
