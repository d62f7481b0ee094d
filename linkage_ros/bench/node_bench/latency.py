# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Section latency of linkage-bench node: suspension_node against the echo node, one corner."""

import sys

import numpy as np

from .driver import sine
from .processes import node_script, Target
from .tables import progress, table, us


def bench_latency(args, log_dir, domain_id):
    """suspension_node and the echo node, measured alternately; then the rate ladder."""
    targets = [Target('node', [node_script(), '--ros-args', '-p', f'scene:={args.scene}'],
                      domain_id, log_dir),
               Target('echo', [sys.executable, '-m', 'linkage_ros.bench.node_bench', '--echo'],
                      domain_id, log_dir)]
    ladder = []
    try:
        for target in targets:
            target.driver.connect()
            target.driver.ping_pong(sine(args.warmup))
        count = args.count * args.scale
        latency = {(t.name, kind): [] for t in targets for kind in ('paced', 'ping-pong')}
        rounds = 4
        for r in range(rounds):
            for target in targets:
                chunk = sine(count // rounds)
                sent, got, _, values = target.driver.paced(chunk, args.latency_rate)
                if got < sent:
                    raise RuntimeError(f'{target.name}: {sent - got} commands lost at '
                                       f'{args.latency_rate:g} Hz')
                latency[target.name, 'paced'] += list(values)
                latency[target.name, 'ping-pong'] += list(target.driver.ping_pong(chunk))
            progress(f'latency: round {r + 1}/{rounds}')
        rows = []
        for kind in ('paced', 'ping-pong'):
            echo = np.median(latency['echo', kind])
            for target in targets:
                values = latency[target.name, kind]
                rows.append((target.name, kind, len(values), us(values), us(values, 99),
                             float(np.median(values) / echo)))
        table(['latency', 'mode', 'commands', 'median_us', 'p99_us', 'ratio_to_echo'], rows)
        for rate in args.rates:
            for target in targets:
                target.driver.connect()         # a backlog of the previous rate drains first
                count = max(1, int(rate * args.duration * args.scale))
                sent, got, lag, values = target.driver.paced(
                    sine(count), rate, label=f'latency: {target.name} at {rate} Hz')
                ladder.append((target.name, rate, sent, got, sent - got, lag * 1000.0,
                               lag * 1000.0 <= args.lag_ms and got == sent, us(values),
                               us(values, 99)))
                progress(f'latency: {target.name} at {rate} Hz: {got}/{sent} answered, '
                         f'last {lag * 1000.0:.1f} ms after the last command')
    finally:
        for target in targets:
            target.close()
    table(['rate', 'hz', 'sent', 'answered', 'lost', 'last_answer_lag_ms', 'kept_up',
           'median_us', 'p99_us'], ladder)
    return ladder
