# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
ROS 2 interfaces as rosbag2 stores them in an MCAP file: schemas, type hashes, QoS profiles.

    message_definition('std_msgs/msg/Float64')  -> the 'ros2msg' schema text: the .msg text
                                                   with every dependency appended, as
                                                   rosbag2_storage_mcap's message_definition_cache
                                                   writes it; a service's request or
                                                   response ('pkg/srv/Solve_Request') is
                                                   that half of its .srv
    type_hash(type name)                        -> 'RIHS01_...' from the installed .json
    qos_profile_dict(QoSProfile or dict)        -> the profile as rosbag2 (metadata version 9)
                                                   writes it
    dump(data)                                  -> YAML as yaml-cpp dumps it for rosbag2
    qualified(topic)                            -> '/topic'

The .msg and .json files are found under share/ of AMENT_PREFIX_PATH and sys.prefix, where
the ROS 2 wheels install them, and last in the package's config/interfaces, which holds
tf2_msgs/msg/TFMessage (tf2_msgs has no wheel: /tf is recorded with this definition and type
hash, those of ROS 2's tf2_msgs). No mcap import: the writer and the reader share this module.
"""

import json
import os
from pathlib import Path
import re
import sys

import yaml

from .errors import RecordingError

PROFILE = 'ros2'
SCHEMA_ENCODING = 'ros2msg'
MESSAGE_ENCODING = 'cdr'
METADATA_VERSION = 9           # rosbag2 Jazzy: QoS policies as words, QoS profiles as lists
SEPARATOR = '=' * 80
INFINITE = {'sec': 9223372036, 'nsec': 854775807}   # RMW_DURATION_INFINITE as rosbag2 dumps it
DEFAULT_QOS = {'history': 'keep_last', 'depth': 10, 'reliability': 'reliable',
               'durability': 'volatile', 'deadline': INFINITE, 'lifespan': INFINITE,
               'liveliness': 'automatic', 'liveliness_lease_duration': INFINITE,
               'avoid_ros_namespace_conventions': False}
_PRIMITIVES = {'bool', 'byte', 'char', 'float32', 'float64', 'int8', 'uint8', 'int16', 'uint16',
               'int32', 'uint32', 'int64', 'uint64', 'string'}
# rosbag2_storage_mcap's MSG_FIELD_TYPE_REGEX: the first word of a line is a field type.
_FIELD_TYPE = re.compile(r'(?:^|\n)\s*([a-zA-Z0-9_/]+)(?:\[[^\]]*\])?\s+')
_TYPE_NAME = re.compile(r'^([a-zA-Z][a-zA-Z0-9_]*)/(?:msg/)?([a-zA-Z][a-zA-Z0-9_]*)$')
# A service's request or response, recorded as a message of its own ('pkg/srv/Name_Request')
_SRV_HALF = re.compile(r'^([a-zA-Z][a-zA-Z0-9_]*)/srv/([a-zA-Z][a-zA-Z0-9_]*)_(Request|Response)$')


def share_dirs():
    """
    Folders searched for <pkg>/msg/<Type>.msg.

    AMENT_PREFIX_PATH entries, then sys.prefix, then the package's config/interfaces (the
    definitions it ships for packages that may not be installed: tf2_msgs).
    """
    from ..core.model import config_dir
    prefixes = [p for p in os.environ.get('AMENT_PREFIX_PATH', '').split(os.pathsep) if p]
    dirs = []
    for share in [Path(prefix) / 'share' for prefix in prefixes + [sys.prefix]] + [
            config_dir() / 'interfaces']:
        if share not in dirs:
            dirs.append(share)
    return dirs


def _split_type(type_name):
    """'pkg/msg/Type' or 'pkg/Type' -> (pkg, Type); RecordingError for anything else."""
    match = _TYPE_NAME.match(type_name)
    if not match:
        raise RecordingError(f'type {type_name!r}', 'expected a ROS 2 message type like '
                             "'std_msgs/msg/Float64'")
    return match.group(1), match.group(2)


def _interface_text(type_name):
    """Return the .msg text of a type, or that half of its .srv for a service's half."""
    half = _SRV_HALF.match(type_name)
    if half is None:
        return _interface_file(type_name, '.msg').read_text()
    package, name, which = half.groups()
    for share in share_dirs():
        path = share / package / 'srv' / f'{name}.srv'
        if path.is_file():
            request, _, response = path.read_text().partition('\n---\n')
            return request + '\n' if which == 'Request' else response
    raise RecordingError(f'type {type_name!r}', f'no {name}.srv found (searched '
                         f'{", ".join(str(s / package / "srv") for s in share_dirs())})')


