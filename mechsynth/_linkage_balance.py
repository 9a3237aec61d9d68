"""Balancing a dimensioned linkage: the glue between synth's motion layer and balance's counterweights,
shared by ``mechsynth balance linkage`` and the scene computation ``balance linkage``.

The linkage is read and moved by :mod:`synth.motion` (``link_rates``: every link's pose and its first
and second derivatives with respect to the input); its moving links, their masses (per link, or bars of
a density) and the options become a :class:`balance.LinkageProblem`, which never sees a synth type.

Example
-------
>>> from synth.motion import read_linkage
>>> problem = linkage_problem(read_linkage("models/motion_four_bar.toml"), {"density": 2.0}, None, "four-bar")
>>> res = problem.solve()
>>> [(c.link, round(c.mass, 9)) for c in res.counterweights], res.full_balance   # Berkof–Lowen: 4.5 and 6.5 kg
([(1, 4.5), (3, 6.5)], True)
"""

from __future__ import annotations

import math

__all__ = ["OPTIONS", "linkage_problem", "balanced_linkage"]

#: the options of a linkage's balance (keys of a [linkage_balance] table) and their command-line flags
OPTIONS = {"density": "--density", "on": "--on", "counter_mass": "--counter-mass", "counter_radius": "--counter-radius",
           "gravity": "--gravity", "range": "--range", "samples": "--samples"}


def linkage_problem(linkage, options: dict, links=None, name: str = "linkage", source: str | None = None,
                    carried=None):
    """The :class:`balance.LinkageProblem` of ``linkage`` (W = 1) with the masses of ``links`` (rows with
    ``link``, ``mass``, ``centre``) or ``options["density"]``, the counterweights ``carried`` (rows with
    ``link``, ``mass``, ``at``: a linkage balanced before) and the other :data:`OPTIONS` (None: default;
    ``range`` in degrees, or m for a prismatic input).  ``source`` names the file in sentences."""
    import numpy as np

    from balance import InvalidInput, LinkageProblem, LinkBody, bar_bodies
    from synth import InvalidOption
    from synth.motion import joint_name, link_rates, motion_range

    options = {key: options.get(key) for key in OPTIONS}
    source = source or name
    if linkage.dof != 1:
        raise InvalidOption(f"{name} has W = {linkage.dof} inputs: balancing by counterweights takes a linkage of one "
                            "input (W = 1)")
    chain, frame = linkage.chain, linkage.frame
    moving = []
    for link in range(chain.links):
        if link != frame:
            named = tuple((joint_name(chain, k), tuple(map(float, linkage.points[k]))) for k in linkage.joints_of(link))
            pivot = next((joint_name(chain, k) for k in linkage.joints_of(link)
                          if frame in chain.joints[k] and linkage.kind(k) == "revolute"), None)
            moving.append((link, named, pivot))
    if links is not None and options["density"] is not None:
        raise InvalidOption(f"{source} gives per-link masses and a density: give the masses one way (a linkage "
                            "'balance linkage --save' wrote carries its links' masses: drop --density)")
    if links is not None:
        given = {row.link: row for row in links}
        wrong = [k for k in given if k == frame or not 0 <= k < chain.links]
        if wrong:
            raise InvalidInput(f"{source}: link {wrong[0]} takes no mass: it is the frame or no link of the linkage "
                               f"(the moving links are {', '.join(str(m[0]) for m in moving)}).")
        missing = [str(link) for link, _, _ in moving if link not in given]
        if missing:
            raise InvalidInput(f"{source}: link{'s' * (len(missing) > 1)} {', '.join(missing)} "
                               f"{'have' if len(missing) > 1 else 'has'} no mass in [linkage_balance] (give 0 for a "
                               "massless link).")
        bodies = [LinkBody(link, named, given[link].mass, tuple(given[link].centre), pivot, given[link].inertia)
                  for link, named, pivot in moving]
    elif options["density"] is not None:
        bodies = bar_bodies(moving, options["density"])
    else:
        raise InvalidOption(f"{source} has no masses: give --density KG_PER_M (the links as bars) or a TOML file with "
                            "a [linkage_balance] table of per-link masses")
    by_link = {link: (named, pivot) for link, named, pivot in moving}
    for row in carried or ():
        if row.link not in by_link:
            raise InvalidInput(f"{source}: link {row.link} carries no counterweight: it is the frame or no link of the "
                               f"linkage (the moving links are {', '.join(str(m[0]) for m in moving)}).")
    weights = tuple(LinkBody(row.link, by_link[row.link][0], row.mass, tuple(row.at), by_link[row.link][1], 0.0)
                    for row in carried or ())  # point masses
    phi0 = float(linkage.pose_inputs[0])
    revolute = linkage.kind(linkage.inputs[0]) == "revolute"
    reach = motion_range(linkage)
    limits = (phi0, phi0 + 2 * math.pi) if reach.full_rotation else reach.limits
    dead = not reach.full_rotation
    if options["range"] is not None:
        lo, hi = (math.radians(v) for v in options["range"]) if revolute else options["range"]
        if not lo < hi:
            raise InvalidOption(f"the range {options['range'][0]:g}..{options['range'][1]:g} is empty: give low..high")
        if not reach.full_rotation:
            tol = 1e-9 * (limits[1] - limits[0])
            if lo < limits[0] - tol or hi > limits[1] + tol:
                unit = (lambda v: f"{math.degrees(v):.6g}°") if revolute else (lambda v: f"{v:.6g} m")
                raise InvalidOption(f"the range reaches beyond the input's limits {unit(limits[0])} … {unit(limits[1])}")
            dead = lo <= limits[0] + tol or hi >= limits[1] - tol
        limits = (lo, hi)
    extra = {} if options["samples"] is None else {"samples": options["samples"]}
    return LinkageProblem(name, chain.links, tuple(bodies),
                          lambda q: link_rates(linkage, np.asarray(q, dtype=float) - phi0),
                          joint_name(chain, linkage.inputs[0]), tuple(limits), "revolute" if revolute else "prismatic",
                          dead, None if options["on"] is None else tuple(options["on"]), options["counter_mass"],
                          options["counter_radius"], tuple(options["gravity"] or (0.0, -9.81)), carried=weights,
                          moment_about=tuple(map(float, linkage.points[linkage.inputs[0]])), **extra)


