"""Number synthesis (CP-SAT) against plain loops over integer vectors, where the other tests stop.

``tests/test_number_synthesis.py`` compares the codes without joint compositions.  Here
the brute force also lists the compositions (v2, v3, …: how many joints join 3, 4, …
links), the multiplicity limit, loop classes K_h, design requirements with both ends,
open chains and the output order — by nested loops over integer vectors, no solver.
"""

from __future__ import annotations

import itertools

import pytest

from synth import Code, number_synthesis


def assortments(n: int, K: int, imax: int, n1_max: int):
    """(n1, n2 … n_imax, v) with Σ n = n, Σ i·n_i + v = 2(K + n − 1), v ≥ 0."""
    for counts in itertools.product(range(n + 1), repeat=imax):
        if sum(counts) != n or counts[0] > n1_max:
            continue
        v = 2 * (K + n - 1) - sum(i * c for i, c in enumerate(counts, start=1))
        if v >= 0:
            yield counts, v


def compositions(v: int, incidences: int, max_multiplicity: int):
    """Joint counts (x3, x4, …) with Σ (m − 2)·x_m = v and Σ m·x_m ≤ incidences (m ≤ max)."""
    sizes = list(range(3, max_multiplicity + 1))
    out = []

    def rec(i, left, chosen):
        if left == 0:
            x = chosen + [0] * (len(sizes) - len(chosen))
            if sum(m * k for m, k in zip(sizes, x)) <= incidences:
                while x and x[-1] == 0:
                    x.pop()
                out.append(tuple(x))
            return
        if i == len(sizes):
            return
        step = sizes[i] - 2
        for k in range(left // step + 1):
            rec(i + 1, left - k * step, chosen + [k])

    rec(0, v, [])
    return out


def brute(dof, K, *, h=3, f=0, n=None, n1_max=0, imax=None, v_range=None, max_multiplicity=None,
          require=None, split=False):
    n = dof + 1 + (h - 1) * K - f if n is None else n
    imax = imax or K + 1
    v_lo, v_hi = v_range if v_range else (0, 2 * (K - 1) + n1_max)
    found = set()
    for counts, v in assortments(n, K, imax, n1_max):
        if not v_lo <= v <= v_hi:
            continue
        if require and any(not (lo <= counts[i - 1] <= (n if hi is None else hi)) for i, (lo, hi) in require.items()):
            continue
        if max_multiplicity == 2 and v:
            continue
        if not split:
            found.add(Code(counts[1:], v, None, counts[0]))
            continue
        incidences = sum(i * c for i, c in enumerate(counts, start=1))
        for comp in compositions(v, incidences, max_multiplicity or n):
            found.add(Code(counts[1:], v, comp, counts[0]))
    return found


@pytest.mark.parametrize("dof", range(4))
@pytest.mark.parametrize("K", range(1, 5))
def test_compositions_equal_brute_force(dof, K):
    assert set(number_synthesis(dof, loops=K, compositions=True)) == brute(dof, K, split=True)


@pytest.mark.parametrize("mm", [2, 3, 4])
@pytest.mark.parametrize("dof, K", [(1, 3), (1, 4), (3, 4), (0, 4)])
def test_multiplicity_limit_equals_brute_force(dof, K, mm):
    assert set(number_synthesis(dof, loops=K, compositions=True, max_multiplicity=mm)) == brute(
        dof, K, split=True, max_multiplicity=mm)
    if mm == 2:
        assert set(number_synthesis(dof, loops=K, max_multiplicity=2)) == brute(dof, K, max_multiplicity=2)


@pytest.mark.parametrize("classes, dof, f", [({3: 2, 5: 1}, 1, 0), ({2: 1, 3: 1}, 1, 0), ({3: 3}, 2, 1),
                                             ({6: 1, 3: 1}, 1, 0)])
def test_loop_classes_equal_brute_force(classes, dof, f):
    K = sum(classes.values())
    n = dof + 1 + sum((h - 1) * k for h, k in classes.items()) - f
    assert set(number_synthesis(dof, loop_classes=classes, f=f)) == brute(dof, K, n=n)


@pytest.mark.parametrize("kwargs, brute_kwargs", [
    (dict(require=["2=4..6", "3=1..3"]), dict(require={2: (4, 6), 3: (1, 3)})),
    (dict(require={4: (0, 0)}, v="1..3"), dict(require={4: (0, 0)}, v_range=(1, 3))),
    (dict(n1="1..2", require=["1=2"]), dict(n1_max=2, require={1: (2, 2)})),
    (dict(max_link_degree="K+W", v=0), dict(imax="K+W", v_range=(0, 0))),
], ids=["ranges", "upper-zero", "open", "K+W"])
@pytest.mark.parametrize("dof, K", [(1, 4), (2, 3), (3, 3)])
def test_requirements_equal_brute_force(dof, K, kwargs, brute_kwargs):
    bk = dict(brute_kwargs)
    if bk.get("imax") == "K+W":
        bk["imax"] = K + dof
    n1_max = bk.get("n1_max", 0)
    if "v_range" not in bk:
        bk["v_range"] = (0, 2 * (K - 1) + n1_max)
    assert set(number_synthesis(dof, loops=K, **kwargs)) == brute(dof, K, **bk)


@pytest.mark.parametrize("dof, K", [(1, 4), (2, 4), (0, 5)])
def test_output_order(dof, K):
    """Sorted by loops, free links, v, assortment, composition; no code twice."""
    codes = number_synthesis(dof, loops=(1, K), compositions=True, n1="0..1")
    keys = [(c.loops, c.n1, c.v, c.assortment, c.composition or ()) for c in codes]
    assert keys == sorted(keys) and len(set(codes)) == len(codes)
    want = set()
    for k in range(1, K + 1):
        want |= brute(dof, k, n1_max=1, split=True)
    assert set(codes) == want
