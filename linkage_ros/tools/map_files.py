"""
The files of a kinematic map: CSV in long form, NumPy .npz of axes and arrays, Parquet.

    <corner>.csv      corner,travel_mm,rack_mm,quantity,value: one value a line, every value
                      written with the fewest digits that read back to the same float64
    <corner>.npz      travel_mm (nt,), rack_mm (nr,) and each quantity as an (nt, nr) array:
                      what a lookup-table block (or scipy's RegularGridInterpolator) takes
    <corner>.parquet  one row per grid point: travel_mm, rack_mm, then a column per quantity
    out_of_reach.csv  corner,travel_mm,rack_mm,reason of every point left NaN

pyarrow (the map extra) is imported only when Parquet is asked for.
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .map_grid import CornerMap

FORMATS = ('csv', 'npz', 'parquet')
UNREACHED = 'out_of_reach.csv'


def write_map(folder: Path, cmap: CornerMap, formats: tuple[str, ...]) -> list[Path]:
    """Write a corner map in each of formats into folder; return the files written."""
    writers = {'csv': write_long_csv, 'npz': write_npz, 'parquet': write_parquet}
    paths = []
    for kind in formats:
        paths.append(folder / f'{cmap.corner}.{kind}')
        writers[kind](paths[-1], cmap)
    return paths


def write_npz(path: Path, cmap: CornerMap) -> None:
    """Write the grid axes and one (nt, nr) array per quantity."""
    arrays = {name: np.ascontiguousarray(cmap.values[:, :, i])
              for i, name in enumerate(cmap.quantities)}
    np.savez(path, travel_mm=cmap.travel, rack_mm=cmap.rack, **arrays)


def write_long_csv(path: Path, cmap: CornerMap) -> None:
    """Write one value a line, grid point by grid point (travel, then rack), exact floats."""
    names = cmap.quantities
    with open(path, 'w') as stream:
        stream.write('corner,travel_mm,rack_mm,quantity,value\n')
        for i, travel in enumerate(cmap.travel.tolist()):
            for j, rack in enumerate(cmap.rack.tolist()):
                start = f'{cmap.corner},{travel!r},{rack!r},'
                stream.writelines(f'{start}{name},{value!r}\n'
                                  for name, value in zip(names, cmap.values[i, j].tolist()))


def write_parquet(path: Path, cmap: CornerMap) -> None:
    """Write one row per grid point: travel_mm, rack_mm, then a column per quantity."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    travel, rack = np.meshgrid(cmap.travel, cmap.rack, indexing='ij')
    columns = {'travel_mm': travel.ravel(), 'rack_mm': rack.ravel()}
    columns.update((name, cmap.values[:, :, i].ravel()) for i, name in enumerate(cmap.quantities))
    pq.write_table(pa.table(columns), path)


def write_unreached(path: Path, maps: list[CornerMap]) -> int:
    """List every point left NaN, with why; return how many."""
    count = 0
    with open(path, 'w', newline='') as stream:
        writer = csv.writer(stream, lineterminator='\n')
        writer.writerow(['corner', 'travel_mm', 'rack_mm', 'reason'])
        for cmap in maps:
            for travel, rack, why in cmap.unreached:
                writer.writerow([cmap.corner, repr(travel), repr(rack), why])
                count += 1
    return count
