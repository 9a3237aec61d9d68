"""The sliding last link as a dynamics check: the mass matrix from Pinocchio.

A three-joint arm carries a link that slides by ``q`` along its own axis (mass ``m``,
transverse central moment ``I``); the last coordinate is cyclic when the mass matrix
``M(q)`` does not depend on it. Pinocchio computes ``M`` of the arm (composite rigid-body
algorithm); the counter-masses (two point masses ``M`` on the slide axis, moved by cranks)
are added from the Jacobians of their points. Four cases:

- ``spatial`` arm (turntable about the vertical, shoulder about a horizontal axis, slide
  along the upper arm): ``∂M/∂q ≠ 0``;
- ``planar`` arm (two joints about the vertical, slide along the vertical): the frame of the
  slide is the one the textbook names (``Ωx = Ωy = 0``, the rest of the arm moves in a plane
  perpendicular to the slide), ``∂M/∂q = 0`` without any counter-mass;
- ``spatial`` with two counter-masses on the laws at ``C_min``: with the crank angle ``η``
  as the coordinate (``q = q_max·cos η``; the laws are then cranks, the ±120° ones for
  ``M = m``), ``∂M/∂η = 0``: the centre of mass and the transverse inertia of the slide
  assembly are constant, and so is its own kinetic-energy coefficient;
- one counter-mass: it keeps the centre of mass (then the inertia grows as ``q²``) or the
  inertia (then only for ``|q| ≤ √((C − I)/m)``, a bounded interval, and the centre of mass
  moves), never both.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mechbase import Row

from .countermass import c_min
from ..errors import InvalidInput

__all__ = ["sliding_arm_urdf", "slide_dynamics", "SlideDynamics", "MassMatrixCase", "OneCounterMass"]


@dataclass(frozen=True)
class MassMatrixCase(Row):
    """How the mass matrix depends on the last coordinate in one case (relative to its largest entry).

    ``max_dM`` is the largest ``|∂M/∂x_n|`` at the sampled configurations (central differences),
    ``max_change_relative`` the largest change of ``M`` along the coordinate's whole range there:
    a check at random configurations (``samples`` of them), not an extreme over the workspace.
    """

    coordinate: str
    max_dM: float
    largest_entry: float
    max_change_relative: float

    row_keys = ("coordinate", "max_dM", "max_dM_relative", "max_change_relative", "largest_entry")

    @property
    def max_dM_relative(self) -> float:
        return self.max_dM / self.largest_entry



@dataclass(frozen=True)
class OneCounterMass(Row):
    """One counter-mass on a slide: keeping the centre of mass (the inertia grows, as the text says) or
    keeping the inertia ``C`` (valid only for ``|q| ≤ valid_interval``)."""

    keeps_centre_of_mass: str
    keeps_inertia_C: float
    valid_interval: float
    valid_interval_text: str


@dataclass(frozen=True)
class SlideDynamics(Row):
    """What :func:`slide_dynamics` finds: each case's dependence of ``M`` on the last coordinate."""

    arm: str
    samples: int
    seed: int
    m: float
    inertia: float
    M: float
    q_max: float
    C_min: float
    cases: dict[str, MassMatrixCase]

    row_keys = ("arm", "samples", "seed", "C_min", "cases", "one_mass", "crank_laws")
    crank_laws = "z1,2 = q_max·(−m·cos η ± √(m² + 2mM)·sin η)/(2M), q = q_max·cos η"

    @property
    def one_mass_interval(self) -> float:
        """One counter-mass keeping the inertia C_min: real only for ``|q| ≤ √((C − I)/m)``."""
        return math.sqrt(max(self.C_min - self.inertia, 0.0) / self.m)

    @property
    def one_mass(self) -> OneCounterMass:
        """What one counter-mass keeps, and what it cannot."""
        m, inertia, M, q_max = self.m, self.inertia, self.M, self.q_max
        return OneCounterMass(
            f"inertia I + m(1 + m/M)·q² grows from {inertia:.4g} to {inertia + m * (1 + m / M) * q_max ** 2:.4g} "
            "kg·m² over the stroke", self.C_min, self.one_mass_interval,
            f"|q| ≤ √((C − I)/m) = {self.one_mass_interval:.4g} m, and its centre of mass moves")


