"""Standard codes: every count a code reports against the chain it stands for, counted by hand, and
every written form and refusal a user reads."""

from __future__ import annotations

import json

import pytest

from synth import Code, MalformedCode


def by_hand(degrees, multiple):
    """Counts of a chain given as its links' joint counts and the orders m_j of its multiple joints
    (links joined by each): n, p = Σ (m_j − 1) over all joints, J, K = p − n + 1."""
    n = len(degrees)
    incidences = sum(degrees)  # Σ over joints of m_j: a simple joint counts 2, a joint of order m counts m
    simple = (incidences - sum(multiple)) // 2
    p = simple + sum(m - 1 for m in multiple)
    joints = simple + len(multiple)
    return n, p, joints, p - n + 1


@pytest.mark.parametrize("text, degrees, multiple", [
    ("6301/0", [2] * 6 + [3] * 3 + [5], []),
    ("7201/1", [2] * 7 + [3] * 2 + [5], [3]),
    ("12,000/4-1", [2] * 12, [3, 3, 3, 3, 4]),
    ("2|50/2", [1, 1] + [2] * 5, [3, 3]),
    ("4600/0", [2] * 4 + [3] * 6, []),
])
def test_counts_against_the_chain(text, degrees, multiple):
    c = Code.parse(text)
    n, p, joints, loops = by_hand(degrees, multiple)
    assert (c.links, c.simple_joint_equivalents, c.joints, c.loops) == (n, p, joints, loops)
    assert c.v == sum(m - 2 for m in multiple)
    for i in range(0, 8):
        assert c.count(i) == degrees.count(i), i
    assert c.max_degree == max(degrees)
    for h in (2, 3, 6):
        for f in (0, 2):
            assert c.dof(h, f) == (n - 1) - (h - 1) * loops + f


def test_max_degree_of_chains_without_assortment():
    assert Code((), 0, n1=2).max_degree == 1  # a lone bar: two free ends
    assert Code((), 0).max_degree == 0
    assert Code((3,), 0).max_degree == 2


@pytest.mark.parametrize("code, text", [
    (Code((11,), 0), "11.0/0"),           # never read back as Pozhbelko's '11' form
    (Code((12, 20), 0), None),
    (Code((4, 6), 0), "4600/0"),
    (Code((2, 0, 1), 0), "201/0"),
    (Code((12,), 6, (4, 1)), "12.0.0.0/4-1"),
    (Code((5,), 2, None, 2), "2|5/2"),
    (Code((10, 1), 1), "10.1/1"),
])
def test_written_forms_read_back(code, text):
    written = str(code)
    if text is not None:
        assert written == text
    assert Code.parse(written) == code and str(Code.parse(written)) == written


def test_compositions_are_kept_without_trailing_zeros():
    c = Code((12,), 6, (4, 1, 0))
    assert c.composition == (4, 1) and str(c) == "12.0.0.0/4-1"
    assert Code.parse("620/0-1").composition == (0, 1) and Code((6, 2), 2, (0, 1)).joints == 8
    assert Code.parse("12.20/0") == Code((12, 2), 0)  # Pozhbelko's form: 12, then one digit per count
    assert Code.parse("10.1/1") == Code((10, 1), 1)


def test_a_composition_of_double_joints_only_is_written_as_v():
    """Six double joints: the composition (6,) is written as v = 6, which reads back as v alone."""
    c = Code((12,), 6, (6,))
    assert str(c) == "12.0.0.0/6" and c.composition == (6,)
    assert Code.parse(str(c)) == Code((12,), 6) and Code.parse(str(c)).composition is None


def test_dict_and_json():
    c = Code((5,), 2, (2,), 2)
    assert c.to_dict() == {"code": "2|5/2", "links": 7, "loops": 1, "v": 2, "assortment": [5], "composition": [2],
                           "n1": 2}
    assert Code((4, 6), 0).to_dict() == {"code": "4600/0", "links": 10, "loops": 4, "v": 0, "assortment": [4, 6],
                                         "composition": []}
    assert "composition" not in Code((6, 2), 2).to_dict() and "n1" not in Code((6, 2), 2).to_dict()
    assert json.loads(c.to_json()) == c.to_dict() and c.to_json().startswith('{"assortment": [5]')
    assert Code.from_dict({"assortment": [5], "v": 2, "n1": 2, "extra": 1}) == Code((5,), 2, None, 2)
    assert Code.from_json(c.to_json()) == c


