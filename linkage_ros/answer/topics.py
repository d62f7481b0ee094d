# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Every topic of suspension_node: its inputs, the answer to a command, and the node's own.

    TOPICS                      (Topic, ...): inputs, then protocol.OUTPUTS in publishing
                                order, then what the node publishes beside the answers
    markdown_table()            the table of doc/node.md#topics, from TOPICS

`python -m linkage_ros.answer.topics` prints the table; doc/node.md holds it between markers,
and test/answer/test_topics.py checks that it is this one. Names are relative to a corner's
namespace (a vehicle's corner: front_left/wheel_travel, ...) unless they start with /.
"""

from __future__ import annotations

from typing import NamedTuple

from .protocol import CONTACT_WRENCH, OUTPUTS, WRENCH_TYPE


class Topic(NamedTuple):
    """One topic of the node: its name, type, direction and content (when: what turns it on)."""

    name: str
    type_name: str
    direction: str      # 'in' or 'out'
    content: str


INPUTS = (
    Topic('wheel_travel', 'std_msgs/msg/Float64', 'in', 'wheel travel, m, + = bump'),
    Topic('steering_rack', 'std_msgs/msg/Float64', 'in',
          'rack travel, m, + = rack to the left; solved at the last travel; only for scenes '
          'with a `steer: rack` link'),
    Topic('joint_states', 'sensor_msgs/msg/JointState', 'in',
          'the position of joint `travel_joint` as the travel, m; with a vehicle, the joints '
          'its file names'),
    Topic(CONTACT_WRENCH, WRENCH_TYPE, 'in',
          "with statics (a scene with bushings, or `-p statics:=true`): the tyre's force (N) "
          'and moment (N m) at the contact patch, in `frame_id`, each component within 1e7 N '
          'and 1e6 N m; every answer is then the loaded pose at the last one '
          '([Statics](#statics-contact-wrench-in-pickup-forces-out))'),
    Topic('/clock', 'rosgraph_msgs/msg/Clock', 'in',
          'only with `use_sim_time`: the node clock, each message taken in order with the '
          'commands ([Simulated time](#simulated-time))'),
)
# The contents the answer's table says more of than protocol.OUTPUTS (its own words).
_ANSWER = {
    'wheel_carrier_pose': 'wheel centre (m) in `frame_id`; carrier orientation relative to its '
                          'design position (identity at design)',
    'camber': 'with `angles` (on by default): rad, + = top of the wheel outboard',
    'toe': 'with `angles` (on by default): rad, + = toe-in',
    'alignment': 'with `-p alignment:=true`: 14 fields of the alignment set in SI '
                 '([doc/alignment.md](alignment.md))',
    'markers': 'with `-p markers:=true`: links (LINE_LIST) and joints (SPHERE_LIST) for RViz',
    'elements': 'only for a scene with `elements`, with `elements` (on by default): `name` the '
                'element names, `position` each length (m), `velocity` each motion ratio d '
                'length / d travel (m/m, + = lengthens in bump: not a speed) '
                '([doc/elements.md](elements.md))',
    '/tf': 'with `tf` (on by default): per answer, the frames of the carrier and of every '
           'link, arm and strut, children of `frame_id`, stamped as the answer '
           '([TF](#tf-and-the-robot-description))',
    'pickup': 'with statics and `pickups` (on by default), per answer: the force (N) on the '
              'body at each pickup (`<link>_base`, `<arm>_axis0`, `<arm>_axis1` or '
              "`<arm>_centre`, `<strut>_top`, `<spring>_body`) and a bushing's couple (N m), in "
              "the pickup's frame",
}
NODE_OUTPUTS = (
    Topic('/diagnostics', 'diagnostic_msgs/msg/DiagnosticArray', 'out',
          'one status per corner, every `diagnostic_period`, and at once for a bad command or '
          'a change of level ([Diagnostics](#diagnostics-and-bad-commands))'),
    Topic('/tf_static', 'tf2_msgs/msg/TFMessage', 'out',
          "with `tf`: each wheel's frame, fixed to its carrier, and with statics each body "
          "pickup's frame `pickup/<name>`; reliable, transient local, depth 1"),
    Topic('robot_description', 'std_msgs/msg/String', 'out',
          'with `tf`: the URDF of the scene or vehicle (`linkage-urdf` writes the same); '
          'transient local, depth 1'),
    Topic('<axle>/roll_centre', 'geometry_msgs/msg/PointStamped', 'out',
          'only with a vehicle file that has axles, with `roll_centres` (on by default): the '
          "axle's roll centre in `frame_id`, m ([doc/axle.md](axle.md#roll-centre))"),
)
TOPICS = (*INPUTS,
          *(Topic('pickup/<name>' if o.name == 'pickup' else o.name, o.type_name, 'out',
                  _ANSWER[o.name]) for o in OUTPUTS),
          *NODE_OUTPUTS)


def markdown_table() -> str:
    """Return the table of every topic (doc/node.md#topics), in TOPICS' order."""
    rows = ['| topic | type | content |', '|---|---|---|']
    for topic in TOPICS:
        package, _, name = topic.type_name.partition('/msg/')
        suffix = ' (in)' if topic.direction == 'in' else ''
        rows.append(f'| `{topic.name}`{suffix} | {package}/{name} | {topic.content} |')
    return '\n'.join(rows) + '\n'


if __name__ == '__main__':
    print(markdown_table(), end='')