def _interface_file(type_name, suffix):
    package, name = _split_type(type_name)
    for share in share_dirs():
        path = share / package / 'msg' / f'{name}{suffix}'
        if path.is_file():
            return path
    searched = ', '.join(str(s / package / 'msg') for s in share_dirs())
    raise RecordingError(f'type {type_name!r}', f'no {name}{suffix} found (searched '
                         f'{searched}); is the message package installed?')


def msg_dependencies(text, package):
    """Sorted dependency names ('pkg/Type') of a .msg text, as rosbag2_storage_mcap finds them."""
    deps = set()
    for match in _FIELD_TYPE.finditer(text):
        kind = match.group(1)
        if kind not in _PRIMITIVES:
            deps.add(kind if '/' in kind else f'{package}/{kind}')
    return sorted(deps)


def message_definition(type_name):
    """
    Return the full 'ros2msg' schema text of a type.

    That is its .msg text, then each dependency (depth first, once each) after a line of 80
    '=' and a line 'MSG: pkg/Type'.
    """
    seen = set()

    def append(name):
        half = _SRV_HALF.match(name)
        package = half.group(1) if half else _split_type(name)[0]
        text = _interface_text(name)
        for dep in msg_dependencies(text, package):
            if dep not in seen:
                seen.add(dep)
                text += f'\n{SEPARATOR}\nMSG: {dep}\n' + append(dep)
        return text

    return append(type_name)


def type_hash(type_name):
    """Return the 'RIHS01_...' hash of a type, from its installed .json ('' if none)."""
    if _SRV_HALF.match(type_name):    # the hash of a service's half is in its .srv's .json
        return ''
    try:
        data = json.loads(_interface_file(type_name, '.json').read_text())
    except RecordingError:
        return ''
    package, name = _split_type(type_name)
    for entry in data.get('type_hashes', []):
        if entry.get('type_name') == f'{package}/msg/{name}':
            return entry.get('hash_string', '')
    return ''


def qos_profile_dict(profile=None):
    """
    Return a QoS profile as rosbag2 (metadata version 9) writes it.

    profile: an rclpy QoSProfile, a dict in rosbag2's form, or None (DEFAULT_QOS). Durations
    of 0 (rclpy's 'default') are written as rosbag2 records the DDS defaults: infinite.
    """
    if profile is None:
        return dict(DEFAULT_QOS)
    if isinstance(profile, dict):    # already in rosbag2's form (e.g. read from a bag)
        return dict(profile)

    def duration(value):
        ns = value.nanoseconds
        return dict(INFINITE) if ns == 0 else {'sec': ns // 10**9, 'nsec': ns % 10**9}

    return {'history': profile.history.name.lower(), 'depth': int(profile.depth),
            'reliability': profile.reliability.name.lower(),
            'durability': profile.durability.name.lower(),
            'deadline': duration(profile.deadline), 'lifespan': duration(profile.lifespan),
            'liveliness': profile.liveliness.name.lower(),
            'liveliness_lease_duration': duration(profile.liveliness_lease_duration),
            'avoid_ros_namespace_conventions': bool(profile.avoid_ros_namespace_conventions)}


class _PlainDumper(yaml.SafeDumper):
    """YAML as yaml-cpp dumps it for rosbag2: no anchors or aliases for repeated values."""

    def ignore_aliases(self, data):
        return True


def dump(data):
    """Return data as YAML the way yaml-cpp dumps it for rosbag2 (no aliases)."""
    return yaml.dump(data, Dumper=_PlainDumper, sort_keys=False, default_flow_style=False)


def qualified(topic):
    """Topic name with a leading '/': recorded names are fully qualified, as rosbag2 records."""
    return topic if topic.startswith('/') else '/' + topic
