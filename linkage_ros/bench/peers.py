# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The solvers linkage-bench compares, and the catalogue of entries (Entry) that runs them.

The solvers are the core's methods, the baselines a user would write first, and exudyn, each
a stateful solver whose solve(travel) starts from its previous answer (continuation),
returning (center, rotation, iterations, converged).

Baselines:
    LUNewton            the paper's 8 equations (paper_method.system), np.linalg.solve (LU)
    RootHybr            scipy.optimize.root (MINPACK hybrj) on the core's 5 pose equations
    LeastSquares6Dof    scipy.optimize.least_squares on the 6-DOF pose (translation + rotation
                        vector), numeric Jacobian: what a user would write first
All lengths in mm, vehicle frame (ISO 8855: x forward, y left, z up); angles in rad.
"""

from dataclasses import dataclass
import math

import numpy as np
from scipy.optimize import least_squares, root
from scipy.spatial.transform import Rotation

from .reference import build, equations, exp_so3, LD, PoseModel
from ..core.solve import compile_scene, Continuation, linearize, paper_method, sweep


class CoreSolver:
    """Continuation of the core as a solve(travel) -> (center, rotation, iterations, ok)."""

    def __init__(self, scene, method, tol, step):
        self.cont = Continuation(scene, method=method, tol=tol, max_step=step)

    def solve(self, travel):
        sol = self.cont.solve(travel)
        return sol.wheel_center, sol.rotation, sol.iterations, sol.success


class ExudynSolver:
    """
    Static solves by exudyn (a multibody engine).

    The carrier is one rigid body (Euler parameters) held by distance constraints (sphere,
    circle), a GenericJoint that frees only the translation along the strut (line), and a
    coordinate constraint on Z_M.
    """

    def __init__(self, scene, tol):
        import exudyn as exu
        from exudyn import itemInterface as ii
        self.exu = exu
        self.sc = exu.SystemContainer()
        mbs = self.mbs = self.sc.AddSystem()
        ground = mbs.AddObject(ii.ObjectGround())
        m0 = scene.wheel_center
        self.node = mbs.AddNode(ii.NodeRigidBodyEP(referenceCoordinates=list(m0) + [1, 0, 0, 0]))
        body = mbs.AddObject(ii.ObjectRigidBody(mass=1.0, inertia=[1, 1, 1, 0, 0, 0],
                                                nodeNumber=self.node))
        for c in scene.constraints:
            if c.type == 'line':
                d = (c.base[0] - c.carrier) / np.linalg.norm(c.base[0] - c.carrier)
                a = np.cross(d, np.eye(3)[int(np.argmin(np.abs(d)))])
                a /= np.linalg.norm(a)
                frame = np.column_stack((a, np.cross(d, a), d))   # joint z along the strut
                on_carrier = mbs.AddMarker(ii.MarkerBodyRigid(
                    bodyNumber=body, localPosition=list(c.carrier - m0)))
                on_body = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=ground,
                                                           localPosition=list(c.base[0])))
                mbs.AddObject(ii.GenericJoint(markerNumbers=[on_carrier, on_body],
                                              constrainedAxes=[1, 1, 0, 0, 0, 0],
                                              rotationMarker0=frame, rotationMarker1=frame))
                continue
            on_carrier = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=body,
                                                             localPosition=list(c.carrier - m0)))
            for base in c.base:
                on_body = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=ground,
                                                              localPosition=list(base)))
                mbs.AddObject(ii.DistanceConstraint(
                    markerNumbers=[on_body, on_carrier],
                    distance=float(np.linalg.norm(c.carrier - base))))
        fixed = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=mbs.AddNode(ii.NodePointGround()),
                                                      coordinate=0))
        z_m = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=self.node, coordinate=2))
        self.travel = mbs.AddObject(ii.CoordinateConstraint(markerNumbers=[fixed, z_m]))
        mbs.Assemble()
        self.settings = exu.SimulationSettings()
        newton = self.settings.staticSolver.newton
        newton.relativeTolerance = newton.absoluteTolerance = tol
        self.settings.staticSolver.numberOfLoadSteps = 1
        self.settings.staticSolver.verboseMode = 0
        self.settings.solution.file.write = False      # no solution file: exudyn's fast path
        self.settings.solution.sensors.active = False
        self.settings.linearSolver.solverType = exu.LinearSolverType.EXUdense
        # Initialized once; each solve is then one SolveSteps from the last solution
        # (continuation), the cheapest way to ask exudyn for one position at a time.
        self.solver = exu.MainSolverStatic()
        self.solver.InitializeSolver(mbs, self.settings)

    def solve(self, travel):
        exu, mbs = self.exu, self.mbs
        mbs.SetObjectParameter(self.travel, 'offset', float(travel))
        ok = self.solver.SolveSteps(mbs, self.settings)
        center = np.array(mbs.GetNodeOutput(self.node, exu.OutputVariableType.Position))
        rotation = np.array(mbs.GetNodeOutput(self.node, exu.OutputVariableType.RotationMatrix)
                            ).reshape(3, 3)
        return center, rotation, int(self.solver.it.newtonStepsCount), bool(ok)


def exudyn_version():
    """Return exudyn's version, or None when the optional 'bench' extra is not installed."""
    try:
        import exudyn
    except ImportError:
        return None
    return exudyn.__version__


