# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
What a node under test wrote, read back: MCAP messages, its TF topics, warnings, URDF text.

Helpers of the pytest plugin (testing.py, which gives them under its own name too); plain
functions, importing what they read with when first called.
"""

import math


def read_mcap_ros2(path):
    """Return {topic: [message]} of an MCAP file as mcap-ros2-support decodes them."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    out = {}
    with open(path, 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        for _, channel, _, message in reader.iter_decoded_messages():
            out.setdefault(channel.topic, []).append(message)
    return out


def live_tf_topics():
    """
    Return the TF topics a node of this environment publishes: /tf and /tf_static, or none.

    Without tf2_msgs (it has no wheel; `linkage-tf2-msgs` builds it where a compiler is) the
    node records its frames but publishes neither (ros/tf.tf2_msgs_missing).
    """
    from ..answer.frames import tf2_msgs_missing
    return set() if tf2_msgs_missing() else {'/tf', '/tf_static'}


def node_warnings(err):
    """
    Return the [WARN] lines of a node's stderr, but the one-time notices of what is not built.

    Those notices (no tf2_msgs, no linkage_ros_interfaces) say what this environment lacks,
    not what the test did.
    """
    from .solve_service import MISSING, solve_type
    from ..answer.frames import tf2_msgs_missing
    missing = [text for text in (tf2_msgs_missing(), solve_type() is None and MISSING) if text]
    return [line for line in err.splitlines()
            if '[WARN]' in line and not any(line.endswith(text) for text in missing)]


def urdf_differences(a, b, abs_tol=1e-12):
    """
    Return where URDF texts a and b differ (empty if they describe the same robot).

    The trees must match element by element and attribute by attribute; an attribute made of
    numbers (xyz and sizes in m, rpy in rad, rgba) compares each number within abs_tol plus
    one unit in the 12th significant digit (robot_description writes 12 digits, so a
    round-off of 1 ulp can change the last one printed). Another text is an exact match.
    """
    import xml.etree.ElementTree as ElementTree

    def numbers(text):
        try:
            return [float(v) for v in text.split()]
        except ValueError:
            return None

    found = []

    def walk(x, y, path):
        if (x.tag, sorted(x.attrib), len(x)) != (y.tag, sorted(y.attrib), len(y)):
            found.append(f'{path}: <{x.tag} {sorted(x.attrib)}> with {len(x)} children '
                         f'against <{y.tag} {sorted(y.attrib)}> with {len(y)}')
            return
        for key, u in x.attrib.items():
            v = y.attrib[key]
            p, q = numbers(u), numbers(v)
            same = (u == v if p is None or q is None or len(p) != len(q) else all(
                math.isclose(s, t, rel_tol=1e-11, abs_tol=abs_tol) for s, t in zip(p, q)))
            if not same:
                found.append(f'{path}/@{key}: {u!r} against {v!r}')
        for i, (s, t) in enumerate(zip(x, y)):
            walk(s, t, f'{path}/{s.tag}[{i}]')

    walk(ElementTree.fromstring(a), ElementTree.fromstring(b), '')
    return found
