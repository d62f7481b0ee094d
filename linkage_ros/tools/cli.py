"""
Command-line manners shared by linkage-replay and linkage-rerun.

Exit statuses: 0 done, the input complete; 1 done, but the input was damaged (what could be
read was used); 2 a user mistake (bad path, missing file, unknown option, bad value, missing
optional package), told in one line on stderr, never a traceback.
"""

import argparse
import os
from pathlib import Path
import sys

DONE, DAMAGED, MISTAKE = 0, 1, 2

EXIT_STATUSES = """exit status:
  0  done; the input was complete
  1  done, but the input was damaged: what could be read was used (and the warning says
     what was lost)
  2  a mistake in the command: bad path, missing or unreadable file, unknown option, bad
     value, or a missing optional package (one line on stderr says which)"""

# Top-level module -> (pip package, extra of linkage_ros that installs it).
PACKAGES = {'mcap': ('mcap', 'record'), 'zstandard': ('zstandard', 'record'),
            'lz4': ('lz4', 'record'), 'rerun': ('rerun-sdk', 'view'),
            'pyarrow': ('rerun-sdk', 'view'), 'rclpy': ('ros-jazzy-rclpy', 'ros')}


class Mistake(Exception):
    """A user mistake: the message is the one line printed after the program name."""


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors: 'prog: error: ... (see prog --help)', status 2."""

    def error(self, message):
        """Print one line naming the mistake and exit with status 2."""
        self.exit(MISTAKE, f'{self.prog}: error: {message} (see {self.prog} --help)\n')


def missing_package(exc, feature):
    """Return the one-line message for an ImportError met loading what feature needs."""
    module = (getattr(exc, 'name', None) or '').split('.')[0]
    if module in PACKAGES:
        package, extra = PACKAGES[module]
        return (f'{feature} needs the Python package {package}, which is not installed: '
                f"pip install -e '.[{extra}]' (in a linkage_ros checkout) or pip install "
                f'{package}')
    if module.endswith('_msgs') or module.startswith(('rcl', 'rosidl', 'builtin_interfaces')):
        return (f'{feature} needs the ROS 2 Python packages ({module} is not installed): '
                "pip install -e '.[ros]' (in a linkage_ros checkout)")
    return f'{feature} needs the Python module {module or exc}, which cannot be imported'


def check_input(path, option='BAG'):
    """Refuse an input that does not exist (a RecordingError names other problems)."""
    if not Path(path).exists():
        raise Mistake(f'{option} {path}: no such file or folder')


def check_output(path, option='-o', inputs=()):
    """
    Refuse an output path that cannot be written, before any work is done.

    A folder that does not exist, a path that is a folder, the input itself, a file that
    cannot be opened for writing: each is a Mistake. The file is not changed (a file that
    did not exist is created and removed again).
    """
    path = Path(path)
    where = f'{option} {path}'
    if path.is_dir():
        raise Mistake(f'{where}: is a folder; give a file name')
    parent = path.parent
    if not parent.exists():
        raise Mistake(f'{where}: folder {parent} does not exist')
    if not parent.is_dir():
        raise Mistake(f'{where}: {parent} is not a folder')
    for other in inputs:
        if other is not None and path.exists() and Path(other).exists() and \
                os.path.samefile(path, other):
            raise Mistake(f'{where}: is the input {other}; give another file name')
    existed = path.exists()
    try:
        with open(path, 'ab'):
            pass
    except OSError as exc:
        raise Mistake(f'{where}: cannot write ({exc.strerror or exc})') from None
    if not existed:
        path.unlink()


def default_output(bag, suffix):
    """Return BAG's stem + suffix in the current folder (never beside the bag)."""
    return str(Path.cwd() / (Path(bag).stem + suffix))


def fail(prog, message):
    """Print 'prog: message' on stderr; returns status 2."""
    print(f'{prog}: {message}', file=sys.stderr)
    return MISTAKE
