# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The writers' rule (issue 36, item 11): a result that is not finite is never written as a number.

Every table writes it as nan (outputs.write_table, doc/tables.md; the setup sheet once left
it empty, as a column that is not the row's); the rest of the table is written, and the
program ends with status 1 and one line naming the columns, as a sweep does for a position
out of reach. A NaN a quantity has by its definition (an alignment quantity
of a scene without a steer axis, Ackermann straight ahead) is no loss: status 0, as before.
The loader refuses the inputs that overflowed (doc/scenes.md#ranges); these scenes and
vehicles are built in Python, past it, as a caller of the core can build them. The tables
are read back with the csv module.
"""

import csv
from dataclasses import replace
import io
import math

from linkage_ros.core.model import load_scene, load_vehicle
from linkage_ros.tools import sweep, vehicle
import numpy as np
import pytest


def table(text):
    """Return the rows of a CSV text as dicts of its header."""
    return list(csv.DictReader(io.StringIO(text)))


def with_spring(**fields):
    """Return double_wishbone with its spring (elements[1]) changed, as built in Python."""
    scene = load_scene('double_wishbone')
    spring = replace(scene.elements[1], **fields)
    return replace(scene, elements=(scene.elements[0], spring))


@pytest.mark.parametrize('fields, lost', [
    ({'rate': 1e308}, ('spring_force_N', 'spring_wheel_rate_N_per_mm')),   # k x deflection
    # the table: an infinite force, and a NaN wheel rate (inf - inf)
    ({'rate': math.nan, 'force_table': np.array([[-100.0, -1e308], [100.0, 1e308]])},
     ('spring_force_N', 'spring_wheel_rate_N_per_mm'))])
def test_a_sweep_writes_no_infinity_and_ends_1_naming_the_columns(monkeypatch, capsys,
                                                                  fields, lost):
    monkeypatch.setattr(sweep, 'load_scene', lambda name: with_spring(**fields))
    status = sweep.main(['double_wishbone', '--elements', '--travel', '-10:10:10'])
    out, err = capsys.readouterr()
    rows = table(out)
    assert status == 1 and len(rows) == 3                  # the table is written whole
    assert 'inf' not in out
    for row in rows:
        assert [row[c] for c in lost] == ['nan', 'nan']
        assert math.isfinite(float(row['spring_length_mm']))   # the rest as it was
    said = err.splitlines()[-1]
    assert said.startswith('linkage-sweep: not finite, so not written as numbers: ')
    assert all(f'{c} at 3 of 3 positions' in said for c in lost), said


def test_a_sweep_with_nan_where_a_quantity_is_undefined_still_ends_0(capsys):
    # five_link has no steer axis (no circle, no strut): its caster is NaN by definition
    assert sweep.main(['five_link', '--alignment', '--elements', '--travel', '-40:40:40']) == 0
    out, err = capsys.readouterr()
    assert {row['caster_deg'] for row in table(out)} == {'nan'}
    assert 'not finite' not in err


def heavy(**mass):
    """Return demo_vehicle with its masses changed, as built in Python."""
    car = load_vehicle('demo_vehicle')
    return replace(car, mass=replace(car.mass, **mass))


def test_a_sheet_writes_no_infinity_and_ends_1_naming_the_cells(monkeypatch, capsys, tmp_path):
    # sprung: 1e308 gave a rear sprung mass of -inf with status 0 (issue 36, item 11)
    monkeypatch.setattr(vehicle, 'load_vehicle', lambda name: heavy(sprung=1e308))
    status = vehicle.main(['demo_vehicle', '--tables', str(tmp_path)])
    out, err = capsys.readouterr()
    rows = {row['axle']: row for row in table(out)}
    assert status == 1 and list(rows) == ['front', 'rear', 'vehicle']
    assert 'inf' not in out
    assert rows['rear']['sprung_mass_kg'] == 'nan' and rows['front']['sprung_mass_kg'] == 'nan'
    assert float(rows['vehicle']['sprung_mass_kg']) == 1e308      # a finite input, as given
    assert float(rows['front']['wheel_rate_N_per_mm']) == pytest.approx(19.77384189)
    lines = [line for line in err.splitlines() if 'not finite' in line]
    assert lines[0].startswith('linkage-vehicle: not finite, so not written as numbers: ')
    assert 'sprung_mass_kg at 2 of 3 rows' in lines[0]
    for path in tmp_path.iterdir():
        assert 'inf' not in path.read_text(), path.name


def test_a_body_its_roll_stiffness_cannot_hold_ends_1_and_says_why(monkeypatch, capsys):
    # 1e7 kg is within the range of a sprung mass; demo_vehicle's 1465 N m/deg of roll
    # stiffness does not hold it at its moment arm of 443 mm: no roll gradient
    monkeypatch.setattr(vehicle, 'load_vehicle', lambda name: heavy(sprung=1e7))
    assert vehicle.main(['demo_vehicle']) == 1
    out, err = capsys.readouterr()
    rows = {row['axle']: row for row in table(out)}
    assert rows['vehicle']['roll_gradient_deg_per_g'] == 'nan'
    assert rows['vehicle']['lltd_front_pct'] == 'nan'
    # m_s g d per degree, from the sheet's own cells: 1e7 kg x g x 0.4427 m x pi / 180
    moment = 1e7 * 9.80665 * float(rows['vehicle']['roll_moment_arm_mm']) / 1000.0 * math.pi / 180
    assert f'overturning moment m_s g d = {moment:.6g} N m/deg' in err
    assert 'roll_gradient_deg_per_g at 1 of 3 rows' in err


def test_the_bundled_sheet_and_its_tables_end_0(capsys, tmp_path):
    # Ackermann is NaN straight ahead (its definition): no loss
    assert vehicle.main(['demo_vehicle', '--tables', str(tmp_path)]) == 0
    assert 'not finite' not in capsys.readouterr().err
    assert 'nan' in {row['ackermann_pct']
                     for row in table((tmp_path / 'front_rack.csv').read_text())}