@pytest.mark.parametrize("call, words", [
    (lambda: Code.from_dict({"v": 1}), "not a code object: 'assortment'"),
    (lambda: Code.from_dict({"assortment": [4, 2], "v": "x"}), "not a code object: invalid literal"),
    (lambda: Code.from_dict({"assortment": 4, "v": 0}), "not a code object: "),
    (lambda: Code.from_json("{x"), "code JSON is not valid JSON: Expecting property name enclosed in double quotes"),
    (lambda: Code.parse(5), "a code must be text such as '6301/0', not 5"),
    (lambda: Code.parse("63a1/0"), "cannot read code '63a1/0': expected digits n2n3…/v such as '6301/0', "
                                   "'12.2.0.0.0/6' or '12,000/4-1'"),
    (lambda: Code.parse("12../0"), "cannot read code '12../0': empty count between separators"),
    # a code copied from a listing with what the listing writes beside it: the option that asks for it named
    (lambda: Code.parse("62/0 K3=1 K5=1"), "cannot read code '62/0 K3=1 K5=1': the code is '62/0'; 'K3=1 K5=1' is "
                                           "written beside it by a listing (asked with --loop-classes H=K,H=K)"),
    (lambda: Code.parse("8310/1 P3"), "cannot read code '8310/1 P3': the code is '8310/1'; 'P3' is written"),
    (lambda: Code.parse("221/0 G3"), "cannot read code '221/0 G3': the code is '221/0'; 'G3' is written beside it by "
                                     "a listing (asked with mechsynth gears)"),
    (lambda: Code.parse("6301/0 x"), "cannot read code '6301/0 x': expected digits"),
    (lambda: Code.parse("7201/0"), "code 7201/0 is impossible: the joint incidences Σ i·n_i + v must be even"),
    (lambda: Code.parse("2|5/1"), "code 2|5/1 is impossible"),
    (lambda: Code((12,), 5, (4, 1)), "composition 4-1 gives v = 6, not v = 5"),
    (lambda: Code((-1, 2), 0), "link counts and v must not be negative"),
    (lambda: Code((4,), -2), "link counts and v must not be negative"),
    (lambda: Code((4,), 0, None, -2), "link counts and v must not be negative"),
    (lambda: Code((4,), 0, (2, -1)), "link counts and v must not be negative"),
])
def test_refusals_say_what_is_wrong(call, words):
    with pytest.raises(MalformedCode) as caught:
        call()
    assert str(caught.value).startswith(words)


def test_a_code_of_more_loops_than_can_be_written_is_refused_briefly():
    """Two binary links and v multiple joints: p = (4 + v)/2, K = p − 1; v = 20 000 gives 10 001 loops, past
    the 10 000 a code is read with (one count per loop); a long text is shown by its first 20 characters."""
    assert Code.parse("2/19998").loops == 10_000
    with pytest.raises(MalformedCode) as caught:
        Code.parse(" 2/20000 ")
    assert str(caught.value) == "code 2/20000 describes a chain of 10001 loops, more than the 10000 a code is read with"
    for width, shown in ((40, "2" + "0" * 33 + "/20000"), (41, "2" + "0" * 19 + "… (41 characters)")):
        with pytest.raises(MalformedCode) as caught:
            Code.parse("2" + "0" * (width - 7) + "/20000")
        assert str(caught.value).startswith(f"code {shown} describes"), width
    wide = "2" + "0" * 40 + "/20000"
    with pytest.raises(MalformedCode) as caught:
        Code.parse(wide)
    assert str(caught.value) == (f"code {wide[:20]}… (47 characters) describes a chain of 10001 loops, more than "
                                 "the 10000 a code is read with")


def test_a_code_of_thousands_of_loops_is_quoted_briefly():
    """A code is written with one count per loop: an impossible code of 10 001 loops is refused in one
    sentence that quotes its head and how many counts it has, not a 20 kB line."""
    with pytest.raises(MalformedCode) as caught:
        Code((0, 20001), 0)
    sentence = str(caught.value)
    assert len(sentence) < 200
    assert sentence.startswith("code 0.20001.0.")
    assert "…/0 (10001 counts n2, n3, …) is impossible" in sentence
    assert Code((0, 20000), 0).brief.endswith("…/0 (10001 counts n2, n3, …)")
    assert len(str(Code((0, 20000), 0))) > 20000  # the notation itself stays whole
