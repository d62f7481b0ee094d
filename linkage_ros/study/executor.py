# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Run a study's batches on the local cores or on a Dask cluster, results in batch order.

    with executor(scheduler=None, workers=None) as run:
        results = run(function, items, progress)

function(item) must be a module-level function (it is sent to other processes) and its
result must depend on the item alone: each batch carries its own seed (a SeedSequence keyed
by the batch index), so that the results are the same bit for bit wherever a batch runs.
Without a scheduler the batches run in this process (one worker, or one batch) or in a pool
of local processes; with one, they are sent to an existing dask.distributed cluster
(Client(address)) as tasks, and gathered in order. Dask is needed only then.
"""

from __future__ import annotations

from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
import contextlib
import gc
import itertools
import multiprocessing
import os
import signal
import socket
import struct
import sys
import time
from typing import Callable, Iterator, Sequence

from ..core.base import LinkageError

CONNECT_TIMEOUT = 5.0   # s: a scheduler that does not answer by then is unreachable
HANDSHAKE_LIMIT = 1 << 20   # bytes: a Dask handshake is a few hundred
PROGRESS_PERIOD = 1.0   # s between progress lines when stderr is not a terminal
BAR = 30                # characters of the progress bar
WINDOW = 2               # batches in flight per local process: the rest are not made yet


class Progress:
    """A progress bar on stderr: redrawn in place on a terminal, a line a second otherwise."""

    def __init__(self, prog: str, total: int, what: str, stream=None) -> None:
        self.prog, self.total, self.what = prog, total, what
        self.stream = stream or sys.stderr
        self.tty = hasattr(self.stream, 'isatty') and self.stream.isatty()
        self._last = -float('inf')

    def update(self, done: int) -> None:
        """Show that done of total items are finished."""
        now = time.monotonic()
        if done != self.total and now - self._last < (0.1 if self.tty else PROGRESS_PERIOD):
            return
        self._last = now
        fraction = done / self.total if self.total else 1.0
        filled = int(round(BAR * fraction))
        line = (f'{self.prog}: [{"#" * filled}{"." * (BAR - filled)}] {done}/{self.total} '
                f'{self.what} ({100 * fraction:.0f}%)')
        end = '\n' if not self.tty or done == self.total else ''
        print(('\r' if self.tty else '') + line, end=end, file=self.stream, flush=True)


def missing_dask(exc: ImportError) -> str:
    """Say that --scheduler needs Dask, and how to install it (after '--scheduler: ')."""
    return ('needs the Python package dask[distributed], which is not installed: '
            f"pip install -e '.[study]' (in a linkage_ros checkout) ({exc})")


@contextlib.contextmanager
def executor(scheduler: str | None = None, workers: int | None = None,
             timeout: float = CONNECT_TIMEOUT, pool_from: int = 2) -> Iterator[Callable]:
    """
    Yield run(function, items, progress=None) -> [function(item) for item in items].

    scheduler: a Dask scheduler's address (tcp://host:8786), or None for the local cores;
    workers: local processes (None: every core; 1: this process); fewer items than pool_from
    run in this process (a local process takes seconds to start: numpy, numba and the
    compiled kernels to load). Raises LinkageError if Dask is missing or the scheduler does
    not answer within timeout s.
    """
    if scheduler is None:
        def run(function, items, progress=None):
            return _local(function, items, progress, workers, pool_from)
        yield run
        return
    try:
        from distributed import Client
    except ImportError as exc:
        raise LinkageError('--scheduler', missing_dask(exc)) from None
    probe(scheduler, timeout)
    try:
        client = Client(scheduler, timeout=timeout, set_as_default=False)
    except (OSError, ValueError, TypeError) as exc:   # unreachable, refused, a bad address
        _forget_client()
        raise LinkageError('--scheduler', f'cannot reach the Dask scheduler {scheduler} '
                           f'within {timeout:g} s ({str(exc).splitlines()[0][:200]})') from None
    try:
        yield lambda function, items, progress=None: _dask(client, function, items, progress)
    finally:
        client.close(timeout=timeout)


def probe(scheduler: str, timeout: float) -> None:
    """
    Refuse a tcp:// scheduler that does not answer as Dask does within timeout s.

    A Dask scheduler writes its handshake (a message of a few hundred bytes, its length
    first: 8 bytes) as soon as it accepts. A server that accepts and never answers, or drips
    a byte at a time, or gives a length no handshake has, hung or drove Dask's own connect
    (which allocated what the length said); here it is LinkageError. Other schemes (tls://)
    are left to Dask.
    """
    scheme, _, rest = scheduler.rpartition('://')
    if scheme not in ('', 'tcp'):
        return
    host, _, port = rest.rpartition(':')
    if not (host and port.isdigit() and 0 < int(port) < 65536):
        raise LinkageError('--scheduler', f'expected tcp://HOST:PORT (PORT a number up to '
                           f'65535), got {scheduler!r}')
    deadline = time.monotonic() + timeout

    def read(sock, count):
        data = b''
        while len(data) < count:
            sock.settimeout(max(deadline - time.monotonic(), 1e-3))
            chunk = sock.recv(count - len(data))
            if not chunk:
                raise ConnectionError('it closed the connection')
            data += chunk
        return data

    try:
        with socket.create_connection((host.strip('[]'), int(port)), timeout=timeout) as sock:
            (length,) = struct.unpack('Q', read(sock, 8))   # as Dask's tcp.py
            if length > HANDSHAKE_LIMIT:
                raise ConnectionError(f'its first message says {length:,} bytes, no Dask '
                                      'handshake')
            read(sock, length)
    except (OSError, ValueError) as exc:   # socket.timeout, refused, unknown host
        why = 'no answer' if isinstance(exc, TimeoutError) else str(exc)[:200]
        raise LinkageError('--scheduler', f'cannot reach the Dask scheduler {scheduler} '
                           f'within {timeout:g} s ({why})') from None


def _forget_client() -> None:
    """Collect a Client whose __init__ failed, its __del__'s traceback unprinted."""
    hook, sys.unraisablehook = sys.unraisablehook, lambda _: None
    try:
        gc.collect()
    finally:
        sys.unraisablehook = hook


class Items(Sequence):
    """count work items (head, i), i = 0 .. count - 1, made as they are taken: never listed."""

    def __init__(self, head, count: int) -> None:
        self.head, self.count = head, count

    def __len__(self) -> int:
        """Return count."""
        return self.count

    def __getitem__(self, index: int):
        """Return (head, index)."""
        if not 0 <= index < self.count:
            raise IndexError(index)
        return self.head, index


def in_process(function, items: Sequence, progress=None) -> list:
    """Run the items one after another in this process: the run of no executor, in order."""
    results = []
    for item in items:
        results.append(function(item))
        if progress:
            progress.update(len(results))
    return results


def _local(function, items: Sequence, progress, workers, pool_from):
    """Run the items in this process or in a pool of local processes, in order."""
    workers = workers or os.cpu_count() or 1
    if workers == 1 or len(items) < max(2, pool_from):
        return in_process(function, items, progress)
    # spawn: a fresh interpreter per worker, nothing inherited (threads, locks, numba state);
    # the workers leave Ctrl-C to this process, which stops them at once
    pool = ProcessPoolExecutor(max_workers=min(workers, len(items)),
                               mp_context=multiprocessing.get_context('spawn'),
                               initializer=signal.signal,
                               initargs=(signal.SIGINT, signal.SIG_IGN))
    try:
        results = _windowed(pool, function, items, progress, WINDOW * workers)
    except BaseException:   # Ctrl-C, or a worker that failed: nothing more is waited for
        for process in list((getattr(pool, '_processes', None) or {}).values()):
            process.terminate()
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown()
    return results


def _windowed(pool, function, items: Sequence, progress, window: int) -> list:
    """Run the items on pool, at most window at a time (taken from items as others end)."""
    results, pending, taken = [None] * len(items), {}, iter(enumerate(items))
    done = 0
    while True:
        for index, item in itertools.islice(taken, window - len(pending)):
            pending[pool.submit(function, item)] = index
        if not pending:
            return results
        finished, _ = wait(pending, return_when=FIRST_COMPLETED)
        for future in finished:
            results[pending.pop(future)] = future.result()
        done += len(finished)
        if progress:
            progress.update(done)


def _dask(client, function, items: Sequence, progress):
    """Run the items as tasks of a Dask cluster; gather the results in order."""
    from distributed import as_completed as completed
    futures = client.map(function, items, pure=False)
    for done, _ in enumerate(completed(futures, loop=client.loop), 1):
        if progress:
            progress.update(done)
    return client.gather(futures)
