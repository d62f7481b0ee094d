# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Section start of linkage-bench node: from a process's launch to its first answer."""

import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from .processes import node_script, Target
from .tables import progress, table
from ...core.model import config_dir

QUICK_DISCOVERY = config_dir() / 'fastdds_quick_discovery.xml'


def bench_start(args, log_dir, domain_id):
    """
    Time launch to first answer: warm and cold (empty) numba cache, default and quick discovery.

    Each launch is timed from a fresh process, whose DDS participant (the client) reads the
    discovery profile as the node does: Fast DDS reads it once per process.
    """
    quick = {'FASTRTPS_DEFAULT_PROFILES_FILE': str(QUICK_DISCOVERY)}
    cases = [('core', 'warm', {}), ('suspension_node', 'warm', {}),
             ('suspension_node', 'warm quick-discovery', quick),
             ('core', 'cold', {}), ('suspension_node', 'cold quick-discovery', quick)]
    rows = []
    for what, case, env in cases:
        times = []
        for _ in range(1 if 'cold' in case else args.starts):
            with tempfile.TemporaryDirectory() as empty:    # a new one each time: cold
                child = dict(os.environ, **env, **(
                    {'NUMBA_CACHE_DIR': empty} if 'cold' in case else {}))
                out = subprocess.run(
                    [sys.executable, '-m', 'linkage_ros.bench.node_bench', '--start-once', what,
                     '--scene', args.scene, '--domain-id', str(domain_id)], env=child,
                    capture_output=True, text=True, check=True, timeout=300)
                times.append([float(v) for v in out.stdout.split()])
        launch = [t[0] for t in times]
        rows.append((what, case, len(times), float(np.median(launch)), max(launch),
                     float(np.median([t[1] for t in times])) if what == 'core' else ''))
        progress(f'start: {what}, {case}: median {rows[-1][3]:.2f} s, max {rows[-1][4]:.2f} s')
    table(['start', 'case', 'starts', 'launch_to_first_answer_median_s', 'max_s',
           'in_process_s'], rows)


def start_once(what, scene, domain_id):
    """
    Print the seconds from launch to the first answer.

    That is the core's (and in process) or suspension_node's (a pose over DDS, pinged every
    20 ms).
    """
    if what == 'core':
        code = ('import time; t = time.perf_counter(); '
                'from linkage_ros import Continuation, load_scene; '
                f'Continuation(load_scene({scene!r})).solve(1.0); '
                'print(time.perf_counter() - t)')
        start = time.perf_counter()
        out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                             check=True)
        print(time.perf_counter() - start, float(out.stdout))
        return 0
    with tempfile.TemporaryDirectory() as log_dir:
        target = Target('suspension_node', [node_script(), '--ros-args', '-p',
                                            f'scene:={scene}'], domain_id, log_dir)
        try:
            target.driver.connect(timeout=120.0, ping_period=0.02)
            print(target.driver.first_answer - target.started)
        finally:
            target.close()
    return 0
