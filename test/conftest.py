"""
The project's tests use the fixtures of its pytest plugin, linkage_ros.ros.testing.

The run enters a private network first where it can (root on Linux): a network namespace
with only lo and a /dev/shm of its own, so that what the cross-process tests publish reaches
no other process of the machine, and nothing of theirs reaches the tests, whatever domain
both use. Elsewhere, or with LINKAGE_ROS_PRIVATE_NETWORK=0, the cross-process tests run on
the user's ROS_DOMAIN_ID (0 if unset) beside the machine's other ROS processes. The header
of the run says which.

They are imported by name rather than through pytest_plugins: once the pytest11 entry point
of an installed linkage_ros registers the same module, pytest_plugins would register it a
second time (an error); names defined here simply take precedence.
"""

import os
from pathlib import Path

from linkage_ros.ros.isolation import enter_private_network, environment_domain_id, \
    PrivateNetwork
from linkage_ros.ros.testing import (  # noqa: F401 (fixtures and helpers for the test modules)
    connect, domain_id, executor, localhost_context, localhost_executor, node_process, Probe,
    probe, ros_context, ros_environment, send_travel, spin_until, stamp_ns, suspension_node)
import pytest

REPO = Path(__file__).resolve().parent.parent
PARAMS_FILE = REPO / 'config' / 'suspension.yaml'
NETWORK = pytest.StashKey[PrivateNetwork]()


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
