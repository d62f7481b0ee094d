#!/bin/bash
# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

# Run the commands of README.md and doc/*.md as written, from the root of a checkout where
# command 1 has run (by hand, not in CI: it starts nodes and takes a few minutes).
# Usage: bash .ci/readme_commands.sh          the commands, but the long ones
#        LONG=1 bash .ci/readme_commands.sh   also the benchmarks, the soak and the screenshots
# Not run here: command 2 and the inner-loop pytest (the suite: .ci/run runs it), the colcon
# route of doc/node.md (.ci/run runs it), `ros2 launch` in README.md and doc/node.md (it needs
# a full ROS install: the launch tooling has no wheel; test/ros/test_launch_file.py checks the
# file), the linkage-plot commands that rewrite the committed
# pictures (test/tools/test_plots.py and test/tools/test_axle_plot.py run them into a temporary folder),
# and the Python of doc/maps.md, doc/elements.md and doc/testing.md (test/tools/test_map_doc.py,
# test/core/test_elements.py and test/ros/test_plugin_example.py run it). Not run even with LONG=1: the
# node benchmarks at --scale 10 and 100 of doc/benchmarks.md (20 to 36 min each) and
# `rerun FILE.rrd`, which opens a window.
set -u
cd "$(dirname "$0")/.." && export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
step() { echo "=== $*"; }
# pyblock FILE TEXT: the ```python block of FILE that holds TEXT
pyblock() {
    .venv/bin/python - "$1" "$2" <<'PY'
import re
import sys
blocks = re.findall(r'```python\n(.*?)```', open(sys.argv[1]).read(), re.S)
print(next(b for b in blocks if sys.argv[2] in b), end='')
PY
}
step warmup
.venv/bin/python -m linkage_ros.core.warmup; echo "rc=$?"
step sweep double_wishbone
.venv/bin/linkage-sweep double_wishbone --travel -40:40:10 -o double_wishbone.csv; echo "rc=$?"; head -2 double_wishbone.csv
step sweep out of reach
.venv/bin/linkage-sweep five_link --travel 0:1000:100 > /dev/null; echo "rc=$?"
step sweep elements
.venv/bin/linkage-sweep double_wishbone --travel -40:40:40 --elements 2>/dev/null | cut -d, -f1,13-; echo "rc=${PIPESTATUS[0]}"
step "chrono import and export (doc/chrono.md)"
.venv/bin/linkage-chrono import config/chrono/generic/suspension/DoubleWishbone.json -o dw.yaml; echo "rc=$?"
.venv/bin/linkage-sweep dw.yaml --travel -40:40:40 --elements > dw.csv; echo "rc=$?"
.venv/bin/linkage-chrono export dw.yaml -o dw.json --like config/chrono/generic/suspension/DoubleWishbone.json; echo "rc=$?"
.venv/bin/linkage-chrono export five_link -o five_link.json; echo "rc=$?"
.venv/bin/linkage-chrono import config/chrono/hmmwv/vehicle/HMMWV_Vehicle.json -o hmmwv.yaml; echo "rc=$?"
.venv/bin/linkage-axle hmmwv.yaml > /dev/null; echo "rc=$?"
rm -f dw.yaml dw.csv dw.json five_link.json hmmwv.yaml hmmwv_front.yaml hmmwv_rear.yaml
step kinematic map
.venv/bin/linkage-map double_wishbone -o maps; echo "rc=$?"; ls maps
step vehicle setup sheet
.venv/bin/linkage-vehicle demo_vehicle > /dev/null; echo "rc=$?"
.venv/bin/linkage-vehicle demo_vehicle --csv sheet.csv --plot sheet.png; echo "rc=$?"; cut -d, -f1-4 sheet.csv
.venv/bin/linkage-vehicle demo_vehicle --tables sheet_tables > /dev/null; echo "rc=$?"; ls sheet_tables
step misspelt parameter
.venv/bin/suspension_node --ros-args -p sceen:=macpherson; echo "rc=$?"
step python snippet of README.md
pyblock README.md 'Continuation(scene).solve' > readme_snippet.py
.venv/bin/python readme_snippet.py; echo "rc=$?"; rm readme_snippet.py
step node with params file + drive.py
.venv/bin/suspension_node --ros-args --params-file config/suspension.yaml > node.log 2>&1 &
NODE=$!
sed -n '/^# drive.py/,/^rclpy.try_shutdown()/p' doc/node.md > drive.py
.venv/bin/python drive.py; echo "rc=$?"
kill -INT $NODE; wait $NODE; echo "node rc=$?"
step node recording
.venv/bin/suspension_node --ros-args -p record_mcap:=run.mcap -p rerun_rrd:=run.rrd > node2.log 2>&1 &
NODE=$!
.venv/bin/python drive.py > /dev/null; echo "rc=$?"
kill -INT $NODE; wait $NODE; echo "node rc=$?"; ls -la run.mcap run.rrd
step vehicle node
.venv/bin/suspension_node --ros-args -p vehicle:=demo_vehicle > node3.log 2>&1 &
NODE=$!; sleep 4; kill -TERM $NODE; wait $NODE; echo "vehicle node rc=$?"
.venv/bin/suspension_node --ros-args -p vehicle:=demo_vehicle_bushings > node_bushed.log 2>&1 &
NODE=$!; sleep 6; kill -TERM $NODE; wait $NODE; echo "bushed vehicle node rc=$?"
.venv/bin/suspension_node --ros-args -p vehicle:=demo_vehicle_bushings -p pickups:=false -p tf:=false -p angles:=false -p elements:=false -p roll_centres:=false > node_lean.log 2>&1 &
NODE=$!; sleep 6; kill -TERM $NODE; wait $NODE; echo "lean bushed vehicle node rc=$?"
step replay
.venv/bin/linkage-replay solve bags/five_link_sweep.mcap -o solved.mcap --scene five_link; echo "rc=$?"
.venv/bin/linkage-replay copy bags/five_link_sweep.mcap -o copy.mcap; echo "rc=$?"
step rerun
.venv/bin/linkage-rerun bags/five_link_sweep.mcap -o five_link_sweep.rrd; echo "rc=$?"
step sim time
ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST .venv/bin/suspension_node --ros-args -p use_sim_time:=true > node4.log 2>&1 &
ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST .venv/bin/linkage-replay publish bags/five_link_sweep.mcap --clock; echo "rc=$?"
kill %1; wait; echo done
step quick discovery
export FASTRTPS_DEFAULT_PROFILES_FILE=$PWD/config/fastdds_quick_discovery.xml
.venv/bin/suspension_node --ros-args --params-file config/suspension.yaml > node5.log 2>&1 &
NODE=$!
.venv/bin/python drive.py | tail -1; echo "rc=$?"
kill -INT $NODE; wait $NODE; echo "node rc=$?"
unset FASTRTPS_DEFAULT_PROFILES_FILE
step solve service and managed node
.venv/bin/suspension_node > node9.log 2>&1 &
NODE=$!
sed -n '/^# solve.py/,/^rclpy.try_shutdown()/p' doc/node.md > solve.py
.venv/bin/python solve.py; echo "rc=$?"
kill -INT $NODE; wait $NODE; echo "node rc=$?"
ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST .venv/bin/suspension_lifecycle_node > node10.log 2>&1 &
NODE=$!
sed -n '/^# manage.py/,/^rclpy.try_shutdown()/p' doc/node.md > manage.py
ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST .venv/bin/python manage.py; echo "rc=$?"
rm -f solve.py manage.py
.venv/bin/python drive.py | tail -1; echo "rc=$?"
kill -INT $NODE; wait $NODE; echo "node rc=$?"
step set params while the node runs
.venv/bin/suspension_node > node6.log 2>&1 &
NODE=$!
sed -n '/^# set_params.py/,/^rclpy.try_shutdown()/p' doc/node.md > set_params.py
.venv/bin/python set_params.py; echo "rc=$?"
kill -INT $NODE; wait $NODE; echo "node rc=$?"
step qos presets
timeout -s INT 8 .venv/bin/suspension_node --ros-args -p qos_overrides./wheel_travel.subscription.depth:=1 -p qos_overrides./wheel_carrier_pose.publisher.depth:=1 > node7.log 2>&1; echo "node rc=$? (124/130 = stopped by timeout)"
timeout -s INT 8 .venv/bin/suspension_node --ros-args -p qos_overrides./wheel_travel.subscription.reliability:=best_effort -p qos_overrides./wheel_travel.subscription.depth:=5 -p qos_overrides./wheel_carrier_pose.publisher.reliability:=best_effort -p qos_overrides./wheel_carrier_pose.publisher.depth:=5 > node8.log 2>&1; echo "node rc=$?"
step urdf and rerun from tf
.venv/bin/linkage-urdf five_link -o five_link.urdf; echo "rc=$?"
.venv/bin/linkage-rerun bags/five_link_sweep.mcap --tf -o five_link_tf.rrd; echo "rc=$?"
.venv/bin/linkage-foxglove demo_vehicle -o demo_vehicle_layout.json; echo "rc=$?"
step axle, anti-roll bar, roll centre picture
.venv/bin/linkage-axle demo_vehicle --axle front --heave -40:40:20 -o front_heave.csv; echo "rc=$?"; cut -d, -f1,2,6,7,8,9,11,17 front_heave.csv | head -3
.venv/bin/linkage-axle demo_vehicle --axle front --heave 0 --roll -4:4:4 | cut -d, -f2,20,21,26; echo "rc=${PIPESTATUS[0]}"
.venv/bin/linkage-axle demo_vehicle --axle front --heave 0 --roll -4:4:2 | cut -d, -f2,20-; echo "rc=${PIPESTATUS[0]}"
.venv/bin/linkage-axle demo_vehicle --axle front > axle.csv; echo "rc=$?"; head -2 axle.csv
.venv/bin/linkage-plot roll-centre -o roll_centre.png; echo "rc=$?"
pyblock doc/axle.md 'solve_axle(axle' > axle_snippet.py
.venv/bin/python axle_snippet.py; echo "rc=$?"; rm axle_snippet.py
step compliance and loaded solves '(doc/kc.md)'
.venv/bin/linkage-kc double_wishbone_bushings --travel -40:40:20 | cut -d, -f1-4; echo "rc=${PIPESTATUS[0]}"
.venv/bin/linkage-kc double_wishbone_bushings --travel 0 --matrix double_wishbone_compliance.csv; echo "rc=$?"; cat double_wishbone_compliance.csv
.venv/bin/linkage-kc double_wishbone_bushings --travel 0 --load 0,4000,0 --at cp -o cornering.csv; echo "rc=$?"; cut -d, -f1-8 cornering.csv
.venv/bin/linkage-kc double_wishbone_bushings --travel -40:40:10 --plot kc_rates.png > kc_rates.csv; echo "rc=$?"
.venv/bin/linkage-kc double_wishbone_bushings --travel 0 --load 0,4000,0 --at cp --plot kc_loaded.png; echo "rc=$?"
pyblock doc/kc.md 'solve_loaded(scene' > kc_snippet.py
.venv/bin/python kc_snippet.py; echo "rc=$?"; rm kc_snippet.py
pyblock doc/kc.md "load_vehicle('demo_vehicle_bushings')" > kc_vehicle.py
.venv/bin/python kc_vehicle.py; echo "rc=$?"; rm kc_vehicle.py
step 'load cases (doc/loads.md)'
.venv/bin/linkage-loads demo_vehicle_loads > loads.csv; echo "rc=$?"; head -2 loads.csv
.venv/bin/linkage-loads demo_vehicle_loads --table summary -o brackets.csv; echo "rc=$?"; head -3 brackets.csv
.venv/bin/linkage-loads demo_vehicle_loads --case bump,cornering --table corners | cut -d, -f1-5; echo "rc=${PIPESTATUS[0]}"
.venv/bin/linkage-loads demo_vehicle_loads --table members -o members.parquet --plot loads.png; echo "rc=$?"
pyblock doc/loads.md 'loads.solve(built_in_cases' > loads_snippet.py
.venv/bin/python loads_snippet.py; echo "rc=$?"; rm loads_snippet.py
.venv/bin/suspension_node --ros-args -p vehicle:=demo_vehicle_loads > node_loads.log 2>&1 &
NODE=$!
sed -n '/^# loads_case.py/,/^rclpy.try_shutdown()/p' doc/loads.md > loads_case.py
.venv/bin/python loads_case.py; echo "rc=$?"
kill -INT $NODE; wait $NODE; echo "node rc=$?"; rm -f loads_case.py
step studies
.venv/bin/linkage-study sensitivity five_link --travel -50 0 50 -o five_link_sensitivity.csv; echo "rc=$?"
.venv/bin/linkage-study tolerance five_link --sigma 0.05 --samples 100000 --travel -50 -25 0 25 50 --plot tolerance.png > tolerance.csv; echo "rc=$?"
.venv/bin/linkage-study tolerance five_link --sigma 1 --tolerances config/study/five_link_tie_rod_length.yaml --samples 4096 --travel -50 0 50 > tolerance_lengths.csv; echo "rc=$?"; head -3 tolerance_lengths.csv
.venv/bin/linkage-study tolerance five_link_bushings --sigma 1 --tolerances config/study/five_link_bushings_15_percent.yaml --samples 4096 --travel -25 0 25 -o bushing_tolerance.csv; echo "rc=$?"; grep -E '^0,toe_per' bushing_tolerance.csv
.venv/bin/linkage-study fit config/study/bump_steer_targets.yaml -o double_wishbone_fitted.yaml --plot fit.png; echo "rc=$?"
step study on a local dask cluster
.venv/bin/dask scheduler --host 127.0.0.1 --port 8786 --no-dashboard > dask_scheduler.log 2>&1 &
timeout 60 bash -c 'until (echo > /dev/tcp/127.0.0.1/8786) 2> /dev/null; do sleep 0.2; done'
.venv/bin/dask worker tcp://127.0.0.1:8786 --nworkers 2 --nthreads 1 --no-dashboard > dask_worker.log 2>&1 &
.venv/bin/linkage-study tolerance five_link --sigma 0.05 --samples 1000000 --travel -50 -25 0 25 50 --scheduler tcp://127.0.0.1:8786 -o tolerance.parquet; echo "rc=$?"
kill %2 %1; wait; echo done
if [ "${LONG:-0}" = 1 ]; then
    step benchmarks
    .venv/bin/pip install -q -e '.[bench]'; echo "rc=$?"
    .venv/bin/linkage-bench map double_wishbone --rounds 20 > /dev/null; echo "rc=$?"
    .venv/bin/linkage-bench axle demo_vehicle --axle front --rounds 21 > /dev/null; echo "rc=$?"
    .venv/bin/linkage-bench axle demo_vehicle --axle rear --roll -3:3:0.5 --heave -40:40:10 --rounds 11 > /dev/null; echo "rc=$?"
    .venv/bin/linkage-bench vehicle demo_vehicle --rounds 3 > /dev/null; echo "rc=$?"
    .venv/bin/linkage-bench kc double_wishbone_bushings --travel -40:40:20 --rounds 3; echo "rc=$?"
    .venv/bin/linkage-bench statics --parts; echo "rc=$?"
    .venv/bin/linkage-bench loads demo_vehicle_loads --rounds 1; echo "rc=$?"
    .venv/bin/linkage-bench accuracy --quick -o bench-report; echo "rc=$?"
    ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST .venv/bin/linkage-bench node --plot node_latency.png > node_bench.csv; echo "rc=$?"
    ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST .venv/bin/linkage-bench node --only vehicle > /dev/null; echo "rc=$?"
    for s in 1; do ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST .venv/bin/linkage-bench node --only callback --modes statics,bushings --scale $s; done > /dev/null; echo "rc=$?"
    ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST .venv/bin/linkage-bench soak > soak.csv; echo "rc=$?"
    step screenshots '(they rewrite the committed pictures: git diff bags/ shows the change)'
    RUST_LOG=error xvfb-run -a -s '-screen 0 3200x1600x24' .venv/bin/rerun --screenshot-to bags/five_link_tf.png --window-size 1400x700 five_link_tf.rrd; echo "rc=$?"
    RUST_LOG=error xvfb-run -a -s '-screen 0 3200x1600x24' .venv/bin/rerun --screenshot-to bags/five_link_rerun.png --window-size 1400x700 five_link_sweep.rrd; echo "rc=$?"
fi
step one vocabulary: --travel/--rack FROM[:TO:STEP], -o, linkage-bench SUBCOMMAND
.venv/bin/linkage-sweep double_wishbone --travel -40:40:40 --rack -10:10:10 -o grid.csv; echo "rc=$?"; wc -l grid.csv
.venv/bin/linkage-bench sweep five_link --travel -10:10:10 --rounds 1; echo "rc=$?"
.venv/bin/linkage-bench --help | head -1; echo "rc=$?"
step git status
git status --short
