"""``mechsynth balance linkage``: counterweights for a dimensioned linkage, checked independently.

The first moment M(q) of the balanced linkage is recomputed from the positions the independent
reference solver (``tests/oracles/motion.py``) gives the links' centres and the counterweights;
the four-bar's counterweights are compared with Berkof & Lowen's closed form, derived here; the
shaking force with central differences of M from the oracle; every reported largest value with a
dense grid.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from balance import LinkBody, body_arrays, first_moment
from mechsynth.cli import main
from synth.motion import Linkage, link_rates, read_linkage
from tests.oracles.motion import follow, oracle_of

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"

#: the four-bar's masses: centres off the bars' lines, so the closed form is no special case
FOUR_BAR_MASSES = """
[linkage_balance]
file = "{file}"
links = [{{ link = 1, mass = 0.8, centre = [0.3, 0.4] }},
         {{ link = 2, mass = 2.5, centre = [1.9, 2.6] }},
         {{ link = 3, mass = 1.7, centre = [3.2, 1.9] }}]
"""

#: the slider-crank with a heavy slider (link 3): counterweights on the crank cannot cancel it
SLIDER_CRANK_MASSES = """
[linkage_balance]
file = "{file}"
links = [{{ link = 1, mass = 0.5, centre = [0.0, 0.5] }},
         {{ link = 2, mass = 1.2, centre = [1.7, 0.8] }},
         {{ link = 3, mass = 2.0, centre = [3.4641016151377544, 0.5] }}]