def _inertial(m: float, com, diag) -> str:
    return (f'<inertial><origin xyz="{com[0]!r} {com[1]!r} {com[2]!r}"/><mass value="{m!r}"/>'
            f'<inertia ixx="{diag[0]!r}" ixy="0" ixz="0" iyy="{diag[1]!r}" iyz="0" izz="{diag[2]!r}"/></inertial>')


def sliding_arm_urdf(kind: str, m: float, inertia: float, q_max: float, length: float = 0.5,
                     parent_mass: float = 10.0) -> str:
    """URDF of the three-joint arm whose last link slides (see the module docstring)."""
    L, mp = float(length), float(parent_mass)
    rod = mp * L * L / 12
    axial = 0.1 * inertia
    if kind == "spatial":
        joints = [("revolute", "0 0 1", (0, 0, 0)), ("revolute", "0 1 0", (0, 0, L)), ("prismatic", "1 0 0", (L, 0, 0))]
        links = [_inertial(mp, (0, 0, L / 2), (rod, rod, 1e-3 * rod)),
                 _inertial(mp, (L / 2, 0, 0), (1e-3 * rod, rod, rod)),
                 _inertial(m, (0, 0, 0), (axial, inertia, inertia))]
    elif kind == "planar":
        joints = [("revolute", "0 0 1", (0, 0, 0)), ("revolute", "0 0 1", (L, 0, 0)), ("prismatic", "0 0 1", (L, 0, 0))]
        links = [_inertial(mp, (L / 2, 0, 0), (1e-3 * rod, rod, rod)),
                 _inertial(mp, (L / 2, 0, 0), (1e-3 * rod, rod, rod)),
                 _inertial(m, (0, 0, 0), (inertia, inertia, axial))]
    else:
        raise InvalidInput(f"the sliding-link arm is 'spatial' or 'planar', not {kind!r}.")
    out = ['<robot name="sliding_arm">', '<link name="l0"/>']
    for i, ((jt, axis, xyz), inert) in enumerate(zip(joints, links), start=1):
        lim = f'<limit lower="{-q_max!r}" upper="{q_max!r}" effort="1" velocity="1"/>' if jt == "prismatic" else \
            '<limit lower="-3.2" upper="3.2" effort="1" velocity="1"/>'
        out.append(f'<link name="l{i}">{inert}</link>')
        out.append(f'<joint name="j{i}" type="{jt}"><parent link="l{i - 1}"/><child link="l{i}"/>'
                   f'<origin xyz="{xyz[0]!r} {xyz[1]!r} {xyz[2]!r}"/><axis xyz="{axis}"/>{lim}</joint>')
    out.append("</robot>")
    return "\n".join(out)


