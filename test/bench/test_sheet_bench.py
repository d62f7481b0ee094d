# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-bench vehicle: the setup sheet timed at multiples of its table sizes."""

from linkage_ros.bench.sheet import benchmark
from linkage_ros.core.model import load_vehicle
from linkage_ros.core.vehicle import setup_sheet


def test_the_benchmark_prints_a_row_per_scale_with_the_positions_solved(capsys):
    benchmark(load_vehicle('demo_vehicle'), setup_sheet, rounds=1, scales=(1, 2))
    lines = capsys.readouterr().out.splitlines()
    assert lines[1].split() == ['scale', 'positions', 'sheet_ms', 'per_position_us']
    rows = [line.split() for line in lines[2:]]
    # per axle: design, heave 31 and roll 25 positions; the front's rack 61 more
    assert [(r[0], r[1]) for r in rows] == [('1', str(2 * 57 + 61)), ('2', str(2 * 113 + 122))]
    assert all(float(r[2]) > 0 for r in rows)
