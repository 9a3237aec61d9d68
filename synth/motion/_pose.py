"""Linkages from any joint positions (a drawing's layout, say), moved off a locked pose if asked."""

from __future__ import annotations

import numpy as np

from ..errors import BadPose, LockedMechanism, MotionError
from ..structure.chain import Mechanism
from ..structure.joints import MESH, PRISMATIC, REVOLUTE
from ._linkage import Linkage
from ._system import check_movable

__all__ = ["linkage_from_pose"]


def linkage_from_pose(mechanism: Mechanism, positions, *, inputs=None, slides=None, meshes=None, tracers=None,
                      nudge: bool = False) -> Linkage:
    """A linkage from any joint positions (for instance a drawing's layout).

    Parameters
    ----------
    mechanism : Mechanism
        Chain and frame; its ``input_link``, if set, chooses the input joint.
    positions : array (J, 2)
        A position per joint, in ``chain.joints`` order.
    inputs : sequence of int, optional
        Input joints; by default the joint of the frame and ``mechanism.input_link``, else the
        frame's first W joints that join it to one moving link each (revolute before prismatic).
    slides : dict, optional
        Sliding directions; by default each prismatic joint slides along the line from its point
        to the first other joint of its links (in the chain's order) not at that point (a guess).
    meshes, tracers : dict, optional
        As in :class:`Linkage`.
    nudge : bool
        If the pose is locked (the inputs cannot move it: a singular pose, as drawings of
        symmetric chains often are), move the joints a little at random (fixed seed) until it
        moves, and say so in :attr:`Linkage.note`; otherwise such a pose raises LockedMechanism.

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = linkage_from_pose(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), [[0, 0], [4, 0], [1, 0], [3, 2]])
    >>> lk.inputs, lk.note
    ((0,), None)
    """
    chain, frame = mechanism.chain, mechanism.frame
    try:
        points = np.array(positions, dtype=float)
    except (TypeError, ValueError):
        raise BadPose("the joint positions must be numbers, one [x, y] per joint") from None
    if points.shape != (len(chain.joints), 2):
        raise BadPose(f"the pose needs one [x, y] per joint ({len(chain.joints)}), not an array of shape {points.shape}")
    kinds = chain.kinds
    if inputs is None:
        on_frame = [k for k, j in enumerate(chain.joints) if len(j) == 2 and frame in j and kinds[k] != MESH]
        if mechanism.input_link is not None:
            on_frame.sort(key=lambda k: mechanism.input_link not in chain.joints[k])
        else:
            on_frame.sort(key=lambda k: (kinds[k] != REVOLUTE, k))
        inputs = on_frame[: max(chain.dof, 0)]  # (each drives its own link: two joints never join the same links)
    if slides is None:
        slides = {}
        for k, kind in enumerate(kinds):
            if kind == PRISMATIC:
                others = [m for x in chain.joints[k] for m in range(len(chain.joints)) if m != k and x in chain.joints[m]]
                d = points[others] - points[k]
                far = d[np.hypot(d[:, 0], d[:, 1]) > 1e-6 * max(float(np.ptp(points, axis=0).max()), 1e-12)]
                slides[k] = tuple(far[0]) if len(far) else (1.0, 0.0)
    linkage = Linkage(mechanism, tuple(inputs), points, slides, meshes or {}, tracers or {})
    why = check_movable(linkage)
    if why is None:
        return linkage
    if not nudge:
        raise LockedMechanism(why)
    rng = np.random.default_rng(0)
    for attempt in range(1, 41):
        size = 0.02 * linkage.scale * (1 + attempt // 10)
        moved = points + rng.uniform(-size, size, points.shape)
        try:
            trial = Linkage(mechanism, tuple(inputs), moved, slides, meshes or {}, tracers or {})
        except MotionError:
            continue
        if check_movable(trial) is None:
            shift = float(np.hypot(*(moved - points).T).max())
            note = (f"the given pose is locked ({why}); the joints were moved by up to {shift:.3g} "
                    f"({shift / linkage.scale:.1%} of the mechanism's size) to a nearby pose that moves")
            return Linkage(mechanism, tuple(inputs), moved, slides, meshes or {}, tracers or {}, note)
    raise LockedMechanism(f"the pose is locked ({why}) and no nearby pose moves")
