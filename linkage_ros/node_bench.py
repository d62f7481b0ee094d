"""linkage-node-bench: suspension_node against a bare rclpy echo node, across processes.

Each node runs in its own process (one after the other, on a fresh ROS domain, discovery kept
to this machine) and is driven from this process over the same topics and QoS (reliable,
keep-last 1000):

- latency, time from publishing wheel_travel to receiving wheel_carrier_pose (median, p99):
  paced at --latency-rate (commands apart, as a controller sends them), and ping-pong (the
  next command as soon as the pose arrives, so it can wait for the rest of the previous
  command's work: camber, toe, diagnostics);
- rate: commands paced at each rate of a ladder for --duration seconds; the highest rate
  with no command lost, and whether the node kept up (its last answer within --lag-ms of the
  last command), with the latency at each rate.

The echo node answers each Float64 with a PoseStamped and nothing else: the transport and
executor cost. The table goes to stdout, progress to stderr.
"""

import argparse
import os
from pathlib import Path
import signal
import statistics
import subprocess
import sys
import tempfile
import time

from geometry_msgs.msg import PoseStamped
import numpy as np
import rclpy
from rclpy.experimental import EventsExecutor
from rclpy.node import Node
from std_msgs.msg import Float64

from .node import QOS, run

DEFAULT_RATES = (250, 500, 1000, 2000, 4000, 8000)


class EchoNode(Node):
    """The bare reference: wheel_travel (Float64) in, a PoseStamped with z = travel out."""

    def __init__(self, **kwargs):
        super().__init__('echo', **kwargs)
        self._pub = self.create_publisher(PoseStamped, 'wheel_carrier_pose', QOS)
        self.create_subscription(Float64, 'wheel_travel', self._on_travel, QOS)

    def _on_travel(self, msg):
        out = PoseStamped()
        out.header.stamp = self.get_clock().now().to_msg()
        out.header.frame_id = 'base_link'
        out.pose.position.z = msg.data
        self._pub.publish(out)


def echo_main(args=None):
    """The echo node process: same executor and spin loop as suspension_node."""
    rclpy.init(args=args)
    return run(EchoNode())


class Driver:
    """Publishes wheel_travel and counts wheel_carrier_pose answers (arrival times, s)."""

    def __init__(self, context):
        self.executor = EventsExecutor(context=context)
        self.node = rclpy.create_node('bench_driver', context=context, enable_rosout=False,
                                      start_parameter_services=False)
        self.arrivals = []
        self.pub = self.node.create_publisher(Float64, 'wheel_travel', QOS)
        self.sub = self.node.create_subscription(
            PoseStamped, 'wheel_carrier_pose',
            lambda _: self.arrivals.append(time.perf_counter()), QOS)
        self.executor.add_node(self.node)

    def spin_until(self, predicate, timeout):
        deadline = time.perf_counter() + timeout
        while not predicate() and time.perf_counter() < deadline:
            self.executor.spin_once(timeout_sec=min(0.01, deadline - time.perf_counter()))
        return predicate()

    def connect(self, timeout=20.0):
        """Wait until the node answers, then until no answer is in flight."""
        if not self.spin_until(lambda: self.pub.get_subscription_count() > 0
                               and self.sub.get_publisher_count() > 0, timeout):
            raise RuntimeError('the node under test was not discovered')
        deadline = time.perf_counter() + timeout
        while not self.arrivals and time.perf_counter() < deadline:
            self.send(0.0)
            self.spin_until(lambda: self.arrivals, 0.5)
        if not self.arrivals:
            raise RuntimeError('the node under test never answered')
        count = -1
        while count != len(self.arrivals):   # answers to extra pings: let them land
            count = len(self.arrivals)
            self.spin_until(lambda: len(self.arrivals) > count, 0.3)
        self.arrivals.clear()

    def send(self, travel_m):
        self.pub.publish(Float64(data=float(travel_m)))

    def latency(self, travels):
        """Round trip (s) of each command, one at a time."""
        times = []
        for travel in travels:
            count = len(self.arrivals)
            start = time.perf_counter()
            self.send(travel)
            if not self.spin_until(lambda: len(self.arrivals) > count, 5.0):
                raise RuntimeError(f'no answer to command {len(times)} within 5 s')
            times.append(self.arrivals[-1] - start)
        return np.array(times)

    def paced(self, travels, rate, drain=3.0):
        """Send travels at rate (Hz); returns (sent rate, received, last answer lag s,
        latencies s). Answers come in command order, so the i-th answers the i-th command."""
        self.arrivals.clear()
        sent = []
        period = 1.0 / rate
        start = time.perf_counter()
        due = start
        for travel in travels:
            now = time.perf_counter()
            while now < due:
                self.executor.spin_once(timeout_sec=due - now)
                now = time.perf_counter()
            sent.append(time.perf_counter())
            self.send(travel)
            due += period
        last_sent = sent[-1]
        sent_rate = len(travels) / (time.perf_counter() - start)
        self.spin_until(lambda: len(self.arrivals) >= len(travels), drain)
        received = len(self.arrivals)
        lag = self.arrivals[-1] - last_sent if received else float('inf')
        latencies = np.array(self.arrivals) - np.array(sent) if received == len(sent) else None
        return sent_rate, received, lag, latencies

    def destroy(self):
        self.executor.remove_node(self.node)
        self.node.destroy_node()
        self.executor.shutdown()


def travels(count, amplitude=0.02):
    """A slow +-20 mm sine (m): small steps, one continuation substep each."""
    return amplitude * np.sin(np.arange(count) * 0.01)


def start(command, domain_id, log_dir):
    env = dict(os.environ, ROS_DOMAIN_ID=str(domain_id), ROS_LOG_DIR=log_dir,
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    return subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)


def stop(process):
    process.send_signal(signal.SIGINT)
    try:
        _, err = process.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        process.kill()
        _, err = process.communicate()
    if process.returncode != 0:
        print(f'linkage-node-bench: the node exited with {process.returncode}: {err.strip()}',
              file=sys.stderr)


def measure(name, command, domain_id, args, log_dir):
    """Latency and rate ladder of one node process."""
    print(f'linkage-node-bench: {name}: starting', file=sys.stderr)
    process = start(command, domain_id, log_dir)
    context = rclpy.context.Context()
    rclpy.init(context=context, domain_id=domain_id)
    driver = Driver(context)
    try:
        driver.connect()
        driver.latency(travels(args.warmup))
        latency = {'ping-pong': driver.latency(travels(args.count))}
        _, received, _, paced = driver.paced(travels(args.count), args.latency_rate)
        if paced is None:
            raise RuntimeError(f'{args.count - received} commands lost at '
                               f'{args.latency_rate} Hz')
        latency['paced'] = paced
        for kind, values in latency.items():
            print(f'linkage-node-bench: {name}: {kind} latency median '
                  f'{np.median(values) * 1e6:.0f} us, p99 {np.percentile(values, 99) * 1e6:.0f}'
                  f' us over {len(values)}', file=sys.stderr)
        ladder = []
        for rate in args.rates:
            count = max(1, int(rate * args.duration))
            driver.connect()     # a backlog of the previous rate drains first
            sent_rate, received, lag, latencies = driver.paced(travels(count), rate)
            kept_up = received == count and lag * 1000.0 <= args.lag_ms
            ladder.append((rate, count, sent_rate, received, lag, kept_up, latencies))
            print(f'linkage-node-bench: {name}: {rate} Hz: sent {count} at '
                  f'{sent_rate:.0f}/s, received {received}, last answer '
                  f'{lag * 1000.0:.1f} ms after the last command', file=sys.stderr)
            if received < count:
                break
    finally:
        driver.destroy()
        rclpy.try_shutdown(context=context)
        stop(process)
    return latency, ladder


def solve_time(scene_name, method, count, gap=0.0):
    """Median time (s) of one Continuation.solve on the bench's command sequence, with the
    process idle for gap (s) before each: an idle process solves slower (cold caches)."""
    from .kinematics import Continuation
    from .scene import load_scene
    cont = Continuation(load_scene(scene_name), method=method)
    times = []
    for travel in travels(count) * 1000.0:
        if gap:
            time.sleep(gap)
        start_time = time.perf_counter()
        cont.solve(travel)
        times.append(time.perf_counter() - start_time)
    return statistics.median(times)


def best_rate(ladder, kept_up=False):
    """Highest rate of the ladder with nothing lost (and kept up, if asked)."""
    good = [rate for rate, count, _, received, _, ok, _ in ladder
            if received == count and (ok or not kept_up)]
    return max(good) if good else 0


def _us(values, q):
    return f'{np.percentile(values, q) * 1e6:.0f}' if values is not None else ''


