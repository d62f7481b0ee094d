# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-study on a real Dask cluster: a scheduler and two worker processes on this machine.

The same command with --scheduler and without must write the same bytes: each batch draws
its variants from its own seed, and the results are gathered in batch order.
"""

from pathlib import Path
import subprocess
import sys

import numpy as np
import pytest

distributed = pytest.importorskip('distributed')   # the study extra
pq = pytest.importorskip('pyarrow.parquet')

PROG = str(Path(sys.executable).parent / 'linkage-study')


def run(*args, cwd):
    """Run linkage-study; return (status, stdout, stderr)."""
    done = subprocess.run([PROG, *args], capture_output=True, text=True, timeout=600, cwd=cwd)
    return done.returncode, done.stdout, done.stderr


@pytest.fixture(scope='module')
def scheduler():
    """Start a local cluster (a scheduler, two worker processes); yield its address."""
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        yield cluster.scheduler_address


def test_a_tolerance_study_on_the_cluster_writes_the_local_runs_bytes(scheduler, tmp_path):
    args = ['tolerance', 'five_link', '--sigma', '0.1', '--samples', '9000', '--travel',
            '-40', '0', '40', '--seed', '5']
    status, _, err = run(*args, '--scheduler', scheduler, '-o', 'dask.csv', cwd=tmp_path)
    assert status == 0, err
    assert f'in 3 batches on {scheduler}' in err and '3/3 batches (100%)' in err
    status, _, err = run(*args, '-o', 'local.csv', cwd=tmp_path)
    assert status == 0, err
    dask = (tmp_path / 'dask.csv').read_bytes()
    assert dask == (tmp_path / 'local.csv').read_bytes()
    assert dask.count(b'\n') == 1 + 3 * 5
    # and as Parquet, read back by pyarrow: the same numbers
    status, _, err = run(*args, '--scheduler', scheduler, '-o', 'dask.parquet', cwd=tmp_path)
    assert status == 0, err
    table = pq.read_table(tmp_path / 'dask.parquet').to_pydict()
    rows = [line.split(',') for line in dask.decode().splitlines()[1:]]
    assert table['quantity'] == [r[1] for r in rows]
    assert np.array_equal(table['std'], [float(r[4]) for r in rows])


def test_a_bushing_study_on_the_cluster_writes_the_local_runs_bytes(scheduler, tmp_path):
    # each variant's compliance rates from a Statics on a worker: the same bits as here
    (tmp_path / 'sd.yaml').write_text('{tie_rod.bushing.radial: 5%, lower_rear.bushing.axial: '
                                      '200, upper_front.base: {x: 0.2}}\n')
    args = ['tolerance', 'five_link_bushings', '--sigma', '0.05', '--samples', '4100',
            '--travel', '-20', '20', '--seed', '3', '--tolerances', 'sd.yaml']
    status, _, err = run(*args, '--scheduler', scheduler, '-o', 'dask.csv', cwd=tmp_path)
    assert status == 0, err
    assert f'in 2 batches on {scheduler}' in err
    status, _, err = run(*args, '-o', 'local.csv', cwd=tmp_path)
    assert status == 0, err
    dask = (tmp_path / 'dask.csv').read_bytes()
    assert dask == (tmp_path / 'local.csv').read_bytes()
    assert dask.count(b'\n') == 1 + 2 * (5 + 12) and b',toe_per_fy_cp_deg_per_kN,' in dask


def test_a_fit_with_several_starts_on_the_cluster_writes_the_local_runs_scene(
        scheduler, tmp_path):
    (tmp_path / 'targets.yaml').write_text("""scene: double_wishbone
free:
  tie_rod.base: {x: [-30, 30], y: [-30, 30], z: [-30, 30]}
targets:
  - {quantity: toe_deg, travel: [-50, 50, 10], value: 0.0}
""")
    args = ['fit', 'targets.yaml', '--starts', '3', '--seed', '2']
    status, _, err = run(*args, '--scheduler', scheduler, '-o', 'dask.yaml', cwd=tmp_path)
    assert status == 0, err
    status, _, err = run(*args, '-o', 'local.yaml', '--workers', '1', cwd=tmp_path)
    assert status == 0, err
    written = [(tmp_path / f).read_text() for f in ('dask.yaml', 'local.yaml')]
    assert written[0] == written[1]