"""


def _balance(capsys, *args) -> dict:
    assert main(["balance", "linkage", *map(str, args), "--format", "json"]) == 0
    return json.loads(capsys.readouterr().out)


def _masses(out: dict, links: int, balanced: bool) -> tuple[np.ndarray, np.ndarray]:
    bodies = [LinkBody(b["link"], (), b["mass"], tuple(b["centre"]), b["pivot"]) for b in out["links"]]
    mass, moment = body_arrays(bodies, links)
    if balanced:
        for c in out["counterweights"]:
            mass[c["link"]] += c["mass"]
            moment[c["link"]] += c["mass"] * np.array(c["at"])
    return mass, moment


def _oracle_points(lk: Linkage, points: list, offsets) -> np.ndarray:
    """Where the points (link, at in the pose) are at the input offsets (S, P, 2), moved by the oracle as tracers."""
    traced = Linkage(lk.mechanism, lk.inputs, lk.points, lk.slides, lk.meshes,
                     {f"T{i}": (link, at) for i, (link, at) in enumerate(points)}, None, lk.driven)
    return follow(oracle_of(traced, tracers=True), offsets)[:, len(lk.chain.joints):]


def _point_masses(out: dict, balanced: bool) -> list:
    """(link, point in the pose, mass, inertia about it) of the links and of the counterweights (point masses)."""
    bodies = [(b["link"], b["centre"], b["mass"], b["inertia"]) for b in out["links"] + out.get("carried", [])]
    return bodies + ([(c["link"], c["at"], c["mass"], 0.0) for c in out["counterweights"]] if balanced else [])


def _oracle_moment(lk: Linkage, out: dict, balanced: bool, offsets) -> np.ndarray:
    """M at the input offsets, every centre and counterweight moved by the oracle (as tracers)."""
    bodies = _point_masses(out, balanced)
    moved = _oracle_points(lk, [(link, at) for link, at, _, _ in bodies], offsets)
    return np.einsum("p,spx->sx", np.array([m for _, _, m, _ in bodies]), moved)


def _oracle_moment_rate(lk: Linkage, out: dict, balanced: bool, x: float, about, h: float = 2.5e-4) -> float:
    """dH/dq at input offset x at unit input speed: H = Σ I θ' + m (r − O) × r' about O, each body's centre
    and a point 1 m beside it moved by the oracle, θ from the two, every derivative a central difference."""
    bodies = _point_masses(out, balanced)
    points = [(link, at) for link, at, _, _ in bodies] + [(link, np.add(at, (1.0, 0.0))) for link, at, _, _ in bodies]
    moved = _oracle_points(lk, points, x + h * np.arange(-2, 3))  # (5, 2B, 2)
    r, beside = moved[:, :len(bodies)] - np.asarray(about), moved[:, len(bodies):]
    theta = np.unwrap(np.arctan2(*(beside - moved[:, :len(bodies)]).transpose(2, 0, 1)[::-1]), axis=0)
    mass, inertia = np.array([b[2] for b in bodies]), np.array([b[3] for b in bodies])

    def momentum(k):  # H at x + (k − 2) h, from the samples k − 1 and k + 1
        dr, dtheta = (r[k + 1] - r[k - 1]) / (2 * h), (theta[k + 1] - theta[k - 1]) / (2 * h)
        return float(np.sum(inertia * dtheta + mass * (r[k][:, 0] * dr[:, 1] - r[k][:, 1] * dr[:, 0])))

    return (momentum(3) - momentum(1)) / (2 * h)


def _pairwise_widest(m: np.ndarray) -> float:
    return float(max(np.hypot(*(m[i] - m[i + 1:]).T).max(initial=0.0) for i in range(len(m) - 1)))


@pytest.fixture(scope="module")
def four_bar(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fourbar")
    path = folder / "four_bar.toml"
    path.write_text(FOUR_BAR_MASSES.format(file=MODELS / "motion_four_bar.toml"))
    return path, read_linkage(MODELS / "motion_four_bar.toml")


def test_four_bar_counterweights_are_berkof_lowen(four_bar, capsys):
    """Crank A0A (link 1), coupler AB (2), rocker B0B (3); as complex numbers z1 = A − A0, z3 = B − B0 and
    the coupler's centre G2 = A + k2 (B − A).  With z2 = z3 − z1 + (B0 − A0), the first moment is
    const + z1 (m1 k1 + m2 − m2 k2) + z3 (m2 k2 + m3 k3), z1 and z3 independent: M is constant iff the
    crank's total moment about A0 is m2 (k2 − 1) z1 and the rocker's about B0 is −m2 k2 z3."""
    path, lk = four_bar
    out = _balance(capsys, path)
    p = {name: complex(*xy) for name, xy in json.loads(json.dumps(lk.to_dict()))["points"].items()}
    a0, a, b, b0 = p["0-1"], p["1-2"], p["2-3"], p["0-3"]
    masses = {x["link"]: (x["mass"], complex(*x["centre"])) for x in out["links"]}
    (m1, g1), (m2, g2), (m3, g3) = masses[1], masses[2], masses[3]
    k2 = (g2 - a) / (b - a)
    needed = {1: m2 * (k2 - 1) * (a - a0) - m1 * (g1 - a0), 3: -m2 * k2 * (b - b0) - m3 * (g3 - b0)}
    assert out["full_balance"] is True and out["on"] == [1, 3]
    for cw in out["counterweights"]:
        got = complex(*cw["moment"])
        assert abs(got - needed[cw["link"]]) <= 1e-12 * abs(needed[cw["link"]])
        pivot = {1: a0, 3: b0}[cw["link"]]
        assert abs(complex(*cw["at"]) - pivot - got / cw["mass"]) <= 1e-12  # placed where its moment says
        assert cw["distance"] == pytest.approx(abs(got) / cw["mass"], rel=1e-12)


def test_four_bar_first_moment_is_constant_under_the_oracle(four_bar, capsys):
    path, lk = four_bar
    out = _balance(capsys, path)
    offsets = np.sort(np.random.default_rng(7).uniform(0, 2 * math.pi, 12))
    before = _oracle_moment(lk, out, False, offsets)
    after = _oracle_moment(lk, out, True, offsets)
    size = sum(c["mass"] * math.hypot(*c["at"]) for c in out["counterweights"]) + \
        sum(b["mass"] * math.hypot(*b["centre"]) for b in out["links"])
    assert np.abs(after - after[0]).max() <= 1e-12 * size
    assert np.abs(before - before[0]).max() > 0.01 * size  # (the unbalanced linkage's moves: the check can fail)


def test_shaking_force_is_the_second_difference_of_the_oracle_moment(four_bar, capsys):
    """M'' from the links' rates (the motion layer) against central differences of M from the oracle."""
    path, lk = four_bar
    out = _balance(capsys, path)
    mass, moment = _masses(out, lk.chain.links, balanced=False)
    h = 1e-3
    for x in (0.4, 2.1, 4.6):
        m = _oracle_moment(lk, out, False, [x - h, x, x + h])
        finite_difference = (m[0] - 2 * m[1] + m[2]) / h ** 2
        analytic = first_moment(mass, moment, link_rates(lk, [x]), order=2)[0]
        assert np.abs(analytic - finite_difference).max() <= 1e-5 * np.abs(analytic).max()
        m1 = first_moment(mass, moment, link_rates(lk, [x]), order=1)[0]
        assert np.abs(m1 - (m[2] - m[0]) / (2 * h)).max() <= 1e-5 * np.abs(m1).max()


