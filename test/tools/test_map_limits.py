# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-map at its limits: grids too large to count, memory limits, output names, full disks.

Each is one line on stderr and exit status 2, said before anything is solved, and nothing
written is cut or replaces an input.
"""

import os
from pathlib import Path
import re
import subprocess
import sys

from linkage_ros.core.base import cgroup_room
from linkage_ros.tools.kinematic_map import Job, main, memory_needed
import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
FIVE_LINK = (REPO / 'config' / 'scenes' / 'five_link.yaml').read_text()


def run_map(capsys, *argv):
    code = main(list(argv))
    return code, capsys.readouterr().err


def renamed(folder, file_name, scene_name):
    """Write five_link under another scene name to folder/file_name; return its path."""
    path = folder / file_name
    path.write_text(re.sub(r'(?m)^name: .*$', f'name: {scene_name}', FIVE_LINK))
    return path


def test_a_grid_too_long_to_count_is_one_line(tmp_path, capsys):
    # 1e308 / 1e-308 overflows a float: counting it raised OverflowError before.
    code, err = run_map(capsys, 'five_link', '--travel', '0:1e308:1e-308', '-o',
                        str(tmp_path / 'maps'))
    assert code == 2 and len(err.splitlines()) == 1
    assert err.startswith('linkage-map: --travel: 0:1e308:1e-308: more than 2**52 points')
    assert not (tmp_path / 'maps').exists()


def test_the_memory_need_is_the_sum_over_every_corner():
    one, two = Job('corner', 'a', (100, 10), 41, None), Job('corner', 'b', (50, 1), 37, None)
    both = memory_needed([one, two])
    assert both.points == 1050
    alone = [memory_needed([job]) for job in (one, two)]
    # the fixed part once, the per-value part of each corner added
    assert both.resident - alone[0].resident == alone[1].resident - memory_needed([]).resident


def test_a_cgroup_v2_limit_less_its_usage_is_the_room(tmp_path):
    group = tmp_path / 'user.slice' / 'job'
    group.mkdir(parents=True)
    (group / 'memory.max').write_text('300000000\n')
    (group / 'memory.current').write_text('100000000\n')
    (tmp_path / 'user.slice' / 'memory.max').write_text('max\n')
    (tmp_path / 'user.slice' / 'memory.current').write_text('5\n')
    room = cgroup_room('0::/user.slice/job\n', tmp_path)
    assert room.size == 200000000 and 'memory.max' in room.limit


def test_a_cgroup_v1_parent_limit_applies_to_its_children(tmp_path):
    parent = tmp_path / 'memory' / 'docker'
    (parent / 'box').mkdir(parents=True)
    (parent / 'memory.limit_in_bytes').write_text('1000\n')
    (parent / 'memory.usage_in_bytes').write_text('400\n')
    (parent / 'box' / 'memory.limit_in_bytes').write_text('9223372036854771712\n')   # none
    (parent / 'box' / 'memory.usage_in_bytes').write_text('300\n')
    room = cgroup_room('12:memory:/docker/box\n3:cpu:/docker/box\n', tmp_path)
    assert room.size == 600 and 'memory.limit_in_bytes' in room.limit


def test_a_map_beyond_the_address_space_limit_is_refused_before_it_is_solved(tmp_path):
    # The limit: what the program holds once started, plus 300 MB; the map needs ~0.5 GB.
    # Before, only MemAvailable was read: it solved for 30 s and died in a traceback.
    code = f"""
import resource, sys
from linkage_ros.tools import kinematic_map
from linkage_ros.core.base import address_space_room
used = int(next(l for l in open('/proc/self/status') if l.startswith('VmSize:')).split()[1])
limit = used * 1024 + 300_000_000
resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
sys.exit(kinematic_map.main(['demo_vehicle', '--travel', '-50:50:0.05', '--rack',
                             '-40:40:1', '-o', {str(tmp_path)!r}]))
