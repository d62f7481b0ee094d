# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The pictures of README.md and doc/ are what their commands make today.

Each is made again here, from the repository's data, into a temporary folder by the command
printed under it in the README or a page of doc/, and compared with the committed file
(matplotlib's image comparison, RMS of the pixel difference): a change of the solver, the
scenes or the plotting that moves a curve makes this fail until the picture is made again and
committed.
"""

from pathlib import Path

from linkage_ros.core.model import load_scene
from linkage_ros.tools.plot import camber_toe_figure, main
from matplotlib.testing.compare import compare_images
import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = '\n'.join(page.read_text()
                 for page in [ROOT / 'README.md', *sorted((ROOT / 'doc').glob('*.md'))])


@pytest.mark.parametrize('picture, args', [
    ('bags/plots/camber_toe.png', ['camber-toe']),
    ('bags/plots/alignment.png', ['alignment']),
    ('bags/plots/node_latency.png', ['latency', 'doc/bench/node_bench.csv']),
])
def test_a_readme_picture_is_what_its_command_makes(tmp_path, picture, args):
    command = f"linkage-plot {' '.join(args)} -o {picture}"
    assert command in DOCS, f'README.md and doc/ show no command {command!r} under {picture}'
    again = tmp_path / Path(picture).name
    assert main([args[0], *[str(ROOT / a) for a in args[1:]], '-o', str(again)]) == 0
    assert compare_images(str(ROOT / picture), str(again), tol=1.0) is None


@pytest.mark.skipif(not Path('/dev/full').exists(), reason='needs /dev/full')
def test_a_picture_that_cannot_be_written_whole_is_one_line_and_status_2(capsys):
    # matplotlib's savefig('/dev/full') raises nothing: linkage-plot once said 'wrote /dev/full'
    assert main(['camber-toe', '-o', '/dev/full']) == 2
    assert capsys.readouterr().err == ('linkage-plot: /dev/full: cannot write (No space left '
                                       'on device)\n')


def legend_and_title(scenes):
    import matplotlib.pyplot as plt
    fig = camber_toe_figure(scenes)
    try:
        legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        return legend, fig._suptitle.get_text()
    finally:
        plt.close(fig)


def test_a_user_s_scene_is_named_in_the_title_with_no_empty_reference_entry(tmp_path):
    # it was titled 'bundled scenes', with a legend entry for reference dots it did not have
    text = (ROOT / 'config' / 'scenes' / 'five_link.yaml').read_text()
    path = tmp_path / 'my_scene.yaml'
    path.write_text(text.split('# Reference results')[0].replace('name: five_link',
                                                                 'name: my_corner'))
    legend, title = legend_and_title([load_scene(path)])
    assert title == 'linkage_ros: my_corner, left wheel'
    assert legend == ['my_corner']


def test_the_bundled_scenes_are_titled_so_with_their_reference_entry():
    legend, title = legend_and_title([load_scene(n) for n in ('five_link', 'double_wishbone')])
    assert title == 'linkage_ros: bundled scenes, left wheel'
    assert legend == ['five_link', 'double_wishbone', 'reference (refdata)']


def test_a_scene_s_warnings_are_printed_before_the_picture(tmp_path, capsys):
    stress = ROOT / 'config' / 'stress' / 'five_link_submillimetre.yaml'
    assert main(['camber-toe', '-o', str(tmp_path / 'small.png'), str(stress)]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith(f'linkage-plot: warning: {stress}: wheel_radius 0.033 mm')
    assert err[1:] == [f'linkage-plot: wrote {tmp_path / "small.png"}']


def test_a_scene_not_solved_whole_is_drawn_in_part_said_in_one_line_and_status_1(
        tmp_path, capsys):
    # five_link_singular solves nothing but its design position: linkage-plot once wrote an
    # empty picture of it and exited 0. five_link beside it is drawn whole.
    singular = ROOT / 'test' / 'data' / 'five_link_singular.yaml'
    out = tmp_path / 'both.png'
    assert main(['camber-toe', '-o', str(out), 'five_link', str(singular)]) == 1
    err = capsys.readouterr().err.splitlines()
    assert out.stat().st_size > 0 and err[-2] == f'linkage-plot: wrote {out}'
    assert err[-1].startswith('linkage-plot: five_link_singular: travel -80 mm is out of '
                              'reach: the guidance equations are singular')
    assert err[-1].endswith('(drawn: 0 positions)')
    assert not any('five_link:' in line for line in err)


def test_the_alignment_picture_says_the_same(tmp_path, capsys):
    singular = ROOT / 'test' / 'data' / 'five_link_singular.yaml'
    assert main(['alignment', '-o', str(tmp_path / 'a.png'), str(singular)]) == 1
    assert 'five_link_singular: travel -80 mm is out of reach' in capsys.readouterr().err