def test_reported_largest_values_are_the_true_ones(four_bar, capsys):
    """The before state's largest shaking force, potential variation and excursion against a dense grid."""
    path, lk = four_bar
    out = _balance(capsys, path)
    mass, moment = _masses(out, lk.chain.links, balanced=False)
    phi0 = float(lk.pose_inputs[0])
    grid = np.linspace(0, 2 * math.pi, 20001)
    motion = link_rates(lk, grid)
    force = np.hypot(*first_moment(mass, moment, motion, order=2).T)
    m = first_moment(mass, moment, motion)
    b = out["before"]
    assert force.max() <= b["shaking_force"] <= force.max() * (1 + 1e-7)
    at = np.hypot(*first_moment(mass, moment, link_rates(lk, [b["shaking_force_at"] - phi0]), order=2).T)[0]
    assert at == pytest.approx(b["shaking_force"], rel=1e-12)
    v = 9.81 * m[:, 1]
    assert np.ptp(v) <= b["potential_variation"] <= np.ptp(v) * (1 + 1e-7)
    widest = _pairwise_widest(m[::10])
    assert widest <= b["moment_excursion"] + 1e-12 <= widest * (1 + 1e-4)
    assert b["com_excursion"] == pytest.approx(b["moment_excursion"] / mass.sum(), rel=1e-12)


def test_watt_six_bar_is_fully_balanced_on_its_frame_pivots(capsys):
    """Watt II: two four-bars in series, each balanced by Berkof–Lowen on its grounded links, the shared
    ternary rocker carrying the sum: frame-pivoted counterweights reach zero (checked by the oracle)."""
    lk = read_linkage(MODELS / "motion_watt_ii.toml")
    out = _balance(capsys, MODELS / "motion_watt_ii.toml", "--density", 1.5)
    assert out["full_balance"] is True and sorted(out["on"]) == [1, 3, 4]
    assert out["after"]["shaking_force"] <= 1e-12 * out["before"]["shaking_force"]
    after = _oracle_moment(lk, out, True, np.sort(np.random.default_rng(3).uniform(0, 2 * math.pi, 8)))
    assert np.abs(after - after[0]).max() <= 1e-12 * out["before"]["moment_excursion"]


def test_slider_crank_keeps_a_residual_reported_as_its_true_maximum(tmp_path, capsys):
    """A slider's mass moves along its guide: the crank's counterweight leaves part of the shaking force,
    and what is left is reported as the true largest value (a dense grid below it, within 1e-7)."""
    path = tmp_path / "slider.toml"
    path.write_text(SLIDER_CRANK_MASSES.format(file=MODELS / "motion_slider_crank.toml"))
    lk = read_linkage(MODELS / "motion_slider_crank.toml")
    out = _balance(capsys, path)
    assert out["full_balance"] is False and out["on"] == [1]
    assert 0.05 < out["residual_share"] < 1
    assert any("link 3 translates" in n for n in out["notes"])
    mass, moment = _masses(out, lk.chain.links, balanced=True)
    grid = np.linspace(0, 2 * math.pi, 20001)
    motion = link_rates(lk, grid)
    force = np.hypot(*first_moment(mass, moment, motion, order=2).T)
    a = out["after"]
    assert force.max() <= a["shaking_force"] <= force.max() * (1 + 1e-7)
    widest = _pairwise_widest(first_moment(mass, moment, motion)[::10])
    assert widest <= a["moment_excursion"] + 1e-12 <= widest * (1 + 1e-4)
    # the fit is the least squares over the turn: moving the crank's moment only widens what is left
    turn = link_rates(lk, np.linspace(0, 2 * math.pi, 3600, endpoint=False))

    def spread(moments):
        m = first_moment(mass, moments, turn)
        return float(np.sum((m - m.mean(axis=0)) ** 2))

    for step in ((1e-2, 0), (0, 1e-2), (-1e-2, 0), (0, -1e-2)):
        nudged = moment.copy()
        nudged[1] += np.array(step)  # the crank's pivot is the origin: its moment about the pivot
        assert spread(nudged) > spread(moment)
    assert out["counterweights"][0]["joint"] == "0-1"


