# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench node: speed on the paths users take, side by side with what it must beat.

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
  service   suspension_node asked by topic and by its <corner>/solve service, alternately, one
            command when the previous is answered: the round trips and their ratio
  lifecycle suspension_lifecycle_node's configure (change_state): cold (an empty numba
            cache), the first of a new process (warm cache, --starts processes) and again
            after a cleanup
  vehicle   vehicle:=demo_vehicle against a four-corner echo node, four corners at --hz each
            for --seconds: one Float64 per corner per step, then one JointState per step;
            then vehicle:=demo_vehicle_bushings, each step a contact_wrench per corner and a
            JointState (the loaded pose of each corner), lean (tf, pickups, angles, elements
            and roll_centres false: the poses alone, as a simulator needs them), with the
            node's defaults (TF, pickup forces, ...) and with every output on, against the
            echo node taking the same traffic; the step latency is from sending a step to
            the last of its four poses, and each process's CPU time per step answered
            (executor and DDS threads included); each row ends with the load average
  step      one step of the bushed vehicle in process (no DDS): its four contact_wrench
            callbacks and its joint_states callback called directly, lean, with the node's
            defaults and with every output on (the vehicle section's three nodes)
  callback  the node's travel callback called in process (no subscribers): plain (the scene
            without its elements, tf off), with its elements (the elements topic), with TF on
            (/tf per answer: the node's default), with the alignment or markers outputs,
            recording to MCAP, mirroring to Rerun, both (all but tf with tf off); and,
            named in --modes, with statics (a contact wrench and a travel per command, both
            callbacks timed): statics:=true on the scene (rigid), and bushings on every
            arm and link (--modes statics,bushings)

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
import os
import sys
import tempfile

from .callback import bench_callback
from .echo import echo_main
from .latency import bench_latency
from .service import bench_lifecycle, bench_service
from .solver import bench_core, bench_sweep
from .start import bench_start, start_once
from .step import bench_step
from .tables import progress
from .vehicle import bench_vehicle
from ...cli import EXIT_STATUS, Parser, plot_problem, program
from ...core.base import LinkageError
from ...core.model import load_scene
from ...core.warmup import compile_if_cold
from ...ros.isolation import environment_domain_id

PROG = 'linkage-bench node'

SECTIONS = ('core', 'sweep', 'start', 'latency', 'service', 'lifecycle', 'vehicle', 'step',
            'callback')
DEFAULT_RATES = (250, 500, 1000, 2000, 4000)


EPILOG = f"""examples:
  ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST linkage-bench node --plot latency.png > bench.csv
  ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST linkage-bench node --only core,vehicle --scale 10

exit status: 0 the tables were written; {EXIT_STATUS}"""


def parse_args(argv):
    parser = Parser(PROG, __doc__, EPILOG)
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
    parser.add_argument('--modes', help='callback: the modes to run, comma separated '
                        '(default: all but statics and bushings, which cost tens of ms a '
                        'command; plain is always run first, the base of the ratios)')
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
        problem = args.plot and plot_problem(args.plot)
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


@program(PROG)
def main(argv: list[str] | None = None) -> int:
    """Run linkage-bench node, or one of the processes it starts (--echo, --start-once)."""
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
    # not within a timed section; the statics kernels too for the bushed vehicle, else each of
    # its node processes compiles them at start, beyond the driver's wait for discovery
    compile_if_cold(PROG, statics=bool({'vehicle', 'step', 'callback'} & set(args.only)))
    with tempfile.TemporaryDirectory(prefix='linkage-bench-node-') as log_dir:
        if 'core' in args.only:
            bench_core(args)
        if 'sweep' in args.only:
            bench_sweep(args)
        if 'start' in args.only:
            bench_start(args, log_dir, args.domain_id)
        if 'latency' in args.only:
            ladder = bench_latency(args, log_dir, args.domain_id)
            if args.plot:
                from ...tools.plot import plot_latency
                plot_latency({name: [(r[1], r[7], r[8]) for r in ladder if r[0] == name and r[3]]
                              for name in ('node', 'echo')}, args.plot)
                progress(f'wrote {args.plot}')
        if 'service' in args.only:
            bench_service(args, log_dir, args.domain_id)
        if 'lifecycle' in args.only:
            bench_lifecycle(args, log_dir, args.domain_id)
        if 'vehicle' in args.only:
            bench_vehicle(args, log_dir, args.domain_id)
        if 'step' in args.only:
            bench_step(args)
        if 'callback' in args.only:
            bench_callback(args)
    progress(f'load average {os.getloadavg()[0]:.2f} (1 min) at the end')
    return 0
