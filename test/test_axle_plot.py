"""linkage-plot roll-centre: the README's axle picture, and its one-line mistakes."""

from pathlib import Path

from linkage_ros.tools.plot import main
from matplotlib.testing.compare import compare_images
import pytest

ROOT = Path(__file__).resolve().parent.parent
PICTURE = 'bags/plots/roll_centre.png'


def test_the_readme_roll_centre_picture_is_what_its_command_makes(tmp_path):
    assert f'linkage-plot roll-centre {PICTURE}' in (ROOT / 'README.md').read_text()
    again = tmp_path / 'roll_centre.png'
    assert main(['roll-centre', str(again)]) == 0
    assert compare_images(str(ROOT / PICTURE), str(again), tol=1.0) is None


@pytest.mark.parametrize('args, says', [
    (['demo_vehicle', 'middle'], "axles: no axle 'middle' (axles: front, rear)"),
    (['nowhere'], "'nowhere': vehicle: no such file"),
    (['demo_vehicle', 'front', 'extra'], 'roll-centre: expected OUT.png [VEHICLE [AXLE]]'),
])
def test_a_mistake_is_one_line_with_status_2_and_no_file(tmp_path, capsys, args, says):
    out = tmp_path / 'x.png'
    assert main(['roll-centre', str(out), *args]) == 2
    err = capsys.readouterr().err
    assert err.count('\n') == 1 and err.startswith('linkage-plot: ') and says in err, err
    assert not out.exists()
