# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Elements in scene files: a mistake is one line naming the file and field, status 2."""

from pathlib import Path

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros.core.measure import element_values
from linkage_ros.core.model import load_scene, SceneError
from linkage_ros.core.solve import sweep
from linkage_ros.tools.sweep import main
import numpy as np
import pytest
import yaml

DAMPER = {'name': 'damper', 'type': 'damper', 'body': [-20.0, 500.0, 620.0]}


def scene_with(tmp_path, *elements, base='double_wishbone'):
    data = yaml.safe_load(Path(load_scene(base).source).read_text())
    data['elements'] = list(elements)
    path = tmp_path / 'scene.yaml'
    path.write_text(yaml.safe_dump(data))
    return str(path)


def sweep_error(capsys, path):
    code = main([path, '--elements', '--travel', '0:10:10'])
    out, err = capsys.readouterr()
    assert code == 2 and out == ''
    assert len(err.splitlines()) == 1 and 'Traceback' not in err
    return err


BAD = [
    ({**DAMPER, 'arm': 'lower_wishbone', 'point': [0.0, 580.0, 170.0]},
     "elements[0] (damper).arm: no arm (circle) named 'lower_wishbone' in the scene "
     '(its arms: upper_arm, lower_arm)'),
    ({**DAMPER, 'link': 'tie_rod', 'point': [-145.0, 495.0, 265.0]},
     'elements[0] (damper).point: 9.997 mm off the line of link tie_rod (a binary link '
     'turns freely about its line'),
    ({**DAMPER, 'type': 'spring', 'arm': 'lower_arm', 'point': [0.0, 580.0, 170.0],
      'rate': -35.0, 'free_length': 320.0},
     'elements[0] (damper).rate: -35.0 N/mm is outside 0.001 to 1e+11 N/mm'),
    ({**DAMPER, 'type': 'spring', 'carrier': [0.0, 700.0, 200.0], 'rate': 35.0},
     'elements[0] (damper).free_length: missing: rate and free_length go together'),
    ({**DAMPER, 'carrier': [0.0, 700.0, 200.0], 'rate': 35.0, 'free_length': 300.0},
     'elements[0] (damper).rate: only a spring has a rate and a free length (this is a '
     'damper)'),
    ({**DAMPER, 'arm': 'tie_rod', 'point': [0.0, 580.0, 170.0]},
     'elements[0] (damper).arm: tie_rod is a link (sphere), not an arm (circle): use '
     'link: tie_rod'),
    ({**DAMPER, 'along': 'lower_arm'},
     'elements[0] (damper).along: lower_arm is an arm (circle), not a strut (line)'),
    ({**DAMPER, 'carier': [0.0, 700.0, 200.0]},
     'elements[0] (damper).carier: unknown key (did you mean carrier?)'),
    ({**DAMPER, 'type': 'shock', 'carrier': [0.0, 700.0, 200.0]},
     "elements[0] (damper).type: unknown value 'shock' (expected one of: spring, damper, "
     'length)'),
    ({**DAMPER, 'carrier': [0.0, 700.0, 200.0], 'arm': 'lower_arm', 'point': [0, 1, 2]},
     'elements[0] (damper): give exactly one of carrier'),
    ({**DAMPER, 'body': [10.0, 700.0, 160.0], 'arm': 'lower_arm', 'point': [10.0, 700.0, 160]},
     'elements[0] (damper): the body point and the moving point coincide at design'),
    ({**DAMPER, 'name': 'damper left', 'carrier': [0.0, 700.0, 200.0]},
     "elements[0].name: 'damper left' is not a ROS name token"),
]


IDS = [said.split(': ', 1)[1][:30] for _, said in BAD]


@pytest.mark.parametrize('element, said', BAD, ids=IDS)
def test_a_bad_element_is_one_line_naming_the_field_and_status_2(tmp_path, capsys, element,
                                                                 said):
    path = scene_with(tmp_path, element)
    assert f'linkage-sweep: {path}: {said}' in sweep_error(capsys, path)


def test_two_elements_of_one_name_are_refused(tmp_path, capsys):
    element = {**DAMPER, 'carrier': [0.0, 700.0, 200.0]}
    path = scene_with(tmp_path, element, element)
    assert 'elements[1] (damper).name: used twice' in sweep_error(capsys, path)


def test_a_strut_element_takes_no_body_point(tmp_path):
    path = scene_with(tmp_path, {'name': 'strut', 'type': 'damper', 'along': 'strut',
                                 'body': [0.0, 0.0, 0.0]}, base='macpherson')
    with pytest.raises(SceneError, match='along: strut takes both ends from the strut'):
        load_scene(path)


def test_a_point_within_the_tolerance_of_a_links_line_is_put_onto_the_line(tmp_path):
    # tie_rod from (-150, 300, 250) to (-140, 690, 260): 0.1 mm off it is accepted (typed
    # coordinates), and the point used is its projection onto the line.
    path = scene_with(tmp_path, {**DAMPER, 'link': 'tie_rod', 'point': [-145.0, 495.0, 255.1]})
    point = load_scene(path).elements[0].mount.point
    assert point == pytest.approx([-145.0, 495.0, 255.0], abs=0.003)


def test_a_metre_scene_reads_rate_in_newtons_per_metre_and_free_length_in_metres(tmp_path):
    path = scene_with(tmp_path, {'name': 'strut', 'type': 'spring', 'along': 'strut',
                                 'rate': 35000.0, 'free_length': 0.4}, base='macpherson')
    spring = load_scene(path).elements[0]
    assert (spring.rate, spring.free_length) == pytest.approx((35.0, 400.0))


def test_elements_of_a_scene_without_any_are_refused_by_the_sweep(capsys):
    code = main(['chrono_generic_macpherson', '--elements'])
    assert code == 2
    assert capsys.readouterr().err == ('linkage-sweep: --elements: chrono_generic_macpherson '
                                       'lists no elements (doc/elements.md)\n')


NAMES = ['lower_arm', 'upper_arm', 'tie_rod', 'strut', 'lower_front', 'spring', 'damper',
         'length', 'carrier']
scalars = (st.none() | st.booleans() | st.integers(-10**400, 10**400) | st.floats()
           | st.text(max_size=8) | st.sampled_from(NAMES))
fuzz_values = st.recursive(scalars, lambda children: st.lists(children, max_size=4)
                           | st.dictionaries(st.text(max_size=6), children, max_size=3),
                           max_leaves=8)
KEYS = ['name', 'type', 'body', 'carrier', 'arm', 'link', 'along', 'point', 'rate',
        'free_length', 'carier']


@settings(deadline=None, database=None, max_examples=150,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(base=st.sampled_from(['double_wishbone', 'five_link', 'macpherson']),
       key=st.sampled_from(KEYS), new=fuzz_values, delete=st.booleans())
def test_an_element_with_one_field_broken_loads_or_is_one_scene_error_naming_it(
        tmp_path, base, key, new, delete):
    data = yaml.safe_load(Path(load_scene(base).source).read_text())
    element = data['elements'][0]
    if delete:
        element.pop(key, None)
    else:
        element[key] = new
    path = tmp_path / 'scene.yaml'
    path.write_text(yaml.safe_dump(data))
    try:
        scene = load_scene(path)
    except SceneError as exc:
        assert exc.field.startswith('elements') and '\n' not in str(exc), str(exc)
        return
    result = sweep(scene, [-20.0, 0.0, 20.0])
    values = element_values(scene, result.wheel_center, result.rotation)
    assert np.isfinite(values.length).all() and np.isfinite(values.ratio).all()
