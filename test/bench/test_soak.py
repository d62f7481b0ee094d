# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-soak: what it counts is what the node did (its speed is for the benchmark to say)."""

import csv
import io

from linkage_ros.bench.soak import BAD_VALUES_M, command_batches, main
import numpy as np


def test_the_commands_are_a_bounded_walk_with_a_bad_value_every_1000():
    travels = np.concatenate([t for _, t in command_batches(12_000, 200, -80.0, 80.0, seed=0)])
    assert len(travels) == 12_000
    bad = np.arange(999, 12_000, 1000)
    for k, value in enumerate(travels[bad]):
        expected = BAD_VALUES_M[k % len(BAD_VALUES_M)]
        assert value == expected or (np.isnan(value) and np.isnan(expected))
    good = np.delete(travels, bad)
    assert np.all(np.abs(good) <= 0.080)   # m: inside five_link's travel block


def test_a_short_soak_answers_every_good_command_with_a_finite_pose(capfd):
    # capfd, not capsys: EventsExecutor enables faulthandler, which needs a real stderr
    # 21 000 commands, 21 of them bad (NaN, inf, -inf, 1e308 m, 10 m beyond the bump limit)
    assert main(['--commands', '21000', '--warmup', '20000', '--progress', '100000']) == 0
    row = next(csv.DictReader(io.StringIO(capfd.readouterr().out)))
    assert int(row['poses']) == 21_000 - 21
    assert int(row['not_finite_poses']) == 0
    assert int(row['errors']) >= 21                 # at least one ERROR status per bad value
    assert float(row['residual_max_mm']) <= 1e-9
