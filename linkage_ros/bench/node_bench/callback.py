# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Section callback of linkage-node-bench: the node's travel callback in process."""

from pathlib import Path
import tempfile
import time

import numpy as np
import rclpy

from .driver import sine
from .tables import progress, table, us
from ...cdr import float64_cdr
from ...core.model import load_scene
from ...ros.isolation import init_context


def bench_callback(args):
    """
    Time the travel callback in process, with each optional output or sink.

    Every mode but elements runs the scene without its elements (a copy of its file without
    the key), so that plain is the answer alone and elements is what they add to it.
    """
    import yaml
    from rclpy.parameter import Parameter

    from ...ros.node import SuspensionNode
    scene = load_scene(args.scene)
    modes = {'plain': {}, 'elements': {'scene': scene.source}, 'tf': {'tf': True},
             'alignment': {'alignment': True},
             'markers': {'markers': True}, 'record_mcap': {'record_mcap': 'run.mcap'},
             'rerun_rrd': {'rerun_rrd': 'run.rrd'},
             'record_mcap+rerun_rrd': {'record_mcap': 'run.mcap', 'rerun_rrd': 'run.rrd'}}
    if not scene.elements:
        del modes['elements']
    context = init_context(args.domain_id, 'OFF')      # no subscriber, and none outside
    travels = sine(args.count * args.scale, 0.05, 0.02)
    rows, base = [], None
    try:
        for mode, params in modes.items():
            with tempfile.TemporaryDirectory() as folder:
                bare = Path(folder) / 'scene.yaml'     # the scene without its elements
                data = yaml.safe_load(Path(scene.source).read_text())
                data.pop('elements', None)
                bare.write_text(yaml.safe_dump(data))
                params = {'scene': str(bare), 'tf': False, **params}
                overrides = [Parameter(k, value=str(Path(folder) / v)
                                       if isinstance(v, str) and k != 'scene' else v)
                             for k, v in params.items()]
                node = SuspensionNode(context=context, parameter_overrides=overrides)
                corner = next(iter(node.corners.values()))
                times = []
                for travel in travels:
                    data = float64_cdr(travel)      # as the raw subscription hands it over
                    start = time.perf_counter()
                    corner.on_travel(data)
                    times.append(time.perf_counter() - start)
                start = time.perf_counter()
                node.destroy_node()          # files are finished here
                closing = time.perf_counter() - start
            base = base or np.median(times)
            rows.append((mode, len(times), us(times), float(np.mean(times) * 1e6),
                         float(np.median(times) / base), closing))
            progress(f'callback: {mode}: median {us(times):.1f} us')
    finally:
        rclpy.try_shutdown(context=context)
    table(['callback', 'commands', 'median_us', 'mean_us', 'ratio_to_plain', 'close_s'], rows)
