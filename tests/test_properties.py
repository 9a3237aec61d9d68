"""Property-based tests (hypothesis, derandomised): counting equations, chain analysis, JSON,
canonical certificates and exact balancing of random revolute arms.
"""

from __future__ import annotations

import functools
import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import balance
import synth
from balance.model.potential import terms_potential
from synth import Chain, Code
from synth.analysis.chains import analyze_chain

# derandomised, no deadline: the profile in conftest.py (HYPOTHESIS_PROFILE=explore randomises)
SETTINGS = settings(max_examples=40)


# ---------------------------------------------------------------------------- counting equations
def _brute_codes(W: int, K: int, h: int, f: int, n1: int, vmax: int) -> set:
    """Every (n2…n_{K+1}, v) with Σ n_i = n − n1, v = 2p − Σ i·n_i in 0..vmax (p = K + n − 1) that
    splits into joints of at most m = K + 1 links (closed) or K + W + 1 (open), the limit theorem:
    the fewest such joints, ⌈v / (m − 2)⌉, take v + 2·⌈v / (m − 2)⌉ link incidences."""
    n = W + 1 + (h - 1) * K - f
    most = K + 1 if n1 == 0 else K + W + 1
    out = set()
    for a in itertools.product(range(max(n - n1, 0) + 1), repeat=K):
        if sum(a) != n - n1:
            continue
        incidences = n1 + sum((i + 2) * x for i, x in enumerate(a))
        v = 2 * (K + n - 1) - incidences
        fewest = 0 if v == 0 else None if most < 3 else -(-v // (most - 2))
        if 0 <= v <= vmax and fewest is not None and v + 2 * fewest <= incidences:
            out.add((a, v))
    return out


def _padded(code: Code, K: int) -> tuple[int, ...]:
    return tuple(code.assortment) + (0,) * (K - len(code.assortment))


@SETTINGS
@given(W=st.integers(0, 3), K=st.integers(1, 4), h=st.sampled_from([2, 3, 4, 5, 6]), f=st.integers(0, 1),
       n1=st.integers(0, 2), compositions=st.booleans())
def test_codes_satisfy_the_counting_equations(W, K, h, f, n1, compositions):
    vmax = 2 * (K - 1) + n1
    try:
        codes = synth.number_synthesis(W, loops=K, h=h, f=f, n1=n1, v=f"0..{vmax}", compositions=compositions)
    except synth.ImpossibleParameters:
        assert not _brute_codes(W, K, h, f, n1, vmax)
        return
    n = W + 1 + (h - 1) * K - f                      # (2b)
    for code in codes:
        a = _padded(code, K)
        incidences = n1 + sum((i + 2) * x for i, x in enumerate(a))
        assert (incidences + code.v) % 2 == 0
        p = (incidences + code.v) // 2                 # simple-joint equivalents
        assert code.links == n == n1 + sum(a)
        assert code.loops == K == p - n + 1
        assert W == (n - 1) - (h - 1) * K + f          # (2a)/(2b)
        if h == 3:
            assert W == 3 * (n - 1) - 2 * p + f        # Grübler
            assert W == 2 * n1 + a[0] - sum((i - 3) * a[i - 2] for i in range(4, K + 2)) - code.v - 3 + f  # (2c)
        assert code.max_degree <= K + 1
        if compositions:
            assert sum((k + 1) * c for k, c in enumerate(code.composition)) == code.v
    # complete: the same set as a brute-force solution of the integer system
    assert {(_padded(c, K), c.v) for c in codes} == _brute_codes(W, K, h, f, n1, vmax)
    assert len(set(codes)) == len(codes)


@SETTINGS
@given(W=st.integers(0, 3), K=st.integers(1, 5), compositions=st.booleans(), data=st.data())
def test_code_json_and_text_round_trip(W, K, compositions, data):
    codes = synth.number_synthesis(W, loops=K, compositions=compositions)
    code = data.draw(st.sampled_from(codes))
    assert Code.from_json(code.to_json()) == code
    assert Code.from_dict(code.to_dict()) == code
    # the text drops a composition it does not need (v = v2 only, or none): compare what it carries
    back = Code.parse(str(code))
    assert str(back) == str(code)
    assert (back.assortment, back.v, back.n1) == (code.assortment, code.v, code.n1)
    if code.composition is not None and len(code.composition) > 1:
        assert back.composition == code.composition
    assert code.dof() == W and code.loops == K


# ---------------------------------------------------------------------------- chains
_QUERIES = [  # (W, n, v): small enough to enumerate in well under a second each
    (1, 4, 0), (1, 6, "0..2"), (1, 8, 0), (1, 8, "0..2"), (2, 5, 0), (2, 7, "0..1"), (2, 9, 0),
    (3, 6, 0), (3, 8, 0), (0, 5, "0..1"), (0, 7, 0),
]


@functools.lru_cache(maxsize=None)
def _chains(W: int, n: int, v) -> tuple[Chain, ...]:
    return tuple(synth.type_synthesis(W, n, v=v, workers=1))


chain_and_query = st.sampled_from(_QUERIES).flatmap(
    lambda q: st.tuples(st.just(q), st.sampled_from(_chains(*q))))


def _relabelled(chain: Chain, data) -> Chain:
    perm = data.draw(st.permutations(range(chain.links)), label="permutation")
    return chain.relabel(perm)


@SETTINGS
@given(item=chain_and_query, data=st.data())
def test_analysis_of_a_generated_chain_returns_its_code_and_W(item, data):
    (W, n, v), chain = item
    for subject in (chain, _relabelled(chain, data)):
        a = analyze_chain(subject.compact(), dof=W)
        assert a.dof == W and a.links == n
        assert a.code == str(chain.code)
        assert a.subchain_defect == "none"
        assert a.loops == (n - W - 1) // 2
    assert synth.analyze(chain.code, dof=W).defect == 0


@SETTINGS
@given(item=chain_and_query, data=st.data())
def test_chain_json_round_trip(item, data):
    _, chain = item
    for c in (chain, _relabelled(chain, data)):
        back = Chain.from_json(c.to_json())
        assert back == c and back.certificate == c.certificate
        assert Chain.parse(c.compact()) == c


@SETTINGS
@given(item=chain_and_query, data=st.data())
def test_certificate_invariant_under_relabelling(item, data):
    _, chain = item
    other = _relabelled(chain, data)
    assert other.certificate == chain.certificate
    assert other.code == chain.code and other.dof == chain.dof
    # and it tells the chain apart from every other chain of the same query
    same = [c for c in _chains(*item[0]) if c.certificate == other.certificate]
    assert same == [chain]


@pytest.mark.parametrize("query", _QUERIES)
def test_certificates_distinct_within_a_query(query):
    certs = [c.certificate for c in _chains(*query)]
    assert len(set(certs)) == len(certs)


# ---------------------------------------------------------------------------- balancing
@st.composite
def revolute_arms(draw) -> dict:
    """A random revolute arm in a vertical plane (optionally on a turntable): exactly balanceable."""
    finite = dict(allow_nan=False, allow_infinity=False)
    links = []
    if draw(st.booleans()):
        links.append({"name": "turntable", "joint": "vertical", "length": 0.3, "weight": 0.0})
    for i in range(draw(st.integers(1, 4))):
        length = draw(st.floats(0.1, 1.5, **finite))
        links.append({
            "name": f"link {i + 1}", "joint": "revolute", "length": length,
            "weight": draw(st.floats(0.0, 200.0, **finite)),
            "com": draw(st.floats(-0.2, 1.0, **finite)) * length,
            "com_lateral": draw(st.floats(-0.1, 0.1, **finite)),
            "offset_deg": draw(st.floats(-45.0, 45.0, **finite)),
        })
    arm = {"zero": draw(st.sampled_from(["vertical", "horizontal"])),
           "drives": draw(st.sampled_from(["joint", "base"])),
           "links": links, "check": {"samples": 300, "seed": draw(st.integers(0, 1000))}}
    loads = [{"name": f"load {k}", "link": draw(st.sampled_from(links[-1:] + links[-2:-1]))["name"],
              "weight": draw(st.floats(0.0, 50.0, **finite))} for k in range(draw(st.integers(0, 2)))]
    if loads:
        arm["loads"] = loads
    return {"arm": arm}


@SETTINGS
@given(doc=revolute_arms(), seed=st.integers(0, 2**31 - 1))
def test_random_revolute_arm_balanced_exactly(doc, seed):
    out = balance.solve_arm(doc).to_dict()
    scale = max(1.0, out["max_gravity_force"])
    assert out["max_residual"] <= 1e-9 * scale
    arm = balance.arm_from_dict(doc)
    terms = arm.harmonic_terms()
    # gravity plus the devices (each −A_k·cos(φ_k + α_k)) is constant at random configurations
    q = np.random.default_rng(seed).uniform(-math.pi, math.pi, size=(200, arm.n))
    total = arm.potential(q) - terms_potential(terms, q)
    weights = sum(ln["weight"] for ln in doc["arm"]["links"]) + sum(ld["weight"] for ld in doc["arm"].get("loads", []))
    reach = sum(ln["length"] for ln in doc["arm"]["links"]) + 1.0
    assert np.ptp(total) <= 1e-9 * max(1.0, weights * reach)
    # and the device amplitudes are what the sine devices are sized for (e·T = A_k)
    ets = sorted(d["sine"]["eT"] for d in out["devices"])
    assert ets == pytest.approx(sorted(t.amplitude for t in terms), rel=1e-12)
