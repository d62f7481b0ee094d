# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-bench chrono: its table (the timing itself lives in doc/benchmarks.md)."""

from pathlib import Path
import subprocess
import sys


def test_chrono_bench_prints_one_row_per_scale_over_the_bundled_files():
    run = subprocess.run([str(Path(sys.executable).parent / 'linkage-bench'), 'chrono',
                          '--scales', '1'], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    header, rule, row = run.stdout.splitlines()
    assert header.startswith('| scale | files |')
    cells = [c.strip() for c in row.strip('|').split('|')]
    assert cells[0] == '1x' and int(cells[1]) == 11   # config/chrono's importable files
    assert float(cells[3]) > 0
