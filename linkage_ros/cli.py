# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Command-line manners shared by the programs of linkage_ros.

A user's mistake (an unknown option, a bad value, a file that cannot be read or written, a
missing optional package) ends in one line on stderr, prefixed with the program's name, and
exit status 2; never in a traceback. Every --help ends with an example and the exit statuses.
A program whose table goes to a reader that stops early (| head) ends quietly, as cat does.
"""

import argparse
import contextlib
import errno
import functools
import math
import os
from pathlib import Path
import re
import select
import signal
import sys
import tempfile
from typing import NamedTuple

from .core.base import LinkageError, say_lost
from .outputs import is_parquet, output_problem, Written

DONE, DAMAGED, MISTAKE = 0, 1, 2
READER_GONE = 128 + signal.SIGPIPE   # the status of cat when its reader stops (| head)
INTERRUPTED = 128 + signal.SIGINT    # the status of a shell's command ended by Ctrl-C
OUTPUT_ERRORS = (errno.ENOSPC, errno.EDQUOT, errno.EFBIG)   # a disk, a quota, ulimit -f

EXIT_STATUS = ('2 a mistake in the command: an unknown option, a bad value, a missing or '
               'unwritable file, a missing optional package (one line on stderr)')

# For the programs that read recordings, which may be damaged.
EXIT_STATUSES = """exit status:
  0  done; the input was complete
  1  done, but the input was damaged: what could be read was used, even if nothing could;
     a message whose bytes do not decode counts as damage (the warnings say what was lost)
  2  a mistake in the command: an unknown option, a bad value, a missing or unwritable
     file, an output that is an input, a file that is not MCAP at all, a missing optional
     package (one line on stderr says which)"""

# Top-level module -> (pip package, extra of linkage_ros that installs it).
PACKAGES = {'mcap': ('mcap', 'record'), 'zstandard': ('zstandard', 'record'),
            'lz4': ('lz4', 'record'), 'rerun': ('rerun-sdk', 'view'),
            'pyarrow': ('rerun-sdk', 'view'), 'matplotlib': ('matplotlib', 'plot'),
            'rclpy': ('ros-jazzy-rclpy', 'ros')}


class Mistake(Exception):
    """A user mistake: the message is the one line printed after the program name."""


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line and exit status 2."""

    def __init__(self, prog: str, description: str, epilog: str = '', **kwargs) -> None:
        super().__init__(prog=prog, description=description, epilog=epilog,
                         formatter_class=argparse.RawDescriptionHelpFormatter, **kwargs)
        # An argument that starts with '-' and a digit is a value, not an option: argparse
        # takes only -80 and -0.5 so, and said "expected one argument" for --rack -20:20:10,
        # --travel -1e3 or --travel -80mm (which then fails as a number, with its own line).
        self._negative_number_matcher = re.compile(r'^-\.?[0-9]')

    def parse_known_args(self, args=None, namespace=None):
        """Parse as argparse does, keeping the arguments for error() to name."""
        self._given = list(sys.argv[1:] if args is None else args)
        return super().parse_known_args(args, namespace)

    def error(self, message: str) -> None:
        """Print one line naming the mistake and exit with status 2."""
        if message.startswith('the following arguments are required'):
            # argparse checks the required arguments before it looks for unknown options:
            # 'linkage-urdf --no-such-option' would be told of its missing target instead.
            unknown = [a for a in getattr(self, '_given', []) if self._unknown_option(a)]
            if unknown:
                message = f'unrecognized arguments: {" ".join(unknown)}'
        sys.exit(fail(self.prog, f'error: {message} (see {self.prog} --help)'))

    def _unknown_option(self, arg: str) -> bool:
        """Tell whether arg looks like an option (not a number) that no option starts with."""
        if not arg.startswith('-') or arg == '-' or self._negative_number_matcher.match(arg):
            return False
        name = arg.split('=', 1)[0]
        return not any(option.startswith(name) for option in self._option_string_actions)


class Span(NamedTuple):
    """A range FROM[:TO:STEP] given on the command line (mm or deg); one value is FROM:FROM:1."""

    start: float
    stop: float
    step: float


SPAN = 'FROM[:TO:STEP]'
NUMBER = r'[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?'


