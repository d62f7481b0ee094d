"""
The project's tests use the fixtures of its pytest plugin, linkage_ros.ros.testing.

They are imported by name rather than through pytest_plugins: once the pytest11 entry point
of an installed linkage_ros registers the same module, pytest_plugins would register it a
second time (an error); names defined here simply take precedence.
"""

from pathlib import Path

from linkage_ros.ros.testing import (  # noqa: F401 (fixtures and helpers for the test modules)
    connect, domain_id, executor, localhost_context, localhost_executor, node_process, Probe,
    probe, ros_context, ros_environment, send_travel, spin_until, stamp_ns, suspension_node)
import pytest

REPO = Path(__file__).resolve().parent.parent
PARAMS_FILE = REPO / 'config' / 'suspension.yaml'


@pytest.fixture(scope='session', autouse=True)
def _ros_log_dir(request):
    """Log every test here, subprocesses included, into a temporary folder."""
    # by name rather than as an argument, which would shadow the imported fixture
    request.getfixturevalue('ros_environment')
