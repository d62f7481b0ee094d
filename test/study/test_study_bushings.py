# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Studies over bushing rates (issue 39 item 5): bushing rates as variables, compliance as outputs.

The Monte Carlo spread of the compliance rates against their first order, the rates'
derivatives against central differences of Statics on scene files edited by hand, and the
bushing standard deviations' input class (names and magnitudes) refused in one line.
"""

import copy
import math

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros.core.base import LinkageError
from linkage_ros.core.model import parse_scene, read_yaml, resolve_scene_path
from linkage_ros.core.statics import Statics
from linkage_ros.core.vary import (bushing_names, bushing_values, compliance_rates, load_design,
                                   rate_names)
from linkage_ros.core.vary.bushings import RELATIVE_STEP
from linkage_ros.study.cli import main
from linkage_ros.study.tolerance import (BATCH, BUSHING_SD_LIMIT, bushing_sigmas, problem,
                                         tolerance)
import numpy as np
import pytest
import yaml

TRAVELS = np.array([-20.0, 0.0, 20.0])
NOISE = 1e-12   # relative scatter of a compliance rate between solves (5x the 2e-13 seen)
FUZZ = settings(deadline=None, database=None, max_examples=60,
                suppress_health_check=[HealthCheck.function_scoped_fixture])


@pytest.mark.parametrize('name, point_sd', [('five_link_bushings', 0.0),
                                            ('double_wishbone_bushings', 0.05)])
def test_at_small_sd_the_monte_carlo_spread_of_a_rate_is_the_first_order_one(name, point_sd):
    # Every bushing rate normal with sd 2 % of itself (and, on double_wishbone_bushings, every
    # hardpoint coordinate with sd 0.05 mm). A compliance rate goes as 1 / k: at 2 % its std
    # differs from the first order by about 2e-2^2 relative, and its mean from the nominal by
    # as much, against the sampling errors: 1 / sqrt(2 (N - 1)) (0.78 % for N = 8192) of a
    # sample std, rss_std / sqrt(N) of a mean. Bounds: 4 of them, as the hardpoint tolerance's.
    design = load_design(name)
    scene = design.scene
    bushings = 0.02 * bushing_values(scene)
    samples = 2 * BATCH
    result = tolerance(problem(design, np.full(design.values.shape, point_sd), samples,
                               TRAVELS, seed=5, bushings=bushings))
    rates = rate_names(scene, TRAVELS)
    assert result.quantities[5:] == rates and len(rates) == 12
    assert result.out_of_reach.sum() == 0
    error = 1.0 / math.sqrt(2 * (samples - 1))
    spread = result.rss_std[:, 5:]
    ratio = result.std[:, 5:] / spread
    assert np.abs(ratio - 1.0).max() < 4 * error, ratio
    bias = 0.02 ** 2 * np.abs(result.nominal[:, 5:])   # second order, from 1 / k
    assert np.all(np.abs(result.mean[:, 5:] - result.nominal[:, 5:])
                  < 4 * spread / math.sqrt(samples) + bias)
    width = (result.p99[:, 5:] - result.p01[:, 5:]) / (2 * 2.3263478740408408 * spread)
    assert np.abs(width - 1.0).max() < 0.05, width
    if point_sd == 0.0:   # the kinematics ignores bushings: no spread but the solver's
        # every variant is the design, solved again from its pose: within the solve's
        # tolerance (1e-10 mm, and its rotation's, ~1e-12 rad)
        assert np.all(result.rss_std[:, :5] == 0.0)
        assert np.all(result.std[:, :5] < 1e-9), result.std[:, :5]


def _edited(name, constraint, field, rate):
    """Return the scene of the bundled file name with one bushing rate set in its data."""
    path = resolve_scene_path(name)
    data = copy.deepcopy(read_yaml(path, 'scene'))
    item = next(c for c in data['constraints'] if c['name'] == constraint)
    item['bushing'][field] = rate
    return parse_scene(data, source=str(path))


@pytest.mark.parametrize('name', ['five_link_bushings', 'double_wishbone_bushings'])
def test_a_bushing_rates_derivative_is_the_central_difference_of_statics_on_edited_files(name):
    # The test's own difference: the 4th-order five-point stencil at h = 0.5 % of the rate,
    # on scenes parsed from the file's data with the rate written in (no with_bushings):
    # truncation ~ f^(5) h^4 / 30, about 3e-9 of a derivative for f ~ 1 / k. Each rate
    # Statics solves scatters by 2e-13 of itself (solved from other starts; NOISE is 5x
    # that), which a difference divides by its step: 1.5 NOISE |f| / h here, 3 NOISE |f| /
    # (h / 2) for the study's Richardson pair at RELATIVE_STEP. Bound: 1e-6 of the largest
    # derivative of each rate, plus that scatter.
    scene = load_design(name).scene
    rates = rate_names(scene, TRAVELS)
    _, by_rate = compliance_rates(scene, TRAVELS, rates, points=np.zeros(scene.points.shape))
    for b, (variable, rate) in enumerate(zip(bushing_names(scene), bushing_values(scene))):
        constraint, _, field = variable.split('.')
        h = 0.005 * rate

        def at(offset):
            statics = Statics(_edited(name, constraint, field, rate + offset))
            return np.array([[statics.rates(t).rates[r] for r in rates] for t in TRAVELS])

        nominal = at(0.0)
        expected = (at(-2 * h) - 8 * at(-h) + 8 * at(h) - at(2 * h)) / (12 * h)
        scatter = NOISE * np.abs(nominal) * (1.5 / h + 6.0 / (RELATIVE_STEP * rate))
        bound = 1e-6 * np.abs(expected).max(axis=0) + scatter
        assert np.all(np.abs(by_rate[:, :, b] - expected) <= bound), variable


def test_the_sensitivity_table_has_the_rates_by_bushing_rate(tmp_path, capsys):
    out = tmp_path / 's.csv'
    assert main(['sensitivity', 'five_link_bushings', '--travel', '0', '--quantity',
                 'toe_per_fy_cp_deg_per_kN', '-o', str(out)]) == 0
    lines = out.read_text().splitlines()[1:]
    scene = load_design('five_link_bushings').scene
    assert len(lines) == scene.points.size + len(bushing_names(scene))
    row = next(line.split(',') for line in lines if ',tie_rod.bushing,radial,' in line)
    _, by_rate = compliance_rates(scene, [0.0], ('toe_per_fy_cp_deg_per_kN',),
                                  points=np.zeros(scene.points.shape))
    # the same computation written and read back: the shortest round-trip digits
    assert float(row[4]) == by_rate[0, 0, bushing_names(scene).index('tie_rod.bushing.radial')]


NAMES = st.text(min_size=1, max_size=40) | st.sampled_from(
    ['upper_front', 'tie_rod', '1st-link', 'ünïcode_arm', 'x' * 300, 'lower_arm'])
FIELDS = st.sampled_from(['axial', 'radial', 'torsion', 'conical']) | st.text(max_size=10)
MAGNITUDES = (st.floats() | st.sampled_from([1.7e308, -1.7e308, 5e-324, -5e-324, 0.0, -0.0,
                                             1e-300, 1e300]))


@FUZZ
@given(constraint=NAMES, field=FIELDS, sd=MAGNITUDES | st.text(max_size=6))
def test_a_bushing_variable_on_a_scene_without_bushings_is_one_line_status_2(
        tmp_path, capsys, constraint, field, sd):
    path = tmp_path / 'sd.yaml'
    key = f'{constraint}.bushing.{field}'
    path.write_text(yaml.safe_dump({key: sd}, allow_unicode=True), encoding='utf-8')
    assert main(['tolerance', 'five_link', '--sigma', '0.1', '--samples', '10', '--travel', '0',
                 '--tolerances', str(path)]) == 2
    out, err = capsys.readouterr()
    assert out == '' and err.startswith('linkage-study: ') and err.endswith('\n')
    assert 'Traceback' not in err
    if not key.endswith('.length'):   # a length's, which length_sigmas refuses
        assert err.count('\n') == 1, err   # a name's line breaks escaped
        assert 'not a bushing rate of the scene five_link (it has no bushings)' in err


@FUZZ
@given(b=st.integers(0, 9), sd=MAGNITUDES, percent=st.booleans())
def test_a_bushing_sd_is_taken_within_its_stated_range_and_refused_outside(b, sd, percent):
    design = load_design('double_wishbone_bushings')
    name, rate = bushing_names(design.scene)[b], float(bushing_values(design.scene)[b])
    given_sd = f'{sd!r}%' if percent else sd
    wanted = sd / 100.0 * rate if percent else sd
    if math.isfinite(wanted) and 0.0 <= wanted <= BUSHING_SD_LIMIT * rate:
        taken = bushing_sigmas(design, {name: given_sd})
        assert taken[b] == wanted and np.count_nonzero(taken) == (wanted != 0.0)
    else:
        with pytest.raises(LinkageError, match=f'{name}: a bushing rate.s standard deviation '
                           f'is a number of .* from 0 to {BUSHING_SD_LIMIT * rate:g}'):
            bushing_sigmas(design, {name: given_sd})


def test_a_bushing_sd_that_is_no_number_is_refused():
    design = load_design('five_link_bushings')
    for bad in ['five', True, None, [1.0], '%', 'abc%']:
        with pytest.raises(LinkageError, match='tie_rod.bushing.axial: a bushing rate'):
            bushing_sigmas(design, {'tie_rod.bushing.axial': bad})
