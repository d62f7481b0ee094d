# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The project's tests use the fixtures of its pytest plugin, linkage_ros_pytest.

The run enters a private network first where it can (root on Linux): a network namespace
with only lo and a /dev/shm of its own, so that what the cross-process tests publish reaches
no other process of the machine, and nothing of theirs reaches the tests, whatever domain
both use. Elsewhere, or with LINKAGE_ROS_PRIVATE_NETWORK=0, the cross-process tests run on
the user's ROS_DOMAIN_ID (0 if unset) beside the machine's other ROS processes. The header
of the run says which.

They are imported by name rather than through pytest_plugins: once the pytest11 entry point
of an installed linkage_ros registers the same module, pytest_plugins would register it a
second time (an error); names defined here simply take precedence.

Markers, set here by what a test uses (pytest_collection_modifyitems), so that the test files
need not say it and a new test is marked as soon as it uses the fixture or the call:
    ros      it starts ROS: a Context, an executor, a node or a probe (the fixtures below), or
             a node in another process
    process  it starts a process: the node_process fixture, or subprocess in the test, in a
             fixture it uses, or in a function of its module that it calls
    slow     one of the longest of the rest (SLOW below, measured with --durations)
    optional its module touches what linkage-tf2-msgs builds (OPTIONAL: live /tf, the solve
             service) or what the node says when they are missing: the tests CI runs again
             in an environment without them
The inner loop is `pytest -m "not ros and not process and not slow"`.
"""

import ast
import functools
import inspect
import os
import sys
import textwrap

from linkage_ros.ros.isolation import enter_private_network, environment_domain_id, \
    PrivateNetwork
from linkage_ros.ros.testing import connect, Probe, spin_until, stamp_ns  # noqa: F401 (helpers)
from linkage_ros_pytest import (  # noqa: F401 (the plugin's fixtures, for the test modules)
    domain_id, executor, localhost_context, localhost_executor, node_process, probe, ros_context,
    ros_environment, send_travel, suspension_node)
import pytest

NETWORK = pytest.StashKey[PrivateNetwork]()
# Fixtures that start ROS in this process or another.
ROS_FIXTURES = {'ros_context', 'localhost_context', 'executor', 'localhost_executor', 'probe',
                'suspension_node', 'send_travel', 'node_process'}
# Names whose use in a test (or in what it calls) starts a process.
# (workers=, processes=: a pool or a Dask cluster of processes)
PROCESS_NAMES = {'subprocess', 'node_process', 'NodeProcess', 'Popen', 'multiprocessing',
                 'ProcessPoolExecutor', 'workers', 'processes'}
# Names whose use starts ROS without a fixture; and what a module that does says (a program's
# main that a test calls, such as linkage-soak's).
ROS_NAMES = {'init_context', 'rclpy', 'SuspensionNode', 'start_suspension_node'}
STARTS_ROS = ('rclpy.init', 'init_context', 'EventsExecutor', 'create_node')
# What a test module names when its tests may go otherwise without tf2_msgs and
# linkage_ros_interfaces (the optional parts that linkage-tf2-msgs builds where it can).
OPTIONAL = ('tf2_msgs', 'linkage_ros_interfaces', 'live_tf_topics', 'node_warnings',
            'solve_service', 'tf_static', "'/tf'", 'robot_description', 'Solve')
# The longest tests of the inner loop (pytest --durations), by file (its basename: basenames
# are unique across test/'s folders) and name without parameters: each more than 9 s on a
# machine shared by several runs (2 s and more alone); together half its time. A name that no
# longer exists in its file is an error, so that a rename cannot drop the mark silently.
SLOW = {
    'test_flake8.py': ['test_flake8'],
    'test_fuzz_inputs.py': [
        'test_a_valid_bag_with_bytes_overwritten_or_cut_gives_a_bag_with_what_is_intact',
        'test_any_declared_size_in_a_chunk_is_checked_before_it_is_read',
        'test_a_bundled_vehicle_with_one_field_broken_loads_or_names_the_field',
        'test_a_bundled_scene_with_one_field_broken_loads_or_names_the_field'],
    'test_stability.py': [
        'test_random_valid_scene_solves_every_reachable_travel_like_the_reference'],
    'test_study_tolerance.py': [
        'test_at_small_sigma_the_monte_carlo_spread_is_the_first_order_one'],
    'test_elements_input.py': [
        'test_an_element_with_one_field_broken_loads_or_is_one_scene_error_naming_it'],
    'test_vary_sensitivity.py': [
        'test_the_compiled_closed_forms_equal_the_jets_for_the_sweep_columns'],
    'test_map.py': ['test_every_stored_value_is_the_direct_solve_at_its_grid_point'],
    'test_statics_energy.py': [
        'test_compliance_rates_agree_with_differences_of_the_energy_reference',
        'test_compliance_matrix_agrees_with_differences_of_the_energy_reference'],
}


def pytest_configure(config):
    """Enter a private network before any test starts ROS (or say why not)."""
    if os.environ.get('LINKAGE_ROS_PRIVATE_NETWORK', '1') == '0':
        config.stash[NETWORK] = PrivateNetwork(False, 'LINKAGE_ROS_PRIVATE_NETWORK=0')
    else:
        config.stash[NETWORK] = enter_private_network()


def pytest_report_header(config):
    """Say where the cross-process tests run: a private network, or the user's domain."""
    return where_ros_runs(config)