"""
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 2, done.stderr
    assert len(done.stderr.splitlines()) == 1
    assert done.stderr.startswith('linkage-map: grid: 328,164 points need about 0.5 GB')
    assert 'RLIMIT_AS' in done.stderr and list(tmp_path.iterdir()) == []


def test_a_scene_named_out_of_reach_does_not_overwrite_the_list(tmp_path, capsys):
    scene = renamed(tmp_path, 'mine.yaml', 'out_of_reach')
    code, err = run_map(capsys, str(scene), '-o', str(tmp_path / 'maps'))
    assert code == 2 and len(err.splitlines()) == 1
    assert err.startswith(f'linkage-map: -o: the map of out_of_reach would be '
                          f'{tmp_path / "maps" / "out_of_reach.csv"}, which is the list of '
                          'points out of reach')
    assert not (tmp_path / 'maps').exists()   # the folder made for the maps is removed again


def test_a_scene_file_inside_out_is_not_overwritten_by_its_map(tmp_path, capsys):
    scene = renamed(tmp_path, 'x.csv', 'x')
    code, err = run_map(capsys, str(scene), '-o', str(tmp_path))
    assert code == 2 and len(err.splitlines()) == 1
    assert err == f'linkage-map: -o: {scene} is the input {scene}; give another folder\n'
    assert scene.read_text().startswith(FIVE_LINK[:20])


def test_a_vehicle_corner_scene_inside_out_is_not_overwritten(tmp_path, capsys):
    renamed(tmp_path, 'rear_left.csv', 'rear')
    vehicle = tmp_path / 'car.yaml'
    vehicle.write_text('corners:\n  rear_left: {scene: rear_left.csv}\n')
    code, err = run_map(capsys, str(vehicle), '-o', str(tmp_path), '--format', 'csv')
    assert code == 2 and len(err.splitlines()) == 1
    assert err == (f'linkage-map: -o: {tmp_path / "rear_left.csv"} is the input '
                   f'{tmp_path / "rear_left.csv"}; give another folder\n')


FULL_DISK = """
import resource, signal, sys
from linkage_ros.tools.kinematic_map import Job, main
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)   # a write past the limit fails with EFBIG
resource.setrlimit(resource.RLIMIT_FSIZE, ({limit}, {limit}))
sys.exit(main(['five_link', '--travel', '-50:50:1', '-o', sys.argv[1], '--format', 'csv']))
"""


def test_a_full_disk_leaves_no_cut_map_and_names_the_file(tmp_path):
    # RLIMIT_FSIZE stands for a full disk (no root needed): the map's CSV does not fit.
    out = tmp_path / 'maps'
    out.mkdir()
    (out / 'five_link.csv').write_text('the map of yesterday\n')
    done = subprocess.run([sys.executable, '-c', FULL_DISK.format(limit=100_000), str(out)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2, done.stderr
    assert done.stderr.splitlines()[-1] == (f'linkage-map: {out / "five_link.csv"}: cannot '
                                            'write (File too large)')
    # the file of before is whole and nothing else is left (no temporary file)
    assert (out / 'five_link.csv').read_text() == 'the map of yesterday\n'
    assert sorted(p.name for p in out.iterdir()) == ['five_link.csv']


def test_a_map_written_whole_reads_back_with_the_permissions_of_a_new_file(tmp_path, capsys):
    code, _ = run_map(capsys, 'five_link', '--travel', '-10:10:10', '-o', str(tmp_path))
    assert code == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ['five_link.csv', 'five_link.npz',
                                                          'out_of_reach.csv']
    assert np.load(tmp_path / 'five_link.npz')['travel_mm'].tolist() == [-10.0, 0.0, 10.0]
    assert (tmp_path / 'five_link.csv').stat().st_mode & 0o777 == 0o666 & ~_umask()


def _umask():
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


@pytest.mark.parametrize('limit', [0, 50])
def test_a_map_cut_at_any_size_leaves_no_file(tmp_path, limit):
    out = tmp_path / 'maps'
    out.mkdir()
    done = subprocess.run([sys.executable, '-c', FULL_DISK.format(limit=limit), str(out)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and 'cannot write (File too large)' in done.stderr
    assert list(out.iterdir()) == []
