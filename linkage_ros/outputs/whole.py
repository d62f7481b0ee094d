# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Writing an output file whole, or a device or FIFO in place; never replacing a device.

    with whole_file(path) as stream: ...   # renamed onto the file once the body is done
    save_figure(fig, path, dpi)            # a matplotlib figure, whole, its format by suffix

A regular file (new or not, named directly or through symbolic links) is written under a
temporary name beside the file the path names and renamed onto it once whole: a full disk, a
quota or a file-size limit met on the way leaves it as it was. A link stays a link. Anything
else that exists is written in place, as a shell's > writes it: a character device
(/dev/null takes it, /dev/full refuses it with ENOSPC, a terminal shows it), a FIFO (the
open waits for a reader), and a regular file named only through /proc (/dev/stdout when
stdout is a file: appended to, as the shell opened it). Folders, block devices and sockets
never get here: the guard (guard.py) refuses them before any work.
"""

from __future__ import annotations

import contextlib
import io
import os
from pathlib import Path
import stat
import tempfile


def in_place(path) -> bool:
    """
    Tell whether path is written in place rather than whole.

    True when it exists and is not a regular file (a device, a FIFO), or is a regular file
    that its resolved name does not reach (a /proc/self/fd link such as /dev/stdout).
    """
    try:
        named = os.stat(path)
    except OSError:
        return False
    if not stat.S_ISREG(named.st_mode):
        return True
    try:
        resolved = os.stat(os.path.realpath(path))
    except OSError:
        return True
    return (resolved.st_dev, resolved.st_ino) != (named.st_dev, named.st_ino)


def temporary_beside(path) -> tuple[int, str]:
    """
    Make the new file that whole_file writes for path; return (fd, its path), or raise.

    It lies in the folder of the file path resolves to (the link's target), named after it.
    """
    target = Path(os.path.realpath(path))
    return tempfile.mkstemp(prefix=f'.{target.name}.', suffix='.partial', dir=target.parent)


@contextlib.contextmanager
def whole_file(path, mode: str = 'w', **kwargs):
    """
    Yield a stream onto path: a new file renamed onto it once the body is done, or in place.

    What is written to a file is whole or absent: an error on the way (or in the body)
    leaves path as it was, removes the new file and raises; an OSError is raised again
    naming path. Devices and FIFOs: see the module.
    """
    if in_place(path):
        regular = stat.S_ISREG(os.stat(path).st_mode)   # only through /proc: append
        try:
            with open(path, mode.replace('w', 'a') if regular else mode, **kwargs) as stream:
                yield stream
        except OSError as exc:
            if isinstance(exc, BrokenPipeError):
                raise
            raise OSError(exc.errno, exc.strerror, str(path)) from None
        return
    target = Path(os.path.realpath(path))
    try:
        fd, temporary = temporary_beside(path)
    except OSError as exc:
        raise OSError(exc.errno, exc.strerror, str(path)) from None
    try:
        os.fchmod(fd, 0o666 & ~_umask())   # as open() would have made it, not mkstemp's 0600
        os.close(fd)
        with open(temporary, mode, **kwargs) as stream:
            yield stream
        os.replace(temporary, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        if isinstance(exc, OSError) and not isinstance(exc, BrokenPipeError):
            raise OSError(exc.errno, exc.strerror, str(path)) from None
        raise


def save_figure(fig, path, dpi) -> None:
    """
    Write fig to path whole (its format by the suffix; PNG without one), or raise OSError.

    matplotlib's savefig(path) says nothing when the disk is full; a file written by this
    function is whole, or an error names it (a matplotlib Figure: the caller imports
    matplotlib, this module does not). The suffix is checked before any work
    (cli.check_plot).
    """
    buffer = io.BytesIO()
    fig.savefig(buffer, format=Path(path).suffix[1:] or None, dpi=dpi)
    with whole_file(path, 'wb') as stream:
        stream.write(buffer.getvalue())


def _umask() -> int:
    """Return the process's umask (read by setting it, and set back at once)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask
