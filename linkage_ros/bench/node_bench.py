"""
linkage-node-bench: speed on the paths users take, side by side with what it must beat.

Sections (all by default; --only picks some), sizes multiplied by --scale (run 1, 10, 100):

  core      one command at a time through Continuation.solve (five_link, steps of up to
            0.75 mm), beside exudyn's static solver on the same commands (one position per
            call), in alternating rounds; the largest residual and the largest difference
  sweep     linkage-sweep five_link to a CSV file at 161, 1601 and 16001 positions: cost per
            position, and per position over the 161-position run
  start     from launching a process to its first answer: the core (import, scene, first
            solve) and suspension_node (first pose over DDS), with the compiled kernels in
            numba's cache (warm) and with an empty cache (cold: compiled at start)
  latency   suspension_node against a bare rclpy echo node (Float64 in, PoseStamped out),
            each in its own process, measured alternately: paced at --latency-rate, and
            ping-pong; then a ladder of command rates (lost commands, lag, latency)
  vehicle   vehicle:=demo_vehicle against a four-corner echo node, four corners at --hz each
            for --seconds: one Float64 per corner per step, then one JointState per step; the
            step latency is from sending a step to the last of its four poses
  callback  the node's travel callback called in process (no subscribers): plain (the scene
            without its elements, tf off), with its elements (the elements topic), with TF on
            (/tf per answer: the node's default), with the alignment or markers outputs,
            recording to MCAP, mirroring to Rerun, both (all but tf with tf off)

Tables go to stdout as CSV (the first cell of each header row names the section), progress
to stderr; --plot writes latency against command rate (node and echo) as a PNG. Every
process runs on the user's ROS domain (ROS_DOMAIN_ID, 0 if unset; --domain-id) and discovery
range (LOCALHOST if ROS_AUTOMATIC_DISCOVERY_RANGE is unset), each node process and its driver
under a namespace of their own (/linkage_node_bench_<pid>/<node>, /diagnostics included), so
that they neither answer nor disturb other nodes on that domain; the callback section's node
is private to its process (discovery OFF).
Absolute times on shared machines are noisy: read the ratios, measured in the same run.
"""

import argparse
import contextlib
import io
import os
from pathlib import Path
import signal
import subprocess
import sys
import tempfile
import time

from geometry_msgs.msg import PoseStamped
import numpy as np
import rclpy
from rclpy.experimental import EventsExecutor
from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

from ..cdr import float64_cdr, joint_state_cdr
from ..cli import EXIT_STATUS, Parser, program, writable_file
from ..core.errors import LinkageError
from ..core.scene import config_dir, load_scene
from ..core.warmup import compile_if_cold
from ..ros.entry import run
from ..ros.isolation import environment_domain_id, init_context
from ..ros.node import QOS

SECTIONS = ('core', 'sweep', 'start', 'latency', 'vehicle', 'callback')
DEFAULT_RATES = (250, 500, 1000, 2000, 4000)
VEHICLE = 'demo_vehicle'
CORNERS = ('front_left', 'front_right', 'rear_left', 'rear_right')
QUICK_DISCOVERY = config_dir() / 'fastdds_quick_discovery.xml'


def progress(text):
    print(f'linkage-node-bench: {text}', file=sys.stderr, flush=True)


def table(header, rows):
    """Print a CSV table: header (first cell: the section) and rows, floats to 4 digits."""
    print(','.join(header))
    for row in rows:
        print(','.join(f'{v:.4g}' if isinstance(v, float) else str(v) for v in row))
    print()


# --- the bare references ---------------------------------------------------------------------

class EchoNode(Node):
    """
    The bare reference: transport and executor cost only.

    Each wheel_travel (Float64) is answered by a PoseStamped with z = travel, under every
    corner prefix; a joint_states message naming '<corner>_travel' joints is answered by one
    pose per corner it names.
    """

    def __init__(self, prefixes=('',), **kwargs):
        super().__init__('echo', **kwargs)
        self.pubs = {}
        for prefix in prefixes:
            pub = self.create_publisher(PoseStamped, prefix + 'wheel_carrier_pose', QOS)
            self.pubs[prefix.rstrip('/')] = pub
            self.create_subscription(Float64, prefix + 'wheel_travel',
                                     lambda msg, pub=pub: self.answer(pub, msg.data), QOS)
        if prefixes != ('',):
            self.create_subscription(JointState, 'joint_states', self.on_joint_states, QOS)

    def answer(self, pub, travel):
        out = PoseStamped()
        out.header.stamp = self.get_clock().now().to_msg()
        out.header.frame_id = 'base_link'
        out.pose.position.z = travel
        pub.publish(out)

    def on_joint_states(self, msg):
        positions = dict(zip(msg.name, msg.position))
        for corner, pub in self.pubs.items():
            if f'{corner}_travel' in positions:
                self.answer(pub, positions[f'{corner}_travel'])


def echo_main(vehicle: bool, args: list[str] | None = None) -> int:
    """Run an echo node process: same executor and spin loop as suspension_node."""
    rclpy.init(args=args)
    return run(EchoNode(tuple(f'{c}/' for c in CORNERS) if vehicle else ('',)))


class Driver:
    """
    Sends steps of commands to one node process and times the poses that answer them.

    prefixes: '' for one scene, '<corner>/' for each corner of a vehicle. A step is one
    Float64 per corner, or (joint_states=True) one JointState naming every corner's travel
    joint. Poses of a corner come in command order, so its i-th answers step i.
    """

    def __init__(self, context, prefixes=('',)):
        self.executor = EventsExecutor(context=context)
        self.node = rclpy.create_node('bench_driver', context=context, enable_rosout=False,
                                      start_parameter_services=False)
        self.prefixes = prefixes
        self.arrivals = {p: [] for p in prefixes}
        self.pubs = [self.node.create_publisher(Float64, p + 'wheel_travel', QOS)
                     for p in prefixes]
        self.joint_pub = self.node.create_publisher(JointState, 'joint_states', QOS)
        # Raw (CDR) both ways: the driver must be much faster than what it measures, so it
        # neither builds nor decodes messages.
        self.subs = [self.node.create_subscription(
            PoseStamped, p + 'wheel_carrier_pose',
            lambda _, times=self.arrivals[p]: times.append(time.perf_counter()), QOS,
            raw=True) for p in prefixes]
        self.joint_layout = joint_state_layout([p.rstrip('/') + '_travel' for p in prefixes])
        self.executor.add_node(self.node)

    def answered(self):
        """Count the steps answered by every corner."""
        return min(len(times) for times in self.arrivals.values())

    def clear(self):
        for times in self.arrivals.values():
            times.clear()

    def step_arrivals(self):
        """Arrival (s) of the last answer of each step answered by every corner."""
        n = self.answered()
        return np.max([times[:n] for times in self.arrivals.values()], axis=0)

    def spin_until(self, predicate, timeout):
        deadline = time.perf_counter() + timeout
        while not predicate() and time.perf_counter() < deadline:
            self.executor.spin_once(timeout_sec=min(0.01, deadline - time.perf_counter()))
        return predicate()

    def send(self, travel_m, joint_states=False):
        if joint_states:
            self.joint_pub.publish(self.joint_layout(travel_m))
        else:
            data = float64_cdr(travel_m)
            for pub in self.pubs:
                pub.publish(data)

    def connect(self, joint_states=False, timeout=20.0, ping_period=0.5):
        """
        Wait until the node answers every corner, then until no answer is in flight.

        A ping goes every ping_period s until then.
        """
        pubs = [self.joint_pub] if joint_states else self.pubs
        if not self.spin_until(lambda: all(p.get_subscription_count() for p in pubs)
                               and all(s.get_publisher_count() for s in self.subs), timeout):
            raise RuntimeError('the node under test was not discovered')
        deadline = time.perf_counter() + timeout
        while not self.answered() and time.perf_counter() < deadline:
            self.send(0.0, joint_states)
            self.spin_until(self.answered, ping_period)
        if not self.answered():
            raise RuntimeError('the node under test never answered')
        self.first_answer = min(times[0] for times in self.arrivals.values())
        count = -1
        while count != sum(len(t) for t in self.arrivals.values()):   # answers to extra pings
            count = sum(len(t) for t in self.arrivals.values())
            self.spin_until(lambda: sum(len(t) for t in self.arrivals.values()) > count, 0.3)
        self.clear()

    def ping_pong(self, travels):
        """Latency (s) of each step sent when the previous one is answered."""
        self.clear()
        times = []
        for i, travel in enumerate(travels):
            start = time.perf_counter()
            self.send(travel)
            if not self.spin_until(lambda: self.answered() > i, 5.0):
                raise RuntimeError(f'no answer to command {i} within 5 s')
            times.append(self.step_arrivals()[i] - start)
        return np.array(times)

    def paced(self, travels, rate, joint_states=False, drain=3.0, label=''):
        """
        Send one step per travel at rate (Hz); with a label, a progress line every 30 s.

        Returns (steps sent, steps answered, lag of the last answer after the last step (s),
        step latencies (s)).
        """
        self.clear()
        sent, period = [], 1.0 / rate
        due = time.perf_counter()
        report = due + 30.0
        for i, travel in enumerate(travels):
            if label and due >= report:
                progress(f'{label}: {i}/{len(travels)} sent, {self.answered()} answered')
                report += 30.0
            now = time.perf_counter()
            while now < due:
                self.executor.spin_once(timeout_sec=due - now)
                now = time.perf_counter()
            sent.append(time.perf_counter())
            self.send(travel, joint_states)
            due += period
        self.spin_until(lambda: self.answered() >= len(travels), drain)
        arrivals = self.step_arrivals()
        lag = arrivals[-1] - sent[-1] if len(arrivals) else float('inf')
        return len(travels), len(arrivals), lag, arrivals - np.array(sent[:len(arrivals)])

    def destroy(self):
        self.executor.remove_node(self.node)
        self.node.destroy_node()
        self.executor.shutdown()


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

    def close(self):
        self.driver.destroy()
        rclpy.try_shutdown(context=self.context)
        stop_process(self.process, self.name)


def joint_state_layout(names):
    """Return a function travel (m) -> CDR of a sensor_msgs/JointState (zero stamp)."""
    return lambda travel: joint_state_cdr((0, 0), '', names, [float(travel)] * len(names))


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


def sine(count, amplitude_m=0.02, step=0.01):
    """Travels (m) of a slow sine: small steps, one continuation substep each."""
    return amplitude_m * np.sin(np.arange(count) * step)


def us(values, q=50):
    return float(np.percentile(values, q) * 1e6) if len(values) else float('nan')


# --- sections ------------------------------------------------------------------------------

def bench_core(args):
    """One command at a time: Continuation.solve beside exudyn, alternating rounds."""
    from . import peers
    from ..core.kinematics import Continuation
    from ..core.scene import load_scene
    scene = load_scene(args.scene)
    count = args.count * args.scale
    travels = 60.0 * np.sin(np.arange(count) * 0.0125)      # mm, steps of up to 0.75 mm
    entries = {'linkage_ros': Continuation(scene)}
    if peers.exudyn_version():
        entries['exudyn'] = peers.ExudynSolver(scene, 1e-10)
    else:
        progress('exudyn is not installed (pip install -e .[bench]): core alone')
    times = {name: [] for name in entries}
    centers = {name: [] for name in entries}
    residual = 0.0
    rounds = 4
    for r, chunk in enumerate(np.array_split(travels, rounds)):
        for name, solver in entries.items():
            for travel in chunk:
                start = time.perf_counter()
                answer = solver.solve(travel)
                times[name].append(time.perf_counter() - start)
                if name == 'linkage_ros':
                    residual = max(residual, answer.residual)
                    centers[name].append(answer.wheel_center)
                else:
                    centers[name].append(answer[0])
        progress(f'core: round {r + 1}/{rounds}')
    base = np.median(times['linkage_ros'])
    rows = []
    for name, values in times.items():
        diff = np.abs(np.array(centers[name]) - np.array(centers['linkage_ros'])).max()
        rows.append((name, count, us(values), us(values, 99), float(np.median(values) / base),
                     residual if name == 'linkage_ros' else '', float(diff)))
    table(['core', 'commands', 'median_us', 'p99_us', 'ratio_to_linkage_ros',
           'residual_max_mm', 'wheel_center_diff_mm'], rows)


