# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
launch/suspension.launch.xml, tested without the launch tooling (it has no wheel).

What can be checked here: the file parses as XML in ROS 2's launch format; it starts an
executable the package installs (console_scripts) from this package; setup.py installs it into
share/linkage_ros/launch; each argument sets a parameter of the node; the parameters file it
names exists, and the node started with it and the arguments' defaults has the file's values,
the arguments' taking precedence. The arguments are given as launch_ros passes a <node>'s
<param name= value=> entries: a parameters file of their own, after the <param from=> one,
under the node's full name (so the node must have the name the launch file gives it), values
typed as launch types them (here all text).
"""

from importlib.metadata import distribution
from pathlib import Path
import re
import xml.etree.ElementTree as ET

from linkage_ros.ros.node import SuspensionNode
from linkage_ros.ros.parameters import PARAMETERS
import yaml

PACKAGE = Path(__file__).resolve().parents[2]
LAUNCH = PACKAGE / 'launch' / 'suspension.launch.xml'
SHARE = '$(find-pkg-share linkage_ros)/'      # share/linkage_ros/X is the repository's X


def launch_file():
    """Return the launch file's root, its <arg> defaults and its one <node>."""
    root = ET.parse(LAUNCH).getroot()
    args = {arg.get('name'): arg.get('default') for arg in root.iter('arg')}
    (node,) = root.iter('node')
    return root, args, node


def substituted(text, args):
    """Return text with $(var NAME) replaced by the argument's default, as ros2 launch does."""
    return re.sub(r'\$\(var (\w+)\)', lambda match: args[match.group(1)], text)


def test_the_launch_file_is_xml_in_the_launch_format_with_described_arguments():
    root, args, _ = launch_file()
    assert root.tag == 'launch'
    assert set(args) == {'params_file', 'scene', 'vehicle', 'record_mcap', 'rerun_rrd'}
    assert all(arg.get('description') for arg in root.iter('arg'))


def test_the_launch_file_starts_an_executable_this_package_installs():
    _, _, node = launch_file()
    package = ET.parse(PACKAGE / 'package.xml').getroot().findtext('name')
    scripts = {entry.name: entry.value for entry in distribution('linkage_ros').entry_points
               if entry.group == 'console_scripts'}
    assert node.get('pkg') == package == 'linkage_ros'
    assert scripts[node.get('exec')] == 'linkage_ros.ros.entry:main'


def test_setup_installs_the_launch_file_into_the_share_folder():
    setup = (PACKAGE / 'setup.py').read_text()
    assert "('share/' + package_name + '/launch', glob('launch/*.launch.xml'))" in setup


def test_every_argument_sets_a_parameter_of_the_node_of_its_name():
    _, args, node = launch_file()
    named = {param.get('name'): param.get('value') for param in node.iter('param')
             if param.get('name')}
    assert set(named) <= set(PARAMETERS)
    assert named == {name: f'$(var {name})' for name in set(args) - {'params_file'}}


def test_the_parameters_file_it_names_exists_and_the_node_takes_it(ros_context, tmp_path):
    _, args, node = launch_file()
    (file_param,) = [param.get('from') for param in node.iter('param') if param.get('from')]
    path = substituted(file_param, args)
    assert path.startswith(SHARE)
    params_file = PACKAGE / path[len(SHARE):]
    assert params_file.is_file()
    given = {param.get('name'): substituted(param.get('value'), args)
             for param in node.iter('param') if param.get('name')}
    launch_params = tmp_path / 'launch_params.yaml'
    launch_params.write_text(yaml.safe_dump({'/' + node.get('name'): {
        'ros__parameters': given}}))
    with params_file.open() as stream:
        in_file = yaml.safe_load(stream)['/**']['ros__parameters']
    started = SuspensionNode(context=ros_context, cli_args=[
        '--ros-args', '--params-file', str(params_file), '--params-file', str(launch_params)])
    try:
        values = {name: started.get_parameter(name).value for name in in_file}
        name = started.get_name()
    finally:
        started.destroy_node()
    assert name == node.get('name')
    assert values == {**in_file, **given}
    assert set(in_file) == set(PARAMETERS)
