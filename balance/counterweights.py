"""Counterweight balancing: put the centre of mass of each link and everything beyond it
on the link's joint axis, working from the tip to the base.
"""

from __future__ import annotations

import math
from dataclasses import replace



from .arm import Arm, Load
from .errors import InvalidArm
from .static import check_terms

__all__ = ["counterweights"]


def counterweights(arm: Arm, arms: dict[int, float], samples: int = 1000, seed: int = 0) -> dict:
    """Counterweights that balance ``arm`` statically, with the added weight and a check.

    Parameters
    ----------
    arm : Arm
        Revolute (and base vertical-axis) joints only: a sliding link moves its centre of
        mass along the stroke, which no fixed counterweight can follow (see
        :mod:`balance.countermass`).
    arms : dict of int to float
        Distance (m) behind each in-plane joint at which its counterweight sits; links
        missing from the dict use half their length (or 0.1 m for a zero length).
    samples, seed : int
        Residual check over random configurations.

    Returns
    -------
    dict
        ``available``, ``weights`` (one per in-plane link: ``link``, ``weight``, ``arm``,
        ``position`` in link coordinates), ``added_weight``, ``arm_weight``, ``ratio``,
        ``max_residual`` (N·m) after adding them.

    Examples
    --------
    >>> from balance.arm import Link
    >>> cw = counterweights(Arm((Link("l", "revolute", 1.0, 10.0, 0.5),)), {0: 0.25}, samples=20)
    >>> cw["added_weight"], cw["max_residual"] < 1e-12
    (20.0, True)
    """
    if any(ln.joint == "prismatic" for ln in arm.links):
        return {
            "available": False,
            "reason": "a prismatic link moves its centre of mass along the stroke; no fixed "
            "counterweight can follow it (use springs or the counter-mass mechanism).",
        }
    masses = arm.masses()
    added: list[Load] = []
    rows = []
    for j in range(arm.n - 1, -1, -1):
        ln = arm.links[j]
        if ln.joint != "revolute":
            continue
        b = arms.get(j, ln.length / 2 if ln.length > 0 else 0.1)
        if not (math.isfinite(b) and b > 0):
            raise InvalidArm(f"link '{ln.name}': the counterweight arm must be positive, not {b}.")
        # first moment (in link j's frame) of everything beyond joint j, counterweights included
        sx = sy = 0.0
        for link, g, s, t in masses + [(ld.link, ld.weight, ld.at, ld.lateral) for ld in added]:
            if link == j:
                sx += g * s
                sy += g * t
            elif link > j:
                sx += g * ln.length  # everything beyond sits (as a resultant) at the next joint
        mom = math.hypot(sx, sy)
        if mom == 0.0:
            continue
        w = mom / b
        at, lat = -b * sx / mom, -b * sy / mom
        added.append(Load(j, w, at, lat, False, f"counterweight {ln.name}"))
        rows.append({"link": ln.name, "weight": w, "arm": b, "position": [at, lat]})
    rows.reverse()
    balanced = replace(arm, loads=arm.loads + tuple(added))
    chk = check_terms(balanced, [], samples=samples, seed=seed)
    total = sum(r["weight"] for r in rows)
    arm_w = sum(g for _, g, _, _ in masses)
    return {
        "available": True,
        "weights": rows,
        "added_weight": total,
        "arm_weight": arm_w,
        "ratio": total / arm_w if arm_w > 0 else math.inf,
        "max_residual": chk.max_residual,
        "potential_spread": chk.potential_spread,
    }


