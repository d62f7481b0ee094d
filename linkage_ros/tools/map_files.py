# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The files of a kinematic map: CSV in long form, NumPy .npz of axes and arrays, Parquet.

For a corner over (travel, rack), in files named for it:

    <corner>.csv      corner,travel_mm,rack_mm,quantity,value: one value a line, every value
                      written with the fewest digits that read back to the same float64
                      (the table writer's rule, outputs/table.py)
    <corner>.npz      travel_mm (nt,), rack_mm (nr,) and each quantity as an (nt, nr) array:
                      what a lookup-table block (or scipy's RegularGridInterpolator) takes
    <corner>.parquet  one row per grid point: travel_mm, rack_mm, then a column per quantity
    out_of_reach.csv  corner,travel_mm,rack_mm,reason of every point left NaN

An axle's map is the same over (left_travel_mm, right_travel_mm), in <axle>_axle.* files.
pyarrow (the map extra) is imported only when Parquet is asked for. Each file is written
under a temporary name and renamed when whole (outputs.whole_file): a full disk leaves no cut
file.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..outputs import whole_file, write_table

if TYPE_CHECKING:
    from .map_grid import GridMap

FORMATS = ('csv', 'npz', 'parquet')
UNREACHED = 'out_of_reach.csv'


def stem(kind: str, name: str) -> str:
    """Return the file name stem of a map: the corner's name, or <axle>_axle."""
    return name if kind == 'corner' else f'{name}_axle'


def map_files(folder: Path, kind: str, name: str, formats: tuple[str, ...]) -> list[Path]:
    """Return the files a map of kind ('corner', 'axle') and name is written to."""
    return [folder / f'{stem(kind, name)}.{fmt}' for fmt in formats]


def write_map(folder: Path, grid: GridMap, formats: tuple[str, ...]) -> list[Path]:
    """Write a map in each of formats into folder; return the files written."""
    writers = {'csv': write_long_csv, 'npz': write_npz, 'parquet': write_parquet}
    paths = map_files(folder, grid.kind, grid.name, formats)
    for fmt, path in zip(formats, paths):
        writers[fmt](path, grid)
    return paths


def write_npz(path: Path, grid: GridMap) -> None:
    """Write the grid axes and one (n0, n1) array per quantity."""
    arrays = {name: np.ascontiguousarray(grid.values[:, :, i])
              for i, name in enumerate(grid.quantities)}
    axes = dict(zip(grid.axis_names, grid.axes))
    with whole_file(path, 'wb') as stream:
        np.savez(stream, **axes, **arrays)


def write_long_csv(path: Path, grid: GridMap) -> None:
    """Write one value a line, grid point by grid point (first axis, then second), exact."""
    names = grid.quantities

    def rows():
        for i, first in enumerate(grid.axes[0].tolist()):
            for j, second in enumerate(grid.axes[1].tolist()):
                for name, value in zip(names, grid.values[i, j].tolist()):
                    yield grid.name, first, second, name, value

    write_table(path, [grid.kind, *grid.axis_names, 'quantity', 'value'], rows())


def write_parquet(path: Path, grid: GridMap) -> None:
    """Write one row per grid point: the two axes, then a column per quantity."""
    first, second = np.meshgrid(*grid.axes, indexing='ij')
    columns = [first.ravel(), second.ravel()] + [grid.values[:, :, i].ravel()
                                                 for i in range(len(grid.quantities))]
    write_table(path, [*grid.axis_names, *grid.quantities], np.column_stack(columns))


def write_unreached(path: Path, maps: list[GridMap]) -> int:
    """List every solve out of reach (its corner, travel and rack), with why; return how many."""
    rows = [row for grid in maps for row in grid.unreached]
    write_table(path, ['corner', 'travel_mm', 'rack_mm', 'reason'], rows)
    return len(rows)
