# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node --help and config/suspension.yaml name everything the node has.

What the node has is asked of the node itself: its topics from the ROS graph (its publishers
and subscriptions by node name, with every output turned on: a vehicle with axles and steered
corners whose scenes have elements, alignment, markers and TF; a single scene with a travel
joint), its parameters from its parameter list. A topic or parameter added to the node and
not to the help or the params file fails here. (Without tf2_msgs the node has no /tf and
/tf_static to ask about: live_tf_topics says which it has.)
"""

from pathlib import Path
import re

from linkage_ros.core.model import load_vehicle
from linkage_ros.ros import solve_service
from linkage_ros.ros.entry import help_text
from linkage_ros.ros.parameters import ROS_PARAMETERS, ROS_PREFIXES
from linkage_ros.ros.testing import live_tf_topics
import pytest
import yaml

PARAMS_FILE = Path(__file__).resolve().parents[2] / 'config' / 'suspension.yaml'
# What rclpy itself creates on every node: not the node's to document.
RCLPY_TOPICS = {'/parameter_events', '/rosout', '/clock'}
EVERY_OUTPUT = {'alignment': True, 'markers': True, 'tf': True}
STARTS = {
    'vehicle': dict(vehicle='demo_vehicle', **EVERY_OUTPUT),
    'scene': dict(scene='double_wishbone', travel_joint='wheel_joint', **EVERY_OUTPUT),
}


def help_section(title: str) -> str:
    """Return the lines of --help from the line starting with title to the next blank line."""
    text = help_text()
    start = text.index('\n' + title) + 1
    return text[start:text.index('\n\n', start)]


def node_topics(node) -> set[str]:
    """Return the node's topics as the ROS graph lists them, rclpy's own left out."""
    name, namespace = node.get_name(), node.get_namespace()
    found = node.get_publisher_names_and_types_by_node(name, namespace) + \
        node.get_subscriber_names_and_types_by_node(name, namespace)
    return {topic for topic, _ in found} - RCLPY_TOPICS


def documented_name(topic: str) -> str:
    """
    Return the name the help gives topic: '/front_left/camber' -> 'camber'.

    A vehicle's corner topics go under the corner's name and an axle's under the axle's
    ('/front/roll_centre' -> '<axle>/roll_centre'); the statics' pickup topics are one family
    ('/pickup/lower_arm_axis1' -> 'pickup/<name>'); /diagnostics, /tf, /tf_static are named
    absolute; any other topic of the root namespace relative ('/camber' -> 'camber').
    """
    vehicle = load_vehicle('demo_vehicle')
    parts = topic.strip('/').split('/')
    if len(parts) > 1 and parts[0] in vehicle.corners:
        parts = parts[1:]
    elif len(parts) == 2 and parts[0] in vehicle.axles.axles:
        return '<axle>/' + parts[1]
    if len(parts) == 2 and parts[0] == 'pickup':
        return 'pickup/<name>'
    assert len(parts) == 1, topic
    return topic if topic in ('/diagnostics', '/tf', '/tf_static') else parts[0]


def listed(name: str, text: str) -> bool:
    """Say whether name stands in text as a whole name (camber, not camber_x or /camber)."""
    return re.search(rf'(?<![\w/<>]){re.escape(name)}(?![\w/])', text) is not None


@pytest.mark.parametrize('start', STARTS)
def test_help_lists_every_topic_the_node_creates(suspension_node, executor, start):
    node = suspension_node(**STARTS[start])
    topics = node_topics(node)
    assert {'/robot_description', *live_tf_topics()} <= topics
    names = {documented_name(topic) for topic in topics}
    text = help_section('topics')
    missing = sorted(name for name in names if not listed(name, text))
    assert missing == [], f'topics of the node ({start}) missing from suspension_node --help'


def test_the_vehicle_start_has_the_topics_the_help_lacked_before(suspension_node, executor):
    names = {documented_name(t) for t in node_topics(suspension_node(**STARTS['vehicle']))}
    assert {'elements', 'robot_description', '<axle>/roll_centre', 'steering_rack',
            'joint_states', '/diagnostics', *live_tf_topics()} <= names


def own_parameters(node) -> dict:
    """Return {name: value} of the node's own parameters (rclpy's and QoS overrides left out)."""
    names = [name for name in node.list_parameters([], 0).names
             if name not in ROS_PARAMETERS and not name.startswith(ROS_PREFIXES)]
    return {name: node.get_parameter(name).value for name in names}


def test_the_params_file_lists_every_parameter_with_its_default(suspension_node, executor):
    defaults = own_parameters(suspension_node())      # the node as started with nothing given
    del defaults['scene']                             # the fixture gives the default scene
    with PARAMS_FILE.open() as stream:
        in_file = yaml.safe_load(stream)['/**']['ros__parameters']
    assert sorted(in_file) == sorted([*defaults, 'scene'])
    assert {name: in_file[name] for name in defaults} == defaults
    assert in_file['scene'] == 'five_link'


def test_help_lists_every_parameter_with_its_default(suspension_node, executor):
    parameters = own_parameters(suspension_node(**STARTS['vehicle']))
    text = help_section('parameters')
    for name in parameters:
        assert re.search(rf'^  {name} +\S', text, re.M), f'{name} missing from --help'
    assert re.search(r'^  tf +True ', text, re.M)


@pytest.mark.parametrize('start', STARTS)
def test_help_lists_every_service_the_node_serves_but_rclpy_s_own(
        suspension_node, executor, start):
    # rclpy's parameter and type-description services are every node's; the node's own are
    # the corners' solve services (where linkage-tf2-msgs built linkage_ros_interfaces).
    node = suspension_node(**STARTS[start])
    served = node.get_service_names_and_types_by_node(node.get_name(), node.get_namespace())
    own = {name.rsplit('/', 1)[1] for name, types in served
           if not types[0].startswith(('rcl_interfaces/', 'type_description_interfaces/'))}
    if solve_service.solve_type() is not None:
        assert own == {'solve'}
    missing = sorted(name for name in own if not listed(name, help_section('topics')))
    assert missing == [], f'services of the node ({start}) missing from suspension_node --help'