def report(results, solve_s, latency_rate, stream):
    """solve_s: (paced, back-to-back) median solve times of the core alone, s."""
    """Summary table, then the rate ladder; CSV with units in the column names."""
    print(f'node,paced_{latency_rate:g}hz_median_us,paced_p99_us,ping_pong_median_us,'
          'ping_pong_p99_us,max_rate_no_loss_hz,max_rate_kept_up_hz', file=stream)
    for name, (latency, ladder) in results.items():
        print(f"{name},{_us(latency['paced'], 50)},{_us(latency['paced'], 99)},"
              f"{_us(latency['ping-pong'], 50)},{_us(latency['ping-pong'], 99)},"
              f'{best_rate(ladder)},{best_rate(ladder, kept_up=True)}', file=stream)
    ratios = [np.percentile(results['node'][0][kind], q) / np.percentile(
        results['echo'][0][kind], q) for kind in ('paced', 'ping-pong') for q in (50, 99)]
    print('ratio node/echo,' + ','.join(f'{r:.2f}' for r in ratios) + ',,', file=stream)
    print(f'core solve alone (median in process),{solve_s[0] * 1e6:.0f},,'
          f'{solve_s[1] * 1e6:.0f},,,', file=stream)
    print('', file=stream)
    print('node,rate_hz,sent,sent_rate_hz,received,lost,last_answer_lag_ms,kept_up,'
          'latency_median_us,latency_p99_us', file=stream)
    for name, (_, ladder) in results.items():
        for rate, count, sent_rate, received, lag, ok, latencies in ladder:
            print(f'{name},{rate},{count},{sent_rate:.0f},{received},{count - received},'
                  f'{lag * 1000.0:.1f},{ok},{_us(latencies, 50)},{_us(latencies, 99)}',
                  file=stream)


def parse_args(argv):
    parser = argparse.ArgumentParser(prog='linkage-node-bench', description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--count', type=int, default=2000,
                        help='commands for each latency measurement (default 2000)')
    parser.add_argument('--latency-rate', type=float, default=200.0,
                        help='command rate of the paced latency, Hz (default 200)')
    parser.add_argument('--warmup', type=int, default=200, help='round trips not counted')
    parser.add_argument('--rates', type=lambda s: [int(r) for r in s.split(',')],
                        default=list(DEFAULT_RATES), help='command rates, Hz, comma separated')
    parser.add_argument('--duration', type=float, default=2.0, help='seconds per rate')
    parser.add_argument('--lag-ms', type=float, default=50.0,
                        help='kept up: last answer at most this long after the last command')
    parser.add_argument('--scene', default='five_link')
    parser.add_argument('--method', default='fast', choices=('fast', 'paper'))
    parser.add_argument('--domain-id', type=int, default=None,
                        help='first of two ROS domain ids to use (default from the pid)')
    parser.add_argument('--echo', action='store_true', help=argparse.SUPPRESS)
    return parser.parse_known_args(argv)


def main(argv=None):
    args, ros_args = parse_args(sys.argv[1:] if argv is None else argv)
    if args.echo:      # the echo node process started by the bench itself
        return echo_main(['echo', *ros_args])
    if args.count < 1 or args.duration <= 0 or args.latency_rate <= 0 or not args.rates:
        print('linkage-node-bench: --count >= 1, --duration > 0, --latency-rate > 0 and '
              '--rates are required', file=sys.stderr)
        return 2
    first = args.domain_id if args.domain_id is not None else 1 + os.getpid() % 100
    node_script = Path(sys.executable).parent / 'suspension_node'
    commands = {
        'echo': [sys.executable, '-m', 'linkage_ros.node_bench', '--echo'],
        'node': [str(node_script), '--ros-args', '-p', f'scene:={args.scene}',
                 '-p', f'method:={args.method}'],
    }
    print(f'linkage-node-bench: {os.cpu_count()} CPUs, load average '
          f'{os.getloadavg()[0]:.2f}; {args.count} commands per latency, rates {args.rates} '
          f'Hz for {args.duration:g} s each', file=sys.stderr)
    results = {}
    with tempfile.TemporaryDirectory(prefix='linkage-node-bench-') as log_dir:
        for offset, (name, command) in enumerate(commands.items()):
            results[name] = measure(name, command, (first + offset) % 101 or 101, args,
                                    log_dir)
    count = min(args.count, 1000)
    solve_s = (solve_time(args.scene, args.method, count, gap=1.0 / args.latency_rate),
               solve_time(args.scene, args.method, count))
    report(results, solve_s, args.latency_rate, sys.stdout)
    return 0


if __name__ == '__main__':
    sys.exit(main())
