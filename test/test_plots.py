"""
The README's pictures are what their commands make today, from the repository's data.

Each is made again here into a temporary folder by the command printed under it in the
README, and compared with the committed file (matplotlib's image comparison, RMS of the
pixel difference): a change of the solver, the scenes or the plotting that moves a curve
makes this fail until the picture is made again and committed.
"""

from pathlib import Path

from linkage_ros.tools.plot import main
from matplotlib.testing.compare import compare_images
import pytest

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / 'README.md').read_text()


@pytest.mark.parametrize('picture, args', [
    ('bags/plots/camber_toe.png', ['camber-toe']),
    ('bags/plots/alignment.png', ['alignment']),
    ('bags/plots/node_latency.png', ['latency', 'doc/bench/node_bench.csv']),
])
def test_a_readme_picture_is_what_its_command_makes(tmp_path, picture, args):
    command = f"linkage-plot {' '.join(args)} {picture}"
    assert command in README, f'the README shows no command {command!r} under {picture}'
    again = tmp_path / Path(picture).name
    assert main([args[0], *[str(ROOT / a) for a in args[1:]], str(again)]) == 0
    assert compare_images(str(ROOT / picture), str(again), tol=1.0) is None


@pytest.mark.skipif(not Path('/dev/full').exists(), reason='needs /dev/full')
def test_a_picture_that_cannot_be_written_whole_is_one_line_and_status_2(capsys):
    # matplotlib's savefig('/dev/full') raises nothing: linkage-plot once said 'wrote /dev/full'
    assert main(['camber-toe', '/dev/full']) == 2
    assert capsys.readouterr().err == ('linkage-plot: /dev/full: cannot write (No space left '
                                       'on device)\n')