@dataclass(frozen=True)
class Entry:
    """
    One solver in the comparison.

    make(scene, tol, step) returns a solve(travel) object ('call') or a run(travels) ->
    (center, rotation, iterations, ok) function ('batch').
    """

    name: str
    kind: str
    make: object
    about: str


def entries(include_exudyn=True):
    """Return the entries compared, in report order."""
    out = [
        Entry('fast', 'call', lambda s, tol, step: CoreSolver(s, 'fast', tol, step),
              'pose Newton (5 unknowns, LU), tangent predictor; stops on the residual'),
        Entry('fast sweep', 'batch', lambda s, tol, step: _batch_sweep(s, tol),
              'the fast variant batched: knots, then all positions in one Newton solve'),
        Entry('paper', 'call', lambda s, tol, step: CoreSolver(s, 'paper', tol, step),
              '8 unknowns (M, N, P), Gauss-Jordan, step test of eqs. 11-12'),
        Entry('newton LU', 'call', lambda s, tol, step: LUNewton(s, tol),
              "the paper's 8 equations, np.linalg.solve, step test, no predictor"),
        Entry('scipy root', 'call', lambda s, tol, step: RootHybr(s, tol),
              'scipy.optimize.root hybr on the 5 pose equations, analytic Jacobian'),
        Entry('scipy lsq 6dof', 'call', lambda s, tol, step: LeastSquares6Dof(s, tol),
              'scipy.optimize.least_squares trf, 6-DOF pose, numeric Jacobian'),
    ]
    if include_exudyn and exudyn_version():
        out.append(Entry('exudyn', 'call', lambda s, tol, step: ExudynSolver(s, tol),
                         f'exudyn {exudyn_version()} static solver, rigid body + distance '
                         'constraints'))
    return out


def _batch_sweep(scene, tol):
    def run(travels):
        result = sweep(scene, travels, method='fast', tol=tol)
        return result.wheel_center, result.rotation, result.iterations, result.success
    return run


class LUNewton:
    """
    The paper's 8-unknown system (eqs. 1-4, 5-7, 10) solved by np.linalg.solve (LU).

    Same equations and stopping test (eqs. 11-12: largest coordinate change <= tol) as the
    paper variant; each solve starts from the previous answer, no predictor, no substeps.
    solve(travel) -> (center, rotation, iterations, converged).
    """

    def __init__(self, scene, tol, max_iter=25):
        self.model = paper_method.build(scene, compile_scene(scene))
        self.tol, self.max_iter = tol, max_iter
        m0, n0, p0 = self.model.m0, self.model.n0, self.model.p0
        self.x = np.concatenate((m0[:2], n0, p0))

    def solve(self, travel):
        z_m = self.model.m0[2] + travel
        x = self.x.copy()
        for iteration in range(1, self.max_iter + 1):
            f, jac = paper_method.system(self.model, x, z_m)
            if f is None:
                return None, None, iteration, False
            try:
                dx = np.linalg.solve(jac, -f)
            except np.linalg.LinAlgError:
                return None, None, iteration, False
            x = x + dx
            step = np.max(np.abs(dx))
            if not np.isfinite(step):
                return None, None, iteration, False
            if step <= self.tol:
                self.x = x
                m, n, p = paper_method.unpack(x, z_m)
                center, rotation = paper_method.pose_of_points(self.model, m, n, p)
                return center, rotation, iteration, True
        return None, None, self.max_iter, False


