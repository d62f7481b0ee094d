# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Where ROS traffic goes: the user's ROS domain, private contexts, a private network for tests.

Programs of this package run on the domain the environment names (ROS_DOMAIN_ID, ROS's own
default 0 when unset), never on one picked by themselves. A context that talks only within
its process uses automatic discovery OFF: on any domain, nothing outside the process sees it
or reaches it. Processes that must talk to each other in tests can be put in a network of
their own (Linux, root): a new network namespace holding only the loopback interface, and a
new mount namespace with a /dev/shm of its own, so that neither DDS over UDP nor Fast DDS's
shared-memory transport reaches a process outside, whatever domain both use.

Only the standard library is imported here (rclpy when a context is made).
"""

import ctypes
import errno
import fcntl
import os
import socket
import struct
import subprocess
import sys
from typing import NamedTuple

# <sched.h>, <sys/mount.h>, <linux/sockios.h>, <net/if.h>
CLONE_NEWNS = 0x00020000
CLONE_NEWNET = 0x40000000
MS_NOSUID, MS_NODEV, MS_REC, MS_PRIVATE = 0x2, 0x4, 0x4000, 0x40000
SIOCGIFFLAGS, SIOCSIFFLAGS, IFF_UP = 0x8913, 0x8914, 0x1

# The namespaces this process was in before enter_private_network (open file descriptors of
# /proc/self/ns/net and /proc/self/ns/mnt), for start_outside; None before.
_OUTSIDE = None


class PrivateNetwork(NamedTuple):
    """What enter_private_network did: entered (bool) and a sentence saying how, or why not."""

    entered: bool
    text: str


def environment_domain_id():
    """Return the ROS domain id the environment names: ROS_DOMAIN_ID, or 0 (ROS's default)."""
    text = os.environ.get('ROS_DOMAIN_ID', '').strip()
    return int(text) if text else 0


def init_context(domain_id=None, discovery_range='OFF', args=None):
    """
    Return a new rclpy Context on domain_id (None: the environment's) and discovery_range.

    rcl reads the range from ROS_AUTOMATIC_DISCOVERY_RANGE when the context is initialised;
    it is set for that moment only. 'OFF' (the default): only nodes of this context see each
    other. args: ROS arguments for every node of the context (['--ros-args', '-r', ...]).
    """
    import rclpy
    previous = os.environ.get('ROS_AUTOMATIC_DISCOVERY_RANGE')
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = discovery_range
    try:
        context = rclpy.context.Context()
        rclpy.init(args=None if args is None else ['linkage_ros', *args], context=context,
                   domain_id=domain_id)
    finally:
        if previous is None:
            del os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE']
        else:
            os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = previous
    return context


def _libc():
    """Return libc with the prototypes of the calls made here (the flags are unsigned long)."""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.unshare.argtypes = [ctypes.c_int]
    libc.setns.argtypes = [ctypes.c_int, ctypes.c_int]
    libc.mount.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_ulong,
                           ctypes.c_char_p]
    return libc


def _libc_call(libc, name, *args):
    """Call libc's name(*args); raise OSError with errno's text if it returns -1."""
    if getattr(libc, name)(*args) != 0:
        code = ctypes.get_errno()
        raise OSError(code, f'{name}: {os.strerror(code)}')


def _bring_up_loopback():
    """Set the loopback interface of this network namespace up (ip link set lo up)."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        request = struct.pack('16sH22x', b'lo', 0)        # struct ifreq: name, flags
        flags = struct.unpack('16sH22x', fcntl.ioctl(sock, SIOCGIFFLAGS, request))[1]
        fcntl.ioctl(sock, SIOCSIFFLAGS, struct.pack('16sH22x', b'lo', flags | IFF_UP))


def enter_private_network():
    """
    Move this process into a network of its own: only lo, and a /dev/shm of its own.

    Every process started afterwards inherits it, so DDS participants of this process and its
    children discover one another (on any domain, with discovery LOCALHOST or wider) and
    nothing else; nothing outside sees them. The /dev/shm of its own keeps Fast DDS's
    shared-memory transport in too (its segments are files there), and vanishes with the
    last process. Call it before any DDS participant exists: sockets opened before stay in
    the old network. Needs Linux and root (CAP_SYS_ADMIN); returns PrivateNetwork(entered,
    text), text saying how or why not (nothing is changed then).
    """
    global _OUTSIDE
    if _OUTSIDE is not None:
        return PrivateNetwork(True, 'already in a private network')
    if not sys.platform.startswith('linux'):
        return PrivateNetwork(False, 'network namespaces are Linux only')
    libc = _libc()
    outside = (os.open('/proc/self/ns/net', os.O_RDONLY), os.open('/proc/self/ns/mnt',
                                                                  os.O_RDONLY))
    try:
        _libc_call(libc, 'unshare', CLONE_NEWNET | CLONE_NEWNS)
    except OSError as exc:
        for fd in outside:
            os.close(fd)
        needs = ' (needs root)' if exc.errno == errno.EPERM else ''
        return PrivateNetwork(False, f'no network namespace: {exc.strerror}{needs}')
    # From here this process is in the new namespaces: there is no way back but start_outside.
    _OUTSIDE = outside
    _bring_up_loopback()
    try:
        # Mounts in the new namespace must not propagate back to the old one.
        _libc_call(libc, 'mount', None, b'/', None, MS_REC | MS_PRIVATE, None)
        _libc_call(libc, 'mount', b'tmpfs', b'/dev/shm', b'tmpfs', MS_NOSUID | MS_NODEV,
                   b'mode=1777')
    except OSError as exc:
        # Measured with Fast DDS 2.14: even with shared memory as its only transport, a
        # participant in a network namespace does not reach one outside it through a shared
        # /dev/shm. A /dev/shm of its own makes that independent of the version.
        return PrivateNetwork(True, 'a private network namespace (only lo), /dev/shm shared '
                                    f'({exc.strerror})')
    return PrivateNetwork(True, 'a private network namespace (only lo) with a /dev/shm of its '
                                'own')


def start_outside(command, **popen_kwargs):
    """
    Start command (subprocess.Popen) in the network and /dev/shm this process had before.

    That is, outside the private network of enter_private_network, beside the machine's other
    processes. RuntimeError if this process is not in a private network.
    """
    if _OUTSIDE is None:
        raise RuntimeError('this process is not in a private network')
    net, mnt = _OUTSIDE
    libc = _libc()

    def leave():    # in the child, between fork and exec: one thread, so setns is allowed
        _libc_call(libc, 'setns', net, CLONE_NEWNET)
        _libc_call(libc, 'setns', mnt, CLONE_NEWNS)

    return subprocess.Popen(command, preexec_fn=leave, **popen_kwargs)