@pytest.mark.parametrize("suffix", [".json", ".toml"])
def test_saved_linkage_balanced_again_needs_no_counterweight(tmp_path, capsys, suffix):
    """--save keeps the links' masses and the counterweights: balanced again, the linkage is in full balance
    with nothing added, its first moment (links and counterweights moved by the oracle) constant; move and
    draw read the file, the counterweights as tracers CW1, CW3; --density beside its masses is refused."""
    saved = tmp_path / f"balanced{suffix}"
    first = _balance(capsys, MODELS / "motion_four_bar.toml", "--density", 2, "--save", saved)
    again = _balance(capsys, saved)
    assert again["full_balance"] is True and again["added_mass"] == 0 <= again["residual_share"] <= 1e-12
    assert all(c["mass"] == 0 for c in again["counterweights"])
    assert [(b["link"], b["mass"], b["centre"]) for b in again["carried"]] == \
        [(c["link"], pytest.approx(c["mass"], rel=1e-15), pytest.approx(c["at"], abs=1e-15))
         for c in first["counterweights"]]
    assert again["before"]["shaking_force"] <= 1e-12 * first["before"]["shaking_force"]
    assert again["before"]["total_mass"] == pytest.approx(first["after"]["total_mass"], rel=1e-15)
    lk = read_linkage(saved)
    assert {"CW1", "CW3", "P"} <= set(lk.tracers) and "balanced by counterweights" in lk.note
    carried = {"links": again["links"], "counterweights": [{"link": b["link"], "mass": b["mass"], "at": b["centre"]}
                                                           for b in again["carried"]]}
    m = _oracle_moment(lk, carried, True, np.sort(np.random.default_rng(5).uniform(0, 2 * math.pi, 8)))
    assert np.abs(m - m[0]).max() <= 1e-12 * first["before"]["moment_excursion"]
    assert main(["move", str(saved), "--steps", "3"]) == 0
    assert "CW1.x" in capsys.readouterr().out
    assert main(["draw", str(saved), "--out", str(tmp_path / "balanced.svg")]) == 0
    capsys.readouterr()
    assert main(["balance", "linkage", str(saved), "--density", "2"]) == 2
    err = capsys.readouterr().err
    assert "per-link masses and a density" in err and err.count("\n") == 1


def test_counterweights_added_to_carried_ones_merge_on_their_link(tmp_path, capsys):
    """The slider-crank balanced on its crank (part left), then again with the rod too: the crank's two
    counterweights are saved as one at their centre of mass, and the scene of the file finds none needed."""
    s1, s2 = tmp_path / "s1.toml", tmp_path / "s2.toml"
    crank = _balance(capsys, MODELS / "motion_slider_crank.toml", "--density", 2, "--save", s1)
    assert crank["full_balance"] is False
    same = _balance(capsys, s1)  # the least squares' optimum: nothing to add, the same share left
    assert same["added_mass"] == 0 and same["residual_share"] == pytest.approx(crank["residual_share"], rel=1e-9)
    both = _balance(capsys, s1, "--on", "1,2", "--save", s2)
    assert both["full_balance"] is True
    (c1,) = [c for c in crank["counterweights"] if c["link"] == 1]
    (n1,) = [c for c in both["counterweights"] if c["link"] == 1]
    mass = c1["mass"] + n1["mass"]
    at = (c1["mass"] * np.array(c1["at"]) + n1["mass"] * np.array(n1["at"])) / mass
    again = _balance(capsys, s2)
    assert again["full_balance"] is True and again["added_mass"] == 0
    (m1,) = [b for b in again["carried"] if b["link"] == 1]
    assert m1["mass"] == pytest.approx(mass, rel=1e-14) and m1["centre"] == pytest.approx(at, abs=1e-14)
    assert sorted(read_linkage(s2).tracers) == ["CW1", "CW2"]
    assert main(["scene", str(s2)]) == 0
    assert "carried: link 1" in capsys.readouterr().out


