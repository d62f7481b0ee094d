# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Springs with a force table (model/elements.py, element_kernel.spring_at).

Force and wheel rate from the table's slope, interpolated linearly and held outside as
Chrono's ChFunctionInterp; bump stops; bad tables.
"""

import copy
from pathlib import Path
import subprocess
import sys

from linkage_ros.core import load_scene, sweep
from linkage_ros.core.measure import element_values, stop_notes
from linkage_ros.core.model.bundled import scene_dir
from linkage_ros.core.model.scene import parse_scene, SceneError
import numpy as np
import pytest
import yaml

TRAVELS = np.arange(-80.0, 81.0, 10.0)


def five_link(spring):
    """Return five_link with its spring's mapping replaced by spring (rate keys dropped)."""
    data = yaml.safe_load((scene_dir() / 'five_link.yaml').read_text())
    item = data['elements'][1]
    for key in ('rate', 'free_length'):
        item.pop(key)
    item.update(spring)
    return parse_scene(copy.deepcopy(data), source='five_link_table')


def values(scene):
    result = sweep(scene, TRAVELS)
    return element_values(scene, result.wheel_center, result.rotation)


def test_linear_table_gives_the_linear_springs_force_and_wheel_rate():
    linear = values(load_scene('five_link'))
    tabled = values(five_link({'free_length': 320.0,
                               'force_table': [[-1000.0, -45000.0], [1000.0, 45000.0]]}))
    np.testing.assert_allclose(tabled.force, linear.force, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(tabled.wheel_rate, linear.wheel_rate, rtol=1e-12, atol=1e-9)


def test_force_is_interpolated_and_wheel_rate_uses_the_segments_slope():
    # five_link's spring is 189-266 mm long over the travel: deflections 54-131 mm cross rows
    table = np.array([[0.0, 0.0], [70.0, 900.0], [100.0, 9000.0], [200.0, 9500.0]])
    v = values(five_link({'free_length': 320.0, 'force_table': table.tolist()}))
    deflection = 320.0 - v.length[:, 1]
    np.testing.assert_allclose(v.force[:, 1], np.interp(deflection, *table.T), rtol=1e-12)
    segment = np.searchsorted(table[:, 0], deflection)   # rows segment-1, segment
    slope = np.diff(table[:, 1])[segment - 1] / np.diff(table[:, 0])[segment - 1]
    expected = slope * v.ratio[:, 1] ** 2 - v.force[:, 1] * v.ratio_rate[:, 1]
    np.testing.assert_allclose(v.wheel_rate[:, 1], expected, rtol=1e-12)


def test_outside_the_table_the_force_is_held_and_the_stiffness_is_zero():
    v = values(five_link({'free_length': 320.0, 'force_table': [[500.0, 10.0], [600.0, 20.0]]}))
    np.testing.assert_array_equal(v.force[:, 1], 10.0)   # every deflection is below 500 mm
    np.testing.assert_allclose(v.wheel_rate[:, 1], -10.0 * v.ratio_rate[:, 1], rtol=1e-12)


def test_bump_stop_engages_only_past_its_deflection():
    # engaged where the spring (189-266 mm over the travel) is shorter than 230 mm
    scene = five_link({'free_length': 230.0, 'force_table': [[0.0, 0.0], [10.0, 5000.0]]})
    v = values(scene)
    engaged = v.length[:, 1] < 230.0
    assert engaged.any() and not engaged.all()
    assert np.all(v.force[engaged, 1] > 0) and np.all(v.force[~engaged, 1] == 0)
    (note,) = stop_notes(scene, TRAVELS, v.force)
    low, high = TRAVELS[engaged].min(), TRAVELS[engaged].max()
    assert f'from travel {low:g} to {high:g} mm' in note


@pytest.mark.parametrize('table, said', [
    ([[0.0, 0.0], [10.0, 5.0], [5.0, 6.0]], 'sorted'),
    ([[0.0, 0.0], [10.0, float('nan')]], 'finite'),
    ([[0.0, 0.0]], 'at least two rows'),
])
def test_bad_table_is_refused_naming_the_field(table, said):
    with pytest.raises(SceneError, match='force_table') as info:
        five_link({'free_length': 320.0, 'force_table': table})
    assert said in str(info.value)


def test_bad_table_is_one_line_and_status_2_for_a_program(tmp_path):
    data = yaml.safe_load((scene_dir() / 'five_link.yaml').read_text())
    data['elements'][1].pop('rate')
    data['elements'][1]['force_table'] = [[0.0, 0.0], [0.0, 1.0]]
    path = tmp_path / 'bad.yaml'
    path.write_text(yaml.safe_dump(data))
    run = subprocess.run([str(Path(sys.executable).parent / 'linkage-sweep'), str(path)],
                         capture_output=True, text=True)
    assert run.returncode == 2 and len(run.stderr.strip().splitlines()) == 1
    assert 'force_table' in run.stderr


def test_element_spring_at_agrees_with_the_compiled_kernel():
    table = [[0.0, 0.0], [70.0, 900.0], [100.0, 9000.0], [200.0, 9500.0]]
    scene = five_link({'free_length': 320.0, 'force_table': table})
    v = values(scene)
    spring = scene.elements[1]
    for length, force in zip(v.length[:, 1], v.force[:, 1]):
        assert spring.spring_at(length)[0] == pytest.approx(force, rel=1e-12)


def test_table_energy_grows_by_the_force_over_a_step():
    # dV/d(deflection) = F: central differences are exact on a linear segment
    spring = five_link({'free_length': 320.0,
                        'force_table': [[0.0, 0.0], [70.0, 900.0], [100.0, 9000.0]]}).elements[1]
    for length in (300.0, 240.0, 200.0, 100.0):   # deflections 20, 80, 120 (held), 220
        force = spring.spring_at(length)[0]
        rise = spring.spring_at(length - 0.5)[2] - spring.spring_at(length + 0.5)[2]
        assert rise == pytest.approx(force, rel=1e-9, abs=1e-9)


def test_statics_of_a_linear_table_spring_equals_the_rate_spring():
    from linkage_ros.core.statics import Load, solve_loaded
    load = Load(force_n=(0.0, 1000.0, 0.0), at='wc', moment_nm=(0.0, 0.0, 0.0))
    linear = solve_loaded(load_scene('five_link'), travel_mm=20.0, load=load)
    tabled = solve_loaded(five_link({'free_length': 320.0, 'force_table':
                                     [[-1000.0, -45000.0], [1000.0, 45000.0]]}),
                          travel_mm=20.0, load=load)
    assert tabled.holding_force_n == pytest.approx(linear.holding_force_n, rel=1e-9)
    assert tabled.spring_forces_n['spring'] == pytest.approx(linear.spring_forces_n['spring'],
                                                             rel=1e-9)
