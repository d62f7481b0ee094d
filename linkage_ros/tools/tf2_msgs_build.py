# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-tf2-msgs: build the interface packages (tf2_msgs, linkage_ros_interfaces) into this env.

tf2_msgs has no wheel on the package index, and rclpy can only publish a message type (or
serve a service) whose generated code is installed. ament_cmake and the rosidl generators do
have wheels, and both are plain interface packages under config/interfaces: tf2_msgs is its
message (`geometry_msgs/TransformStamped[] transforms`, the definition and type hash of ROS 2's
tf2_msgs/msg/TFMessage), linkage_ros_interfaces the node's solve service (srv/Solve.srv), each
with a CMakeLists that builds it against the ROS 2 wheels. This program installs the
generators (config/interfaces/build-requirements.txt, with CMake and Ninja), then configures,
builds and installs each package that does not import yet into sys.prefix, where the wheels'
libraries and message packages are, and checks that a new Python imports it.

It needs a C and a C++ compiler and the Python headers (Debian: build-essential python3-dev);
where they are missing it says so in one line and builds nothing: suspension_node then
records /tf but publishes it only where tf2_msgs is installed (any full ROS 2 install), and
serves no <corner>/solve service, and says both at start-up. A package that imports already is
not built again (--force: build anyway).
"""

from __future__ import annotations

import os
from pathlib import Path
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import time

from .. import cli
from ..core.model import config_dir
from ..outputs import output_problem

PROG = 'linkage-tf2-msgs'
EXAMPLE = """example:
  .venv/bin/linkage-tf2-msgs             build tf2_msgs and linkage_ros_interfaces into .venv
                                         (about a minute each, once)
  .venv/bin/linkage-tf2-msgs --optional  the same, but status 0 where it cannot be built

