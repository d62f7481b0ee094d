"""
Command-line manners shared by the programs of linkage_ros.

A user's mistake (an unknown option, a bad value, a file that cannot be read or written, a
missing optional package) ends in one line on stderr, prefixed with the program's name, and
exit status 2; never in a traceback. Every --help ends with an example and the exit statuses.
"""

import argparse
import os
from pathlib import Path
import sys

EXIT_STATUS = ('2 a mistake in the command: an unknown option, a bad value, a missing or '
               'unwritable file, a missing optional package (one line on stderr)')


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line and exit status 2."""

    def __init__(self, prog: str, description: str, epilog: str = '', **kwargs) -> None:
        super().__init__(prog=prog, description=description, epilog=epilog,
                         formatter_class=argparse.RawDescriptionHelpFormatter, **kwargs)

    def error(self, message: str) -> None:
        """Print one line naming the mistake and exit with status 2."""
        sys.exit(fail(self.prog, f'{message} (see {self.prog} --help)'))


def fail(prog: str, message: str) -> int:
    """Print one line, 'prog: message', on stderr; return exit status 2."""
    print(f'{prog}: {message}', file=sys.stderr)
    return 2


def writable_file(path: str) -> str:
    """
    Check that path can be created or overwritten as a file.

    Returns the problem in a few words, or '' if there is none: a missing folder, a folder
    where the file should be, no permission.
    """
    target = Path(path)
    if target.is_dir():
        return f'{path} is a folder, not a file'
    folder = target.parent if str(target.parent) else Path('.')
    if not folder.is_dir():
        return f'cannot write {path}: no folder {folder}'
    if not os.access(target if target.exists() else folder, os.W_OK):
        return f'cannot write {path}: permission denied'
    return ''


def missing_package(exc: ImportError, extra: str) -> str:
    """Say which optional package is missing and how to install it (the extra's name)."""
    name = getattr(exc, 'name', None) or str(exc)
    return (f'needs the Python package {name}, which is not installed: '
            f"pip install -e '.[{extra}]' (from the linkage_ros checkout)")
