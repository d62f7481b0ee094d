# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Names that topics, TF frames and URDF names are made of are ROS name tokens (issue 36, item 3).

A constraint's, an element's and a vehicle corner's name becomes part of the node's topics
(<corner>/pickup/<constraint>_axis0, <corner>/solve, ...), its TF frames and the URDF's link
and joint names. The rule (core.model.NAME_TOKEN_RULE): a letter, then letters, digits and _,
without __ or a trailing _, at most 64 characters. Generated names (hypothesis): every
accepted one gives topics and frames that rclpy's own validators accept and a URDF that
parses with every joint between links it names; every refused one is one line at load naming
the file, the field, the name and the rule (unicode, dashes, digits first, long, __).
"""

import copy
from pathlib import Path
import xml.etree.ElementTree as ElementTree

from hypothesis import example, given, HealthCheck, settings, strategies as st
from linkage_ros.answer.frames import CornerFrames
from linkage_ros.answer.pickups import pickup_points
from linkage_ros.answer.robot_description import robot_description
from linkage_ros.core.base.errors import bounded, WHERE_LIMIT
from linkage_ros.core.model import load_scene, load_vehicle, NAME_TOKEN_MAX, SceneError, \
    token_problem
from linkage_ros.core.model.fields import PLAIN_KEY
from linkage_ros.ros.corner import corner_topics
from rclpy.validate_full_topic_name import validate_full_topic_name
from rclpy.validate_namespace import validate_namespace
import yaml

ROOT = Path(__file__).resolve().parents[2]
BASE = yaml.safe_load((ROOT / 'config' / 'scenes' / 'double_wishbone_bushings.yaml').read_text())
CONSTRAINTS = [c['name'] for c in BASE['constraints']]     # upper_arm, lower_arm, tie_rod
PARAMS = {'travel_joint': 'wheel', 'statics': True, 'alignment': True, 'markers': True,
          'tf': True}
NAMES = settings(deadline=None, database=None, max_examples=60,
                 suppress_health_check=[HealthCheck.function_scoped_fixture,
                                        HealthCheck.too_slow])
tokens = st.from_regex(r'\A[A-Za-z][A-Za-z0-9_]{0,70}\Z').filter(lambda n: not token_problem(n))
hostile = (st.text(min_size=0, max_size=80) | st.sampled_from(
    ['lower-arm', 'unterer_Querlenker_ü', '9arm', 'arm_', 'a__b', '_arm', 'arm 1', 'x' * 65,
     'Arm\x00', '/arm', 'arm/1', 'ärm', '', 'x' * 5000])).filter(lambda n: bool(token_problem(n)))


def quoted(name):
    """Return name as a YAML double-quoted scalar, every character escaped (U and 8 digits)."""
    return '"' + ''.join(f'\\U{ord(c):08x}' for c in name) + '"'


def scene_named(tmp_path, names, element='spring'):
    """
    Write double_wishbone_bushings with its constraints and spring renamed; return it.

    Each name goes in as a YAML double-quoted scalar with every character escaped (quoted):
    the file's reader reads back exactly the name given, whatever it holds.
    """
    data = copy.deepcopy(BASE)
    data.pop('reference')
    given = {f'NAME{i}x': name for i, name in enumerate([*names, element])}
    rename = dict(zip(CONSTRAINTS, given))
    for c in data['constraints']:
        c['name'] = rename[c['name']]
    for e in data['elements']:
        e['arm'] = rename[e['arm']]
        if e['name'] == 'spring':
            e['name'] = f'NAME{len(names)}x'
    text = yaml.safe_dump(data)
    for placeholder, name in given.items():
        text = text.replace(placeholder, quoted(name))
    path = tmp_path / 'scene.yaml'
    path.write_text(text, encoding='utf-8')
    return path


def assert_valid_topic(name):
    validate_full_topic_name(name if name.startswith('/') else '/' + name)   # raises if not


@NAMES
@given(names=st.lists(tokens, min_size=3, max_size=3, unique=True), element=tokens,
       corner=tokens)
@example(names=['a', 'B', 'c1'], element='s', corner='x' * NAME_TOKEN_MAX)
def test_every_accepted_name_makes_valid_topics_frames_and_a_urdf(
        tmp_path, names, element, corner):
    if element == 'damper':
        element = 'damper2'      # the scene's other element
    scene = load_scene(scene_named(tmp_path, names, element))
    prefix = f'{corner}/'
    validate_namespace('/' + corner)
    topics = corner_topics(scene, PARAMS, prefix) + [prefix + 'solve']
    assert f'{prefix}pickup/{element}_body' in topics
    for topic in topics:
        assert_valid_topic(topic)
    frames = CornerFrames(scene, 'base_link', prefix, {
        f'{prefix}pickup/{n}': p for n, p in pickup_points(scene).items()})
    for frame in [*frames.names, *frames.pickups]:
        assert_valid_topic(frame)          # a frame is a topic-like name: tf2 takes it
    urdf = ElementTree.fromstring(robot_description({prefix: scene}, 'base_link', 'robot'))
    links = [link.get('name') for link in urdf.iter('link')]
    assert len(links) == len(set(links)) and set(frames.names) <= set(links)
    for joint in urdf.iter('joint'):
        assert {joint.find('parent').get('link'), joint.find('child').get('link')} <= set(links)


@NAMES
@given(name=hostile, where=st.sampled_from(['constraint', 'element', 'corner']))
@example(name='lower-arm', where='constraint')
@example(name='unterer_Querlenker_ü', where='constraint')
@example(name='9arm', where='corner')
def test_every_refused_name_is_one_line_naming_file_field_name_and_rule(tmp_path, name, where):
    if where == 'corner':
        path = tmp_path / 'vehicle.yaml'     # an explicit key: any length, any character
        path.write_text(f'corners:\n  ? {quoted(name)}\n  : {{scene: macpherson}}\n')
        field = f'corners.{name if PLAIN_KEY.match(name) else repr(name)}'
    else:
        names = [name, 'lower_arm', 'tie_rod'] if where == 'constraint' else CONSTRAINTS
        path = scene_named(tmp_path, names, name if where == 'element' else 'spring')
        field = 'constraints[0].name' if where == 'constraint' else 'elements[1].name'
    try:
        (load_vehicle if where == 'corner' else load_scene)(path)
    except SceneError as exc:
        said = str(exc)
    else:
        raise AssertionError(f'{name!r} was taken as a {where} name')
    assert '\n' not in said
    # a name of thousands of characters is cut in the middle, as every error line is
    assert said.startswith(f"{bounded(f'{path}: {field}', WHERE_LIMIT)}: ")
    assert 'is not a ROS name token' in said and f'at most {NAME_TOKEN_MAX} characters' in said
    assert repr(name)[:60] in said


def test_two_constraints_of_one_name_are_refused_naming_both(tmp_path):
    path = scene_named(tmp_path, ['upper_arm', 'lower_arm', 'tie_rod'])
    data = yaml.safe_load(path.read_text())
    data['constraints'][2]['name'] = 'upper_arm'      # a sphere: pickup upper_arm_base
    path.write_text(yaml.safe_dump(data))
    try:
        load_scene(path)
    except SceneError as exc:
        assert str(exc) == (f'{path}: constraints[2] (upper_arm).name: used twice '
                            '(constraints[0] too): names make topics, frames and columns, so '
                            'each constraint needs its own')
    else:
        raise AssertionError('two constraints named upper_arm were taken')


def test_the_doc_s_example_line_is_what_the_loader_says():
    said = f"my_corner.yaml: constraints[1].name: {token_problem('lower-arm')}"
    assert f'linkage-sweep: {said}\n' in (ROOT / 'doc' / 'scenes.md').read_text()