def pytest_terminal_summary(terminalreporter, config):
    """Say it at the end under -q too, which leaves the header out."""
    if config.get_verbosity() < 0:
        terminalreporter.write_line(where_ros_runs(config))


def where_ros_runs(config):
    """Return one line: where the cross-process tests of this run talk, and on which domain."""
    network, domain = config.stash[NETWORK], environment_domain_id()
    if network.entered:
        return (f'ROS: cross-process tests in {network.text}, on domain {domain}; '
                'in-process tests with discovery OFF')
    return (f'ROS: cross-process tests on domain {domain} (ROS_DOMAIN_ID) with discovery '
            f'LOCALHOST, beside the other ROS processes of this machine ({network.text}); '
            'in-process tests with discovery OFF')


@pytest.fixture
def private_network(request):
    """Give the PrivateNetwork of this run: entered (bool) and how, or why not."""
    return request.config.stash[NETWORK]


@pytest.fixture(scope='session', autouse=True)
def _ros_log_dir(request):
    """Log every test here, subprocesses included, into a temporary folder."""
    # by name rather than as an argument, which would shadow the imported fixture
    request.getfixturevalue('ros_environment')


def _names_used(function):
    """Return the names a function's source uses: variables, attributes, keyword arguments."""
    try:
        tree = ast.parse(textwrap.dedent(inspect.getsource(function)))
    except (OSError, TypeError, SyntaxError):
        return set()
    fields = {ast.Name: 'id', ast.Attribute: 'attr', ast.keyword: 'arg'}
    return {getattr(n, fields[type(n)]) for n in ast.walk(tree) if type(n) in fields} - {None}


@functools.lru_cache(maxsize=None)
def _starts_ros(module_name):
    """Tell whether a module's own source starts ROS (STARTS_ROS)."""
    try:
        source = inspect.getsource(sys.modules[module_name])
    except (KeyError, OSError, TypeError):
        return False
    return any(text in source for text in STARTS_ROS)


@functools.lru_cache(maxsize=None)
def _optional(module_name):
    """Tell whether a test module's source names one of OPTIONAL."""
    try:
        source = inspect.getsource(sys.modules[module_name])
    except (KeyError, OSError, TypeError):
        return False
    return any(text in source for text in OPTIONAL)


class _Uses:
    """What the functions of one test module use, their module's own functions followed."""

    def __init__(self, module):
        self.module, self.cache = module, {}

    def names(self, function, seen=()):
        """Return the names function uses, with those of the module functions it calls."""
        key = getattr(function, '__qualname__', id(function))
        if key in self.cache:
            return self.cache[key]
        names = _names_used(function)
        for name in list(names):
            called = getattr(self.module, name, None)
            if (inspect.isfunction(called) and called.__module__ == self.module.__name__
                    and name not in seen):
                names |= self.names(called, (*seen, name))
        self.cache[key] = names
        return names


@pytest.hookimpl(tryfirst=True)     # before -m reads the marks
def pytest_collection_modifyitems(config, items):
    """Mark each test ros, process, slow and optional by what it uses (the module docstring)."""
    uses, found = {}, {}
    for item in items:
        module = getattr(item, 'module', None)
        function = getattr(item, 'function', None)
        if module is None or function is None:
            continue
        if module not in uses:
            uses[module] = _Uses(module)
        names = set(uses[module].names(function))
        for fixture in item.fixturenames:
            for definition in item._fixtureinfo.name2fixturedefs.get(fixture, ()):
                if getattr(definition.func, '__module__', None) == module.__name__:
                    names |= uses[module].names(definition.func)
        fixtures = set(item.fixturenames)
        imported = {getattr(getattr(module, n, None), '__module__', None) for n in names}
        if (fixtures & ROS_FIXTURES or names & ROS_NAMES
                or any(_starts_ros(m) for m in imported if m and m != module.__name__)):
            item.add_marker(pytest.mark.ros)
        if 'node_process' in fixtures or names & PROCESS_NAMES:
            item.add_marker(pytest.mark.process)
        if _optional(module.__name__):
            item.add_marker(pytest.mark.optional)
        file = item.path.name
        found[file] = module
        if (item.originalname or item.name) in SLOW.get(file, ()):
            item.add_marker(pytest.mark.slow)
    for file, module in found.items():
        lost = sorted(name for name in SLOW.get(file, ()) if not hasattr(module, name))
        if lost:
            raise pytest.UsageError(f'test/conftest.py: SLOW names {lost}, which {file} no '
                                    'longer has')
