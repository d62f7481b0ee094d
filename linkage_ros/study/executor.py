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

from concurrent.futures import as_completed, ProcessPoolExecutor
import contextlib
import multiprocessing
import os
import sys
import time
from typing import Callable, Iterator, Sequence

from ..core.base import LinkageError

CONNECT_TIMEOUT = 5.0   # s: a scheduler that does not answer by then is unreachable
PROGRESS_PERIOD = 1.0   # s between progress lines when stderr is not a terminal
BAR = 30                # characters of the progress bar


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
    try:
        client = Client(scheduler, timeout=timeout, set_as_default=False)
    except (OSError, ValueError, TypeError) as exc:   # unreachable, refused, a bad address
        raise LinkageError('--scheduler', f'cannot reach the Dask scheduler {scheduler} '
                           f'within {timeout:g} s ({str(exc).splitlines()[0][:200]})') from None
    try:
        yield lambda function, items, progress=None: _dask(client, function, items, progress)
    finally:
        client.close()


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
    # spawn: a fresh interpreter per worker, nothing inherited (threads, locks, numba state)
    context = multiprocessing.get_context('spawn')
    with ProcessPoolExecutor(max_workers=min(workers, len(items)), mp_context=context) as pool:
        futures = [pool.submit(function, item) for item in items]
        for done, _ in enumerate(as_completed(futures), 1):
            if progress:
                progress.update(done)
        return [f.result() for f in futures]


def _dask(client, function, items: Sequence, progress):
    """Run the items as tasks of a Dask cluster; gather the results in order."""
    from distributed import as_completed as completed
    futures = client.map(function, items, pure=False)
    for done, _ in enumerate(completed(futures, loop=client.loop), 1):
        if progress:
            progress.update(done)
    return client.gather(futures)
