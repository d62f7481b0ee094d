#!/bin/bash
# Run the README's commands as written, from the root of a checkout where command 1 has run
# (by hand, not in CI: it starts nodes and takes about 2 minutes). Usage: bash .ci/readme_commands.sh
set -u
cd "$(dirname "$0")/.." && export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
step() { echo "=== $*"; }
step sweep double_wishbone
.venv/bin/linkage-sweep double_wishbone --travel -40:40:10 -o double_wishbone.csv; echo "rc=$?"; head -2 double_wishbone.csv
step sweep out of reach
.venv/bin/linkage-sweep five_link --travel 0:1000:100 > /dev/null; echo "rc=$?"
step kinematic map
.venv/bin/linkage-map double_wishbone -o maps; echo "rc=$?"; ls maps
step misspelt parameter
.venv/bin/suspension_node --ros-args -p sceen:=macpherson; echo "rc=$?"
step python snippet
.venv/bin/python -c "
from linkage_ros import Continuation, load_scene, sweep

scene = load_scene('five_link')
table = sweep(scene, range(-80, 81))              # mm -> Sweep: arrays over the positions
solution = Continuation(scene).solve(12.5)        # one command, mm -> Solution
print(solution.camber, solution.wheel_center)     # rad, mm (vehicle frame)
"; echo "rc=$?"
step node with params file + drive.py
.venv/bin/suspension_node --ros-args --params-file config/suspension.yaml > node.log 2>&1 &
NODE=$!
sed -n '/^# drive.py/,/^rclpy.try_shutdown()/p' README.md > drive.py
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
step set params while the node runs
.venv/bin/suspension_node > node6.log 2>&1 &
NODE=$!
sed -n '/^# set_params.py/,/^rclpy.try_shutdown()/p' README.md > set_params.py
.venv/bin/python set_params.py; echo "rc=$?"
kill -INT $NODE; wait $NODE; echo "node rc=$?"
step qos presets
timeout -s INT 8 .venv/bin/suspension_node --ros-args -p qos_overrides./wheel_travel.subscription.depth:=1 -p qos_overrides./wheel_carrier_pose.publisher.depth:=1 > node7.log 2>&1; echo "node rc=$? (124/130 = stopped by timeout)"
timeout -s INT 8 .venv/bin/suspension_node --ros-args -p qos_overrides./wheel_travel.subscription.reliability:=best_effort -p qos_overrides./wheel_travel.subscription.depth:=5 -p qos_overrides./wheel_carrier_pose.publisher.reliability:=best_effort -p qos_overrides./wheel_carrier_pose.publisher.depth:=5 > node8.log 2>&1; echo "node rc=$?"
step urdf and rerun from tf
.venv/bin/linkage-urdf five_link -o five_link.urdf; echo "rc=$?"
.venv/bin/linkage-rerun bags/five_link_sweep.mcap --tf -o five_link_tf.rrd; echo "rc=$?"
.venv/bin/linkage-foxglove demo_vehicle -o demo_vehicle_layout.json; echo "rc=$?"
step axle, roll centre picture
.venv/bin/linkage-axle demo_vehicle --axle front > axle.csv; echo "rc=$?"; head -2 axle.csv
.venv/bin/linkage-plot roll-centre -o roll_centre.png; echo "rc=$?"
.venv/bin/linkage-axle demo_vehicle --axle front --heave -40:40:20 -o front_heave.csv; echo "rc=$?"
.venv/bin/linkage-axle demo_vehicle --axle front --heave 0 --roll -4:4:4 | cut -d, -f2,20,21,26; echo "rc=$?"
step studies
.venv/bin/linkage-study sensitivity five_link --travel -50 0 50 -o five_link_sensitivity.csv; echo "rc=$?"
.venv/bin/linkage-study tolerance five_link --sigma 0.05 --samples 10000 --travel -50 0 50 > tolerance.csv; echo "rc=$?"
.venv/bin/linkage-study fit config/study/bump_steer_targets.yaml -o double_wishbone_fitted.yaml; echo "rc=$?"
step one vocabulary: --travel/--rack FROM[:TO:STEP], -o, linkage-bench SUBCOMMAND
.venv/bin/linkage-sweep double_wishbone --travel -40:40:40 --rack -10:10:10 -o grid.csv; echo "rc=$?"; wc -l grid.csv
.venv/bin/linkage-bench sweep five_link --travel -10:10:10 --rounds 1; echo "rc=$?"
.venv/bin/linkage-bench --help | head -1; echo "rc=$?"
step git status
git status --short
