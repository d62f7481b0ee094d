# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The node processes linkage-bench node measures: started in a namespace, stopped, found."""

import os
from pathlib import Path
import signal
import subprocess
import sys
import time

import rclpy

from .driver import Driver
from .tables import progress


class Target:
    """A node process under test in a namespace of its own, and the Driver that talks to it."""

    def __init__(self, name, command, domain_id, log_dir, prefixes=('',), env=None):
        self.name = name
        namespace = f'/linkage_node_bench_{os.getpid()}/{name}'
        remaps = ['-r', f'__ns:={namespace}', '-r', f'/diagnostics:={namespace}/diagnostics']
        self.started = time.perf_counter()
        ros_args = remaps if '--ros-args' in command else ['--ros-args', *remaps]
        self.process = start_process([*command, *ros_args], domain_id, log_dir, env)
        self.context = rclpy.context.Context()
        rclpy.init(args=['bench_driver', '--ros-args', *remaps], context=self.context,
                   domain_id=domain_id)
        self.driver = Driver(self.context, prefixes)

    def cpu_seconds(self):
        """
        Return the CPU time (s, user + system, every thread) the process has used so far.

        Read from /proc/<pid>/stat (Linux): what the node's executor and its DDS threads
        cost, wherever the time goes.
        """
        with open(f'/proc/{self.process.pid}/stat', encoding='ascii') as stat:
            fields = stat.read().rsplit(')', 1)[1].split()   # after the command's name
        return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')

    def close(self):
        self.driver.destroy()
        rclpy.try_shutdown(context=self.context)
        stop_process(self.process, self.name)


def start_process(command, domain_id, log_dir, env=None):
    env = dict(os.environ, **(env or {}), ROS_DOMAIN_ID=str(domain_id), ROS_LOG_DIR=log_dir)
    return subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)


def stop_process(process, name):
    process.send_signal(signal.SIGINT)
    try:
        _, err = process.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        process.kill()
        _, err = process.communicate()
    if process.returncode != 0:
        progress(f'{name} exited with {process.returncode}: {err.strip()}')


def node_script():
    return str(Path(sys.executable).parent / 'suspension_node')