def span(text: str) -> Span:
    """
    Read FROM or FROM:TO:STEP into a Span: an argparse type (its option names the mistake).

    Every value finite, STEP > 0; TO may be below FROM (the range runs down). A unit after a
    number (-80mm) is refused, saying how to give it: plain numbers, as millimetres() takes.
    """
    parts = text.split(':')
    try:
        values = [float(v) for v in parts]
    except ValueError:
        values = []
    if len(values) == 1:
        values = values * 2 + [1.0]
    if len(values) == 3 and all(math.isfinite(v) for v in values) and values[2] > 0:
        return Span(*values)
    if any(re.fullmatch(rf'\s*{NUMBER}\s*[a-zA-Z]+\s*', v) for v in parts):
        raise argparse.ArgumentTypeError(
            f'{text!r}: give {SPAN} as plain numbers, without a unit')
    raise argparse.ArgumentTypeError(
        f'expected {SPAN}, finite numbers with STEP > 0, got {text!r}')


def program(prog: str):
    """
    Wrap a console script's main(argv) for what can happen to its outputs on the way.

    A reader of stdout that went away (`linkage-sweep five_link | head -1`) ends it quietly,
    status READER_GONE; a full disk, a quota or a file-size limit met while writing is one
    line, status 2. Other errors are raised as before: they are not the user's.

    stdout is flushed here, before main's status (or its sys.exit, as argparse's --help)
    leaves: where stdout is a pipe it is block-buffered (PYTHONUNBUFFERED unset, as in a
    fresh shell), so a short table or help is written only at the flush, and a flush left to
    the interpreter's exit meets the gone reader as "Exception ignored ... BrokenPipeError",
    status 120.
    """
    def wrap(main):
        @functools.wraps(main)
        def run(argv=None, **kwargs):
            try:
                try:
                    status = main(argv, **kwargs)
                except SystemExit:
                    _flush_stdout()
                    raise
                _flush_stdout()
                return status
            except BrokenPipeError:
                if not stdout_reader_gone():
                    raise
                return READER_GONE
            except OSError as exc:
                if exc.errno not in OUTPUT_ERRORS:
                    raise
                return fail(prog, f'{exc.filename or "an output"}: cannot write '
                                  f'({exc.strerror})')
        return run
    return wrap


def _flush_stdout() -> None:
    """Flush sys.stdout, if there is one still open: a BrokenPipeError comes out here."""
    if sys.stdout is not None and not sys.stdout.closed:
        sys.stdout.flush()


def stdout_reader_gone() -> bool:
    """
    Tell whether stdout's reader went away.

    If it did, stdout is pointed at /dev/null, so that the flush at exit says nothing.
    """
    try:
        fd = sys.stdout.fileno()
        poll = select.poll()
        poll.register(fd, select.POLLOUT)
        gone = any(events & select.POLLERR for _, events in poll.poll(0))
    except (AttributeError, OSError, ValueError):   # stdout replaced or closed
        return False
    if gone:   # a pipe whose read end is closed polls as an error
        os.dup2(os.open(os.devnull, os.O_WRONLY), fd)
    return gone