class _Arm:
    def __init__(self, kind, m, inertia, q_max, length, parent_mass):
        from ..model.urdf import pinocchio_model

        self.model = pinocchio_model(sliding_arm_urdf(kind, m, inertia, q_max, length, parent_mass))
        self.data = self.model.createData()
        self.axis = np.array([1.0, 0.0, 0.0]) if kind == "spatial" else np.array([0.0, 0.0, 1.0])

    def mass_matrix(self, q: np.ndarray) -> np.ndarray:
        import pinocchio as pin

        M = pin.crba(self.model, self.data, np.asarray(q, dtype=float))
        return np.triu(M) + np.triu(M, 1).T

    def point_jacobian(self, q: np.ndarray, z: float) -> np.ndarray:
        """Linear-velocity Jacobian (3 × 2) over the first two joints of the point ``z`` on the slide
        axis (carried by link 2, measured from the slide's mid-stroke origin)."""
        import pinocchio as pin

        q = np.asarray(q, dtype=float)
        pin.computeJointJacobians(self.model, self.data, q)
        pin.framesForwardKinematics(self.model, self.data, q)
        J = pin.getJointJacobian(self.model, self.data, 2, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        o2 = self.data.oMi[2]
        origin3 = o2.act(self.model.jointPlacements[3].translation)
        p = origin3 + o2.rotation @ (z * self.axis)
        r = p - o2.translation
        v, w = J[:3, :2], J[3:, :2]
        return v - np.cross(r, w.T).T  # v_p = v_o + ω × r = v_o − r × ω


def _crank_laws(m: float, M: float, q_max: float):
    """The C_min laws as cranks in η: z1,2 = q_max·(−m·cos η ± s·sin η)/(2M), s = √(m² + 2mM)."""
    s = math.sqrt(m * m + 2 * m * M)

    def z(eta):
        c, sn = math.cos(eta), math.sin(eta)
        return (q_max * (-m * c + s * sn) / (2 * M), q_max * (-m * c - s * sn) / (2 * M))

    def dz(eta):
        c, sn = math.cos(eta), math.sin(eta)
        return (q_max * (m * sn + s * c) / (2 * M), q_max * (m * sn - s * c) / (2 * M))

    return z, dz


def slide_dynamics(m: float, inertia: float, M: float, q_max: float, kind: str = "spatial", length: float = 0.5,
                   parent_mass: float = 10.0, samples: int = 200, seed: int = 0) -> SlideDynamics:
    """How the mass matrix depends on the last coordinate, without and with counter-masses.

    For each case: ``max |∂M/∂x_n|`` by central differences and the largest change of ``M``
    along the last coordinate's whole range at fixed other joints, both relative to the
    largest entry of ``M``, over ``samples`` random configurations (seeded).
    """
    if samples < 1:
        raise InvalidInput(f"the dynamics check needs at least one sample, not {samples}.")
    for name, v in (("link mass m", m), ("counter-mass M", M), ("stroke q_max", q_max), ("length", length),
                    ("parent mass", parent_mass)):
        if not (math.isfinite(v) and v > 0):
            raise InvalidInput(f"the {name} must be a positive number, not {v}.")
    rng = np.random.default_rng(seed)
    arm = _Arm(kind, m, inertia, q_max, length, parent_mass)
    zs, dzs = _crank_laws(m, M, q_max)
    C = c_min(m, inertia, M, q_max)

    def bare(x):  # coordinates (q1, q2, q): Pinocchio alone
        return arm.mass_matrix(x)

    def countered(x):  # coordinates (q1, q2, η): the slide driven by a crank, two counter-masses
        eta = x[2]
        q = q_max * math.cos(eta)
        T = np.diag([1.0, 1.0, -q_max * math.sin(eta)])
        out = T.T @ arm.mass_matrix([x[0], x[1], q]) @ T
        for z, dz in zip(zs(eta), dzs(eta)):
            J = np.zeros((3, 3))
            J[:, :2] = arm.point_jacobian([x[0], x[1], q], z)
            J[:, 2] = _axis_world(arm, [x[0], x[1], q]) * dz
            out += M * J.T @ J
        return out

    def one_mass_com(x):  # one counter-mass keeping the centre of mass: z = −m·q/M
        q = x[2]
        J = np.zeros((3, 3))
        J[:, :2] = arm.point_jacobian(x, -m * q / M)
        J[:, 2] = _axis_world(arm, x) * (-m / M)
        return arm.mass_matrix(x) + M * J.T @ J

    cases = {"without counter-masses": (bare, "q", (-q_max, q_max))}
    if kind == "spatial":
        cases["two counter-masses, crank angle η"] = (countered, "η", (0.0, 2 * math.pi))
        cases["one counter-mass keeping the centre of mass"] = (one_mass_com, "q", (-q_max, q_max))
    out_cases = {}
    h = 1e-4  # of the coordinate's range: central differences, exact for the quadratic dependence on q
    for label, (fn, coord, (lo, hi)) in cases.items():
        worst_d = worst_spread = scale = 0.0
        for _ in range(samples):
            x = np.array([rng.uniform(-math.pi, math.pi), rng.uniform(-math.pi, math.pi), rng.uniform(lo, hi)])
            Mx = fn(x)
            scale = max(scale, float(np.max(np.abs(Mx))))
            dx = np.array([0.0, 0.0, h * (hi - lo)])
            dM = (fn(x + dx) - fn(x - dx)) / (2 * dx[2])
            worst_d = max(worst_d, float(np.max(np.abs(dM))))
            along = [fn(np.array([x[0], x[1], t])) for t in np.linspace(lo, hi, 9)]
            worst_spread = max(worst_spread, float(max(np.max(np.abs(a - along[0])) for a in along)))
        out_cases[label] = MassMatrixCase(coord, worst_d, scale, worst_spread / scale)
    return SlideDynamics(kind, samples, seed, m, inertia, M, q_max, C, out_cases)


def _axis_world(arm: _Arm, q) -> np.ndarray:
    import pinocchio as pin

    pin.forwardKinematics(arm.model, arm.data, np.asarray(q, dtype=float))
    return arm.data.oMi[2].rotation @ arm.axis