def bench_sweep(args):
    """linkage-sweep to a CSV file at 161, 1601, 16001 positions (x scale)."""
    from ..tools import sweep
    rows, base = [], None
    with tempfile.TemporaryDirectory() as folder:
        with contextlib.redirect_stderr(io.StringIO()):   # untimed: loads the kernels
            sweep.main([args.scene, '--csv', str(Path(folder) / 'warmup.csv')])
        for step in (1.0, 0.1, 0.01):
            step /= args.scale
            positions = int(round(160 / step)) + 1
            out = Path(folder) / 'sweep.csv'
            with contextlib.redirect_stderr(io.StringIO()):
                start = time.perf_counter()
                sweep.main([args.scene, '--step', repr(step), '--csv', str(out)])
                seconds = time.perf_counter() - start
            base = base or (positions, seconds)
            over = ((seconds - base[1]) / (positions - base[0]) * 1e6
                    if positions > base[0] else '')
            rows.append((positions, seconds, seconds / positions * 1e6, over))
            progress(f'sweep: {positions} positions in {seconds:.2f} s')
    table(['sweep', 'seconds', 'us_per_position', 'us_per_position_over_the_first'], rows)


def bench_start(args, log_dir, domain_id):
    """
    Time launch to first answer: warm and cold (empty) numba cache, default and quick discovery.

    Each launch is timed from a fresh process, whose DDS participant (the client) reads the
    discovery profile as the node does: Fast DDS reads it once per process.
    """
    quick = {'FASTRTPS_DEFAULT_PROFILES_FILE': str(QUICK_DISCOVERY)}
    cases = [('core', 'warm', {}), ('suspension_node', 'warm', {}),
             ('suspension_node', 'warm quick-discovery', quick),
             ('core', 'cold', {}), ('suspension_node', 'cold quick-discovery', quick)]
    rows = []
    for what, case, env in cases:
        times = []
        for _ in range(1 if 'cold' in case else args.starts):
            with tempfile.TemporaryDirectory() as empty:    # a new one each time: cold
                child = dict(os.environ, **env, **(
                    {'NUMBA_CACHE_DIR': empty} if 'cold' in case else {}))
                out = subprocess.run(
                    [sys.executable, '-m', 'linkage_ros.bench.node_bench', '--start-once', what,
                     '--scene', args.scene, '--domain-id', str(domain_id)], env=child,
                    capture_output=True, text=True, check=True, timeout=300)
                times.append([float(v) for v in out.stdout.split()])
        launch = [t[0] for t in times]
        rows.append((what, case, len(times), float(np.median(launch)), max(launch),
                     float(np.median([t[1] for t in times])) if what == 'core' else ''))
        progress(f'start: {what}, {case}: median {rows[-1][3]:.2f} s, max {rows[-1][4]:.2f} s')
    table(['start', 'case', 'starts', 'launch_to_first_answer_median_s', 'max_s',
           'in_process_s'], rows)


def start_once(what, scene, domain_id):
    """
    Print the seconds from launch to the first answer.

    That is the core's (and in process) or suspension_node's (a pose over DDS, pinged every
    20 ms).
    """
    if what == 'core':
        code = ('import time; t = time.perf_counter(); '
                'from linkage_ros import Continuation, load_scene; '
                f'Continuation(load_scene({scene!r})).solve(1.0); '
                'print(time.perf_counter() - t)')
        start = time.perf_counter()
        out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                             check=True)
        print(time.perf_counter() - start, float(out.stdout))
        return 0
    with tempfile.TemporaryDirectory() as log_dir:
        target = Target('suspension_node', [node_script(), '--ros-args', '-p',
                                            f'scene:={scene}'], domain_id, log_dir)
        try:
            target.driver.connect(timeout=120.0, ping_period=0.02)
            print(target.driver.first_answer - target.started)
        finally:
            target.close()
    return 0


