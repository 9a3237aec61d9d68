"""Counterweight balancing: put the centre of mass of each joint's sub-arm on the joint's axis.

Working from the tip to the base, each revolute joint gets a point mass on its own link,
``arm`` metres from the axis, opposite the part of the sub-arm's centre of mass that lies
off the axis. Once the sub-arm beyond a joint is balanced, its centre of mass sits on that
joint's axis, a point fixed in the link before it, so the sub-arm of the joint before is a
rigid body for this purpose: after the pass no joint carries any gravity torque, in any
configuration. A turntable (an axis that stays vertical) needs none; a slide moves the centre
of mass along its stroke and no fixed mass can follow it.

The same algorithm serves every arm: it runs on the arm's Pinocchio model (a TOML arm is
written as URDF first). The result keeps the balanced model, so the added inertia each joint
sees and the motor torque it costs can be computed from it.

Examples
--------
>>> from balance.model.arm import Arm, Link
>>> cw = counterweights(Arm((Link("l", "revolute", 1.0, 10.0, 0.5),)), {0: 0.25}, samples=20)
>>> round(cw.added_weight, 9), cw.max_residual < 1e-12
(20.0, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from mechbase import Row

from ..errors import InvalidArm
from ..extremes import box_extremes
from ..model.arm import Arm, ArmModel
from ..model.urdf import UrdfArm, pinocchio_gravity

__all__ = ["Counterweight", "Counterweights", "counterweights", "place_counterweights"]


@dataclass(frozen=True)
class Counterweight(Row):
    """One counterweight: a point mass on the link a joint moves.

    Attributes
    ----------
    link : str
        The link (or joint) it sits on.
    coordinate : str
        ``q1 … qn``: the joint it balances.
    mass, weight : float
        kg and N.
    arm : float
        Its distance from the joint's axis (m).
    position : tuple of float
        Where it sits: for a planar TOML arm ``(along the link, to its left)`` from the joint
        (m); for a URDF arm ``(x, y, z)`` in the joint's frame.
    point : tuple of float
        ``(x, y, z)`` in the frame of the joint of the arm's Pinocchio model (``coordinate``'s).
    """

    link: str
    coordinate: str
    mass: float
    weight: float
    arm: float
    position: tuple[float, ...]
    point: tuple[float, float, float] = (0.0, 0.0, 0.0)

    row_keys = ("link", "coordinate", "weight", "mass", "arm", "position")


@dataclass(frozen=True)
class Counterweights(Row):
    """What :func:`counterweights` finds for an arm (or why it cannot).

    ``max_residual`` (N·m) is the largest gravity force left over the workspace, a true extreme
    (:mod:`balance.extremes`), ``potential_spread`` the spread of the potential and ``worst`` the
    configuration of the largest force (all three None when not checked:
    :func:`place_counterweights`); ``balanced`` is the arm's Pinocchio model with the counterweights.
    """

    available: bool
    reason: str | None = None
    weights: tuple[Counterweight, ...] = ()
    added_weight: float = 0.0
    arm_weight: float = 0.0
    max_residual: float | None = None
    potential_spread: float | None = None
    worst: tuple[float, ...] | None = None
    balanced: UrdfArm | None = field(default=None, repr=False, compare=False)

    @property
    def ratio(self) -> float:
        """Added weight over the arm's own."""
        return self.added_weight / self.arm_weight if self.arm_weight > 0 else math.inf

    @property
    def row_keys(self) -> tuple[str, ...]:
        """The row: why not, or the weights and what they leave."""
        if not self.available:
            return ("available", "reason")
        return ("available", "weights", "added_weight", "arm_weight", "ratio", "max_residual", "potential_spread",
                "worst")


def _default_arm(arm: ArmModel, j: int, pa: UrdfArm, axis_point: np.ndarray, axis: np.ndarray) -> float:
    """Half the link: a TOML link's length, or a URDF joint's distance to the next joint off its axis."""
    if isinstance(arm, Arm):
        length = arm.links[j].length
        return length / 2 if length > 0 else 0.1
    model = pa.model
    children = [k for k in range(1, model.njoints) if model.parents[k] == j + 1]
    for k in children:
        off = model.jointPlacements[k].translation - axis_point
        off = off - (off @ axis) * axis
        if np.linalg.norm(off) > 1e-9:
            return float(np.linalg.norm(off)) / 2
    return 0.1


def _subtree_com(model, data, joint: int) -> tuple[float, np.ndarray]:
    """Mass and centre of mass (world) of everything the joint ``joint`` carries."""
    mass, moment = 0.0, np.zeros(3)
    for k in range(joint, model.njoints):
        a = k
        while a > joint:
            a = model.parents[a]
        if a != joint:
            continue
        inertia = model.inertias[k]
        mass += inertia.mass
        moment += inertia.mass * data.oMi[k].act(inertia.lever)
    return mass, (moment / mass if mass > 0 else np.zeros(3))


