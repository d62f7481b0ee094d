# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The pictures of linkage-kc --plot, read back from the rendered figure.

Each test runs linkage-kc with --plot, takes the figure at the moment it is written (the
module's save_figure, replaced), draws it as the file is drawn, and reads every text's box
from the renderer (Text.get_window_extent, display pixels). The loaded mechanism names every
arrow in each view (each pickup's force on the body, the load, its moment, the holding
force) with its size; the moment is drawn, along its vector; no label covers another text and
each lies inside its view. The rates' legends name every column and cover neither another
text nor a plot.
"""

import math

from linkage_ros.core.model import load_scene
from linkage_ros.core.statics import Load, solve_loaded
from linkage_ros.tools import kc, kc_plot
import matplotlib
from matplotlib.colors import to_rgba
from matplotlib.text import Text
import numpy as np
import pytest

matplotlib.use('Agg')


class Taken:
    """The figure linkage-kc writes, drawn, with the boxes of its texts (display px)."""

    def __init__(self, fig):
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        self.fig = fig
        self.axes = [ax for ax in fig.axes if ax.get_visible() and ax.axison]
        self.frames = [ax.get_window_extent(renderer) for ax in self.axes]
        # a label's own box: an Annotation's extent would take in its leader line too
        self.texts = [(text, Text.get_window_extent(text, renderer)) for text in drawn_texts(fig)
                      if text.get_visible() and text.get_text().strip()]
        self.legends = [legend.get_window_extent(renderer) for legend in
                        [ax.get_legend() for ax in self.axes] + fig.legends if legend]

    def labels(self, ax):
        """Return [(text, box)] of the texts drawn in the data area of ax (its labels)."""
        own = {id(t) for t in ax.texts}
        return [(t.get_text(), box) for t, box in self.texts if id(t) in own]


def drawn_texts(fig):
    """
    Return the texts matplotlib draws in fig.

    Titles, axis labels, the labels of the ticks inside each axis' view (a Tick outside it
    keeps a Text that is not drawn), legends, texts and annotations, the figure's own.
    """
    texts = [fig._suptitle] if fig._suptitle else []
    for legend in fig.legends:
        texts += legend.get_texts()
    for ax in fig.axes:
        if not ax.axison:
            continue
        texts += [ax.title, ax._left_title, ax._right_title, ax.xaxis.label, ax.yaxis.label]
        for axis, (low, high) in ((ax.xaxis, sorted(ax.get_xlim())),
                                  (ax.yaxis, sorted(ax.get_ylim()))):
            slack = 1e-9 * (high - low)
            texts += [tick.label1 for tick in axis.get_major_ticks()
                      if low - slack <= tick.get_loc() <= high + slack]
        if ax.get_legend():
            texts += ax.get_legend().get_texts()
        texts += ax.texts
    return texts


def overlap(a, b):
    """Tell whether two Bboxes share an area (boxes that only touch do not)."""
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def inside(box, frame):
    return frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 \
        and box.y1 <= frame.y1


@pytest.fixture
def taken(monkeypatch, tmp_path):
    """Give run(argv) -> Taken: linkage-kc with --plot, its figure taken as it is written."""
    figures = []

    def keep(fig, path, dpi):
        fig.set_dpi(dpi)          # as savefig draws it
        figures.append(Taken(fig))

    monkeypatch.setattr(kc_plot, 'save_figure', keep)

    def run(argv):
        status = kc.main([*argv, '-o', str(tmp_path / 'kc.csv'), '--plot',
                          str(tmp_path / 'kc.png')])
        assert status == 0
        (figure,) = figures
        return figure
    return run


LOADS = {   # scene, travel mm, force N, at, moment N m
    'dw, lateral at cp, Mz': ('double_wishbone_bushings', 0.0, (0.0, 4000.0, 0.0), 'cp',
                              (0.0, 0.0, 500.0)),
    'five-link, every axis': ('five_link_bushings', 30.0, (3000.0, -2000.0, 1000.0), 'cp',
                              (200.0, -300.0, 400.0)),
    'dw, braking at wc': ('double_wishbone_bushings', -40.0, (-2000.0, 0.0, 0.0), 'wc',
                          (0.0, 0.0, 0.0))}


def loaded_argv(scene, travel, force, at, moment):
    return [scene, '--travel', f'{travel:g}', '--load', ','.join(f'{v:g}' for v in force),
            '--at', at, '--moment', ','.join(f'{v:g}' for v in moment)]


@pytest.mark.parametrize('case', sorted(LOADS))
def test_every_arrow_of_the_loaded_picture_is_named_in_each_view_with_its_size(case, taken):
    scene, travel, force, at, moment = LOADS[case]
    figure = taken(loaded_argv(*LOADS[case]))
    # the sizes, from a solve of our own (the plot draws linkage-kc's)
    result = solve_loaded(load_scene(scene), travel, Load(force, at=at, moment_nm=moment))
    expected = sorted([f'{name} {np.linalg.norm(f):.0f} N'
                       for name, f in result.body_forces_n.items()]
                      + [f'load {np.linalg.norm(force):.0f} N',
                         f'holding {abs(result.holding_force_n):.0f} N']
                      + ([f'moment {np.linalg.norm(moment):.0f} N m'] if any(moment) else []))
    assert len(figure.axes) == 2
    for ax in figure.axes:
        assert sorted(text for text, _ in figure.labels(ax)) == expected


@pytest.mark.parametrize('case', sorted(LOADS))
def test_no_label_of_the_loaded_picture_covers_another_text_or_leaves_its_view(case, taken):
    figure = taken(loaded_argv(*LOADS[case]))
    texts = figure.texts
    for i, (text, box) in enumerate(texts):
        for other, other_box in texts[i + 1:]:
            assert not overlap(box, other_box), (text.get_text(), other.get_text())
    for ax, frame in zip(figure.axes, figure.frames):
        for text, box in figure.labels(ax):
            assert inside(box, frame), text


def test_the_load_s_moment_is_drawn_along_its_vector_with_a_double_head(taken):
    scene, travel, force, at, moment = LOADS['five-link, every axis']
    figure = taken(loaded_argv(scene, travel, force, at, moment))
    purple = to_rgba('C4')
    for ax, across in zip(figure.axes, (1, 0)):    # front view: y across; side view: x
        arrows = [a for a in ax.texts if getattr(a, 'arrow_patch', None) is not None
                  and a.get_text() == '' and a.arrow_patch.get_edgecolor() == purple]
        assert len(arrows) == 2                     # the shaft's head and the second head
        drawn = [np.subtract(a.xy, a.xyann) for a in arrows]
        along = np.array([moment[across], moment[2]])
        for vector in drawn:                        # each along the moment's projection
            cos = vector @ along / (np.linalg.norm(vector) * np.linalg.norm(along))
            assert math.isclose(cos, 1.0, abs_tol=1e-9)
        assert sorted(np.linalg.norm(v) for v in drawn)[0] < \
            sorted(np.linalg.norm(v) for v in drawn)[1]   # the second head short of the tip


def test_the_rates_legends_name_every_column_and_cover_no_plot_and_no_text(taken, tmp_path):
    figure = taken(['double_wishbone_bushings', '--travel', '-60:60:10'])
    header = (tmp_path / 'kc.csv').read_text().splitlines()[0].split(',')
    named = sorted(t.get_text() for ax in figure.axes if ax.get_legend()
                   for t in ax.get_legend().get_texts())
    assert named == sorted(header[1:])
    for legend in figure.legends:
        for frame in figure.frames:
            assert not overlap(legend, frame)
    texts = figure.texts
    for i, (text, box) in enumerate(texts):
        for other, other_box in texts[i + 1:]:
            assert not overlap(box, other_box), (text.get_text(), other.get_text())
