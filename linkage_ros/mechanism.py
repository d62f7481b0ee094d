"""The 5 guidance equations of a scene, written on the carrier pose (M, R).

The pose is the wheel-centre position M (mm, vehicle frame) and the carrier rotation R
relative to design: a carrier point at design position b0 is at M + R (b0 - M0).
Residuals are lengths in mm, so a tolerance reads the same in every scene:
  sphere (eq. 2, 13): |B - A| - l, written (|B - A|^2 - l^2) / 2l so it stays smooth;
  circle (eqs. 3-4): two spheres about the two axis points;
  line (strut):       distance of the top mount T from the carrier-fixed strut line,
                      as two components along carrier-fixed normals of the line.
"""

from dataclasses import dataclass

import numpy as np

from .geometry import cross, unit


@dataclass(frozen=True)
class Mechanism:
    """Arrays compiled from a Scene. Shapes: m carrier points, k distance eqs, q line eqs."""

    design_center: np.ndarray    # M0 (3,)
    offsets: np.ndarray          # (m, 3) carrier points minus M0, carrier frame = design frame
    point_names: tuple           # (m,) names of the carrier points
    dist_point: np.ndarray       # (k,) index into offsets
    dist_base: np.ndarray        # (k, 3)
    dist_length: np.ndarray      # (k,)
    dist_steer: np.ndarray       # (k,) 1.0 where the base point moves with the steering rack
    line_point: np.ndarray       # (q,) index into offsets
    line_base: np.ndarray        # (q, 3) top mount T
    line_normal: np.ndarray      # (q, 3) carrier-fixed unit normals of the strut line
    equation_names: tuple        # (k + q,) for diagnostics
    spin_axis: np.ndarray        # (3,) design outboard spin-axis unit vector
    lever: float                 # mm: largest |offset|, turns a rotation step into mm

    @property
    def n_equations(self):
        return len(self.dist_length) + len(self.line_base)

    @property
    def inv_length(self):
        return (1.0 / self.dist_length)[:, None]

    @property
    def half_inv_length(self):
        return 0.5 / self.dist_length


def compile_scene(scene):
    """Build the Mechanism of a validated Scene."""
    m0 = scene.wheel_center
    names, offsets = [], []
    dist_point, dist_base, dist_length, dist_steer, eq_names = [], [], [], [], []
    line_point, line_base, line_normal, line_names = [], [], [], []
    for c in scene.constraints:
        idx = len(offsets)
        names.append(c.name)
        offsets.append(c.carrier - m0)
        if c.type in ('sphere', 'circle'):
            for j, base in enumerate(c.base):
                dist_point.append(idx)
                dist_base.append(base)
                dist_length.append(np.linalg.norm(c.carrier - base))
                dist_steer.append(1.0 if c.steer == 'rack' else 0.0)
                eq_names.append(c.name if len(c.base) == 1 else f'{c.name}[{j}]')
        else:
            for j, normal in enumerate(line_normals(c.base[0] - c.carrier, scene.wheel_center
                                                    - scene.spin_axis_point)):
                line_point.append(idx)
                line_base.append(c.base[0])
                line_normal.append(normal)
                line_names.append(f'{c.name}[{j}]')
    offsets = np.array(offsets)
    return Mechanism(
        design_center=m0.copy(), offsets=offsets, point_names=tuple(names),
        dist_point=np.array(dist_point, dtype=int), dist_base=np.array(dist_base).reshape(-1, 3),
        dist_length=np.array(dist_length), dist_steer=np.array(dist_steer),
        line_point=np.array(line_point, dtype=int),
        line_base=np.array(line_base).reshape(-1, 3),
        line_normal=np.array(line_normal).reshape(-1, 3),
        equation_names=tuple(eq_names + line_names),
        spin_axis=unit(scene.wheel_center - scene.spin_axis_point),
        lever=float(np.max(np.linalg.norm(offsets, axis=1))))


def line_normals(direction, spin_axis):
    """Two unit normals of a strut line, chosen square to each other and to the line."""
    d = unit(direction)
    helper = spin_axis if np.linalg.norm(np.cross(d, unit(spin_axis))) > 0.1 else [1.0, 0, 0]
    n1 = unit(np.cross(d, helper))
    return n1, np.cross(d, n1)


def carrier_points(mech, center, rotation):
    """Carrier points (m, 3) of the pose; batched: center (n, 3), rotation (n, 3, 3)."""
    return center[..., None, :] + mech.offsets @ np.swapaxes(rotation, -1, -2)


def rack_derivative(mech, center, rotation, rack=0.0):
    """d(residuals)/d(rack) (..., 5): the steer rows' base points move along +y."""
    r = mech.offsets[mech.dist_point] @ np.swapaxes(rotation, -1, -2)
    d_y = r[..., 1] + (center[..., None, 1] - mech.dist_base[:, 1]) \
        - np.asarray(rack)[..., None] * mech.dist_steer
    out = np.zeros(center.shape[:-1] + (mech.n_equations,))
    out[..., :len(mech.dist_length)] = -d_y / mech.dist_length * mech.dist_steer
    return out


def length_errors(mech, center, rotation, rack=0.0):
    """Largest constraint violation (mm) as a true length: link length error or strut offset."""
    pts = carrier_points(mech, center, rotation)
    d = pts[..., mech.dist_point, :] - mech.dist_base
    d[..., 1] -= np.asarray(rack)[..., None] * mech.dist_steer
    dist = np.abs(np.linalg.norm(d, axis=-1) - mech.dist_length)
    normals = mech.line_normal @ np.swapaxes(rotation, -1, -2)
    line = np.abs(np.einsum('...i,...i->...', mech.line_base - pts[..., mech.line_point, :],
                            normals))
    return np.max(np.concatenate((dist, line), axis=-1), axis=-1)


def linearize(mech, center, rotation, rack=0.0):
    """Residuals (..., 5) and their Jacobian d/d(M, omega) (..., 5, 6).

    omega is a small rotation applied in the vehicle frame (R <- exp(omega) R); Jacobian
    column 2 (dZ_M) is the travel direction, columns 0, 1, 3, 4, 5 the unknowns.
    rack (mm, scalar or (...,)): steering rack travel, + = to the left, moving the base
    points of steer: rack constraints along y.
    Written for speed: it is the inner loop of every solve.
    """
    rt = np.swapaxes(rotation, -1, -2)
    k = len(mech.dist_length)
    f = np.empty(center.shape[:-1] + (mech.n_equations,))
    jac = np.empty(center.shape[:-1] + (mech.n_equations, 6))
    # sphere rows: F = (|d|^2 - l^2) / 2l, dF = (d / l) . (dM + omega x r)
    r = mech.offsets[mech.dist_point] @ rt
    d = r + (center[..., None, :] - mech.dist_base)
    if np.any(rack):
        d[..., 1] -= np.asarray(rack)[..., None] * mech.dist_steer
    f[..., :k] = (np.einsum('...i,...i->...', d, d) - mech.dist_length**2) * mech.half_inv_length
    d *= mech.inv_length
    jac[..., :k, :3] = d
    jac[..., :k, 3:] = cross(r, d)
    if len(mech.line_point):
        # line rows: F = (T - B) . n, n = R n0; dF = -n . dM + omega . (n x (T - B) - r x n)
        r = mech.offsets[mech.line_point] @ rt
        normals = mech.line_normal @ rt
        to_base = (mech.line_base - center[..., None, :]) - r
        f[..., k:] = np.einsum('...i,...i->...', to_base, normals)
        jac[..., k:, :3] = -normals
        jac[..., k:, 3:] = cross(normals, to_base) - cross(r, normals)
    return f, jac