def counterweights(arm: ArmModel, arms: dict[int, float] | None = None, samples: int = 1000, seed: int = 0,
                   g: float = 9.80665) -> Counterweights:
    """Counterweights that balance ``arm`` statically, with the added weight and a check: the
    largest gravity force left over the workspace and the spread of the potential.

    Parameters
    ----------
    arm : ArmModel
        A TOML arm or a URDF arm. An arm with a slide is answered with ``available=False``
        and the reason.
    arms : dict of int to float, optional
        Distance (m) from each joint's axis at which its counterweight sits; a joint missing
        from the dict uses half its link (:func:`_default_arm`).
    samples, seed : int
        Starts of the search for the largest residual over the workspace.
    g : float
        Gravity (m/s²) of a TOML arm's model.

    Returns
    -------
    Counterweights
    """
    cw = place_counterweights(arm, arms, g)
    if not cw.available:
        return cw
    base, balanced = pinocchio_gravity(arm, g), cw.balanced
    lo, hi = arm.box
    pts = arm.sample(samples, seed)
    scale = max(float(np.max(np.abs(base.gravity_forces(pts[:50])))), 1e-300)
    ext = box_extremes(balanced.gravity_forces, lo, hi, pts, floor=1e-11 * scale)
    per = [max(-a.value, b.value) for a, b in ext]
    j_worst = int(np.argmax(per))
    worst = ext[j_worst][0].at if -ext[j_worst][0].value > ext[j_worst][1].value else ext[j_worst][1].at
    (u_lo, u_hi), = box_extremes(lambda x: balanced.potential(x)[:, None] - balanced.potential(pts[:1])[0],
                                 lo, hi, pts, floor=1e-11 * scale)
    return replace(cw, max_residual=max(per), potential_spread=u_hi.value - u_lo.value, worst=tuple(worst))


def place_counterweights(arm: ArmModel, arms: dict[int, float] | None = None, g: float = 9.80665) -> Counterweights:
    """The counterweights of :func:`counterweights` without its check (``max_residual``,
    ``potential_spread`` and ``worst`` are None): for a caller that measures what they leave
    in its own way, as ``balance compare`` does over the workspace and the payload range.

    Examples
    --------
    >>> from balance.model.arm import Arm, Link
    >>> cw = place_counterweights(Arm((Link("l", "revolute", 1.0, 10.0, 0.5),)), {0: 0.25})
    >>> round(cw.added_weight, 9), cw.max_residual
    (20.0, None)
    """
    import pinocchio as pin

    if any(c.joint == "prismatic" for c in arm.coordinates):
        return Counterweights(False, "a prismatic link moves its centre of mass along the stroke; no fixed "
                                     "counterweight can follow it (use springs or the counter-mass mechanism).")
    arms = arms or {}
    base = pinocchio_gravity(arm, g)
    model = base.model.copy()
    data = model.createData()
    q0 = base.config(np.zeros(arm.n))
    pin.forwardKinematics(model, data, q0)
    pin.computeJointJacobians(model, data, q0)
    up = -model.gravity.linear / np.linalg.norm(model.gravity.linear)
    rows = []
    vertical_so_far = True
    axes = []
    for j in range(1, model.njoints):  # which joints keep a vertical axis in every configuration
        jac = np.asarray(pin.getJointJacobian(model, data, j, pin.ReferenceFrame.WORLD)).reshape(6, model.nv)
        w = jac[3:, model.joints[j].idx_v]
        vertical = abs(abs(w @ up) - np.linalg.norm(w)) < 1e-12 and vertical_so_far and model.parents[j] == j - 1
        vertical_so_far = vertical
        axes.append((w / np.linalg.norm(w), vertical))
    for j in range(model.njoints - 1, 0, -1):
        axis_w, vertical = axes[j - 1]
        if vertical:
            continue
        pin.forwardKinematics(model, data, q0)
        mass, com = _subtree_com(model, data, j)
        frame = data.oMi[j]
        axis = frame.rotation.T @ axis_w
        c = frame.actInv(com)
        off = c - (c @ axis) * axis
        if mass == 0 or np.linalg.norm(off) <= 1e-12 * max(1.0, np.linalg.norm(c)):
            continue
        b = arms.get(j - 1)
        if b is None:
            b = _default_arm(arm, j - 1, base, np.zeros(3), axis)
        if not (math.isfinite(b) and b > 0):
            raise InvalidArm(f"joint q{j}: the counterweight's distance from the axis must be positive, not {b}.")
        m_cw = mass * np.linalg.norm(off) / b
        p = -b * off / np.linalg.norm(off) + (c @ axis) * axis
        model.inertias[j] = model.inertias[j] + pin.Inertia(m_cw, p, np.zeros((3, 3)))
        rows.append((j - 1, m_cw, b, p))
    weights = tuple(_row(arm, j, m, b, p, g) for j, m, b, p in sorted(rows))
    own = sum(float(model.inertias[k].mass) for k in range(1, model.njoints)) - sum(w.mass for w in weights)
    return Counterweights(True, None, weights, sum(w.weight for w in weights), own * g, None, None, None,
                          base.copy(model))


def _row(arm: ArmModel, j: int, m: float, b: float, p: np.ndarray, g: float) -> Counterweight:
    """A counterweight in the words of the arm it was given as (planar link coordinates for TOML)."""
    if isinstance(arm, Arm):
        u0 = np.array([0.0, 0.0, 1.0]) if arm.zero == "vertical" else np.array([1.0, 0.0, 0.0])
        nrm = np.array([-1.0, 0.0, 0.0]) if arm.zero == "vertical" else np.array([0.0, 0.0, 1.0])
        position = (float(p @ u0) + 0.0, float(p @ nrm) + 0.0)
        link = arm.links[j].name
    else:
        position = tuple(float(v) + 0.0 for v in p)
        link = arm.link_name(j)
    return Counterweight(link, f"q{j + 1}", float(m), float(m * g), float(b), position,
                         tuple(float(v) + 0.0 for v in p))