class RootHybr:
    """
    scipy.optimize.root (method 'hybr', MINPACK hybrj) on the core's 5 pose equations.

    Unknowns u = (x_M, y_M, w): the carrier is exp(w) R_prev. The analytic Jacobian is the
    core's (mechanism.linearize) times the left Jacobian of SO(3), exact for any w.
    xtol (relative, MINPACK's test) is tol / |u|, so the last step is about tol mm.
    solve(travel) -> (center, rotation, iterations (Jacobian evaluations), converged).
    """

    def __init__(self, scene, tol):
        self.mech = compile_scene(scene)
        self.tol = tol
        self.center, self.rotation = self.mech.design_center.copy(), np.eye(3)

    def solve(self, travel):
        z = self.mech.design_center[2] + travel
        rotation0 = self.rotation

        def fun(u):
            center = np.array([u[0], u[1], z])
            f, jac = linearize(self.mech, center, exp_so3(u[2:]) @ rotation0)
            return f, np.hstack((jac[:, :2], jac[:, 3:] @ _left_jacobian(u[2:])))

        u0 = np.concatenate((self.center[:2], np.zeros(3)))
        xtol = max(self.tol / max(np.linalg.norm(u0), 1.0), 1e-16)
        out = root(fun, u0, jac=True, method='hybr', options={'xtol': xtol})
        if not out.success or not np.all(np.isfinite(out.x)):
            return None, None, int(out.get('njev', 0)), False
        self.center = np.array([out.x[0], out.x[1], z])
        self.rotation = exp_so3(out.x[2:]) @ rotation0
        return self.center, self.rotation, int(out.njev), True


class LeastSquares6Dof:
    """
    scipy.optimize.least_squares on the plain 6-DOF pose: what a user would write first.

    x = (M, rotation vector of the carrier relative to design); residuals = the 5 guidance
    equations (true lengths) and Z_M - Z_M0 - travel; default method 'trf' and the default
    numeric ('2-point') Jacobian. xtol (relative) is tol / |x|; ftol and gtol are off so the
    step test alone stops it, as in the other entries.
    solve(travel) -> (center, rotation, iterations (function evaluations), converged).
    """

    def __init__(self, scene, tol):
        self.model = build(scene)
        self.m0 = self.model.m0.astype(float)
        self.f64 = _float_model(self.model)
        self.tol = tol
        self.x = np.concatenate((self.m0, np.zeros(3)))

    def solve(self, travel):
        def fun(x):
            return equations(self.f64, x[:3], Rotation.from_rotvec(x[3:]).as_matrix(), travel)

        xtol = max(self.tol / max(np.linalg.norm(self.x), 1.0), 1e-16)
        out = least_squares(fun, self.x, xtol=xtol, ftol=None, gtol=None)
        if out.status <= 0 or not np.all(np.isfinite(out.x)):
            return None, None, int(out.nfev), False
        self.x = out.x
        return out.x[:3].copy(), Rotation.from_rotvec(out.x[3:]).as_matrix(), int(out.nfev), True


def _float_model(model):
    """Return the PoseModel in float64 (for baselines that a user would write in double)."""
    fields = {k: (np.asarray(v, float) if isinstance(v, np.ndarray) and v.dtype == LD else v)
              for k, v in model.__dict__.items()}
    return PoseModel(**fields)


def _left_jacobian(w):
    """Left Jacobian of SO(3): d(exp(w)) = [J(w) dw]x exp(w)."""
    t2 = float(w @ w)
    k = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    if t2 < 1e-12:
        return np.eye(3) + 0.5 * k + k @ k / 6
    t = math.sqrt(t2)
    return np.eye(3) + (1 - math.cos(t)) / t2 * k + (t - math.sin(t)) / (t2 * t) * (k @ k)
