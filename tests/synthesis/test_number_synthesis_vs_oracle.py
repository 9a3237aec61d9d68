"""Number synthesis (CP-SAT) against plain loops over integer vectors, where the other tests stop.

``tests/synthesis/test_number_synthesis.py`` compares the codes without joint compositions.  Here
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
        # the limit theorem's default: joints of order ≤ K (closed) or ≤ K + W (open)
        most = max_multiplicity or (K + 1 if n1_max == 0 else K + dof + 1)
        incidences = sum(i * c for i, c in enumerate(counts, start=1))
        splits = compositions(v, incidences, most)
        if not split:
            if splits:
                found.add(Code(counts[1:], v, None, counts[0]))
            continue
        for comp in splits:
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
    # without compositions a code needs only some split of v (the fewest joints decide it)
    assert set(number_synthesis(dof, loops=K, max_multiplicity=mm)) == brute(dof, K, max_multiplicity=mm)


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


@pytest.mark.parametrize("dof, n, h, f", [(1, 10, 3, 0), (1, 8, 4, 0), (1, 9, 5, 1), (2, 9, 2, 0), (0, 6, 6, 0),
                                          (1, 7, 6, 0), (3, 11, 3, 1), (1, 5, 2, 0)])
def test_links_give_the_loops(dof, n, h, f):
    """Given n, K = (n − W − 1 + f)/(h − 1) loops: the same codes as the brute force for that K."""
    K = (n - dof - 1 + f) // (h - 1)
    assert (n - dof - 1 + f) % (h - 1) == 0
    assert set(number_synthesis(dof, links=n, h=h, f=f)) == brute(dof, K, h=h, f=f, n=n)


@pytest.mark.parametrize("kwargs, sentence", [
    (dict(dof=1, links=9), "no whole number of loops fits: n = W + 1 + (h − 1)·K − f needs n − W − 1 + f = 7 to be a "
                           "non-negative multiple of h − 1 = 2 (W=1, n=9, h=3, f=0)"),
    (dict(dof=1, links=9, h=4, f=1), "no whole number of loops fits: n = W + 1 + (h − 1)·K − f needs n − W − 1 + f = 8 "
                                     "to be a non-negative multiple of h − 1 = 3 (W=1, n=9, h=4, f=1)"),
    (dict(dof=5, links=3), "no whole number of loops fits: n = W + 1 + (h − 1)·K − f needs n − W − 1 + f = -3 "),
    (dict(dof=1, links=8, h=1), "with h = 1 the number of links does not fix the loops: give loops=K"),
    (dict(dof=1, loops=2, require=["0=1"]), "a link carries at least one joint; requirement on n0 is impossible"),
])
def test_impossible_parameters_say_why(kwargs, sentence):
    from synth import ImpossibleParameters

    with pytest.raises(ImpossibleParameters) as info:
        number_synthesis(**kwargs)
    assert str(info.value).startswith(sentence)


@pytest.mark.parametrize("require, sentence", [
    (["x=1"], "a requirement names the number of joints on a link, not 'x'"),
    (["5"], "a requirement is written I=N, I=A..B or I=A.. (e.g. 5=1..), not '5'"),
    (["5=1=2"], "n5 must be a whole number or a range A..B, not '1=2'"),
])
def test_bad_requirements_say_why(require, sentence):
    from synth import InvalidOption

    with pytest.raises(InvalidOption) as info:
        number_synthesis(1, loops=3, require=require)
    assert str(info.value).startswith(sentence)


def test_links_zero_loops_and_single_loop():
    """h = 1 with loops given; a single loop is K = 1 with n = W + h."""
    assert set(number_synthesis(1, loops=1, h=1, n1="0..2")) == brute(1, 1, h=1, n1_max=2)
    assert [str(c) for c in number_synthesis(1, links=4)] == ["4/0"]


def test_a_query_object_and_its_keywords_ask_the_same():
    """``CodeQuery`` carries the keywords whole: the query and its keywords give the same codes,
    and the keywords that do not belong to it, or contradict each other, are refused."""
    from synth import CodeQuery, InvalidOption

    assert number_synthesis(CodeQuery(1, loops="1..3", require=["4=1.."])) == \
        number_synthesis(1, loops="1..3", require=["4=1.."]) == number_synthesis(dof=1, loops="1..3", require=["4=1.."])
    for kwargs, sentence in [
        (dict(loops=2, loop_classes={3: 1}), "give exactly one of loops (K), links (n) or loop classes (K_h)"),
        (dict(loops=2, colour="red"), "unknown option(s) for number synthesis: colour"),
        (dict(loops=2, dof=1), "W is given twice (as the first argument and as dof)"),
    ]:
        with pytest.raises(InvalidOption) as info:
            number_synthesis(1, **kwargs)
        assert str(info.value) == sentence
    with pytest.raises(InvalidOption, match="give a query or its options, not both"):
        number_synthesis(CodeQuery(1, loops=2), h=5)


def test_make_problem_defaults():
    """Planar (h = 3), no extra pair mobility, closed chains, no compositions unless asked."""
    from synth.synthesis.number_synthesis import make_problem

    p = make_problem(1, loops=4)
    assert (p.links, p.loops, p.n1, p.v, p.compositions, p.max_link_degree) == (10, 4, (0, 0), (0, 6), False, 5)
    assert make_problem(2, links=9).loops == 3


@pytest.mark.parametrize("kwargs, error, sentence", [
    (dict(dof=1.5, loops=2), "InvalidOption", "the degree of freedom W must be a whole number, not 1.5"),
    (dict(dof=True, loops=2), "InvalidOption", "the degree of freedom W must be a whole number, not True"),
    (dict(dof=1, loops=2, h=2.0), "InvalidOption", "the motion space h must be a whole number, not 2.0"),
    (dict(dof=1, loops=2, f="1"), "InvalidOption", "the extra pair mobility f must be a whole number, not '1'"),
    (dict(dof=-1, loops=2), "ImpossibleParameters", "the degree of freedom W must be 0 or more, not -1"),
    (dict(dof=1, loops=2, h=0), "ImpossibleParameters", "the motion space h of a loop is 1 … 6 (6: general spatial loop), not 0"),
    (dict(dof=1, loops=2, h=7), "ImpossibleParameters", "the motion space h of a loop is 1 … 6 (6: general spatial loop), not 7"),
    (dict(dof=1, loops=2, f=-1), "ImpossibleParameters", "the extra pair mobility f must be 0 or more, not -1"),
    (dict(dof=1), "InvalidOption", "give exactly one of loops (K), links (n) or loop classes (K_h)"),
    (dict(dof=1, loops=2, links=6), "InvalidOption", "give exactly one of loops (K), links (n) or loop classes (K_h)"),
    (dict(dof=1, loop_classes={}), "ImpossibleParameters", "loop classes are pairs h=K_h with h ≥ 1 and K_h ≥ 0"),
    (dict(dof=1, loop_classes={0: 1}), "ImpossibleParameters", "loop classes are pairs h=K_h with h ≥ 1 and K_h ≥ 0"),
    (dict(dof=1, loop_classes={3: -1, 5: 1}), "ImpossibleParameters", "loop classes are pairs h=K_h"),
    (dict(dof=1, loops=-1), "ImpossibleParameters", "the number of loops K must be 0 or more, not -1"),
    (dict(dof=1, loops=True), "ImpossibleParameters", "the number of loops K must be 0 or more, not True"),
    (dict(dof=1, links=0), "ImpossibleParameters", "the number of links n must be 1 or more, not 0"),
    (dict(dof=1, links=2.0), "ImpossibleParameters", "the number of links n must be 1 or more, not 2.0"),
    (dict(dof=1, links=2), "ImpossibleParameters", "a closed chain has at least one loop"),
    (dict(dof=0, links=1), "ImpossibleParameters", "a closed chain has at least one loop"),
    (dict(dof=1, loops=2, require={"3": "1", 3: "2"}), "ImpossibleParameters", "conflicting requirements on n3: (1, 1) and (2, 2)"),
])
def test_make_problem_refusals(kwargs, error, sentence):
    import synth
    from synth.synthesis.number_synthesis import make_problem

    with pytest.raises(getattr(synth, error)) as info:
        make_problem(**kwargs)
    assert str(info.value).startswith(sentence)


@pytest.mark.parametrize("kwargs, links, loops", [
    (dict(dof=1, loop_classes={1: 1, 3: 1}), 4, 2),       # a class with h = 1 (an elastic coupling)
    (dict(dof=1, loop_classes={3: 0, 5: 1}), 6, 1),       # an empty class is allowed
    (dict(dof=2, loops=0, n1=2), 3, 0),                   # an open chain has no loop
    (dict(dof=1, links=2, n1="0..2"), 2, 0),              # nor here: n = W + 1
    (dict(dof=1, loops=2, require=["3=1", "3=1"]), 6, 2),  # the same requirement twice is one
])
def test_make_problem_accepts(kwargs, links, loops):
    from synth.synthesis.number_synthesis import make_problem

    p = make_problem(**kwargs)
    assert (p.links, p.loops) == (links, loops)


@pytest.mark.parametrize("kwargs, brute_kwargs", [
    (dict(), dict()),
    (dict(compositions=True), dict(split=True)),
    (dict(compositions=True, max_multiplicity=3), dict(split=True, max_multiplicity=3)),
    (dict(require=["2=3..5"]), dict(require={2: (3, 5)})),
    (dict(require=["2=..3"]), dict(require={2: (0, 3)})),
    (dict(require=["3=1.."], max_link_degree=4), dict(require={3: (1, None)}, imax=4)),
    (dict(max_link_degree="K+W"), dict(imax="K+W")),
], ids=["plain", "compositions", "multiplicity", "n2-low", "n2-high", "n3", "K+W"])
@pytest.mark.parametrize("dof", [0, 1, 3])
def test_single_loop_equals_brute_force_and_the_model(dof, kwargs, brute_kwargs):
    """One loop (every link binary) is listed without CP-SAT: the same codes as the model."""
    from synth.synthesis.number_synthesis import _direct_codes, _model_codes, make_problem

    bk = dict(brute_kwargs)
    if bk.get("imax") == "K+W":
        bk["imax"] = max(2, 1 + dof)  # a closed chain allows binary links whatever the bound
    problem = make_problem(dof, loops=1, **kwargs)
    assert set(_direct_codes(problem)) == set(_model_codes(problem)) == brute(dof, 1, **bk)
    assert set(number_synthesis(dof, loops=1, **kwargs)) == brute(dof, 1, **bk)


@pytest.mark.parametrize("text, minimum, result", [
    ("x", 0, "InvalidOption: v must be a whole number or a range A..B, not 'x'"),
    ("1..2..3", 0, "InvalidOption: v must be a whole number or a range A..B, not '1..2..3'"),
    (True, 0, "InvalidOption: v must be a whole number or a range A..B, not True"),
    ([1], 0, "InvalidOption: v must be a whole number or a range A..B, not [1]"),
    ((1, 2, 3), 0, "InvalidOption: v must be a whole number or a range A..B, not (1, 2, 3)"),
    ("-1", 0, "ImpossibleParameters: v must not be below 0 (got '-1')"),
    ((None, 2), 0, "ImpossibleParameters: v must not be below 0 (got (None, 2))"),
    ("2..", 3, "ImpossibleParameters: v must not be below 3 (got '2..')"),
    ("3..1", 0, "InvalidOption: the range for v is empty: 3..1"),
    ("..3", 1, (1, 3)), ("3..", 3, (3, None)), (" 2 .. 4 ", 0, (2, 4)), ((1, 2), 0, (1, 2)), (5, 0, (5, 5)),
])
def test_parse_range_readings_and_sentences(text, minimum, result):
    from synth.synthesis.number_synthesis import parse_range

    try:
        got = parse_range(text, "v", minimum=minimum)
    except Exception as exc:  # noqa: BLE001 - the sentence is the result
        got = f"{type(exc).__name__}: {exc}"
    assert got == result


@pytest.mark.parametrize("bound, name", [(None, "K+1"), ("K+W", "K+W"), ("K+1", "K+1"), (4, "4"), (" 4 ", "4")])
def test_a_required_link_beyond_the_bound_names_the_bound(bound, name):
    from synth import ImpossibleParameters

    with pytest.raises(ImpossibleParameters) as refused:
        number_synthesis(1, loops=3, require=["6=1"], max_link_degree=bound)
    assert str(refused.value).endswith(f"(the bound {name} with K = 3 loops)")


def test_the_single_loop_without_a_solver():
    """K = 1, closed: n binary links and v = 0, whatever else is asked; with compositions an empty one."""
    assert [str(c) for c in number_synthesis(1, loops=1)] == ["4/0"]
    assert [str(c) for c in number_synthesis(1, loops=1, v="0..2")] == ["4/0"]
    assert number_synthesis(1, loops=1, require=["2=0..3"]) == [] and number_synthesis(1, loops=1, require=["3=0"])
    assert [str(c) for c in number_synthesis(1, loops=1, require=["2=4.."])] == ["4/0"]
    (code,) = number_synthesis(2, loops=1, compositions=True)
    assert (code.assortment[0], code.v, code.n1, code.composition) == (5, 0, 0, ())  # no multiple joint


@pytest.mark.parametrize("kwargs, sentence", [
    (dict(links=3), "no whole number of loops fits: n = W + 1 + (h − 1)·K − f needs n − W − 1 + f = 1 to be a "
                    "non-negative multiple of h − 1 = 2 (W=1, n=3, h=3, f=0)"),
    (dict(dof=3, links=4, n1=5), "n1 = 5 single-joint links do not fit in 4 links"),
    (dict(dof=3, links=6, n1="7.."), "n1 = 7 single-joint links do not fit in 6 links"),
    (dict(dof=3, links=6, n1="6.."), None),  # every link a free end is still a size
    (dict(loops=0), "a closed chain has at least one loop (K ≥ 1); for open chains give n1"),
    (dict(loops=3, v=9), "v = 9 is too large: a chain with K = 3 loops and 8 links has v ≤ 2(K − 1) + n1 = 4"),
    (dict(loops=3, v="5..9"), "v = 5 is too large: a chain with K = 3 loops and 8 links has v ≤ 2(K − 1) + n1 = 4"),
    (dict(loops=3, max_link_degree="x"), "the largest link degree is a whole number, 'K+1' or 'K+W', not 'x'"),
    (dict(loops=3, max_link_degree=1),
     "the largest link degree must be 2 or more (a link of a closed chain carries at least 2 joints), not 1"),
    (dict(loops=3, max_link_degree=2), None),
    (dict(dof=3, links=6, n1=2, max_link_degree=0),
     "the largest link degree must be 1 or more (a link of an open chain carries at least 1 joint), not 0"),
    (dict(dof=3, links=6, n1=2, max_link_degree=1), None),
    (dict(loops=3, require=["1=1"]), "a closed chain has no single-joint links; give n1 for an open chain"),
    (dict(loops=3, require=["1=0"]), None),
    (dict(loops=3, require=["3=9"]), "n3 ≥ 9 links is more than the 8 links of the chain"),
    (dict(loops=3, require=["2=5", "3=5"]), "the requirements ask for 10 links, more than n = 8"),
    (dict(loops=3, max_multiplicity=1), "a joint joins at least 2 links: the largest multiplicity must be 2 or more, not 1"),
    (dict(loops=3, max_multiplicity="3"),
     "a joint joins at least 2 links: the largest multiplicity must be 2 or more, not '3'"),
    (dict(loops=3, n1=-1), "n1 must not be below 0 (got -1)"),
])
def test_make_problem_sentences(kwargs, sentence):
    """Each refusal of the counting problem, word for word; the cases beside them are accepted."""
    from synth.synthesis.number_synthesis import make_problem

    kwargs = {"dof": 1, **kwargs}
    if sentence is None:
        problem = make_problem(**kwargs)
        assert problem.dof == kwargs["dof"]
        return
    with pytest.raises(Exception) as refused:
        make_problem(**kwargs)
    assert str(refused.value) == sentence
