# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The registry of quantities: every quantity an output names, declared once.

Each Quantity has its name as tables write it (the unit in the name: `camber_deg`), its table
unit, the SI unit and factor (table value x factor = SI value, as ROS messages carry it),
its sign convention, its group (the block of columns it belongs to, in output order) and a
one-line doc. Axes ISO 8855 / REP 103: x forward, y left, z up; a right wheel mirrors y, so
camber (+ = top outboard), toe (+ = toe-in) and the outboard shifts read alike on both sides.

A name may be a template: `{element}_length_mm` (one per element of a scene, the element's
name in place) or `{side}_camber_deg` (left and right). quantity(name) finds a concrete name
through its template.

    quantity('camber_deg').si_name       -> 'camber_rad'
    columns('travel', 'wheel')           -> ['travel_mm', 'camber_deg', 'toe_deg', ...]
    columns_of_element('spring', rate=True) -> ['spring_length_mm', 'spring_ratio', ...]
    TOPICS['alignment']                  -> the table names of the alignment message's fields

Data only: this module imports nothing of the package (it sits at the bottom of core).
doc/quantities.md is markdown_table() (test/core/test_quantities.py checks it); to write it again:
python -m linkage_ros.core.measure.quantities > doc/quantities.md
"""

from __future__ import annotations

import math
import re
from typing import NamedTuple

DEG = math.pi / 180.0

# table unit: (SI unit, factor table -> SI, factor core -> SI). The core holds angles in rad and
# everything else in the table's unit. A unit is spelt in names as suffix() says.
UNITS = {
    'mm': ('m', 1e-3, 1e-3),
    'deg': ('rad', DEG, 1.0),
    'deg/mm': ('rad/m', DEG * 1e3, 1e3),
    'mm/rad': ('m/rad', 1e-3, 1e-3),
    'N': ('N', 1.0, 1.0),
    'N/mm': ('N/m', 1e3, 1e3),
    'Nm': ('Nm', 1.0, 1.0),
    'Nm/deg': ('Nm/rad', 1.0 / DEG, 1.0),
    # compliance rates (core/statics): per kN and per kN m (SI: per N, per N m)
    'deg/kN': ('rad/N', DEG * 1e-3, 1e-3),
    'mm/kN': ('m/N', 1e-6, 1e-6),
    'deg/kNm': ('rad/Nm', DEG * 1e-3, 1e-3),
    '%': ('1', 1e-2, 1e-2),
    'kg': ('kg', 1.0, 1.0),
    'Hz': ('Hz', 1.0, 1.0),
    'deg/g': ('rad/mps2', DEG / 9.80665, DEG / 9.80665),
    'deg/mm2': ('rad/m2', DEG * 1e6, 1e6),
    '1': ('1', 1.0, 1.0),
}
# What a template's placeholder stands for (a regular expression).
PLACEHOLDERS = {'element': r'.+', 'side': r'left|right', 'link': r'.+', 'pickup': r'.+',
                'bushing': r'.+'}
SIDES = ('left', 'right')


def suffix(unit: str) -> str:
    """Return how a unit is spelt at the end of a name: 'deg/mm' -> 'deg_per_mm', '1' -> ''."""
    return {'%': 'pct', '1': ''}.get(unit, unit.replace('/', '_per_'))


class Quantity(NamedTuple):
    """One quantity: its name in tables and what it means."""

    name: str       # as in tables, unit included; may hold {element} or {side}
    unit: str       # table unit, a key of UNITS ('1': a number without unit)
    sign: str       # sign convention ('' where none applies)
    group: str      # the block of columns it belongs to
    doc: str        # one line
    needs: str = ''  # what a scene or axle must have for the quantity to be written

    @property
    def si_unit(self) -> str:
        """Return the SI unit (ROS messages)."""
        return UNITS[self.unit][0]

    @property
    def factor(self) -> float:
        """Return the factor from the table unit to SI (SI value = table value x factor)."""
        return UNITS[self.unit][1]

    @property
    def core_factor(self) -> float:
        """Return the factor from the core's unit (the table's, angles in rad) to SI."""
        return UNITS[self.unit][2]

    @property
    def stem(self) -> str:
        """Return the name without its unit: 'camber_gain_deg_per_mm' -> 'camber_gain'."""
        end = suffix(self.unit)
        return self.name[:-len(end) - 1] if end else self.name

    @property
    def si_name(self) -> str:
        """Return the name in SI, as ROS messages label it: 'caster_deg' -> 'caster_rad'."""
        end = suffix(self.si_unit)
        return f'{self.stem}_{end}' if end else self.stem

    @property
    def label(self) -> str:
        """Return the stem in words, for plot titles: 'camber_gain_deg_per_mm' -> 'camber gain'."""
        return self.stem.replace('_', ' ')


def _q(name, unit, sign, group, doc, needs=''):
    return Quantity(name, unit, sign, group, doc, needs)


_STEER_AXIS = 'a steer: rack link'
_PATCH = 'wheel_radius'
_BUSHING = 'a bushing'
_BUSHING_PATCH = 'a bushing, wheel_radius'
_DECLARED = (
    # the sweep's leading columns (linkage-sweep, maps, study)
    _q('travel_mm', 'mm', '+ = bump', 'travel',
       'wheel travel: the wheel centre height from design'),
    _q('camber_deg', 'deg', '+ = top outboard', 'wheel', 'camber of the wheel to the body'),
    _q('toe_deg', 'deg', '+ = toe-in', 'wheel', 'toe of the wheel to the body'),
    _q('wheel_center_x_mm', 'mm', '+ = forward', 'wheel', 'wheel centre x, vehicle frame'),
    _q('wheel_center_y_mm', 'mm', '+ = left', 'wheel', 'wheel centre y, vehicle frame'),
    _q('wheel_center_z_mm', 'mm', '+ = up', 'wheel', 'wheel centre z, vehicle frame'),
    _q('qx', '1', '', 'rotation', 'carrier rotation from design, quaternion x'),
    _q('qy', '1', '', 'rotation', 'carrier rotation from design, quaternion y'),
    _q('qz', '1', '', 'rotation', 'carrier rotation from design, quaternion z'),
    _q('qw', '1', '', 'rotation', 'carrier rotation from design, quaternion w (1 at design)'),
    _q('residual_mm', 'mm', '', 'solver', 'largest constraint violation of the solved pose'),
    _q('iterations', '1', '', 'solver', 'Newton iterations of the last continuation step'),
    _q('rack_mm', 'mm', '+ = rack to the left', 'rack', 'steering rack travel', _STEER_AXIS),
    # the alignment set (linkage-sweep --alignment; core/measure/alignment.py)
    _q('camber_gain_deg_per_mm', 'deg/mm', '+ = camber grows in bump', 'alignment',
       'd camber / d travel'),
    _q('bump_steer_deg_per_mm', 'deg/mm', '+ = toe-in grows in bump', 'alignment',
       'd toe / d travel'),
    _q('wheel_center_vx_per_travel', '1', '+ = forward in bump', 'alignment',
       'd wheel centre x / d travel'),
    _q('wheel_center_vy_per_travel', '1', '+ = left in bump', 'alignment',
       'd wheel centre y / d travel'),
    _q('caster_deg', 'deg', '+ = top rearward', 'alignment',
       'caster of the instantaneous steer axis', _STEER_AXIS),
    _q('kingpin_inclination_deg', 'deg', '+ = top inboard', 'alignment',
       'kingpin inclination of the instantaneous steer axis', _STEER_AXIS),
    _q('scrub_radius_mm', 'mm', '+ = axis meets the ground inboard of the patch', 'alignment',
       'where the instantaneous steer axis meets the ground, along y', _STEER_AXIS),
    _q('mechanical_trail_mm', 'mm', '+ = axis meets the ground ahead of the patch', 'alignment',
       'where the instantaneous steer axis meets the ground, along x', _STEER_AXIS),
    _q('track_change_mm', 'mm', '+ = wider', 'alignment',
       '2 x the outboard shift of the contact patch from design', _PATCH),
    _q('wheelbase_change_mm', 'mm', '+ = forward', 'alignment',
       'shift of the contact patch from design along x', _PATCH),
    _q('wheel_center_lateral_shift_mm', 'mm', '+ = outboard', 'alignment',
       'shift of the wheel centre from design along y'),
    _q('wheel_center_longitudinal_shift_mm', 'mm', '+ = forward', 'alignment',
       'shift of the wheel centre from design along x'),
    _q('svic_x_mm', 'mm', '+ = forward', 'alignment', 'side-view instant centre x'),
    _q('svic_z_mm', 'mm', '+ = up', 'alignment', 'side-view instant centre z'),
    _q('fvic_y_mm', 'mm', '+ = left', 'alignment', 'front-view instant centre y'),
    _q('fvic_z_mm', 'mm', '+ = up', 'alignment', 'front-view instant centre z'),
    _q('screw_axis_x', '1', '', 'alignment', "carrier's instantaneous screw axis, unit x"),
    _q('screw_axis_y', '1', '', 'alignment', "carrier's instantaneous screw axis, unit y"),
    _q('screw_axis_z', '1', '', 'alignment', "carrier's instantaneous screw axis, unit z"),
    _q('screw_pitch_mm_per_rad', 'mm/rad', '', 'alignment', 'pitch of that screw axis'),
    # the geometric kingpin (core/measure/kingpin.py), beside the instantaneous steer axis
    _q('caster_geometric_deg', 'deg', '+ = top rearward', 'kingpin',
       'caster of the geometric kingpin axis', 'a kingpin'),
    _q('kingpin_inclination_geometric_deg', 'deg', '+ = top inboard', 'kingpin',
       'kingpin inclination of the geometric axis', 'a kingpin'),
    _q('scrub_radius_geometric_mm', 'mm', '+ = axis meets the ground inboard of the patch',
       'kingpin', 'where the geometric axis meets the ground, along y', 'a kingpin'),
    _q('mechanical_trail_geometric_mm', 'mm', '+ = axis meets the ground ahead of the patch',
       'kingpin', 'where the geometric axis meets the ground, along x', 'a kingpin'),
    _q('kingpin_offset_wheel_centre_geometric_mm', 'mm', '+ = axis inboard', 'kingpin',
       "lateral distance from the wheel centre to the axis at the wheel centre's height",
       'a kingpin'),
    # per element of a scene (linkage-sweep --elements; core/measure/elements.py)
    _q('{element}_length_mm', 'mm', '', 'element', "the element's length"),
    _q('{element}_ratio', '1', '+ = lengthens in bump', 'element',
       'motion ratio d length / d travel'),
    _q('{element}_force_N', 'N', '+ = compressed', 'element', "the spring's force",
       'a spring rate'),
    _q('{element}_wheel_rate_N_per_mm', 'N/mm', '', 'element',
       "the spring's rate at the wheel", 'a spring rate'),
    # an axle (linkage-axle, linkage-map; core/axle/axle.py)
    _q('heave_mm', 'mm', '+ = bump', 'axle', 'both wheels travel by the heave'),
    _q('roll_deg', 'deg', '+ = right side down', 'axle', 'body roll over the ground'),
    _q('{side}_travel_mm', 'mm', '+ = bump', 'axle', "each wheel's travel"),
    _q('roll_centre_y_mm', 'mm', '+ = left', 'roll_centre', 'roll centre y, vehicle frame',
       _PATCH),
    _q('roll_centre_z_mm', 'mm', '+ = up', 'roll_centre', 'roll centre z, vehicle frame',
       _PATCH),
    _q('roll_centre_height_mm', 'mm', '+ = up', 'roll_centre',
       'roll centre above the ground line through the contact patches', _PATCH),
    _q('track_mm', 'mm', '', 'roll_centre', 'left patch y minus right patch y', _PATCH),
    _q('{side}_camber_deg', 'deg', '+ = top outboard', 'axle_wheel',
       "each wheel's camber to the body"),
    _q('{side}_toe_deg', 'deg', '+ = toe-in', 'axle_wheel', "each wheel's toe to the body"),
    _q('{side}_camber_ground_deg', 'deg', '+ = top outboard', 'axle_ground',
       "each wheel's camber to the ground"),
    _q('{side}_toe_ground_deg', 'deg', '+ = toe-in', 'axle_ground',
       "each wheel's toe to the ground"),
    _q('anti_dive_pct', '%', '', 'anti', 'anti-dive of a front axle in braking',
       'brake_share, cg_height'),
    _q('anti_lift_pct', '%', '', 'anti',
       'anti-lift: a rear axle in braking, a front axle in drive', 'a share, cg_height'),
    _q('anti_squat_pct', '%', '', 'anti', 'anti-squat of a rear axle in drive',
       'drive_share, cg_height'),
    _q('{side}_steer_deg', 'deg', '+ = to the left', 'axle_steer', "each wheel's steer (yaw)",
       'a rack'),
    _q('mean_steer_deg', 'deg', '+ = to the left', 'axle_steer', 'mean of the two steers',
       'a rack'),
    _q('ackermann_pct', '%', '', 'axle_steer', 'Ackermann of the two steers',
       'a rack, wheel_radius, wheelbase'),
    # an axle's anti-roll bar (core/axle/anti_roll_bar.py)
    _q('arb_{side}_angle_deg', 'deg', '', 'anti_roll_bar',
       "each arm's angle about the bar's axis, directed to the left", 'an anti_roll_bar'),
    _q('arb_twist_deg', 'deg', '', 'anti_roll_bar', 'left minus right arm angle',
       'an anti_roll_bar'),
    _q('arb_ratio_deg_per_deg_roll', '1', '', 'anti_roll_bar', 'd twist / d roll',
       'an anti_roll_bar'),
    _q('arb_ratio_{side}_deg_per_mm', 'deg/mm', '', 'anti_roll_bar',
       'd twist / d travel of one wheel, the other held', 'an anti_roll_bar'),
    _q('arb_torque_Nm', 'Nm', '', 'anti_roll_bar', "the bar's torque", 'a bar rate'),
    _q('arb_roll_moment_Nm', 'Nm', '', 'anti_roll_bar', 'the roll moment the bar resists with',
       'a bar rate'),
    _q('arb_roll_stiffness_Nm_per_deg', 'Nm/deg', '', 'anti_roll_bar',
       "the bar's roll stiffness", 'a bar rate'),
    # compliance at one travel, travel and rack held (core/statics, linkage-kc): first-order
    # rates at the zero-load equilibrium; cp = the contact patch, wc = the wheel centre
    _q('toe_per_fy_cp_deg_per_kN', 'deg/kN', '+ = toe-in per + y (left) force', 'kc_fy_cp',
       'toe per lateral force at the contact patch', _BUSHING_PATCH),
    _q('camber_per_fy_cp_deg_per_kN', 'deg/kN', '+ = top outboard per + y force', 'kc_fy_cp',
       'camber per lateral force at the contact patch', _BUSHING_PATCH),
    _q('wc_dy_per_fy_cp_mm_per_kN', 'mm/kN', '+ = left per + y force', 'kc_fy_cp',
       "wheel centre's lateral move per lateral force at the contact patch", _BUSHING_PATCH),
    _q('cp_dy_per_fy_cp_mm_per_kN', 'mm/kN', '+ = left per + y force', 'kc_fy_cp',
       "contact patch's lateral move per lateral force there", _BUSHING_PATCH),
    _q('jacking_per_fy_cp', '1', '+ = up per + y force', 'kc_fy_cp',
       'holding (jacking) force change per lateral force at the contact patch, N/N',
       _BUSHING_PATCH),
    _q('toe_per_fx_cp_deg_per_kN', 'deg/kN', '+ = toe-in per + x (forward) force', 'kc_fx_cp',
       'toe per longitudinal force at the contact patch (braking is -x)', _BUSHING_PATCH),
    _q('camber_per_fx_cp_deg_per_kN', 'deg/kN', '+ = top outboard per + x force', 'kc_fx_cp',
       'camber per longitudinal force at the contact patch', _BUSHING_PATCH),
    _q('wc_dx_per_fx_cp_mm_per_kN', 'mm/kN', '+ = forward per + x force', 'kc_fx_cp',
       "wheel centre's longitudinal move per longitudinal force at the contact patch",
       _BUSHING_PATCH),
    _q('toe_per_fx_wc_deg_per_kN', 'deg/kN', '+ = toe-in per + x force', 'kc_fx_wc',
       'toe per longitudinal force at the wheel centre (traction)', _BUSHING),
    _q('wc_dx_per_fx_wc_mm_per_kN', 'mm/kN', '+ = forward per + x force', 'kc_fx_wc',
       "wheel centre's longitudinal move per longitudinal force there", _BUSHING),
    _q('toe_per_mz_deg_per_kNm', 'deg/kNm', '+ = toe-in per + z moment', 'kc_mz',
       'toe per moment about the z axis (aligning torque)', _BUSHING),
    _q('camber_per_mz_deg_per_kNm', 'deg/kNm', '+ = top outboard per + z moment', 'kc_mz',
       'camber per moment about the z axis', _BUSHING),
    # a loaded solve (core/statics, linkage-kc --load): after the wheel columns, the forces
    # (a spring's is {element}_force_N, as above)
    _q('holding_force_N', 'N', '+ = up', 'kc_loaded',
       'vertical force at the wheel centre that holds the travel (the jacking force)'),
    _q('{link}_body_end_tension_N', 'N', '+ = tension', 'kc_loaded',
       'a link that carries a spring: its force along itself at its body end (on its base)'),
    _q('{link}_carrier_end_tension_N', 'N', '+ = tension', 'kc_loaded',
       'a link that carries a spring: its force along itself at its carrier end'),
    _q('{link}_tension_N', 'N', '+ = tension', 'kc_loaded', "a link's force along itself"),
    _q('{pickup}_fx_N', 'N', '+ = forward', 'kc_loaded',
       "force on the body at a pickup: an arm's pivot (<arm>_axis0, _axis1 or _centre), a "
       "link's base (<link>_base), a spring's body end (<spring>_body), a strut's top "
       '(<strut>_top), x'),
    _q('{pickup}_fy_N', 'N', '+ = left', 'kc_loaded', 'force on the body at a pickup, y'),
    _q('{pickup}_fz_N', 'N', '+ = up', 'kc_loaded', 'force on the body at a pickup, z'),
    _q('{bushing}_mx_Nm', 'Nm', '+ = about + x', 'kc_loaded',
       'couple of a bushing on the body at its pickup (<arm>_axis0, ..., <link>_base): its '
       "offset's d x K d and its torsion and conical torque, x"),
    _q('{bushing}_my_Nm', 'Nm', '+ = about + y', 'kc_loaded',
       'couple of a bushing on the body, y'),
    _q('{bushing}_mz_Nm', 'Nm', '+ = about + z', 'kc_loaded',
       'couple of a bushing on the body, z'),
)
_SHEET = 'mass, tyre_rate'
_DECLARED += (
    # the setup sheet (linkage-vehicle; core/vehicle, doc/vehicle.md): a row per axle
    _q('axle', '1', '', 'setup_axle', 'the row: front, rear or vehicle (text)'),
    _q('axle_x_mm', 'mm', '+ = forward', 'setup_axle',
       'x of the axle: the mean of its design contact patches'),
    _q('sprung_mass_kg', 'kg', '', 'setup_axle',
       "the sprung mass (the axle's share: statics over the wheelbase)", _SHEET),
    _q('unsprung_mass_kg', 'kg', '', 'setup_axle', "the axle's two unsprung masses", _SHEET),
    _q('tyre_rate_N_per_mm', 'N/mm', '', 'setup_axle', 'vertical rate of one tyre', _SHEET),
    _q('wheel_rate_N_per_mm', 'N/mm', '', 'setup_axle',
       "each wheel's rate in heave from every elastic part (exact ratios, preload term)",
       _SHEET),
    _q('ride_rate_N_per_mm', 'N/mm', '', 'setup_axle', 'the wheel rate in series with the tyre',
       _SHEET),
    _q('ride_frequency_Hz', 'Hz', '', 'setup_axle',
       'sqrt(ride rate / sprung mass per wheel) / 2 pi', _SHEET),
    _q('roll_stiffness_springs_Nm_per_deg', 'Nm/deg', '', 'setup_axle',
       "d2 V / d roll2 of the axle's springs, the body rolled over the ground", _SHEET),
    _q('roll_stiffness_bar_Nm_per_deg', 'Nm/deg', '', 'setup_axle',
       "d2 V / d roll2 of the axle's anti-roll bar (0 without one)", _SHEET),
    _q('roll_stiffness_Nm_per_deg', 'Nm/deg', '', 'setup_axle',
       'roll stiffness of springs and bar (an axle), of both axles (the vehicle)', _SHEET),
    _q('roll_stiffness_textbook_Nm_per_deg', 'Nm/deg', '', 'setup_axle',
       '0.5 k MR^2 t^2 of the springs (design ratio, no preload) plus k_b ratio^2 of the bar',
       _SHEET),
    _q('load_transfer_geometric_N', 'N', '+ = onto the outer wheel', 'setup_axle',
       'lateral load transfer at 1 g: sprung mass through the roll centre', _SHEET),
    _q('load_transfer_elastic_N', 'N', '+ = onto the outer wheel', 'setup_axle',
       'lateral load transfer at 1 g: through the roll stiffness', _SHEET),
    _q('load_transfer_unsprung_N', 'N', '+ = onto the outer wheel', 'setup_axle',
       'lateral load transfer at 1 g: the unsprung masses', _SHEET),
    _q('load_transfer_N', 'N', '+ = onto the outer wheel', 'setup_axle',
       'lateral load transfer at 1 g: the three paths', _SHEET),
    _q('steering_ratio_deg_per_mm', 'deg/mm', '+ = rack to the left steers left',
       'setup_axle', 'd mean steer / d rack (at rack 0 in the sheet)', 'a rack'),
    _q('steering_ratio_change_deg_per_mm2', 'deg/mm2', '', 'setup_axle',
       'd steering ratio / d rack', 'a rack'),
    # the setup sheet: the vehicle's row
    _q('mass_kg', 'kg', '', 'setup_vehicle', 'sprung plus four unsprung masses', _SHEET),
    _q('cg_x_mm', 'mm', '+ = forward', 'setup_vehicle', "x of the sprung mass's centre",
       _SHEET),
    _q('cg_height_mm', 'mm', '+ = up', 'setup_vehicle',
       "the sprung mass's centre above the ground", _SHEET),
    _q('cg_height_total_mm', 'mm', '+ = up', 'setup_vehicle',
       "the whole car's centre (sprung and four unsprung masses) above the ground: the h of "
       'the pitch gradient', _SHEET),
    _q('wheelbase_mm', 'mm', '', 'setup_vehicle', 'front minus rear axle x'),
    _q('roll_axis_height_at_cg_mm', 'mm', '+ = up', 'setup_vehicle',
       'the line through the front and rear roll centres, above the ground at cg_x', _SHEET),
    _q('roll_moment_arm_mm', 'mm', '+ = cg above the axis', 'setup_vehicle',
       'cg height less the roll axis height under it', _SHEET),
    _q('roll_gradient_deg_per_g', 'deg/g', '+ = rolls outward', 'setup_vehicle',
       'm_s d / (K - m_s g d), the overturning moment included', _SHEET),
    _q('lltd_front_pct', '%', '', 'setup_vehicle',
       "the front axle's share of the lateral load transfer", _SHEET),
    _q('pitch_gradient_braking_deg_per_g', 'deg/g', '+ = nose down', 'setup_vehicle',
       'body pitch per g of braking, springs less anti, tyres', _SHEET),
    _q('pitch_gradient_drive_deg_per_g', 'deg/g', '+ = nose down', 'setup_vehicle',
       'body pitch per g of drive, springs less anti, tyres', _SHEET),
    _q('pitch_centre_braking_x_mm', 'mm', '+ = forward', 'setup_vehicle',
       'where the side-view force lines of the two axles meet, braking'),
    _q('pitch_centre_braking_height_mm', 'mm', '+ = up', 'setup_vehicle',
       'its height above the ground'),
    _q('pitch_centre_drive_x_mm', 'mm', '+ = forward', 'setup_vehicle',
       'where the side-view lines through the wheel centres meet, drive'),
    _q('pitch_centre_drive_height_mm', 'mm', '+ = up', 'setup_vehicle',
       'its height above the ground'),
)
_LOADS = 'mass, tyre_rate'
_DECLARED += (
    # load cases on a vehicle (linkage-loads; core/loads, doc/loads.md): per case and corner
    _q('case', '1', '', 'loads_corner', 'the load case (text)'),
    _q('corner', '1', '', 'loads_corner',
       'the corner (text; an axle for its anti-roll bar)'),
    _q('status', '1', '', 'loads_corner',
       'OK, or why the corner is not solved: OUT_OF_REACH, NOT_CARRIED (text)'),
    _q('tyre_fx_N', 'N', '+ = forward', 'loads_corner',
       "the ground's force on the tyre, x", _LOADS),
    _q('tyre_fy_N', 'N', '+ = left', 'loads_corner', "the ground's force on the tyre, y",
       _LOADS),
    _q('tyre_fz_N', 'N', '+ = up', 'loads_corner',
       "the ground's force on the tyre, z: the vertical tyre load", _LOADS),
    _q('tyre_mx_Nm', 'Nm', 'right-hand about + x', 'loads_corner',
       "the ground's moment on the tyre about the contact patch, x", _LOADS),
    _q('tyre_my_Nm', 'Nm', 'right-hand about + y', 'loads_corner',
       "the ground's moment on the tyre about the contact patch, y", _LOADS),
    _q('tyre_mz_Nm', 'Nm', 'right-hand about + z', 'loads_corner',
       "the ground's moment on the tyre about the contact patch, z", _LOADS),
    # the force at every pickup: on the body (end body), on the carrier (end carrier), on an
    # anti-roll bar (end bar)
    _q('pickup', '1', '', 'loads_pickup',
       'the pickup: <link>_base, <arm>_axis0, <constraint>_carrier, ... (text)'),
    _q('end', '1', '', 'loads_pickup',
       'the part the force acts on: body, carrier or bar (text)'),
    _q('x_mm', 'mm', '+ = forward', 'loads_pickup', 'where the pickup is, x (loaded pose)'),
    _q('y_mm', 'mm', '+ = left', 'loads_pickup', 'where the pickup is, y (loaded pose)'),
    _q('z_mm', 'mm', '+ = up', 'loads_pickup', 'where the pickup is, z (loaded pose)'),
    _q('fx_N', 'N', '+ = forward', 'loads_pickup', 'the force on that part at the pickup, x'),
    _q('fy_N', 'N', '+ = left', 'loads_pickup', 'the force on that part at the pickup, y'),
    _q('fz_N', 'N', '+ = up', 'loads_pickup', 'the force on that part at the pickup, z'),
    _q('force_magnitude_N', 'N', '', 'loads_pickup',
       'the size of that force; in the summary, the largest over the cases'),
    _q('mx_Nm', 'Nm', 'right-hand about + x', 'loads_pickup',
       "a bushing's couple on the body at the pickup, x"),
    _q('my_Nm', 'Nm', 'right-hand about + y', 'loads_pickup',
       "a bushing's couple on the body at the pickup, y"),
    _q('mz_Nm', 'Nm', 'right-hand about + z', 'loads_pickup',
       "a bushing's couple on the body at the pickup, z"),
    # what each member carries
    _q('member', '1', '', 'loads_member', 'a link, arm bushing, spring, stop or bar (text)'),
    _q('kind', '1', '', 'loads_member',
       'link, drop_link, spring, stop, bushing or bar (text)'),
    _q('force_N', 'N', '+ = tension (a link), + = compressed (a spring, a stop)',
       'loads_member', "the member's force along itself; a bushing's force on the body, its "
       'size'),
    _q('deflection_mm', 'mm', '', 'loads_member',
       "a bushing's deflection: the arm's or link's point from its body point, its size"),
    _q('deflection_x_mm', 'mm', '+ = forward', 'loads_member', "a bushing's deflection, x"),
    _q('deflection_y_mm', 'mm', '+ = left', 'loads_member', "a bushing's deflection, y"),
    _q('deflection_z_mm', 'mm', '+ = up', 'loads_member', "a bushing's deflection, z"),
    _q('torque_Nm', 'Nm', '', 'loads_member', "an anti-roll bar's torque, rate x twist"),
    _q('twist_deg', 'deg', '+ = left arm turned further about + y', 'loads_member',
       "an anti-roll bar's twist, left minus right arm angle"),
)
QUANTITIES = {q.name: q for q in _DECLARED}

# The quantities each of a corner's topics carries (names relative to the corner's namespace),
# in message order: std_msgs/Float64 (SI), the pose's wheel centre (m) and quaternion, the
# alignment message's fields (labelled by si_name), the elements JointState (position, velocity).
TOPICS = {
    'wheel_travel': ('travel_mm',),
    'steering_rack': ('rack_mm',),
    'wheel_carrier_pose': ('wheel_center_x_mm', 'wheel_center_y_mm', 'wheel_center_z_mm',
                           'qx', 'qy', 'qz', 'qw'),
    'camber': ('camber_deg',),
    'toe': ('toe_deg',),
    'alignment': ('camber_gain_deg_per_mm', 'bump_steer_deg_per_mm', 'caster_deg',
                  'kingpin_inclination_deg', 'scrub_radius_mm', 'mechanical_trail_mm',
                  'track_change_mm', 'wheelbase_change_mm', 'wheel_center_lateral_shift_mm',
                  'wheel_center_longitudinal_shift_mm', 'svic_x_mm', 'svic_z_mm', 'fvic_y_mm',
                  'fvic_z_mm'),
    'elements': ('{element}_length_mm', '{element}_ratio'),
}


def _pattern(template: str) -> re.Pattern:
    parts = re.split(r'\{(\w+)\}', template)
    return re.compile(''.join(re.escape(p) if i % 2 == 0 else f'(?:{PLACEHOLDERS[p]})'
                              for i, p in enumerate(parts)) + r'\Z')


_TEMPLATES = [(_pattern(q.name), q) for q in _DECLARED if '{' in q.name]


def quantity(name: str) -> Quantity:
    """Return the Quantity of a name (a template's, for a concrete name); KeyError if none."""
    if name in QUANTITIES:
        return QUANTITIES[name]
    for pattern, q in _TEMPLATES:
        if pattern.match(name):
            return q
    raise KeyError(f'{name!r} is no quantity of linkage_ros.core.measure.quantities')


def known(name: str) -> bool:
    """Tell whether a table name is a quantity of the registry."""
    try:
        quantity(name)
    except KeyError:
        return False
    return True


def known_si(name: str) -> bool:
    """Tell whether an SI name (a message label: 'caster_rad') is one of a quantity."""
    return any(q.si_name == name for q in _DECLARED)


def names(*groups: str) -> list[str]:
    """Return the names declared in groups (templates as such), group after group."""
    return [q.name for g in groups for q in _DECLARED if q.group == g]


def sides(template: str) -> list[str]:
    """Return a {side} template's names, left then right; a plain name alone."""
    return [template.format(side=s) for s in SIDES] if '{side}' in template else [template]


def columns(*groups: str) -> list[str]:
    """Return the columns of groups: names(*groups), each {side} template left then right."""
    return [n for template in names(*groups) for n in sides(template)]


def columns_of_element(element: str, rate: bool, wheel_rate: bool = True) -> list[str]:
    """
    Return an element's columns: length and ratio; with a spring rate, force (and wheel rate).

    wheel_rate False leaves the wheel rate out (it needs the carrier's second-order motion).
    """
    wanted = [q.name for q in _DECLARED if q.group == 'element'
              and (rate or not q.needs) and (wheel_rate or 'wheel_rate' not in q.name)]
    return [n.format(element=element) for n in wanted]


def title(name: str) -> str:
    """Return a plot title of a quantity: 'camber (deg)'."""
    return f'{quantity(name).label} ({quantity(name).unit})'


def markdown_table() -> str:
    """Return the registry as doc/quantities.md (a markdown table per group)."""
    lines = ['# Quantities', '',
             'Every quantity an output of linkage_ros names, from its registry',
             '(`linkage_ros/core/measure/quantities.py`; this file is `markdown_table()`, and',
             '`test/core/test_quantities.py` checks that it matches). Tables are in the '
             'table unit,',
             'with the unit in the name; ROS messages are in SI: SI value = table value x factor,',
             'labelled by the SI name. `{element}` stands for each element of a scene,',
             '`{side}` for left and right. Axes ISO 8855 / REP 103 (x forward, y left, z up);',
             'a right wheel mirrors y.', '']
    header = ['| name | unit | SI name | SI unit | factor | sign | needs | meaning |',
              '|---|---|---|---|---|---|---|---|']
    for group in dict.fromkeys(q.group for q in _DECLARED):
        lines += [f'## {group}', ''] + header
        for q in _DECLARED:
            if q.group == group:
                lines.append(f'| `{q.name}` | {q.unit} | `{q.si_name}` | {q.si_unit} | '
                             f'{q.factor:.10g} | {q.sign} | {q.needs} | {q.doc} |')
        lines.append('')
    topics = ['## Topics', '', "The quantities of a corner's topics, in message order.", '',
              '| topic | quantities |', '|---|---|']
    topics += [f'| `{t}` | ' + ', '.join(f'`{n}`' for n in ns) + ' |'
               for t, ns in TOPICS.items()]
    return '\n'.join(lines + topics) + '\n'


if __name__ == '__main__':   # python -m linkage_ros.core.measure.quantities > doc/quantities.md
    print(markdown_table(), end='')
