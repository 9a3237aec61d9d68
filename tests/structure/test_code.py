import pytest
from hypothesis import given, strategies as st

from synth import Code, MalformedCode


@pytest.mark.parametrize(
    "text, assortment, v, composition, canonical",
    [
        ("6301/0", (6, 3, 0, 1), 0, (), "6301/0"),
        ("4600/0", (4, 6), 0, (), "4600/0"),
        ("12.2000/6", (12, 2), 6, None, "12.2.0.0.0/6"),
        ("12,000/6", (12,), 6, None, "12.0.0.0/6"),
        ("12,000/4-1", (12,), 6, (4, 1), "12.0.0.0/4-1"),
        ("12.2.0.0.0/6", (12, 2), 6, None, "12.2.0.0.0/6"),
        ("2|50/2", (5,), 2, None, "2|5/2"),
        ("64200/0", (6, 4, 2), 0, (), "64200/0"),
    ],
)
def test_parse_and_format(text, assortment, v, composition, canonical):
    c = Code.parse(text)
    assert (c.assortment, c.v, c.composition) == (assortment, v, composition)
    assert str(c) == canonical
    assert Code.parse(str(c)) == c
    assert Code.from_json(c.to_json()) == c


def test_counts_of_seed_codes():
    c = Code.parse("12,000/4-1")  # NaCl-lattice-like structure
    assert (c.links, c.loops, c.dof()) == (12, 4, 3)
    assert Code.parse("8310/1").dof() == 3
    assert Code.parse("64200/0").loops == 5
    # trailing zeros are kept to K digits
    assert str(Code((4, 6), 0)) == "4600/0"


@pytest.mark.parametrize("bad", ["", "6301", "63a1/0", "6301/x", "/0", "12../0", "6,/0", "7201/0", "44/0-", "12,000/4-"])
def test_malformed(bad):
    with pytest.raises(MalformedCode):
        Code.parse(bad)


def test_forced_compositions_are_filled_in():
    # v = 0: no multiple joint; v = 1: exactly one double joint; v >= 2 stays unknown unless given
    assert Code.parse("42/0") == Code((4, 2), 0, ()) and Code.parse("51/1") == Code((5, 1), 1, (1,))
    assert Code.parse("620/2").composition is None


def test_composition_must_match_v():
    with pytest.raises(MalformedCode):
        Code((12,), 5, (4, 1))
    with pytest.raises(MalformedCode):
        Code((-1, 2), 0)


@given(st.lists(st.integers(0, 14), min_size=1, max_size=6), st.integers(0, 12))
def test_round_trip_any(counts, v):
    if (sum(i * c for i, c in enumerate(counts, start=2)) + v) % 2:
        v += 1
    c = Code(tuple(counts), v)
    if c.loops < 0:
        return
    assert Code.parse(str(c)) == c
