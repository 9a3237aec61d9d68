"""Motion of dimensioned planar mechanisms: position, velocity and acceleration over an input sweep,
range of motion, dead and toggle positions, transmission angles, coupler curves.

A :class:`Linkage` is a chain with its joint kinds, a frame, W input joints and the position of
every joint in one assembled pose.  :func:`sweep` moves it through its input range on the assembly
branch of that pose (closed forms for the Assur dyads RRR, RRP, PRR, RPR, PRP; Newton with
continuation on the loop-closure equations for higher groups); :func:`motion_range` says whether the
input turns fully and finds the branch's ends to 1e-9.  This floor imports only the chain types
(docs/motion.md).

Example
-------
>>> from synth.motion import Linkage, sweep
>>> from synth.structure.chain import Chain, Mechanism
>>> crank_rocker = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,),
...                        [[0, 0], [4, 0], [1, 0], [3.5, 3]])       # joints 0-1 0-3 1-2 2-3
>>> motion = sweep(crank_rocker, steps=7)
>>> motion.joints.shape, motion.stopped
((7, 4, 2), None)
"""

from .._lazy import lazy_exports

_WHERE = {
    "Linkage": "._linkage", "read_linkage": "._linkage", "linkage_from_pose": "._pose", "joint_name": "._linkage",
    "Motion": "._sweep", "MotionRange": "._sweep", "sweep": "._sweep", "sweep_grid": "._sweep",
    "motion_range": "._sweep", "assemble": "._sweep", "pose_branch": "._sweep", "Branch": "._sweep",
    "LinkPoses": "._sweep", "link_poses": "._sweep",
    "LinkRates": "._sweep", "link_rates": "._sweep", "refine_extreme": "._sweep",
}

__all__ = list(_WHERE)


__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
