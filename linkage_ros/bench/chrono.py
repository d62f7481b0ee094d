# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench chrono: import a Chrono suspension file, solve its sweep and write the scene.

Each file: read (comments allowed), map its template, load the scene and solve it at design
travel (linkage_ros.chrono.import_file), sweep its travel range (161 positions) and write the
scene. Timed per file after one untimed import (numba's first compile), at 1x, 10x and 100x
the bundled Chrono files (config/chrono, importable ones cycled). ms per file: median and
largest.
"""

import argparse
from pathlib import Path
import statistics
import sys
import tempfile
import time

from ..cli import fail

PROG = 'linkage-bench chrono'
SCALES = (1, 10, 100)


def main(argv=None, prog=PROG):
    """Run the benchmark; returns the exit status."""
    parser = argparse.ArgumentParser(prog=prog, description=__doc__.strip().splitlines()[0])
    parser.add_argument('files', nargs='*', metavar='CHRONO.json',
                        help='Chrono suspension files (default: the bundled importable ones)')
    parser.add_argument('--scales', default='1,10,100', help='copies of the set per round')
    args = parser.parse_args(argv)
    from ..core import sweep
    from ..core.model import config_dir, parse_scene
    from ..chrono import ChronoError, import_file
    import numpy as np
    import yaml
    files = [Path(f) for f in args.files] or sorted(
        (config_dir() / 'chrono').glob('*/suspension/*.json'))
    try:
        scales = [int(s) for s in args.scales.split(',')]
    except ValueError:
        return fail(prog, f'error: --scales: expected whole numbers, got {args.scales!r}')
    with tempfile.TemporaryDirectory() as folder:
        out = str(Path(folder) / 'scene.yaml')

        def once(path):
            texts, _ = import_file(str(path), out)
            scene = parse_scene(yaml.safe_load(texts[out]), source=out)
            low, high, step = scene.travel
            sweep(scene, np.arange(low, high + step / 2, step))
            Path(out).write_text(texts[out])

        usable = []
        for path in files:
            try:
                once(path)   # untimed: the first compile, and the files that do import
                usable.append(path)
            except ChronoError:
                continue
        if not usable:
            return fail(prog, 'no importable Chrono suspension file given')
        print('| scale | files | seconds | ms per file, median | largest |')
        print('|---|---|---|---|---|')
        for scale in scales:
            times = []
            start = time.perf_counter()
            for path in usable * scale:
                t0 = time.perf_counter()
                once(path)
                times.append(time.perf_counter() - t0)
            total = time.perf_counter() - start
            print(f'| {scale}x | {len(times)} | {total:.2f} | '
                  f'{1e3 * statistics.median(times):.1f} | {1e3 * max(times):.1f} |')
            sys.stdout.flush()
    return 0
