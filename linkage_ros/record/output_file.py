# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The file a recorder writes: claimed for it alone, and watched for removal or replacement.

    fd = claim(path)          # opened, locked (flock, exclusive), probed with a byte, emptied
    whereabouts(fd, path)     # '' while path still names that file; else what happened to it

Both recorders (McapRecorder, RerunRecorder) use these, so that two recorders (in one process
or two nodes) never write one file, and a file removed or replaced under a running recorder is
said, not written on unseen into an inode that nothing names any more.
"""

import errno
import fcntl
import os
import stat

from .errors import RecordingError


def claim(path):
    """
    Open path for writing, locked against every other recorder, and empty it; return the fd.

    The lock (flock, exclusive, not waited for) is held as long as the fd is open; another
    recorder of the same file is refused with RecordingError, and the file is left as it was
    (it is truncated only once the lock is held). Only regular files are locked (a device
    such as /dev/null may take several recordings). A byte is written first, so that a file
    that cannot be written (/dev/full, a full disk) is refused here with the reason. A FIFO
    is refused without opening it (the open would wait for a reader, and an MCAP writer keeps
    offsets into its file, which a FIFO has none of).
    """
    try:
        fifo = stat.S_ISFIFO(os.stat(path).st_mode)
    except OSError:   # none yet, or the open below says what is wrong
        fifo = False
    if fifo:
        raise RecordingError(path, 'is a FIFO; a recording is written to a file (or a device '
                             'such as /dev/null)')
    try:
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_CLOEXEC, 0o666)
    except OSError as exc:
        raise RecordingError(path, f'cannot write ({exc.strerror or exc})') from None
    try:
        regular = stat.S_ISREG(os.fstat(fd).st_mode)   # not /dev/null, which all may share
        try:
            if regular:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            if exc.errno in (errno.EWOULDBLOCK, errno.EAGAIN):
                raise RecordingError(path, 'another recorder is writing this file (it holds '
                                     'its lock); give another file name') from None
            # A file system without locks (some network ones): recorded unlocked.
        if regular:
            os.ftruncate(fd, 0)
        os.write(fd, b'\0')
        if regular:
            os.ftruncate(fd, 0)
            os.lseek(fd, 0, os.SEEK_SET)
    except OSError as exc:
        os.close(fd)
        raise RecordingError(path, f'cannot write ({exc.strerror or exc})') from None
    except RecordingError:
        os.close(fd)
        raise
    return fd


def whereabouts(fd, path):
    """
    Say what happened to the file open as fd that path named, or '' if path still names it.

    'removed while recording' (nothing is at path any more) or 'replaced by another file
    while recording' (path names another file: what the recorder writes reaches no one).
    """
    try:
        now = os.stat(path)
    except FileNotFoundError:
        return f'{path} was removed while recording'
    except OSError:
        return ''      # cannot be told (a folder made unreadable): not a removal
    mine = os.fstat(fd)
    if (now.st_ino, now.st_dev) != (mine.st_ino, mine.st_dev):
        return f'{path} was replaced by another file while recording'
    return ''
