# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A program that runs the statics kernels says their first compile, as for the others.

linkage-kc compiled the statics kernels for a minute without a word: it asked
warmup.compile_if_cold for the kinematic kernels only. Each program runs here in a fresh
Python in which numba's cache is taken to lack the statics kernels and to hold every other
(warmup._in_cache answers so, whatever the cache holds: a kernel it lacks is compiled where it
is first run, unsaid, as before) and compile_in_child only notes what it is asked to compile.
Afterwards, the statics kernels that ran in that process are read off numba (a Dispatcher's
signatures: compiled or loaded there). A program that ran one must have
said the compile once, before its work, and asked for the statics kernels; one that ran none
need not. kc and replay (solve and sweep) on a scene with bushings run them; sweep, axle and
vehicle on scenes with bushings (kinematics, springs and bar) do not, today.
"""

import json
from pathlib import Path
import subprocess
import sys

from linkage_ros.core import warmup
import pytest

CHILD = """
import importlib, json, sys
from numba.core.dispatcher import Dispatcher
from linkage_ros.core import warmup
warmup._in_cache = lambda kernel: kernel.py_func.__module__ not in warmup.STATICS_MODULES
asked = []
warmup.compile_in_child = lambda statics=False: asked.append(statics) or True
module, name, argv = sys.argv[1], sys.argv[2], sys.argv[3:]
status = getattr(importlib.import_module(module), name)(argv)
ran = sorted(f'{m}.{n}' for m in warmup.STATICS_MODULES
             for n, kernel in vars(importlib.import_module(m)).items()
             if isinstance(kernel, Dispatcher) and kernel.signatures)
sys.stdout.flush()
print(json.dumps({'status': status, 'asked': asked, 'ran': ran}), file=sys.stderr)
"""
# The line that begins a program's work: the compile must be said before it.
WORK = {'linkage-kc': ': compliance rates, ', 'linkage-replay': ': solving '}
VEHICLE = Path(__file__).resolve().parents[2] / 'config' / 'vehicles' / 'demo_vehicle.yaml'


def bushed_vehicle(folder):
    """Write demo_vehicle with the bundled bushed scenes at its corners; return its path."""
    text = VEHICLE.read_text().replace('scene: double_wishbone,',
                                       'scene: double_wishbone_bushings,')
    path = folder / 'bushed_vehicle.yaml'
    path.write_text(text.replace('scene: five_link,', 'scene: five_link_bushings,'))
    return path


def run(prog, module, argv, cwd):
    """Run module's main(argv) as CHILD does; return (said lines, report dict)."""
    done = subprocess.run([sys.executable, '-c', CHILD, module, 'main', *argv],
                          capture_output=True, text=True, timeout=600, cwd=cwd)
    *lines, report = done.stderr.splitlines()
    return lines, json.loads(report)


CASES = {
    'kc': ('linkage-kc', 'linkage_ros.tools.kc',
           ['double_wishbone_bushings', '--travel', '-20:20:20', '-o', 'kc.csv'], True),
    'replay sweep': ('linkage-replay', 'linkage_ros.tools.replay',
                     ['sweep', '--scene', 'five_link_bushings', '-o', 'run.mcap'], True),
    'replay solve': ('linkage-replay', 'linkage_ros.tools.replay',
                     ['solve', 'bushed.mcap', '-o', 'solved.mcap'], True),
    'sweep': ('linkage-sweep', 'linkage_ros.tools.sweep',
              ['double_wishbone_bushings', '-o', 'sweep.csv'], False),
    'axle': ('linkage-axle', 'linkage_ros.tools.axle',
             ['bushed_vehicle.yaml', '-o', 'axle.csv'], False),
    'vehicle': ('linkage-vehicle', 'linkage_ros.tools.vehicle',
                ['bushed_vehicle.yaml', '-o', 'sheet.csv'], False),
}


@pytest.mark.parametrize('case', sorted(CASES))
def test_a_program_that_runs_the_statics_kernels_says_their_compile(case, tmp_path):
    prog, module, argv, runs_statics = CASES[case]
    bushed_vehicle(tmp_path)
    if case == 'replay solve':     # a recording of a corner with bushings
        made = subprocess.run([sys.executable, '-m', 'linkage_ros.tools.replay', 'sweep',
                               '--scene', 'double_wishbone_bushings', '-o', 'bushed.mcap'],
                              capture_output=True, text=True, timeout=600, cwd=tmp_path)
        assert made.returncode == 0, made.stderr
    lines, report = run(prog, module, argv, tmp_path)
    assert report['status'] == 0, lines
    assert bool(report['ran']) == runs_statics, report     # what this case is about
    said = f'{prog}: {warmup.STATICS_MESSAGE}'    # the other kernels taken as cached
    if report['ran']:
        solving = next(i for i, line in enumerate(lines) if WORK[prog] in line)
        assert lines.count(said) == 1 and lines.index(said) < solving, lines   # before work
        assert report['asked'] == [True], report                    # the statics kernels too
    else:
        assert not any('compiling' in line for line in lines) and report['asked'] == [], \
            (lines, report)
