"""Sweeps of a linkage's inputs, its range of motion, and the result types."""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np

from ._linkage import Linkage, joint_name

__all__ = ["Motion", "MotionRange", "sweep", "sweep_grid", "motion_range", "assemble"]


@dataclass(frozen=True, eq=False)
class Motion:
    """The result of a sweep: where every joint and tracer point is at each step.

    Attributes
    ----------
    linkage : Linkage
    inputs : ndarray (S, W)
        Input values per step: a revolute input's angle in rad, a prismatic input's displacement.
    joints : ndarray (S, J, 2)
        Every joint's position (a prismatic joint: its point carried by the joint's first link).
    tracers : dict str -> ndarray (S, 2)
    velocities, accelerations : ndarray (S, J, 2) or None
        Per unit input rate (rad/s or length/s), input accelerating at zero; None unless asked for.
        With W > 1, velocities are (S, W, J, 2): one per input.  NaN where the step is a dead position.
    stopped : str or None
        One sentence when the sweep ended at a dead or singular position (with the input there).
    transmission : dict
        Per closed-form dyad (key ``"links i, j"``): ``min`` and ``max`` transmission angle (rad,
        π/2 best, 0 or π locked) and the inputs ``at_min``, ``at_max`` where they occur.
    angles : ndarray (S, n)
        Each link's rotation from the pose (rad).
    """

    linkage: Linkage
    inputs: np.ndarray
    joints: np.ndarray
    tracers: dict
    angles: np.ndarray
    velocities: np.ndarray | None = None
    accelerations: np.ndarray | None = None
    stopped: str | None = None
    transmission: dict = field(default_factory=dict)

    @property
    def steps(self) -> int:
        return len(self.inputs)

    def extent(self) -> dict[str, tuple[float, float, float, float]]:
        """Each tracer's curve extent ``(x_min, y_min, x_max, y_max)`` (NaN steps left out)."""
        out = {}
        for name, xy in self.tracers.items():
            ok = xy[np.isfinite(xy).all(axis=1)]
            out[name] = tuple(float(v) for v in (*ok.min(axis=0), *ok.max(axis=0))) if len(ok) else (math.nan,) * 4
        return out

    def rows(self) -> Iterator[dict]:
        """One JSON-able dict per step: ``step``, ``input`` (a list for W > 1), each joint's ``x``/``y``
        keyed by its name (``"1-2.x"``), each tracer's, and velocities (``"1-2.vx"``) and accelerations
        (``"1-2.ax"``) where computed (None where undefined)."""
        chain = self.linkage.chain
        names = [joint_name(chain, k) for k in range(len(chain.joints))]

        def num(v):
            v = float(v)
            return v if math.isfinite(v) else None

        for s in range(self.steps):
            row = {"step": s, "input": num(self.inputs[s, 0]) if self.inputs.shape[1] == 1
                   else [num(v) for v in self.inputs[s]]}
            for k, name in enumerate(names):
                row[f"{name}.x"], row[f"{name}.y"] = num(self.joints[s, k, 0]), num(self.joints[s, k, 1])
            for name, xy in self.tracers.items():
                row[f"{name}.x"], row[f"{name}.y"] = num(xy[s, 0]), num(xy[s, 1])
            for label, values in (("v", self.velocities), ("a", self.accelerations)):
                if values is not None and values.ndim == 3:
                    for k, name in enumerate(names):
                        row[f"{name}.{label}x"], row[f"{name}.{label}y"] = num(values[s, k, 0]), num(values[s, k, 1])
            yield row


@dataclass(frozen=True)
class MotionRange:
    """How far the input of a 1-DOF linkage moves on the branch of its pose.

    Attributes
    ----------
    full_rotation : bool
        The (revolute) input turns fully: a crank.
    limits : (float, float) or None
        The input's lower and upper limits (rad or length) where it does not turn fully, each a
        dead position located to 1e-9.
    dead_positions : tuple of (float, str)
        The inputs where the branch ends, with a sentence naming the group that locks.
    toggles : tuple of (float, int)
        Inputs where a link jointed to the frame (an output) stops and turns back, and that link:
        a dead position if that link drives.
    grashof : str or None
        For a four-bar of revolute joints: its Grashof class, e.g. ``"crank-rocker"``.
    """

    full_rotation: bool
    limits: tuple[float, float] | None
    dead_positions: tuple = ()
    toggles: tuple = ()
    grashof: str | None = None


def sweep(linkage: Linkage, *, steps: int = 360, start: float | None = None, stop: float | None = None,
          velocities: bool = False, accelerations: bool = False) -> Motion:
    """Move a 1-DOF linkage through its input range on the assembly branch of its pose.

    Parameters
    ----------
    linkage : Linkage
    steps : int
        Number of input values, start and stop included (2 … 10 000 000).
    start, stop : float, optional
        Input range.  Default: a crank turns once from its pose; a rocker goes from its lower to
        its upper limit.
    velocities, accelerations : bool
        Also compute them (linear solves, per unit input rate).
    """
    raise NotImplementedError


def sweep_grid(linkage: Linkage, ranges, *, steps=None, velocities: bool = False) -> Motion:
    """Move a W-DOF linkage over a grid of its inputs (W ≥ 1): ``ranges`` one (start, stop) per
    input, ``steps`` one count per input; cells the pose's branch does not reach are NaN."""
    raise NotImplementedError


def motion_range(linkage: Linkage) -> MotionRange:
    """Whether the input of a 1-DOF linkage turns fully, its limits, dead and toggle positions."""
    raise NotImplementedError


def assemble(linkage: Linkage, value: float) -> Linkage:
    """The same linkage posed at input ``value`` on its branch (CannotAssemble if it cannot reach it)."""
    raise NotImplementedError