def bench_latency(args, log_dir, domain_id):
    """suspension_node and the echo node, measured alternately; then the rate ladder."""
    targets = [Target('node', [node_script(), '--ros-args', '-p', f'scene:={args.scene}'],
                      domain_id, log_dir),
               Target('echo', [sys.executable, '-m', 'linkage_ros.bench.node_bench', '--echo'],
                      domain_id, log_dir)]
    ladder = []
    try:
        for target in targets:
            target.driver.connect()
            target.driver.ping_pong(sine(args.warmup))
        count = args.count * args.scale
        latency = {(t.name, kind): [] for t in targets for kind in ('paced', 'ping-pong')}
        rounds = 4
        for r in range(rounds):
            for target in targets:
                chunk = sine(count // rounds)
                sent, got, _, values = target.driver.paced(chunk, args.latency_rate)
                if got < sent:
                    raise RuntimeError(f'{target.name}: {sent - got} commands lost at '
                                       f'{args.latency_rate:g} Hz')
                latency[target.name, 'paced'] += list(values)
                latency[target.name, 'ping-pong'] += list(target.driver.ping_pong(chunk))
            progress(f'latency: round {r + 1}/{rounds}')
        rows = []
        for kind in ('paced', 'ping-pong'):
            echo = np.median(latency['echo', kind])
            for target in targets:
                values = latency[target.name, kind]
                rows.append((target.name, kind, len(values), us(values), us(values, 99),
                             float(np.median(values) / echo)))
        table(['latency', 'mode', 'commands', 'median_us', 'p99_us', 'ratio_to_echo'], rows)
        for rate in args.rates:
            for target in targets:
                target.driver.connect()         # a backlog of the previous rate drains first
                count = max(1, int(rate * args.duration * args.scale))
                sent, got, lag, values = target.driver.paced(
                    sine(count), rate, label=f'latency: {target.name} at {rate} Hz')
                ladder.append((target.name, rate, sent, got, sent - got, lag * 1000.0,
                               lag * 1000.0 <= args.lag_ms and got == sent, us(values),
                               us(values, 99)))
                progress(f'latency: {target.name} at {rate} Hz: {got}/{sent} answered, '
                         f'last {lag * 1000.0:.1f} ms after the last command')
    finally:
        for target in targets:
            target.close()
    table(['rate', 'hz', 'sent', 'answered', 'lost', 'last_answer_lag_ms', 'kept_up',
           'median_us', 'p99_us'], ladder)
    return ladder


def bench_vehicle(args, log_dir, domain_id):
    """Four corners at args.hz each: Float64 per corner, then one JointState per step."""
    prefixes = tuple(f'{c}/' for c in CORNERS)
    targets = [Target('node', [node_script(), '--ros-args', '-p', f'vehicle:={VEHICLE}'],
                      domain_id, log_dir, prefixes),
               Target('echo', [sys.executable, '-m', 'linkage_ros.bench.node_bench',
                               '--echo-vehicle'], domain_id, log_dir, prefixes)]
    rows, medians = [], {}
    try:
        steps = int(args.hz * args.seconds * args.scale)
        for joint_states in (False, True):
            mode = 'joint_states' if joint_states else 'float64_per_corner'
            for target in targets:
                target.driver.connect(joint_states)
                sent, got, lag, values = target.driver.paced(
                    sine(steps), args.hz, joint_states, label=f'vehicle: {target.name}, {mode}')
                medians[target.name, mode] = np.median(values) if len(values) else np.nan
                rows.append([target.name, mode, sent, got, sent - got, lag * 1000.0,
                             us(values), us(values, 99)])
                progress(f'vehicle: {target.name}, {mode}: {got}/{sent} steps answered, last '
                         f'{lag * 1000.0:.1f} ms after the last step')
    finally:
        for target in targets:
            target.close()
    for row in rows:
        row.append(float(medians[row[0], row[1]] / medians['echo', row[1]]))
    table(['vehicle', 'mode', 'steps', 'answered', 'lost', 'last_answer_lag_ms',
           'step_median_us', 'step_p99_us', 'ratio_to_echo'], rows)


def bench_callback(args):
    """
    Time the travel callback in process, with each optional output or sink.

    Every mode but elements runs the scene without its elements (a copy of its file without
    the key), so that plain is the answer alone and elements is what they add to it.
    """
    import yaml
    from rclpy.parameter import Parameter

    from ..ros.node import SuspensionNode
    scene = load_scene(args.scene)
    modes = {'plain': {}, 'elements': {'scene': scene.source}, 'tf': {'tf': True},
             'alignment': {'alignment': True},
             'markers': {'markers': True}, 'record_mcap': {'record_mcap': 'run.mcap'},
             'rerun_rrd': {'rerun_rrd': 'run.rrd'},
             'record_mcap+rerun_rrd': {'record_mcap': 'run.mcap', 'rerun_rrd': 'run.rrd'}}
    if not scene.elements:
        del modes['elements']
    context = init_context(args.domain_id, 'OFF')      # no subscriber, and none outside
    travels = sine(args.count * args.scale, 0.05, 0.02)
    rows, base = [], None
    try:
        for mode, params in modes.items():
            with tempfile.TemporaryDirectory() as folder:
                bare = Path(folder) / 'scene.yaml'     # the scene without its elements
                data = yaml.safe_load(Path(scene.source).read_text())
                data.pop('elements', None)
                bare.write_text(yaml.safe_dump(data))
                params = {'scene': str(bare), 'tf': False, **params}
                overrides = [Parameter(k, value=str(Path(folder) / v)
                                       if isinstance(v, str) and k != 'scene' else v)
                             for k, v in params.items()]
                node = SuspensionNode(context=context, parameter_overrides=overrides)
                corner = next(iter(node.corners.values()))
                times = []
                for travel in travels:
                    data = float64_cdr(travel)      # as the raw subscription hands it over
                    start = time.perf_counter()
                    corner.on_travel(data)
                    times.append(time.perf_counter() - start)
                start = time.perf_counter()
                node.destroy_node()          # files are finished here
                closing = time.perf_counter() - start
            base = base or np.median(times)
            rows.append((mode, len(times), us(times), float(np.mean(times) * 1e6),
                         float(np.median(times) / base), closing))
            progress(f'callback: {mode}: median {us(times):.1f} us')
    finally:
        rclpy.try_shutdown(context=context)
    table(['callback', 'commands', 'median_us', 'mean_us', 'ratio_to_plain', 'close_s'], rows)


def node_script():
    return str(Path(sys.executable).parent / 'suspension_node')


EPILOG = f"""examples:
  ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST linkage-node-bench --plot latency.png > bench.csv
  ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST linkage-node-bench --only core,vehicle --scale 10

exit status: 0 the tables were written; {EXIT_STATUS}"""


def parse_args(argv):
    parser = Parser('linkage-node-bench', __doc__, EPILOG)
    parser.add_argument('--only', default=','.join(SECTIONS),
                        help=f'sections to run, comma separated (default: all: '
                        f'{",".join(SECTIONS)})')
    parser.add_argument('--scale', type=int, default=1,
                        help='multiply every size (commands, positions, durations) by this')
    parser.add_argument('--scene', default='five_link', help='scene of the single-scene runs')
    parser.add_argument('--latency-rate', type=float, default=200.0,
                        help='command rate of the paced latency, Hz (default 200)')
    parser.add_argument('--warmup', type=int, default=200, help='round trips not counted')
    parser.add_argument('--rates', type=lambda s: [int(r) for r in s.split(',')],
                        default=list(DEFAULT_RATES), help='ladder of command rates, Hz')
    parser.add_argument('--duration', type=float, default=2.0, help='seconds per rate')
    parser.add_argument('--lag-ms', type=float, default=50.0,
                        help='kept up: last answer at most this long after the last command')
    parser.add_argument('--starts', type=int, default=5,
                        help='start: launches per warm case (default 5)')
    parser.add_argument('--hz', type=float, default=1000.0, help='vehicle: steps per second')
    parser.add_argument('--seconds', type=float, default=5.0, help='vehicle: seconds per mode')
    parser.add_argument('--plot', help='write latency against command rate here (PNG)')
    parser.add_argument('--quick', action='store_true',
                        help='a smoke run: every size cut to a tenth or less, low rates')
    parser.add_argument('--domain-id', type=int, default=None,
                        help='ROS domain of every process (default: ROS_DOMAIN_ID, else 0)')
    parser.add_argument('--echo', action='store_true', help=argparse.SUPPRESS)
    parser.add_argument('--echo-vehicle', action='store_true', help=argparse.SUPPRESS)
    parser.add_argument('--start-once', choices=('core', 'suspension_node'),
                        help=argparse.SUPPRESS)
    args, ros_args = parser.parse_known_args(argv)
    if not (args.echo or args.echo_vehicle or args.start_once):   # the user's command
        if ros_args:            # only the echo processes take ROS arguments
            parser.error(f'unrecognized arguments: {" ".join(ros_args)}')
        problem = args.plot and writable_file(args.plot)
        if problem:
            parser.error(f'--plot: {problem}')
        try:
            load_scene(args.scene)
        except LinkageError as exc:
            parser.error(str(exc))
    args.only = [s for s in args.only.split(',') if s]
    args.count = 200 if args.quick else 2000      # commands per core, latency, callback run
    if args.quick:
        args.rates, args.duration, args.hz, args.seconds, args.warmup = [100], 0.3, 100, 0.3, 20
    unknown = [s for s in args.only if s not in SECTIONS]
    if unknown:
        parser.error(f'--only: unknown section {unknown[0]!r} (sections: {", ".join(SECTIONS)})')
    if args.plot and 'latency' not in args.only:   # the plot is of the latency section
        parser.error('--plot draws the latency section: add latency to --only')
    if args.scale < 1 or args.duration <= 0 or args.latency_rate <= 0 or not args.rates:
        parser.error('--scale >= 1, --duration > 0, --latency-rate > 0 and --rates are required')
    return args, ros_args


@program('linkage-node-bench')
def main(argv: list[str] | None = None) -> int:
    """Run linkage-node-bench, or one of the processes it starts (--echo, --start-once)."""
    args, ros_args = parse_args(sys.argv[1:] if argv is None else argv)
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')   # for its children too
    if args.domain_id is None:
        args.domain_id = environment_domain_id()
    if args.echo or args.echo_vehicle:      # an echo node process started by the bench
        return echo_main(args.echo_vehicle, ['echo', *ros_args])
    if args.start_once:                     # one launch timed by the start section
        return start_once(args.start_once, args.scene, args.domain_id)
    progress(f'{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}; sections '
             f'{",".join(args.only)}, scale {args.scale}; ROS domain {args.domain_id}, '
             f'discovery {os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"]}, topics under '
             f'/linkage_node_bench_{os.getpid()}')
    compile_if_cold('linkage-node-bench')   # not within a timed section
    with tempfile.TemporaryDirectory(prefix='linkage-node-bench-') as log_dir:
        if 'core' in args.only:
            bench_core(args)
        if 'sweep' in args.only:
            bench_sweep(args)
        if 'start' in args.only:
            bench_start(args, log_dir, args.domain_id)
        if 'latency' in args.only:
            ladder = bench_latency(args, log_dir, args.domain_id)
            if args.plot:
                from ..tools.plot import plot_latency
                plot_latency({name: [(r[1], r[7], r[8]) for r in ladder if r[0] == name and r[3]]
                              for name in ('node', 'echo')}, args.plot)
                progress(f'wrote {args.plot}')
        if 'vehicle' in args.only:
            bench_vehicle(args, log_dir, args.domain_id)
        if 'callback' in args.only:
            bench_callback(args)
    return 0


if __name__ == '__main__':
    sys.exit(main())
