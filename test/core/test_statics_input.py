# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""A Statics never raises for numerics: any finite command is an answer with a status."""

import math

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros.core.base import LinkageError, Status
from linkage_ros.core.model import load_scene
from linkage_ros.core.statics import Load, Statics
import numpy as np
import pytest

SCENE = load_scene('double_wishbone_bushings')
STATICS = Statics(SCENE)   # one for every example: each goes on from the last, as a node's
# magnitudes from the subnormal to the largest finite, either sign, and zero
MAGNITUDES = st.one_of(
    st.just(0.0), st.sampled_from([5e-324, 2.2e-308, 1e-300, 1.7e308, 8.9e307, 1e307, 1e30]),
    st.floats(-1e4, 1e4), st.floats(allow_nan=False, allow_infinity=False))
VECTORS = st.tuples(MAGNITUDES, MAGNITUDES, MAGNITUDES)


def check(res):
    """Assert an answer: OK with a finite pose and forces, or one line and no pose."""
    assert isinstance(res.status, Status)
    if res.status == Status.OK:
        assert np.isfinite(res.wheel_center_mm).all() and np.isfinite(res.rotation).all()
        assert all(np.isfinite(f).all() for f in res.body_forces_n.values())
        assert math.isfinite(res.holding_force_n)
    else:
        assert res.wheel_center_mm is None and len(res.message.splitlines()) == 1


@given(travel=MAGNITUDES, rack=MAGNITUDES, force=VECTORS, moment=VECTORS,
       at=st.sampled_from(['cp', 'wc']))
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
def test_any_finite_loaded_command_is_an_answer_with_a_status(travel, rack, force, moment, at):
    check(STATICS.solve(travel, Load(force, at, moment), rack))
    good = STATICS.solve(5.0, Load((0.0, 1000.0, 0.0), 'cp'))   # and the next good one
    check(good)
    assert good.status == Status.OK


@given(travel=MAGNITUDES, rack=MAGNITUDES)
@settings(max_examples=30, deadline=None)
def test_rates_at_any_finite_travel_and_rack_are_an_answer_with_a_status(travel, rack):
    comp = STATICS.rates(travel, rack)
    assert isinstance(comp.status, Status)
    if comp.status == Status.OK:
        assert all(math.isfinite(v) for v in comp.rates.values())
        assert np.isfinite(comp.matrix).all()
    else:
        assert not comp.rates and len(comp.message.splitlines()) == 1


@pytest.mark.parametrize('travel, rack', [(math.nan, 0.0), (0.0, math.inf), (-math.inf, 1.0)])
def test_a_travel_or_rack_that_is_not_a_number_is_not_finite(travel, rack):
    res = STATICS.solve(travel, Load(), rack)
    assert res.status == Status.NOT_FINITE and res.wheel_center_mm is None


@pytest.mark.parametrize('load, field', [(Load((math.nan, 0.0, 0.0)), 'load.force_n'),
                                         (Load(moment_nm=(0.0, math.inf, 0.0)), 'load.moment_nm'),
                                         (Load(at='xx'), 'load.at')])
def test_a_load_that_is_not_finite_is_bad_input_and_raises(load, field):
    with pytest.raises(LinkageError, match=field.replace('.', r'\.')):
        STATICS.solve(0.0, load)