def balanced_linkage(linkage, result, options: dict) -> tuple:
    """``linkage`` with each counterweight it carries as a tracer ``CW<link>`` (so ``draw`` and ``move`` show
    it), and its ``[linkage_balance]`` table: the links' masses and the counterweights (those ``result`` found
    and those the linkage carried, one per link at their centre of mass), with the ``options`` of
    :data:`OPTIONS` that set the problem (the range, the samples, gravity, the links to carry them), so that
    balancing it again finds none needed.

    >>> from synth.motion import read_linkage
    >>> lk = read_linkage("models/motion_four_bar.toml")
    >>> res = linkage_problem(lk, {"density": 2.0}).solve()
    >>> balanced, table = balanced_linkage(lk, res, {"density": 2.0})
    >>> sorted(balanced.tracers), [(c["link"], round(c["mass"], 9)) for c in table["counterweights"]]
    (['CW1', 'CW3', 'P'], [(1, 4.5), (3, 6.5)])
    """
    from synth.motion import Linkage

    merged = {}
    for link, mass, at in [(b.link, b.mass, b.centre) for b in result.carried] + \
                          [(c.link, c.mass, c.at) for c in result.counterweights]:
        m, moment = merged.get(link, (0.0, (0.0, 0.0)))
        merged[link] = (m + mass, (moment[0] + mass * at[0], moment[1] + mass * at[1]))
    placed = {link: (m, (mx / m, my / m)) for link, (m, (mx, my)) in sorted(merged.items()) if m > 0}
    tracers = dict(linkage.tracers) | {f"CW{link}": (link, at) for link, (_, at) in placed.items()}
    note = "balanced by counterweights: " + ", ".join(f"CW{link} {m:.6g} kg on link {link}"
                                                      for link, (m, _) in placed.items())
    table = {"links": [{"link": b.link, "mass": b.mass, "centre": list(b.centre)}
                       | ({} if b.inertia is None else {"inertia": b.inertia}) for b in result.links],
             "counterweights": [{"link": link, "mass": m, "at": list(at)} for link, (m, at) in placed.items()]}
    table |= {key: list(value) if isinstance(value, tuple) else value for key, value in options.items()
              if key in ("on", "gravity", "range", "samples") and value is not None}
    return (Linkage(linkage.mechanism, linkage.inputs, linkage.points, linkage.slides, linkage.meshes, tracers,
                    note if placed else linkage.note, linkage.driven), table)
