# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The memory a run may take, known before it starts: one check for every program.

    room = memory_room()                               # Room(bytes, what limits it), or None
    refuse_if_short(Need(points, resident, address), field, what, advice)   # LinkageError

A program says what its run needs (Need: bytes resident and of address space, estimated from
its own measurements: linkage-map's maps, linkage-study's variants) and refuses a run that
does not fit before it starts, in one line. The room is the smallest of what applies to this
process: the host's MemAvailable, the address-space limit (RLIMIT_AS, `ulimit -v`) less the
address space in use, and the cgroup's memory.max (v2) or memory.limit_in_bytes (v1) less
what the cgroup already uses, at every level of its path. The address-space limit counts
reserved address space (pyarrow reserves plenty); the others count resident memory, so each
is compared with its own need.
"""

from __future__ import annotations

import os
from pathlib import Path
import resource
from typing import NamedTuple

from .errors import LinkageError

CGROUP_ROOT = Path('/sys/fs/cgroup')


class Need(NamedTuple):
    """What a run needs: its points (solves), bytes resident, bytes of address space."""

    points: int
    resident: float
    address_space: float


class Room(NamedTuple):
    """The memory a run may take, bytes, and what sets it (said when it is too little)."""

    size: float      # bytes
    limit: str

    def wanted(self, need: Need) -> float:
        """Return the bytes of need this room holds: address space for RLIMIT_AS, else resident."""
        return need.address_space if self.limit == ADDRESS_SPACE else need.resident


ADDRESS_SPACE = 'the address-space limit RLIMIT_AS, ulimit -v'


def refuse_if_short(need: Need, field: str, what: str, advice: str) -> None:
    """
    Refuse a run whose Need does not fit the memory this process may take.

    Raises LinkageError(field, '<what> need about 3.2 GB of memory and 1.0 GB is available
    (<the limit>): <advice>'); returns quietly when it fits or no limit is known.
    """
    room = memory_room()
    if room is not None and room.wanted(need) > room.size:
        raise LinkageError(field, f'{what} need about {_gb(room.wanted(need))} of memory and '
                           f'{_gb(room.size)} is available ({room.limit}): {advice}')


def _gb(value: float) -> str:
    return f'{value / 1e9:,.1f} GB'


def memory_room(cgroup_root: Path = CGROUP_ROOT) -> Room | None:
    """Return the smallest Room that applies to this process, or None if none is known."""
    rooms = [room for room in (mem_available(), address_space_room(),
                               cgroup_room(_read('/proc/self/cgroup'), cgroup_root))
             if room is not None]
    return min(rooms, default=None)


def mem_available() -> Room | None:
    """Return the host's MemAvailable (or the free pages), or None if unknown."""
    for line in _read('/proc/meminfo').splitlines():
        if line.startswith('MemAvailable:'):
            return Room(int(line.split()[1]) * 1024.0, 'MemAvailable')
    try:
        return Room(float(os.sysconf('SC_AVPHYS_PAGES') * os.sysconf('SC_PAGE_SIZE')),
                    'the free memory')
    except (ValueError, OSError):
        return None


def address_space_room() -> Room | None:
    """Return RLIMIT_AS (soft) less the address space in use (VmSize), or None: no limit."""
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft == resource.RLIM_INFINITY:
        return None
    used = 0.0
    for line in _read('/proc/self/status').splitlines():
        if line.startswith('VmSize:'):
            used = int(line.split()[1]) * 1024.0
    return Room(max(soft - used, 0.0), ADDRESS_SPACE)


def cgroup_room(proc_cgroup: str, root: Path = CGROUP_ROOT) -> Room | None:
    """
    Return the least room (limit less usage) of the cgroups in proc_cgroup, or None.

    proc_cgroup: the text of /proc/self/cgroup ('0::/path' for v2, 'N:memory:/path' for
    v1); every level of the path is read under root (a limit of a parent applies too), and
    root itself, which is the process's own cgroup inside a container.
    """
    rooms = []
    for line in proc_cgroup.splitlines():
        _, controllers, path = (line.split(':', 2) + ['', ''])[:3]
        if controllers == '':
            files, base = ('memory.max', 'memory.current'), root
        elif 'memory' in controllers.split(','):
            files, base = ('memory.limit_in_bytes', 'memory.usage_in_bytes'), root / 'memory'
        else:
            continue
        parts = [p for p in path.split('/') if p]
        for depth in range(len(parts) + 1):
            room = _cgroup_level(base.joinpath(*parts[:depth]), *files)
            if room is not None:
                rooms.append(room)
    return min(rooms, default=None)


def _cgroup_level(folder: Path, limit_file: str, usage_file: str) -> Room | None:
    """Return one cgroup's limit less its usage, or None: no limit ('max', huge) or no file."""
    limit, usage = _read(folder / limit_file).strip(), _read(folder / usage_file).strip()
    if not (limit.isdigit() and usage.isdigit()) or int(limit) >= 2 ** 62:   # v1: no limit
        return None
    return Room(max(int(limit) - int(usage), 0) * 1.0, f"the cgroup's {limit_file} "
                f'({folder})')


def _read(path) -> str:
    """Return a small system file's text, '' if it cannot be read."""
    try:
        with open(path) as stream:
            return stream.read(1 << 20)
    except (OSError, UnicodeDecodeError):
        return ''
