# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-plot roll-centre: the axle picture of doc/axle.md, and its one-line mistakes."""

from pathlib import Path

from linkage_ros.tools.plot import main
from matplotlib.testing.compare import compare_images
import pytest

ROOT = Path(__file__).resolve().parents[2]
PICTURE = 'bags/plots/roll_centre.png'
DOCS = '\n'.join(page.read_text()
                 for page in [ROOT / 'README.md', *sorted((ROOT / 'doc').glob('*.md'))])


def test_the_roll_centre_picture_of_the_docs_is_what_its_command_makes(tmp_path):
    assert f'linkage-plot roll-centre -o {PICTURE}' in DOCS
    again = tmp_path / 'roll_centre.png'
    assert main(['roll-centre', '-o', str(again)]) == 0
    assert compare_images(str(ROOT / PICTURE), str(again), tol=1.0) is None


@pytest.mark.parametrize('args, says', [
    (['demo_vehicle', 'middle'], "axles: no axle 'middle' (axles: front, rear)"),
    (['nowhere'], "'nowhere': vehicle: no such file"),
    (['demo_vehicle', 'front', 'extra'], 'roll-centre: expected OUT.png [VEHICLE [AXLE]]'),
])
def test_a_mistake_is_one_line_with_status_2_and_no_file(tmp_path, capsys, args, says):
    out = tmp_path / 'x.png'
    assert main(['roll-centre', '-o', str(out), *args]) == 2
    err = capsys.readouterr().err
    assert err.count('\n') == 1 and err.startswith('linkage-plot: ') and says in err, err
    assert not out.exists()


def test_an_axle_out_of_reach_is_drawn_in_part_said_and_status_1(tmp_path, capsys):
    # An axle of five_link_singular corners (nothing but the design position solves) once
    # ended in a traceback (IndexError) while labelling its empty heave curve.
    scene = ROOT / 'test' / 'data' / 'five_link_singular.yaml'
    vehicle = tmp_path / 'singular_vehicle.yaml'
    vehicle.write_text(
        'name: singular_vehicle\nunits: mm\ncorners:\n'
        f'  front_left: {{scene: {scene}, offset: [1400.0, 0.0, 0.0]}}\n'
        f'  front_right: {{scene: {scene}, offset: [1400.0, 0.0, 0.0], mirror: true}}\n'
        'axles:\n  front: {left: front_left, right: front_right}\n')
    out = tmp_path / 'roll_centre.png'
    assert main(['roll-centre', '-o', str(out), str(vehicle), 'front']) == 1
    err = capsys.readouterr().err.splitlines()
    assert out.stat().st_size > 0 and f'linkage-plot: wrote {out}' in err
    assert err[-2].startswith('linkage-plot: heave -60 mm, roll 0 deg, rack 0 mm: the left '
                              'wheel (front_left): travel -60 mm is out of reach')
    assert err[-1].startswith('linkage-plot: heave 0 mm, roll -4 deg')
