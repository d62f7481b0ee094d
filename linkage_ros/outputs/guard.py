# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The output guard: which paths a run may write, checked before any work, for every program.

    check_outputs([(option, path), ...], inputs)   LinkageError(option, why) for the first
                                                   output that cannot be written, is an input,
                                                   or is another output
    output_problem(path, inputs)                   why one path cannot be written, or ''
    output_folder(option, folder, names, inputs)   an output folder: made if missing, able to
                                                   hold files, and each file it will hold checked
    same_file(output, source)                      the file of source that output would replace

An output may be a regular file, new or not, also through symbolic links (written whole beside
the file and renamed onto it: whole.py); a character device (/dev/null, a terminal), written
in place and never replaced, and refused here if it refuses writes (/dev/full); or a FIFO,
written in place as a shell's > writes it, and not opened here (an open waits for a reader,
and its close would end the reader's stream). Never a folder, a block device (a disk), a
socket, or an input: a file read by the run, named by its path, a symbolic link to it or a
hard link (one st_dev and st_ino), where a folder input (a rosbag2 bag) stands for each file
in it.
"""

from __future__ import annotations

import contextlib
import errno
import os
from pathlib import Path
import stat
from typing import Iterable, Sequence

from .whole import in_place, temporary_beside
from ..core.base import LinkageError

KINDS = {stat.S_IFBLK: 'a block device (a disk)', stat.S_IFSOCK: 'a socket'}


def check_outputs(outputs: Sequence[tuple[str, str]], inputs: Iterable = ()) -> None:
    """
    Refuse an output that cannot be written, is an input, or is another output.

    outputs: (option, path) pairs, those without a path left out; inputs: every file the run
    reads. Raises LinkageError naming the option. Two outputs may both be one character
    device (-o /dev/null --matrix /dev/null): both are written in place.
    """
    inputs = tuple(inputs)
    given = [(option, path) for option, path in outputs if path]
    for k, (option, path) in enumerate(given):
        problem = output_problem(path, inputs)
        if problem:
            raise LinkageError(option, problem)
        for other, earlier in given[:k]:
            if same_file(path, earlier) and not _is_device(path):
                raise LinkageError(option, f'{path} is also the output of {other}; give '
                                   'another file name')


def check_output(path: str, option: str = '-o', inputs: Iterable = ()) -> None:
    """Refuse one output (check_outputs): LinkageError naming option."""
    check_outputs([(option, path)], inputs)


def output_problem(path, inputs: Iterable = ()) -> str:
    """
    Say in a few words why path cannot be an output; '' if it can (see the module).

    Leaves every file as it was: a new file is made and removed again beside the file path
    names (only making one tells: root passes os.access), and a character device is written
    no byte (a write of none is refused by /dev/full as one of many would be).
    """
    text = os.fspath(path)
    if not text:
        return 'an empty name: give a file name'
    problem = input_problem(text, inputs)
    if problem:
        return f'{problem}; give another file name'
    try:
        mode = os.stat(text).st_mode
    except FileNotFoundError:
        return _new_file_problem(text)
    except OSError as exc:   # a name too long, a loop of links, a file where a folder should be
        return _new_file_problem(text) if exc.errno == errno.ENOTDIR else \
            f'cannot write {text}: {exc.strerror or exc}'
    if stat.S_ISDIR(mode):
        return f'{text} is a folder, not a file'
    if stat.S_IFMT(mode) in KINDS:
        return f'{text} is {KINDS[stat.S_IFMT(mode)]}, not a file; give a file name'
    if stat.S_ISCHR(mode):
        return _device_problem(text)
    if stat.S_ISFIFO(mode):
        return '' if os.access(text, os.W_OK) else f'cannot write {text}: Permission denied'
    try:
        with open(text, 'ab'):
            pass
    except OSError as exc:
        return f'cannot write {text}: {exc.strerror or exc}'
    problem = '' if in_place(text) else _cannot_make(text)
    return problem and f'cannot write {text}: {problem}'


def input_problem(path, inputs: Iterable = ()) -> str:
    """Say which input path is ('<path> is the input <source>'), or '' if none."""
    for source in inputs:
        hit = source is not None and same_file(path, source)
        if hit:
            return f'{path} is ' + (f'the input {source}' if hit == str(source) else
                                    f'{hit}, in the input {source}')
    return ''


def output_folder(option: str, folder, names: Iterable[str] = (), inputs: Iterable = ()) -> Path:
    """
    Make an output folder if missing and check it; return it as a Path.

    It must be a folder that can hold a new file (not /proc, not read-only), and each of
    names (the files it will hold) must be a writable output that is no input. Raises
    LinkageError naming option; a folder made here is removed again when refused.
    """
    path = Path(folder)
    if os.path.lexists(path) and not path.is_dir():
        raise LinkageError(option, f'{folder} is a file, not a folder')
    made = [p for p in (path, *path.parents) if not os.path.lexists(p)][::-1]
    try:
        try:
            path.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise LinkageError(option, f'cannot make the folder {folder} '
                               f'({exc.strerror or exc})') from None
        problem = _cannot_make(path / 'probe')
        if problem:
            raise LinkageError(option, f'cannot write into the folder {folder} ({problem})')
        inputs = tuple(inputs)
        for name in names:
            problem = input_problem(path / name, inputs)
            if problem:
                raise LinkageError(option, f'{problem}; give another folder')
        check_outputs([(option, str(path / name)) for name in names])
    except LinkageError:
        for made_here in reversed(made):
            with contextlib.suppress(OSError):
                made_here.rmdir()
        raise
    return path


def same_file(output, source) -> str:
    """
    Return the file of source that writing output would replace, or ''.

    Compared by resolved path (links and '..' followed) and, where both exist, as one file
    (a hard link: the same st_dev and st_ino). A source that is a folder (a rosbag2 bag
    folder) stands for every file in it.
    """
    target = Path(os.path.realpath(output))
    origin = Path(source)
    try:
        files = sorted(origin.iterdir()) if origin.is_dir() else [origin]
    except OSError:
        files = [origin]
    for file in files:
        if Path(os.path.realpath(file)) == target or _one_file(output, file):
            return str(file) if origin.is_dir() else str(source)
    return ''


def _one_file(a, b) -> bool:
    with contextlib.suppress(OSError, ValueError):
        return os.path.samefile(a, b)
    return False


def _is_device(path) -> bool:
    with contextlib.suppress(OSError, ValueError):
        return stat.S_ISCHR(os.stat(path).st_mode)
    return False


def _new_file_problem(text: str) -> str:
    """Say why a file that does not exist cannot be made at text, or ''."""
    folder = Path(os.path.realpath(text)).parent
    if not folder.exists():
        return f'cannot write {text}: no folder {folder}'
    if not folder.is_dir():
        return f'cannot write {text}: {folder} is not a folder'
    problem = _cannot_make(text)
    return problem and f'cannot write {text}: {problem}'


def _cannot_make(text) -> str:
    """Say why whole_file cannot make its new file beside text (the reason only), or ''."""
    try:
        fd, temporary = temporary_beside(text)
    except OSError as exc:
        return str(exc.strerror or exc)
    os.close(fd)
    os.unlink(temporary)
    return ''


def _device_problem(text: str) -> str:
    """Say why a character device cannot be written, or '' (it is opened, written no byte)."""
    try:
        # O_NONBLOCK: a serial line or a terminal never waits here for its other end
        fd = os.open(text, os.O_WRONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as exc:
        return f'cannot write {text}: {exc.strerror or exc}'
    try:
        os.write(fd, b'')
    except OSError as exc:
        return f'{text}: cannot write ({exc.strerror or exc})'
    finally:
        os.close(fd)
    return ''
