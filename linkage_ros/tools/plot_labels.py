# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Labels of a matplotlib axes laid out so that none covers another, an arrow or a line.

    labels = Labels(ax)
    labels.add('spring_body 4126 N', at=(y, z), away=(dy, dz), color='C3')   # data units
    labels.obstacle(points)                 # a polyline (k, 2) the labels keep off
    ... everything drawn, the figure laid out (tight_layout) ...
    labels.place()                          # measures each label as the renderer draws it

Each label is an annotation at its point (the tip of its arrow, say). place() tries its box
beyond the point along away (the way the arrow points: clear of the arrow's own shaft),
then beside, over and under it, then on rings further out, nearest first, and takes the first
box that lies inside the axes and clear of every label placed before and of every obstacle.
A label that finds no such box (a crowded corner) takes the nearest one clear of the other
labels alone; one moved off its point gets a thin leader line to it. The boxes are the
renderer's (Text.get_window_extent), so they are the sizes of the written file at any dpi:
offsets are kept in points.
"""

from __future__ import annotations

import math

import numpy as np

GAP_PT = 3.0       # pt between a point and its label's box
RING_PT = 14.0     # pt between the rings of places tried further out
RINGS = 8          # rings tried (to about 110 pt from the point)
DIRECTIONS = 16    # places tried on each ring
LEADER_PT = 6.0    # a label whose box is further than this from its point: a leader line


class Labels:
    """The labels of one axes, placed by place() once the figure is drawn (module doc)."""

    def __init__(self, ax) -> None:
        self.ax = ax
        self.items = []        # (annotation, away (2,) unit, in display axes)
        self.lines = []        # obstacle polylines (k, 2), data units

    def add(self, text: str, at, away=(1.0, 0.0), color='k', fontsize=7):
        """Add a label of text at the point at (data units); away: the way it would rather go."""
        ann = self.ax.annotate(text, xy=tuple(at), xytext=(GAP_PT, GAP_PT),
                               textcoords='offset points', ha='left', va='bottom',
                               fontsize=fontsize, color=color, zorder=6,
                               annotation_clip=False)
        ann.set_in_layout(False)   # tight_layout lays out the axes, not the labels inside
        away = np.asarray(away, float)
        norm = np.linalg.norm(away)
        self.items.append((ann, away / norm if norm > 0 else np.array([1.0, 0.0])))
        return ann

    def obstacle(self, points) -> None:
        """Keep the labels off a polyline (k, 2) in data units (an arrow, a link)."""
        points = np.asarray(points, float)
        if len(points) > 1 and np.all(np.isfinite(points)):
            self.lines.append(points)

    def place(self) -> list:
        """Lay out every label as the module doc says; return the annotations, in order."""
        fig = self.ax.figure
        renderer = fig.canvas.get_renderer()
        frame = self.ax.get_window_extent(renderer)
        per_pt = fig.dpi / 72.0
        segments = [seg for line in self.lines
                    for seg in _segments(self.ax.transData.transform(line))]
        taken, placed = [], []
        for ann, away in self.items:
            ann.xyann = (0.0, 0.0)
            box = ann.get_window_extent(renderer)
            size = np.array([box.width, box.height])
            point = np.asarray(self.ax.transData.transform(ann.xy), float)
            # the display's y grows upwards, as the data's do in these views
            away_px = _display_direction(self.ax, ann.xy, away)
            places = _places(size, away_px, GAP_PT * per_pt)
            best = None
            for corner in places:
                lower, upper = point + corner, point + corner + size
                if not (frame.x0 <= lower[0] and upper[0] <= frame.x1
                        and frame.y0 <= lower[1] and upper[1] <= frame.y1):
                    continue
                if any(_overlap(lower, upper, *other) for other in taken):
                    continue
                if best is None:
                    best = corner       # clear of the labels: the fallback
                if not any(_crosses(lower, upper, *seg) for seg in segments):
                    best = corner
                    break
            if best is None:            # no room inside the axes: beyond the point, as drawn
                best = places[0]
            taken.append((point + best, point + best + size))
            ann.xyann = tuple(best / per_pt)
            if _distance(best, size) > LEADER_PT * per_pt:
                ann = _with_leader(self.ax, ann)
            placed.append(ann)
        return placed


def _display_direction(ax, at, away):
    """Return away (data units, at the point at) as a unit direction on the display."""
    at = np.asarray(at, float)
    span = np.ptp(ax.get_xlim()) + np.ptp(ax.get_ylim())
    ends = ax.transData.transform([at, at + away * 1e-3 * span])
    step = ends[1] - ends[0]
    norm = np.linalg.norm(step)
    return step / norm if norm > 0 else np.array([1.0, 0.0])


def _places(size, away, gap):
    """
    Return the lower-left corners (px from the point) to try for a box of size, best first.

    First the four places touching the point (beside, over, under) and the one beyond it
    along away, sorted by how far they go along away; then rings further out.
    """
    width, height = size
    near = [(gap, -height / 2), (-width - gap, -height / 2), (-width / 2, gap),
            (-width / 2, -height - gap), (gap, gap), (-width - gap, gap), (gap, -height - gap),
            (-width - gap, -height - gap)]
    reach = (width / 2 + gap) * abs(away[0]) + (height / 2 + gap) * abs(away[1])
    near.append(tuple(away * reach * 1.1 - size / 2))
    near.sort(key=lambda c: -float(np.dot(np.asarray(c) + size / 2, away)))
    rings = []
    for ring in range(1, RINGS + 1):
        radius = reach + ring * RING_PT * gap / GAP_PT
        for k in range(DIRECTIONS):
            angle = math.atan2(away[1], away[0]) + 2.0 * math.pi * k / DIRECTIONS
            rings.append((radius * math.cos(angle) - width / 2,
                          radius * math.sin(angle) - height / 2))
    return [np.asarray(c, float) for c in near + rings]


def _distance(corner, size):
    """Return the distance (px) from the point to a box (lower-left corner, size) off it."""
    nearest = np.clip(np.zeros(2), corner, corner + size)
    return float(np.linalg.norm(nearest))


def _segments(points):
    """Return the segments ((2,), (2,)) of a polyline (k, 2)."""
    return [(points[i], points[i + 1]) for i in range(len(points) - 1)]


def _overlap(lower, upper, other_lower, other_upper):
    """Tell whether boxes (lower, upper corners) overlap."""
    return bool(np.all(lower < other_upper) and np.all(other_lower < upper))


def _crosses(lower, upper, a, b):
    """Tell whether segment a-b enters the box (lower, upper): Liang-Barsky clipping."""
    start, stop = 0.0, 1.0
    delta = b - a
    for axis in (0, 1):
        for p, q in ((-delta[axis], a[axis] - lower[axis]), (delta[axis], upper[axis] - a[axis])):
            if p == 0.0:
                if q < 0.0:
                    return False
                continue
            t = q / p
            if p < 0.0:
                start = max(start, t)
            else:
                stop = min(stop, t)
            if start > stop:
                return False
    return True


def _with_leader(ax, ann):
    """Return ann drawn again with a thin line from its box to its point."""
    color, text, xy, offset = ann.get_color(), ann.get_text(), ann.xy, ann.xyann
    size = ann.get_fontsize()
    ann.remove()
    moved = ax.annotate(text, xy=xy, xytext=offset, textcoords='offset points', ha='left',
                        va='bottom', fontsize=size, color=color, zorder=6,
                        annotation_clip=False,
                        arrowprops={'arrowstyle': '-', 'color': color, 'lw': 0.5,
                                    'alpha': 0.6, 'shrinkA': 1, 'shrinkB': 2})
    moved.set_in_layout(False)
    return moved


__all__ = ['Labels']