exit status:
  0  both import (built now, or there already)
  1  one could not be built: the line says why (no compiler, no Python headers, a failed
     step, with its log); status 0 instead with --optional
  2  a mistake in the command"""
# package: (a line that imports it, what the node lacks without it)
PACKAGES = {
    'tf2_msgs': ('import tf2_msgs.msg; tf2_msgs.msg.TFMessage()',
                 'suspension_node records /tf but publishes it only where tf2_msgs is '
                 'installed'),
    'linkage_ros_interfaces': ('import linkage_ros_interfaces.srv as s; s.Solve.Request()',
                               'suspension_node serves no <corner>/solve service'),
}


def source_dir(package: str = 'tf2_msgs') -> Path:
    """Return the folder of a bundled interface package (config/interfaces/<package>)."""
    return config_dir() / 'interfaces' / package


def importable(python: str = sys.executable, package: str = 'tf2_msgs') -> bool:
    """Tell whether a new process of python imports package (a line of PACKAGES)."""
    done = subprocess.run([python, '-c', PACKAGES[package][0]], capture_output=True)
    return done.returncode == 0


def missing_tools() -> list[str]:
    """
    Return what the build needs that this machine lacks, each said with what provides it.

    A C and a C++ compiler (CC and CXX, else cc and c++) and Python.h of this Python.
    """
    missing = []
    for variable, names, what in (('CC', ('cc', 'gcc', 'clang'), 'a C compiler'),
                                  ('CXX', ('c++', 'g++', 'clang++'), 'a C++ compiler')):
        given = os.environ.get(variable)
        if not (shutil.which(given) if given else any(shutil.which(n) for n in names)):
            missing.append(f'{what} (Debian: build-essential)')
    headers = Path(sysconfig.get_paths()['include']) / 'Python.h'
    if not headers.is_file():
        missing.append(f'the Python headers ({headers}; Debian: python3-dev)')
    return missing


class BuildError(Exception):
    """A step of the build failed: the message says which, and where its log is."""


def run_step(what: str, command: list[str], log: Path, env: dict, cwd: Path) -> None:
    """Run one step, its output appended to log; BuildError naming the step if it fails."""
    with open(log, 'a') as out:
        out.write(f'\n$ {" ".join(command)}\n')
        out.flush()
        done = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, env=env, cwd=cwd)
    if done.returncode != 0:
        tail = log.read_text(errors='replace').strip().splitlines()[-1:]
        raise BuildError(f'{what} failed (status {done.returncode}; {" ".join(tail)[:200]}); '
                         f'the whole log: {log}')


def build(prefix: Path, log: Path, stream=sys.stderr,
          packages: tuple[str, ...] = ('tf2_msgs',)) -> None:
    """Install the generators, then build and install packages into prefix; else BuildError."""
    bindir = Path(sys.executable).parent
    env = dict(os.environ, PATH=f'{bindir}{os.pathsep}{os.environ.get("PATH", "")}',
               AMENT_PREFIX_PATH=os.environ.get('AMENT_PREFIX_PATH') or str(prefix))
    requirements = config_dir() / 'interfaces' / 'build-requirements.txt'
    with tempfile.TemporaryDirectory(prefix='linkage_tf2_msgs_') as folder:
        work = Path(folder)
        print(f'{PROG}: installing the rosidl generators, CMake and Ninja '
              f'({requirements.name})', file=stream, flush=True)
        run_step('installing the generators', [sys.executable, '-m', 'pip', 'install', '-q',
                                               '-r', str(requirements)], log, env, work)
        for package in packages:
            print(f'{PROG}: building {package} into {prefix}', file=stream, flush=True)
            build_one(package, prefix, log, env, work)


def build_one(package: str, prefix: Path, log: Path, env: dict, work: Path) -> None:
    """Configure, build and install one interface package into prefix; else BuildError."""
    bindir = Path(sys.executable).parent
    source, built = work / package, work / f'build_{package}'
    shutil.copytree(source_dir(package), source, ignore=shutil.ignore_patterns('COLCON_IGNORE'))
    cmake = shutil.which('cmake', path=str(bindir)) or 'cmake'
    run_step(f'configuring {package} (cmake)', [
        cmake, '-S', str(source), '-B', str(built), '-G', 'Ninja',
        f'-DCMAKE_MAKE_PROGRAM={shutil.which("ninja", path=str(bindir)) or "ninja"}',
        f'-DCMAKE_INSTALL_PREFIX={prefix}', f'-DCMAKE_PREFIX_PATH={prefix}',
        f'-DPython3_EXECUTABLE={sys.executable}', '-DBUILD_TESTING=OFF',
        '-DCMAKE_BUILD_TYPE=Release',
        # CMake 4 refuses projects that ask for less than 3.5 (some ament files do)
        '-DCMAKE_POLICY_VERSION_MINIMUM=3.5'], log, env, work)
    run_step(f'building {package}', [cmake, '--build', str(built)], log, env, work)
    run_step(f'installing {package}', [cmake, '--install', str(built)], log, env, work)


@cli.program(PROG)
def main(argv=None) -> int:
    """Run linkage-tf2-msgs; returns the exit status."""
    parser = cli.Parser(PROG, __doc__.strip().splitlines()[1], epilog=EXAMPLE)
    parser.add_argument('--force', action='store_true',
                        help='build even what imports already')
    parser.add_argument('--optional', action='store_true',
                        help='exit with status 0 where it cannot be built (still saying why)')
    parser.add_argument('--log', metavar='FILE',
                        help="write the build steps' output here (default: a file in the "
                        'temporary folder, named on failure)')
    args = parser.parse_args(argv)
    failed = cli.DONE if args.optional else cli.DAMAGED
    wanted = tuple(p for p in PACKAGES if args.force or not importable(package=p))
    if not wanted:
        print(f'{PROG}: {" and ".join(PACKAGES)} import already: nothing to build',
              file=sys.stderr)
        return cli.DONE
    missing = missing_tools()
    if missing:
        print(f'{PROG}: cannot build {" and ".join(wanted)} here: it needs '
              f'{" and ".join(missing)}; {", and ".join(PACKAGES[p][1] for p in wanted)}',
              file=sys.stderr)
        return failed
    log = Path(args.log) if args.log else Path(tempfile.gettempdir()) / 'linkage_tf2_msgs.log'
    problem = output_problem(log)
    if problem:
        return cli.fail(PROG, f'--log {log}: {problem}')
    log.write_text('')
    start = time.monotonic()
    try:
        build(Path(sys.prefix), log, packages=wanted)
    except (BuildError, OSError) as exc:
        print(f'{PROG}: not built: {exc}', file=sys.stderr)
        return failed
    broken = [p for p in wanted if not importable(package=p)]
    if broken:
        print(f'{PROG}: {" and ".join(broken)} built into {sys.prefix} but not importable '
              f'(see {log})', file=sys.stderr)
        return failed
    print(f'{PROG}: {" and ".join(wanted)} built and installed into {sys.prefix} in '
          f'{time.monotonic() - start:.0f} s: suspension_node publishes /tf live and serves '
          '<corner>/solve', file=sys.stderr)
    return cli.DONE


if __name__ == '__main__':
    sys.exit(main())
