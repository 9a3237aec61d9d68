"""The [pantograph] problem (balance.problems.pantograph) against a slow method: every range it reports (cylinder
and hand forces by payload, the cylinder's length and lever arm) against a dense grid of the workspace, the
reported extremes attained where they are said to be; the row's numbers by hand, the notes, the table read
field by field and the refusal of a cylinder through A."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance.errors import InvalidArm, SchemaError
from balance.model.pantograph import Pantograph
from balance.problems.pantograph import PantographProblem, pantograph_problem

DOC = {"pantograph": {"l2": 0.8, "l3": 1.0, "ratio": 4.0, "tool": 20.0, "payload": 100.0,
                      "range_upper_deg": [-30.0, 80.0], "range_forearm_deg": [-80.0, 40.0],
                      "upper": {"weight": 60.0, "com": 0.3}, "forearm": {"weight": 40.0, "com": 0.4},
                      "bar_eb": {"weight": 8.0}, "bar_fb": {"weight": 6.0}, "parallelogram_bars": {"weight": 5.0},
                      "elbow_plate": {"weight": 4.0}, "wrist_plate": {"weight": 10.0},
                      "parallelogram_offset": 0.15, "cylinder": {"base": [0.3, -0.8]},
                      "spring": {"r": 0.1, "r0": 0.3}, "check": {"samples": 1000, "seed": 7}}}


def grid(p: Pantograph, n: int = 301) -> np.ndarray:
    t2 = np.linspace(*p.range2, n)
    t3 = np.linspace(*p.range3, n)
    return np.stack(np.meshgrid(t2, t3), axis=-1).reshape(-1, 2)


def test_the_table_is_read_field_by_field():
    prob = pantograph_problem(DOC, "p.toml")
    p = prob.pantograph
    assert (p.l2, p.l3, p.k, p.w2, p.w3, p.w9, p.w8, p.w14, p.w15, p.w16, p.w4) == \
        (0.8, 1.0, 4.0, 60.0, 40.0, 8.0, 6.0, 5.0, 5.0, 4.0, 10.0)
    assert (p.s2, p.s3, p.tool, p.payload, p.offset, p.base) == (0.3, 0.4, 20.0, 100.0, 0.15, (0.3, -0.8))
    assert p.range2 == pytest.approx((math.radians(-30), math.radians(80)), rel=1e-15)
    assert p.range3 == pytest.approx((math.radians(-80), math.radians(40)), rel=1e-15)
    assert (prob.r, prob.r0, prob.samples, prob.seed) == (0.1, 0.3, 1000, 7)
    bare = pantograph_problem({"pantograph": {"l2": 0.8, "l3": 1.0, "ratio": 4.0}})
    assert bare.pantograph.base is None and (bare.r, bare.r0) == (None, None)
    with pytest.raises(InvalidArm) as err:
        pantograph_problem({"pantograph": {"l2": 0.8, "l3": 1.0, "ratio": 0.5}}, "p.toml")
    assert str(err.value) == "p.toml: the pantograph ratio k = AC/AB must exceed 1, not 0.5."
    with pytest.raises(SchemaError) as err:
        pantograph_problem({"pantograph": {"l2": 0.8, "l3": 1.0, "ratio": 4.0, "lenght": 2}}, "p.toml")
    assert str(err.value) == ("p.toml: [pantograph] has an unknown key 'lenght' (allowed: bar_eb, bar_fb, check, "
                              "cylinder, elbow_plate, forearm, l2, l3, parallelogram_bars, parallelogram_offset, "
                              "payload, range_forearm_deg, range_upper_deg, ratio, spring, tool, upper, wrist_plate).")


def test_every_reported_range_is_the_true_one_over_the_workspace():
    res = pantograph_problem(DOC).solve()
    p = res.pantograph
    th = grid(p)
    length, _, lever = p.cylinder(th)
    for fraction in (0.0, 0.5, 1.0):
        f = p.cylinder_force(th, fraction)
        lo, hi = res.force[fraction]
        # never beaten by the grid, and within the grid's spacing of its best
        assert lo.value <= f.min() + 1e-9 and hi.value >= f.max() - 1e-9
        assert lo.value == pytest.approx(f.min(), rel=1e-3) and hi.value == pytest.approx(f.max(), rel=1e-3)
        # attained where it is said to be
        assert p.cylinder_force(np.array([lo.at]), fraction)[0] == pytest.approx(lo.value, rel=1e-12)
        assert p.cylinder_force(np.array([hi.at]), fraction)[0] == pytest.approx(hi.value, rel=1e-12)
        h = p.hand_force(th, fraction)
        hlo, hhi = res.hand[fraction]
        assert hlo.value <= h.min() + 1e-9 and hhi.value >= h.max() - 1e-9
        assert hlo.value == pytest.approx(h.min(), abs=1e-3 * np.abs(h).max())
        assert hhi.value == pytest.approx(h.max(), abs=1e-3 * np.abs(h).max())
        assert res.residual[fraction] < 1e-9 * res.max_gravity_force
    assert res.length[0].value == pytest.approx(length.min(), rel=1e-4)
    assert res.length[1].value == pytest.approx(length.max(), rel=1e-4)
    assert res.lever[0].value == pytest.approx(lever.min(), rel=1e-4)
    assert res.lever[1].value == pytest.approx(lever.max(), rel=1e-4)
    # the forces over payloads 0 … max: those of the payload's ends, the force linear in it
    f_all = np.concatenate([p.cylinder_force(th, 0.0), p.cylinder_force(th, 1.0)])
    lo, hi = res.force_range
    assert (lo.value, hi.value) == (min(res.force[0.0][0].value, res.force[1.0][0].value),
                                    max(res.force[0.0][1].value, res.force[1.0][1].value))
    assert lo.value == pytest.approx(f_all.min(), rel=1e-3) and hi.value == pytest.approx(f_all.max(), rel=1e-3)
    h_all = np.concatenate([p.hand_force(th, 0.0), p.hand_force(th, 1.0)])
    hlo, hhi = res.hand_range
    assert hlo.value == pytest.approx(h_all.min(), abs=1e-3 * np.abs(h_all).max())
    assert hhi.value == pytest.approx(h_all.max(), abs=1e-3 * np.abs(h_all).max())
    # the largest gravity force, by hand: −∂U/∂θ2 = −Σ w·a·cos θ2 is largest at θ2 = 0 (inside the range) with
    # the full payload; the grid, which misses θ2 = 0, never beats it
    gmax = sum(w * a for _, w, a, _ in p.height_coefficients(1.0))
    assert gmax == pytest.approx(167.8, rel=1e-14)
    assert res.max_gravity_force == pytest.approx(gmax, rel=1e-9)
    assert max(np.abs(p.gravity_forces(th, f)).max() for f in (0.0, 0.5, 1.0)) <= res.max_gravity_force
    assert res.relative_residual == res.max_residual / res.max_gravity_force


def test_the_row_by_hand():
    res = pantograph_problem(DOC).solve()
    out = res.to_dict()
    # substitution weights at half payload: W_D = 60·0.3/0.8 + 40·0.6 + 8/(2·4) + 6·(3/4)/2 + 5/2 + 5/2 + 4 = 58.75 N
    wd = 60 * 0.3 / 0.8 + 40 * (1 - 0.4) + 0.5 * 8 / 4 + 0.5 * 6 * (1 - 1 / 4) + 0.5 * 5 + 0.5 * 5 + 4
    assert out["point_weights"]["D"] == pytest.approx(wd, rel=1e-14)
    wc0 = 40 * 0.4 + 0.5 * 6 / 4 + 0.5 * 5 + 10 + 20  # without payload
    assert out["point_weights_without_payload"]["C"] == pytest.approx(wc0, rel=1e-14)
    assert out["point_weights"]["C"] == pytest.approx(wc0 + 50, rel=1e-14)
    a = wd * 0.8  # the spring's amplitude W_D·l2
    assert out["term"]["amplitude"] == pytest.approx(a, rel=1e-14) and out["term"]["form_text"] == "θ2"
    assert out["spring_moment"] == f"{a:.6g}·cos θ2 on the upper arm (base point C above A)"
    assert out["device"]["sine"]["eT"] == pytest.approx(a, rel=1e-14)
    assert out["device"]["tension"]["c"] == pytest.approx(a / (0.1 * 0.4), rel=1e-14)
    assert out["device"]["tension"]["zero_at_deg"] == 90.0
    wb = 0.5 * 8 + 0.5 * 6
    assert out["drive_force"] == pytest.approx(wb + 4 * (wc0 + 50), rel=1e-14)
    assert out["drive_force_range"] == pytest.approx([wb + 4 * wc0, wb + 4 * (wc0 + 100)], rel=1e-14)
    cyl = out["cylinder"]
    assert cyl["base"] == [0.3, -0.8]
    assert (cyl["length_min"], cyl["length_max"]) == (res.length[0].value, res.length[1].value)
    levers = sorted((abs(res.lever[0].value), abs(res.lever[1].value)))
    assert (cyl["lever_min"], cyl["lever_max"]) == (levers[0], levers[1])
    cf = out["cylinder_force"]
    lo, hi = res.force_range
    assert (cf["min"], cf["max"]) == (lo.value, hi.value)
    assert cf["at_min_deg"] == pytest.approx([math.degrees(v) for v in lo.at], rel=1e-14)
    assert cf["at_max_deg"] == pytest.approx([math.degrees(v) for v in hi.at], rel=1e-14)
    assert cf["half_payload"]["min"] == res.force[0.5][0].value and cf["half_payload"]["max"] == res.force[0.5][1].value
    assert cf["half_payload"]["at_max_deg"] == pytest.approx([math.degrees(v) for v in res.force[0.5][1].at])
    assert cf["by_payload"] == {str(f): {"min": res.force[f][0].value, "max": res.force[f][1].value}
                                for f in (0.0, 0.5, 1.0)}
    assert cf["sampled"] == {"min": lo.sampled, "max": hi.sampled}
    assert out["hand_force"] == {"min": res.hand_range[0].value, "max": res.hand_range[1].value}
    assert out["residual_by_payload"] == {str(f): res.residual[f] for f in (0.0, 0.5, 1.0)}
    assert (out["samples"], out["seed"]) == (1000, 7)


def test_the_notes_say_when_the_cylinder_pulls_and_how_much_the_operator_holds():
    res = pantograph_problem(DOC).solve()
    lo, hi = res.hand_range
    peak = max(-lo.value, hi.value)
    load = res.pantograph.vertical_load(1.0)
    hand = (f"the operator holds up to {peak:.3g} N along A→C ({100 * peak / load:.3g} % of the full load "
            f"{load:.4g} N reduced to B): a base P further below B keeps the cylinder nearer vertical")
    pulls = "the cylinder pulls somewhere in the workspace (negative force): it must be double-acting"
    assert res.force_range[0].value > 0 and peak > 0.05 * load
    assert res.notes == [hand]
    # the scene's own base: the hand force within 5 % of the load, no note
    scene = pantograph_problem({"pantograph": dict(DOC["pantograph"], cylinder={"base": [0.3, -1.6]})}).solve()
    lo, hi = scene.hand_range
    assert 0 < max(-lo.value, hi.value) < 0.05 * load and scene.notes == []
    # a base above B: the cylinder hangs the pantograph and pulls
    above = PantographProblem(Pantograph(l2=0.8, l3=1.0, k=4.0, w2=60.0, w3=40.0, tool=20.0, payload=100.0,
                                         base=(0.25, 3.0)), samples=100).solve()
    assert above.force_range[1].value < 0 and above.notes[0] == pulls


def test_a_cylinder_whose_line_passes_through_a_is_refused():
    # the base at A itself: the lever arm is zero everywhere
    with pytest.raises(InvalidArm) as err:
        PantographProblem(Pantograph(l2=0.8, l3=1.0, k=4.0, w2=60.0, base=(0.0, 0.0)), samples=50).solve()
    assert str(err.value) == ("the cylinder's line of action passes through A in the workspace, so it cannot hold "
                              "the pantograph there; move its base (cylinder.base).")
    # a base on the far side of A: the line sweeps through A somewhere in the workspace
    with pytest.raises(InvalidArm):
        PantographProblem(Pantograph(l2=0.8, l3=1.0, k=4.0, w2=60.0, base=(-0.2, 0.0)), samples=50).solve()


def test_a_check_past_the_work_limit_is_refused_before_it_starts():
    from balance.budget import TooMuchWork

    p = Pantograph(l2=0.8, l3=1.0, k=4.0, w2=60.0, w3=40.0, tool=20.0)
    # a hundred thousand configurations take well over a microsecond (were the limit ignored: seconds, no refusal)
    with pytest.raises(TooMuchWork) as err:
        PantographProblem(p, samples=10**5, work_limit=1e-6).solve()
    assert str(err.value).startswith("checking 100000 configurations would take about ")
    assert err.value.limit == 1e-6 and err.value.seconds > 1e-6
