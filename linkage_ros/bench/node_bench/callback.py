# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Section callback of linkage-bench node: the node's travel callback in process.

With statics (issue 29), each command is a contact wrench then a travel, both callbacks
timed together: statics:=true on the scene as it is (rigid: the loaded solve gives the
kinematic pose and the multipliers), and the scene with bushings on every arm and link
(config/bench/bushings.yaml, unless the scene has its own). Those two run only when --modes
names them: each command costs tens of milliseconds.
"""

import math
from pathlib import Path
import tempfile
import time

import numpy as np
import rclpy

from .driver import sine
from .tables import progress, table, us
from ...answer.cdr import float64_cdr, wrench_stamped_cdr
from ...core.base import LinkageError
from ...core.model import config_dir, load_scene
from ...ros.isolation import init_context

STATICS_MODES = ('statics', 'bushings')


def with_bushings(data):
    """
    Put config/bench/bushings.yaml's bushing on every arm and link of a scene's data.

    A scene that has bushings is left as it is. The file's rates are N/mm: an m scene's
    are N/m.
    """
    import yaml
    rates = yaml.safe_load((config_dir() / 'bench' / 'bushings.yaml').read_text())
    if any('bushing' in c for c in data['constraints']):
        return data
    per_length = 1000.0 if data.get('units') == 'm' else 1.0   # the file's rates: N/mm
    for c in data['constraints']:
        kind = {'circle': 'arm', 'sphere': 'link'}.get(c['type'])
        if kind:
            c['bushing'] = {key: value * per_length if key in ('axial', 'radial') else value
                            for key, value in rates[kind].items()}
    return data


def contact_loads(count, frame_id='base_link'):
    """Return the contact wrenches (CDR) of a cornering force swept as a sine, N and N m."""
    phase = np.linspace(0.0, 2.0 * math.pi, count)
    return [wrench_stamped_cdr((0, 0), frame_id, (200.0 * math.cos(p), 3000.0 * math.sin(p),
                                                  4000.0), (0.0, 0.0, 50.0 * math.sin(p)))
            for p in phase]


def bench_callback(args):
    """
    Time the travel callback in process, with each optional output or sink.

    Every mode but elements runs the scene without its elements (a copy of its file without
    the key), so that plain is the answer alone and elements is what they add to it. The
    statics modes time a contact wrench and a travel per command (module docstring).
    """
    import yaml
    from rclpy.parameter import Parameter

    from ...ros.node import SuspensionNode
    scene = load_scene(args.scene)
    modes = {'plain': {}, 'elements': {'scene': scene.source}, 'tf': {'tf': True},
             'alignment': {'alignment': True},
             'markers': {'markers': True}, 'record_mcap': {'record_mcap': 'run.mcap'},
             'rerun_rrd': {'rerun_rrd': 'run.rrd'},
             'record_mcap+rerun_rrd': {'record_mcap': 'run.mcap', 'rerun_rrd': 'run.rrd'},
             'statics': {'statics': True}, 'bushings': {}}
    if not scene.elements:
        del modes['elements']
    chosen = [m for m in modes if m not in STATICS_MODES]   # statics: tens of ms a command
    if args.modes:
        chosen = ['plain', *(m for m in args.modes.split(',') if m and m != 'plain')]
    unknown = [m for m in chosen if m not in modes]
    if unknown:
        raise LinkageError('--modes', f'unknown mode {unknown[0]!r} (modes: '
                           f'{", ".join(modes)})')
    modes = {m: modes[m] for m in chosen}
    context = init_context(args.domain_id, 'OFF')      # no subscriber, and none outside
    travels = sine(args.count * args.scale, 0.05, 0.02)
    loads = contact_loads(len(travels))
    rows, base = [], None
    try:
        for mode, params in modes.items():
            with tempfile.TemporaryDirectory() as folder:
                bare = Path(folder) / 'scene.yaml'     # the scene without its elements
                data = yaml.safe_load(Path(scene.source).read_text())
                data.pop('elements', None)
                bare.write_text(yaml.safe_dump(with_bushings(data) if mode == 'bushings'
                                               else data))
                params = {'scene': str(bare), 'tf': False, **params}
                overrides = [Parameter(k, value=str(Path(folder) / v)
                                       if isinstance(v, str) and k != 'scene' else v)
                             for k, v in params.items()]
                node = SuspensionNode(context=context, parameter_overrides=overrides)
                corner = next(iter(node.corners.values()))
                times = []
                statics = mode in STATICS_MODES
                for travel, load in zip(travels, loads):
                    data = float64_cdr(travel)      # as the raw subscription hands it over
                    start = time.perf_counter()
                    if statics:
                        corner.on_wrench(load)
                    corner.on_travel(data)
                    times.append(time.perf_counter() - start)
                if statics and corner.health.failures_total:
                    progress(f'callback: {mode}: {corner.health.failures_total} commands '
                             f'not answered: {corner.health.message}')
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