@pytest.mark.parametrize("args, words", [
    (["{five}", "--density", "2"], "W = 2"),
    (["{m}/motion_four_bar.toml"], "has no masses"),
    (["{m}/motion_four_bar.toml", "--density", "-2"], "not -2"),
    (["{m}/motion_four_bar.toml", "--density", "2", "--on", "0"], "link 0 cannot carry a counterweight"),
    (["{m}/motion_four_bar.toml", "--density", "2", "--on", "9"], "link 9 cannot carry a counterweight"),
    (["{m}/motion_four_bar.toml", "--density", "2", "--counter-mass", "1", "--counter-radius", "1"], "not both"),
    (["{m}/motion_four_bar.toml", "--density", "2", "--counter-mass", "-1"], "not -1"),
    (["{m}/motion_four_bar.toml", "--density", "2", "--on", "1,2", "--counter-radius", "1"], "link 2 floats"),
    (["{neg}"], "mass -1 kg"),
    (["{tab}", "--density", "3"], "--density is also given"),
    (["{m}/motion_triad.toml", "--density", "2", "--range", "0..400"], "beyond the input's limits"),
    (["{m}/motion_four_bar.toml", "--density", "2", "--samples", "2"], "9 … 100,000, not 2"),
    (["{m}/motion_four_bar.toml", "--density", "2", "--range", "50..50"], "is empty"),
    (["{m}/motion_four_bar.toml", "--density", "2", "--on", "1,1"], "named twice"),
    (["{cw0}"], "link 0 carries no counterweight"),
    (["{cw0}", "--density", "2"], "--density is also given"),
])
def test_bad_input_is_one_sentence_and_exit_2(tmp_path, capsys, args, words):
    five = tmp_path / "five.json"
    assert main(["move", "--chain", "0-1 1-2 2-3 3-4 4-0", "--frame", "0", "--save", str(five)]) == 0
    neg = tmp_path / "neg.toml"
    neg.write_text(FOUR_BAR_MASSES.format(file=MODELS / "motion_four_bar.toml").replace("mass = 0.8", "mass = -1"))
    tab = tmp_path / "tab.toml"
    tab.write_text(f'[linkage_balance]\nfile = "{MODELS / "motion_four_bar.toml"}"\ndensity = 2\n')
    cw0 = tmp_path / "cw0.toml"
    cw0.write_text(tab.read_text() + "counterweights = [{ link = 0, mass = 1, at = [0, 0] }]\n")
    capsys.readouterr()
    argv = [a.format(m=MODELS, five=five, neg=neg, tab=tab, cw0=cw0) for a in args]
    assert main(["balance", "linkage", *argv]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1 and "Traceback" not in err, err


@pytest.mark.parametrize("balanced", [False, True])
def test_shaking_moment_is_the_rate_of_the_oracle_angular_momentum(four_bar, capsys, balanced):
    """The shaking moment per ω² (the rate of the links' angular momentum about the input's pivot, the bars'
    inertias, the counterweights point masses) against central differences of the angular momentum computed
    from the oracle's positions, at three inputs and where its largest value is reported; that largest
    value against a dense grid. Reported before and after, not minimised: the counterweights raise it."""
    from balance import LinkBody, moment_rate

    lk = read_linkage(MODELS / "motion_four_bar.toml")
    out = _balance(capsys, MODELS / "motion_four_bar.toml", "--density", 2)
    about = lk.points[lk.inputs[0]]
    bodies = [LinkBody(link, (), m, tuple(at), None, inertia) for link, at, m, inertia in _point_masses(out, balanced)]
    state = out["after" if balanced else "before"]
    phi0 = float(lk.pose_inputs[0])
    for x in (0.4, 2.1, 4.6, state["shaking_moment_at"] - phi0):
        analytic = moment_rate(bodies, link_rates(lk, [x]), about)[0]
        # (the differences' error, O(h²): 1.3e-6 at h = 2.5e-4, 2.1e-5 at 1e-3, of a largest value of 14.5)
        assert analytic == pytest.approx(_oracle_moment_rate(lk, out, balanced, x, about),
                                         abs=1e-6 * state["shaking_moment"])
    assert abs(analytic) == pytest.approx(state["shaking_moment"], rel=1e-12)
    dense = np.abs(moment_rate(bodies, link_rates(lk, np.linspace(0, 2 * math.pi, 20001)), about))
    assert dense.max() <= state["shaking_moment"] <= dense.max() * (1 + 1e-7)
    assert out["after"]["shaking_moment"] > 2 * out["before"]["shaking_moment"]


def test_save_never_writes_over_a_file_it_reads(tmp_path, capsys):
    """`--save` naming the linkage file given, or the linkage a [linkage_balance] table names, is refused in
    one sentence before any work, and the file stays as it was (it used to be written over, exit 0)."""
    linkage = tmp_path / "four_bar.toml"
    linkage.write_bytes((MODELS / "motion_four_bar.toml").read_bytes())
    table = tmp_path / "masses.toml"
    table.write_text('[linkage_balance]\nfile = "four_bar.toml"\ndensity = 2\n')
    before = linkage.read_bytes(), table.read_bytes()
    for argv in ([linkage, "--density", "2", "--save", linkage], [table, "--save", linkage],
                 [table, "--save", table], [linkage, "--density", "2", "--save", tmp_path / "." / "four_bar.toml"]):
        capsys.readouterr()
        assert main(["balance", "linkage", *map(str, argv)]) == 2
        err = capsys.readouterr().err
        assert "--save would overwrite it" in err and err.count("\n") == 1, err
    assert (linkage.read_bytes(), table.read_bytes()) == before
