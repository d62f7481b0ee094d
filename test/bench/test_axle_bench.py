# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-bench axle: an axle's positions against its corners', timed by bench."""

from linkage_ros.bench import axle as axle_bench
from linkage_ros.core.axle import solve_axle
import numpy as np


def test_the_benchmark_times_every_position_it_counts_within_the_travel_limits(
        capsys, monkeypatch):
    # Its copies of the heaves are shifted by up to 0.099 mm: away from the middle, the copies
    # of the 80 mm heave went past the travel limit, and solve_axle stopped there.
    solved = []

    def counting(*args, **kwargs):
        result = solve_axle(*args, **kwargs)
        solved.append((len(np.ravel(args[1])), len(result.heave), result.success))
        return result

    monkeypatch.setattr(axle_bench, 'solve_axle', counting)
    code = axle_bench.main(['--heave', '-80:80:40'], 1)
    out = capsys.readouterr().out
    assert code == 0 and len(out.splitlines()) == 5   # the title, the header, 3 sizes
    assert out.splitlines()[1].split() == ['positions', 'one_corner_us', 'two_corners_us',
                                           'axle_us', 'axle/one_corner', 'axle/two_corners']
    assert [n for n, _, _ in solved] == [5, 50, 500]
    assert all(asked == done and success for asked, done, success in solved), solved


def test_a_request_linkage_axle_refuses_is_refused_in_its_words(capsys):
    assert axle_bench.main(['demo_vehicle', '--axle', 'middle'], 1) == 2
    out, err = capsys.readouterr()
    assert out == '' and err.count('\n') == 1
    assert err.startswith('linkage-axle: ') and "no axle 'middle'" in err, err
