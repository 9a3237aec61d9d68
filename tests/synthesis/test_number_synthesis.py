"""Number synthesis against Pozhbelko's tables (docs/theory.md) and an independent brute force (plain loops)."""

import itertools

import pytest

from synth import Code, ImpossibleParameters, InvalidOption, number_synthesis


def brute_force_codes(dof, K, *, h=3, f=0, imax=None, n1_max=0, v_max=None, require=None):
    """All (n1, n2, …, n_imax, v) with Σn = n and Σ i·n_i + v = 2(K + n − 1), by nested loops."""
    n = dof + 1 + (h - 1) * K - f
    imax = imax or K + 1
    v_max = 2 * (K - 1) + n1_max if v_max is None else v_max
    found = set()
    for counts in itertools.product(range(n + 1), repeat=imax):
        if sum(counts) != n or counts[0] > n1_max:
            continue
        if require and any(not (lo <= counts[i - 1] <= (hi if hi is not None else n)) for i, (lo, hi) in require.items()):
            continue
        v = 2 * (K + n - 1) - sum(i * c for i, c in enumerate(counts, start=1))
        if 0 <= v <= v_max:
            found.add(Code(counts[1:], v, None, counts[0]))
    return found


def test_universal_table_1():
    codes = number_synthesis(1, loops="1..5")
    assert len(codes) == 89
    per_k = [sum(1 for c in codes if c.loops == k) for k in range(1, 6)]
    assert per_k == [1, 3, 9, 23, 53]
    assert all(c.v <= 2 * (c.loops - 1) for c in codes)


def test_locomotive_drive():
    codes = number_synthesis(1, loops=4, require={5: (1, None)})
    assert [str(c) for c in codes] == ["6301/0", "7111/0", "8002/0", "7201/1", "8011/1", "8101/2", "9001/3"]


@pytest.mark.parametrize("K, code", [(2, "32/0"), (3, "430/1"), (3, "520/2"), (4, "9000/6"), (5, "81200/3")])
def test_trusses(K, code):
    assert Code.parse(code) in number_synthesis(0, loops=K)


def test_seed_codes_are_standard():
    assert Code.parse("64200/0") in number_synthesis(1, loops=5)
    assert Code.parse("8310/1") in number_synthesis(3, loops=4)
    assert Code.parse("12,000/6") in number_synthesis(3, loops=4)
    comps = number_synthesis(3, loops=4, v=6, compositions=True)
    assert Code.parse("12,000/4-1") in comps


@pytest.mark.parametrize("dof", range(6))
@pytest.mark.parametrize("K", range(1, 6))
def test_agrees_with_brute_force(dof, K):
    assert set(number_synthesis(dof, loops=K)) == brute_force_codes(dof, K)


@pytest.mark.parametrize(
    "kwargs, brute",
    [
        (dict(dof=4, loops=1, n1=(0, 2)), dict(dof=4, K=1, n1_max=2)),
        (dict(dof=2, loops=2, n1=(0, 3)), dict(dof=2, K=2, n1_max=3)),
        (dict(dof=1, loops=2, h=6), dict(dof=1, K=2, h=6)),
        (dict(dof=1, loops=3, h=4, f=1), dict(dof=1, K=3, h=4, f=1)),
        (dict(dof=1, loops=4, max_link_degree=7), dict(dof=1, K=4, imax=7)),
        (dict(dof=2, loops=3, max_link_degree="K+W"), dict(dof=2, K=3, imax=5)),
        (dict(dof=1, loops=5, require=["3=0..2", "4=1.."]), dict(dof=1, K=5, require={3: (0, 2), 4: (1, None)})),
        (dict(dof=1, loops=4, v="1..2"), None),
    ],
)
def test_agrees_with_brute_force_variants(kwargs, brute):
    got = set(number_synthesis(**kwargs))
    if brute is None:  # a v range is a filter of the full table
        full = brute_force_codes(kwargs["dof"], kwargs["loops"])
        assert got == {c for c in full if 1 <= c.v <= 2}
    else:
        assert got == brute_force_codes(**brute)


def test_compositions_split_v():
    plain = number_synthesis(1, loops=3)
    split = number_synthesis(1, loops=3, compositions=True)
    for code in plain:
        parts = [c for c in split if c.assortment == code.assortment and c.v == code.v]
        assert parts and all(c.composition is not None for c in parts)
    # v = 2 in a 3-loop chain: two double joints or one triple joint
    assert {c.composition for c in split if c.assortment == (6, 2) and c.v == 2} >= {(2,), (0, 1)}


def test_deterministic_order():
    a = [str(c) for c in number_synthesis(2, loops="1..4")]
    assert a == [str(c) for c in number_synthesis(2, loops="1..4")]
    assert len(a) == len(set(a))


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(dof=1, links=11),  # W + 1 + 2K ≠ n
        dict(dof=-1, loops=2),
        dict(dof=1, loops=-2),
        dict(dof=1, loops=3, v=9),
        dict(dof=1, loops=3, h=0),
        dict(dof=1, loops=3, require=["7=1.."]),
        dict(dof=1, loops=3, require=["2=9.."]),
        dict(dof=1, loops=3, require=["3=5..", "2=5.."]),
        dict(dof=1, loops=3, f=-1),
        dict(dof=1, loops=0),
    ],
)
def test_impossible_parameters(kwargs):
    with pytest.raises(ImpossibleParameters):
        number_synthesis(**kwargs)


@pytest.mark.parametrize(
    "kwargs",
    [dict(dof=1), dict(dof=1, loops=2, links=6), dict(dof=1, loops="a..b"), dict(dof=1, loops="3..1"),
     dict(dof=1, loops=2, require=["x"]), dict(dof=1, loops=2, max_link_degree="big")],
)
def test_invalid_options(kwargs):
    with pytest.raises(InvalidOption):
        number_synthesis(**kwargs)