@contextlib.contextmanager
def held_stderr():
    """Hold what is written on file descriptor 2; write it out unless the body raises."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as store:
        os.dup2(store.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved, 2)
            os.close(saved)
        store.seek(0)   # reached only when the body did not raise
        os.write(2, store.read())


def millimetres(text: str) -> float:
    """
    Return an option's value in mm as a float: an argparse type.

    A unit after the number (-80mm) is refused, saying how to give it: the programs take
    millimetres as plain numbers.
    """
    try:
        return float(text)
    except ValueError:
        unit = re.fullmatch(rf'\s*{NUMBER}\s*([a-zA-Z]+)\s*', text)
        if unit:
            number = text[:unit.start(1)].strip()
            example = f' (e.g. {number})' if unit.group(1) == 'mm' else ''
            raise argparse.ArgumentTypeError(
                f'{text!r}: give millimetres as a plain number, without a unit{example}') \
                from None
        raise argparse.ArgumentTypeError(f'expected a number of millimetres, got {text!r}') \
            from None


def summary(doc: str) -> str:
    """Return a program module's one-line summary: its docstring's first line after 'prog: '."""
    return doc.strip().splitlines()[0].split(': ', 1)[1]


def counted(count: int, noun: str) -> str:
    """Say a count with its noun in the right number: '1 position', '3 positions'."""
    return f'{count} {noun}' + ('' if count == 1 else 's')


def warn(prog: str, warnings: tuple = ()) -> None:
    """Print each warning (of a Scene or a Vehicle) once, 'prog: warning: ...', on stderr."""
    for line in dict.fromkeys(warnings):
        print(f'{prog}: warning: {line}', file=sys.stderr)


def fail(prog: str, message: object) -> int:
    """Print one line, 'prog: message', on stderr; return exit status 2."""
    print(f'{prog}: {message}', file=sys.stderr)
    return MISTAKE


def check_input(path: str, option: str = 'BAG') -> None:
    """Refuse an input that does not exist (a RecordingError names other problems)."""
    if not Path(path).exists():
        raise Mistake(f'{option} {path}: no such file or folder')


def default_output(source: str, suffix: str) -> str:
    """Return the source's stem + suffix in the current folder (never beside the source)."""
    return str(Path.cwd() / (safe_name(Path(os.path.abspath(source)).stem) + suffix))


def safe_name(text: str, fallback: str = 'output') -> str:
    """
    Return text as a file name that stays in the current folder, for a default output.

    Every run of characters other than letters, digits, '.', '_' and '-' (a '/' among them)
    becomes '_', and leading dots, '_' and '-' go: '../escaped' -> 'escaped'. fallback if
    nothing is left.
    """
    return re.sub(r'[^\w.-]+', '_', str(text)).lstrip('._-') or fallback


def missing_package(exc: ImportError, feature: str) -> str:
    """Say which optional package the feature needs and how to install it."""
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


def plot_problem(path: str, inputs=()) -> str:
    """
    Tell why a plot cannot be written to path, in a few words; '' if it can.

    The file cannot be an output (outputs.output_problem, inputs the files the run reads),
    matplotlib is not installed (said as missing_package says it), or the suffix is no
    format matplotlib writes (rates.txt; no suffix is PNG). Checked before any work.
    """
    problem = output_problem(path, inputs)
    if problem:
        return problem
    try:
        from matplotlib.backend_bases import FigureCanvasBase
    except ImportError as exc:
        return missing_package(exc, 'plotting')
    formats = FigureCanvasBase.get_supported_filetypes()
    suffix = Path(path).suffix[1:].lower()
    if suffix and suffix not in formats:
        return (f'{path}: matplotlib writes no .{suffix} files (formats: '
                f'{", ".join(sorted(formats))}; no suffix: png)')
    return ''


def check_plot(path: str, option: str = '--plot', inputs=()) -> None:
    """Raise LinkageError naming option if a plot cannot be written to path (plot_problem)."""
    problem = path and plot_problem(path, inputs)
    if problem:
        raise LinkageError(option, problem)


def check_table(path: str, option: str = '-o', extra: str = 'map') -> None:
    """
    Raise LinkageError naming option if path asks for Parquet and pyarrow is missing.

    extra: the extra of linkage_ros that installs pyarrow, named in the message.
    """
    if is_parquet(path):
        try:
            import pyarrow.parquet  # noqa: F401 (only whether it is there)
        except ImportError:
            raise LinkageError(option, 'needs the Python package pyarrow, which is not '
                               f"installed: pip install -e '.[{extra}]' (in a linkage_ros "
                               'checkout) or pip install pyarrow') from None


def table_status(prog: str, written: Written, rows: str = 'row', where: str = '') -> int:
    """
    Return DAMAGED, saying in one line what a table lost, if it lost a cell; else DONE.

    The writers' rule (doc/tables.md): a result that is not finite is written nan, never as
    a number, the rest of the table is whole, and the program ends 1 naming the columns
    (base.say_lost; rows: what a row is, 'position'; where: the file, for a folder's tables).
    """
    if not written.lost:
        return DONE
    print(f'{prog}: {where + ": " if where else ""}{say_lost(written.lost, rows)}',
          file=sys.stderr)
    return DAMAGED
