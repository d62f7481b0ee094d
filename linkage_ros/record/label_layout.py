# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Where the labels of a 3D view go so that none covers another (pure geometry, no Rerun).

    anchors, kept = place_labels(points, labels, eye_position, look_target)

Rerun draws a point's label in a box just under the point, whatever else is there: labels of
points that lie close on screen cover each other. The view opens on a known camera (the
blueprint's eye, Rerun's perspective of FOV_Y), so the boxes can be laid out for it: each
label is drawn at an anchor point of its own, moved off its point (above, beside, further
down) until its box is clear of every box placed before and of every point, or left out if
no place near its point is clear. A moved label stays within a few label heights of its
point. Screen sizes are for a 3D view VIEW_PX high (the 1400 x 700 window of
doc/recording.md); in a smaller window the boxes are relatively larger and may touch.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..core.base import unit

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import ArrayLike

FOV_Y = math.radians(55.0)   # Rerun's 3D view: vertical field of view of its camera
VIEW_PX = 600.0              # px: height of the 3D view the labels are laid out for
CHAR_PX = 7.0                # px: width of one character of a label (Rerun's font)
PAD_PX = 12.0                # px: a label box's width beyond its characters
LABEL_PX = 18.0              # px: height of a label box
GAP_PX = 6.0                 # px: from a point down to the top of its label box
MARK_PX = 10.0               # px: side of the square kept clear around every point
FOCAL_PX = VIEW_PX / (2.0 * math.tan(FOV_Y / 2.0))   # px per unit of tan(angle off the axis)


def screen(points: ArrayLike, position: ArrayLike, target: ArrayLike,
           up: Sequence[float] = (0.0, 0.0, 1.0)) -> tuple[np.ndarray, np.ndarray]:
    """
    Return where points (k, 3) appear in a view from position looking at target.

    (xy (k, 2) px from the view's centre, x right and y up; depth (k,) along the view, in
    the points' unit), for the pinhole camera of FOV_Y and a view VIEW_PX high.
    """
    forward, right, upward = _axes(position, target, up)
    rel = np.asarray(points, dtype=float) - position
    depth = rel @ forward
    return FOCAL_PX * np.stack([rel @ right, rel @ upward], axis=-1) / depth[:, None], depth


def _axes(position, target, up):
    """Return the camera's unit axes: forward (to the target), right, upward."""
    forward = unit(np.asarray(target, dtype=float) - position)
    right = unit(np.cross(forward, up))
    return forward, right, np.cross(right, forward)


def label_box(xy: Sequence[float], label: str) -> tuple[float, float, float, float]:
    """Return the box (left, bottom, right, top) px of a label drawn at an anchor at xy px."""
    half = (CHAR_PX * len(label) + PAD_PX) / 2.0
    return (xy[0] - half, xy[1] - GAP_PX - LABEL_PX, xy[0] + half, xy[1] - GAP_PX)


def place_labels(points: ArrayLike, labels: Sequence[str], position: ArrayLike,
                 target: ArrayLike) -> tuple[np.ndarray, list[int]]:
    """
    Lay out the labels of points (k, 3) for the view from position looking at target.

    Returns (anchors (j, 3), kept: the indexes of the j labels that found room, in order):
    the label of points[kept[i]] is drawn at anchors[i], in the plane through the point
    square to the view. Labels earlier in the list are placed first.
    """
    points = np.asarray(points, dtype=float)
    xy, depth = screen(points, position, target)
    _, right, upward = _axes(position, target, (0.0, 0.0, 1.0))
    half = MARK_PX / 2.0
    taken = [(x - half, y - half, x + half, y + half) for x, y in xy]
    anchors, kept = [], []
    for i, label in enumerate(labels):
        for dx, dy in _moves(label):
            box = label_box(xy[i] + (dx, dy), label)
            if not any(_overlap(box, other) for other in taken):
                taken.append(box)
                scale = depth[i] / FOCAL_PX       # px -> scene units at the point's depth
                anchors.append(points[i] + scale * (dx * right + dy * upward))
                kept.append(i)
                break
    return np.array(anchors).reshape(-1, 3), kept


def _moves(label):
    """Offsets (px) of the anchor to try, nearest first: under, over, beside, further down."""
    step = LABEL_PX + GAP_PX
    side = (CHAR_PX * len(label) + PAD_PX) / 2.0 + MARK_PX
    over = LABEL_PX + 2.0 * GAP_PX
    return [(0.0, 0.0), (0.0, over), (side, step / 2.0), (-side, step / 2.0), (0.0, -step),
            (0.0, over + step), (side, -step / 2.0), (-side, -step / 2.0), (0.0, -2.0 * step),
            (0.0, over + 2.0 * step)]


def _overlap(a, b):
    """Tell whether boxes (left, bottom, right, top) a and b overlap."""
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]
