# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Chrono::Vehicle's named suspension templates as data: their parts, point keys and scene names.

One table serves the import (importer.py) and the export (exporter.py), so a
point's key is written once. Keys and frames are those of Chrono's readers
(src/chrono_vehicle/wheeled_vehicle/suspension/<Template>.cpp): SI points in the
suspension's frame, ISO axes (x forward, y left, z up), left side; Chrono mirrors the right.
The wheel centre is the spindle's "COM"; the spin axis is the spindle's y axis turned by
"Camber Angle (deg)" and "Toe Angle (deg)" (ChDoubleWishbone::Initialize:
Rz(-toe) Rx(-camber) on the left), which is the scene's camber + = top outboard, toe + =
toe-in (model/scene.py, carrier.static).
"""

from __future__ import annotations

from typing import NamedTuple

ARM_KEYS = ('Location Chassis Front', 'Location Chassis Back', 'Location Upright')
LINK_KEYS = ('Location Chassis', 'Location Upright')


class Part(NamedTuple):
    """A guidance part: its JSON object, its scene constraint name and kind."""

    key: str      # the JSON object ("Upper Control Arm")
    name: str     # the scene constraint (UpperControlArm): Chrono's part name, spaces out
    kind: str     # 'arm' (circle), 'link' (sphere), 'strut' (line through "Spring")
    steer: bool = False


class Tsda(NamedTuple):
    """A spring or shock: its JSON object, the key of its moving point and what carries it."""

    key: str      # "Spring", "Shock"
    point: str    # "Location Arm", "Location Upright", "Location Link"
    on: str       # the scene constraint carrying the point ('' = the carrier)


class Template(NamedTuple):
    """A named Chrono template: guidance parts, springs and shocks."""

    parts: tuple[Part, ...]
    tsdas: tuple[Tsda, ...]


_WISHBONES = (Part('Upper Control Arm', 'UpperControlArm', 'arm'),
              Part('Lower Control Arm', 'LowerControlArm', 'arm'),
              Part('Tierod', 'Tierod', 'link', steer=True))

TEMPLATES = {
    'DoubleWishbone': Template(_WISHBONES, (Tsda('Spring', 'Location Arm', 'LowerControlArm'),
                                            Tsda('Shock', 'Location Arm', 'LowerControlArm'))),
    'DoubleWishboneReduced': Template(_WISHBONES, (Tsda('Shock', 'Location Upright', ''),)),
    'MacPhersonStrut': Template(
        (Part('Control Arm', 'ControlArm', 'arm'), Part('Tierod', 'Tierod', 'link', steer=True),
         Part('Spring', 'Strut', 'strut')),
        (Tsda('Spring', 'Location Upright', 'Strut'), Tsda('Shock', 'Location Upright', ''))),
    'MultiLink': Template(
        (Part('Upper Arm', 'UpperArm', 'arm'), Part('Lateral', 'Lateral', 'link'),
         Part('Trailing Link', 'TrailingLink', 'link'),
         Part('Tierod', 'Tierod', 'link', steer=True)),
        (Tsda('Spring', 'Location Link', 'TrailingLink'),
         Tsda('Shock', 'Location Link', 'TrailingLink'))),
}
GENERIC = 'GenericWheeledSuspension'

# Templates refused, and why (one line each): the wheel carrier is itself an arm, or the
# wheels share an axle; scenes have no constraint for either.
CARRIER_ARM = ('its wheel carrier is itself an arm turning about a body-fixed axis, a '
               'constraint kind scenes do not have')
SOLID = 'a solid (beam) axle: both wheels on one body, not an independent corner'
REFUSED = {'SemiTrailingArm': CARRIER_ARM, 'ThreeLinkIRS': CARRIER_ARM,
           'SingleWishbone': CARRIER_ARM, 'RigidSuspension': 'a rigid suspension: no travel',
           'RigidPinnedAxle': SOLID, 'HendricksonPRIMAXX': SOLID}

# The kingpin of a template whose lower ball joint is virtual (model/kingpin.py)
KINGPIN = {'MultiLink': ['UpperArm', ['Lateral', 'TrailingLink']]}

DESIGN_AXIS_M = 0.1   # spin_axis_point: this far inboard of the wheel centre (m), as bundled
TRAVEL_M = {'min': -0.08, 'max': 0.08, 'step': 0.001}
WHEEL_RADIUS_M = 0.33   # not in a suspension file (the tyre's); --wheel-radius sets it


def supported() -> str:
    """Return the importable templates, for messages."""
    return ', '.join(list(TEMPLATES) + [GENERIC])
