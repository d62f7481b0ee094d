# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-bench node's tables print measured floats to 4 significant digits."""

import math

from linkage_ros.bench.node_bench.tables import table


def test_a_timing_prints_4_significant_digits_and_counts_stay_whole(capsys):
    table(['callback', 'commands', 'median_us', 'ratio'],
          [('tf', 200, 24.055999347183388, 1.315326061719027), ('nan', 0, math.nan, 0.5)])
    lines = capsys.readouterr().out.splitlines()
    assert lines[:3] == ['callback,commands,median_us,ratio', 'tf,200,24.06,1.315',
                         'nan,0,nan,0.5']
