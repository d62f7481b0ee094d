# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-bench statics: its table (the timing itself lives in doc/benchmarks.md)."""

import csv
import io
import math

from linkage_ros.bench import statics as bench
from linkage_ros.bench.statics import main


def test_the_table_gives_1x_10x_and_100x_side_by_side_with_the_ratios(capsys):
    assert main(['five_link_bushings', '--commands', '3', '--rounds', '1']) == 0
    out, err = capsys.readouterr()
    rows = list(csv.reader(io.StringIO(out)))
    assert rows[0] == list(bench.COLUMNS)
    assert [r[:2] for r in rows[1:]] == [['five_link_bushings', '3'],
                                         ['five_link_bushings', '30'],
                                         ['five_link_bushings', '300']]
    for row in rows[1:]:
        continuation, loaded, rates, loaded_ratio, rates_ratio = map(float, row[2:])
        assert min(continuation, loaded, rates) > 0
        # the ratios are of the times printed (3 significant digits each)
        assert math.isclose(loaded_ratio, loaded / continuation, rel_tol=2e-2)
        assert math.isclose(rates_ratio, rates / continuation, rel_tol=2e-2)
    assert err.count('load average') == 2


def test_the_commands_go_on_along_one_sine_of_the_travel_and_the_wrench():
    """Round k takes commands k N to (k + 1) N: no jump between rounds (a cold start)."""
    travels, loads = bench.commands(4, 10)
    assert travels[0] == bench.AMPLITUDE_MM * math.sin(2 * math.pi * 10 / bench.RATE_HZ)
    whole, _ = bench.commands(14)
    assert whole[10:] == travels
    assert loads[2].at == 'cp' and loads[2].force_n[2] == 4000.0


def test_the_parts_of_a_loaded_command_compile_and_are_timed():
    # --parts times the kernels' pieces: each compiles from the statics' own kernels (a piece
    # that no longer compiled broke --parts unseen once). Only that is asserted: the times are
    # the benchmark's, and a piece taken as a difference of two times may be < 0 under load
    from linkage_ros.bench.statics_parts import parts
    from linkage_ros.core.model import load_scene
    pieces = parts(load_scene('five_link_bushings'), bench.commands(4), bench.commands(4, 4))
    assert {'Statics.solve', 'its compiled call', 'exact assembly (x2)', 'factorisation (x2)',
            'KKT solve (x4)', 'pickup forces (x1)'} <= set(pieces)
    assert all(math.isfinite(us) for us in pieces.values()), pieces
