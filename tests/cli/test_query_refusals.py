"""Every refusal of a chain query names what is wrong in words a user can act on, and the
options that reach the scheduler and the limits are the ones given.

The CLI prints these sentences as they are (one line, exit 2), so their wording is part of the
contract: a message that lost its numbers or its reason is a bug a user meets.
"""

import pytest

import synth
from synth.structure.query import ChainQuery, parse_cranks as _parse_cranks
from synth.synthesis.type_synthesis import _MAX_BRANCH, plan_codes, plan_jobs


def _codes_of(query: dict):
    """The codes of a query (as the engine plans them), its stage-A jobs' codes."""
    return [code for code, _ in plan_jobs(ChainQuery.of(**query))], None
from synth.execution.scheduler import SchedulerUnreachable
from synth.errors import ImpossibleParameters, InvalidOption, QueryTooLarge


@pytest.mark.parametrize("cranks, text", [
    (["5"], "cranks are written I=C (a link with I joints carrying C cranks), not '5'"),
    (["5=x"], "cranks are written I=C (a link with I joints carrying C cranks), not '5=x'"),
    ({3: "two"}, "cranks are written I=C (a link with I joints carrying C cranks), not '3=two'"),
])
def test_malformed_cranks_are_quoted_back(cranks, text):
    with pytest.raises(InvalidOption) as err:
        _parse_cranks(cranks)
    assert str(err.value) == text


@pytest.mark.parametrize("cranks, i, c", [(["2=3"], 2, 3), (["4=0"], 4, 0), (["0=1"], 0, 1), ({-1: -2}, -1, -2)])
def test_impossible_cranks_say_which(cranks, i, c):
    with pytest.raises(ImpossibleParameters) as err:
        _parse_cranks(cranks)
    assert str(err.value) == f"a link with {i} joints cannot carry {c} cranks"


def test_the_least_cranks_are_accepted():
    # one crank on a link, a link with one joint carrying its one crank: the boundary values
    assert _parse_cranks(["3=1", "1=1", "5=5"]) == ((1, 1), (3, 1), (5, 5))
    assert _parse_cranks({4: 2}) == ((4, 2),)


def test_cranks_against_a_requirement_that_forbids_their_link():
    with pytest.raises(ImpossibleParameters) as err:
        synth.plan_units(1, 10, cranks=["5=5"], require=["5=0"], workers=1)
    assert str(err.value) == "cranks 5=5 need a link with 5 joints, but the requirement n5 = 0 forbids one"


@pytest.mark.parametrize("query, text", [
    (dict(dof=2, links=9, require=["7=1"]),
     "no chain with W = 2 and 9 links has a link with 7 joints: with K = 3 loops a link carries at most 6 "
     "(2K, fractionated chains included)"),
    (dict(dof=2, links=9, require=["6=1"], fractionated=False),
     "no chain with W = 2 and 9 links has a link with 6 joints: with K = 3 loops a link carries at most 4 (K+1)"),
    (dict(dof=1, links=10, require=["6=1"]),
     "no chain with W = 1 and 10 links has a link with 6 joints: with K = 4 loops a link carries at most 5 (K+1)"),
    (dict(dof=3, links=8, n1="0..2", require=["7=1"]),
     "no chain with W = 3 and 8 links has a link with 7 joints: with K = 2 loops a link carries at most 6 "
     "(2K, fractionated chains included, and 2 more for single-joint links)"),
    (dict(dof=1, links=8, n1="0..2", require=["7=1"]),
     "no chain with W = 1 and 8 links has a link with 7 joints: with K = 3 loops a link carries at most 6 "
     "(K+1, and 2 more for single-joint links)"),
])
def test_a_link_degree_beyond_the_bound_says_which_bound(query, text):
    with pytest.raises(ImpossibleParameters) as err:
        plan_codes(**query)
    assert str(err.value) == text


def test_the_degree_bound_is_reached_not_refused():
    # the largest link the bound allows is planned (2K = 6 at W = 2, 9 links; K + 1 = 5 at W = 1, 10 links)
    assert any(c.count(6) for c in plan_codes(2, 9, require=["6=1"]))
    assert all(c.count(5) == 1 for c in plan_codes(1, 10, require=["5=1"]))
    with pytest.raises(ImpossibleParameters, match="carries at most 4 \\(K\\+1\\)"):
        plan_codes(2, 9, require=["6=1"], fractionated=False)


def test_fractionated_chains_are_planned_unless_refused():
    assert plan_codes(2, 9) == plan_codes(2, 9, fractionated=True) != plan_codes(2, 9, fractionated=False)


def test_a_query_without_links_or_code():
    with pytest.raises(InvalidOption) as err:
        plan_codes(1)
    assert str(err.value) == "give the number of links (or a code)"
    with pytest.raises(InvalidOption) as err:
        plan_codes()
    assert str(err.value) == "give the degree of freedom W (and the links), or a code"


@pytest.mark.parametrize("option, value", [("v", "x"), ("n1", "2..x")])
def test_a_malformed_range_names_its_option(option, value):
    with pytest.raises(InvalidOption) as err:
        plan_codes(3, 8, **{option: value})
    assert str(err.value) == f"{option} must be a whole number or a range A..B, not {value!r}"


def test_an_open_code_against_another_n1():
    with pytest.raises(ImpossibleParameters) as err:
        plan_codes(4, 7, code="2|5/2", n1="1")
    assert str(err.value) == "code 2|5/2 has n1 = 2, not the requested n1 = 1"
    with pytest.raises(InvalidOption, match="^n1 must be a whole number"):
        plan_codes(4, 7, code="2|5/2", n1="x")


def test_unknown_options_are_listed():
    with pytest.raises(InvalidOption) as err:
        _codes_of(dict(dof=1, links=8, colour="red", bogus=1))
    assert str(err.value) == "unknown option(s) for a chain query: bogus, colour"


@pytest.mark.parametrize("h", [1, 0, 7])
def test_motion_spaces_without_chains_are_refused(h):
    with pytest.raises(ImpossibleParameters):
        _codes_of(dict(dof=1, links=8, h=h))


def test_the_branch_vertex_limit_is_inclusive():
    # m ternary links and 3 binary ones: W = 3(m + 2) − 2(3m/2 + 3) = 0, m branch vertices
    codes, _ = _codes_of(dict(dof=0, code=f"3.{_MAX_BRANCH}.0/0"))
    assert [c.count(3) for c in codes] == [_MAX_BRANCH]
    with pytest.raises(QueryTooLarge, match=rf"^code 3\.{_MAX_BRANCH + 2}[.0]*/0 has {_MAX_BRANCH + 2} branch vertices") as err:
        _codes_of(dict(dof=0, code=f"3.{_MAX_BRANCH + 2}.0/0"))
    assert f"need 2^{_MAX_BRANCH + 2} sub-chain conditions" in str(err.value)


@pytest.mark.parametrize("count", [synth.count_chains, synth.count_mechanisms])
def test_counts_hand_the_scheduler_and_its_timeout_on(count):
    # port 9 (discard) has nothing listening here: the refusal quotes the address and the timeout
    with pytest.raises(SchedulerUnreachable) as err:
        count(1, 6, scheduler="tcp://127.0.0.1:9", timeout=0.7)
    assert str(err.value).startswith("cannot reach the Dask scheduler at tcp://127.0.0.1:9 within 0.7 s")
    with pytest.raises(SchedulerUnreachable) as err:
        count(1, 6, scheduler="tcp://127.0.0.1:9")
    assert "within 5 s" in str(err.value)


def test_a_table_beyond_its_row_limit_writes_nothing_and_says_how_to_stream(monkeypatch):
    """Whatever feeds a table (a listing the sizing under-estimated, an atlas export), it holds at most
    ``TABLE_ROWS`` rows: one more and it refuses before writing anything; jsonl streams the same rows."""
    import io
    import itertools

    from mechsynth._output import write_rows

    monkeypatch.setattr(synth, "TABLE_ROWS", 3)
    out = io.StringIO()
    assert write_rows([{"a": i} for i in range(3)], ["a"], "table", out) == 3
    endless = ({"a": i} for i in itertools.count())  # bounded only by the limit
    out = io.StringIO()
    with pytest.raises(QueryTooLarge) as err:
        write_rows(endless, ["a"], "table", out)
    assert out.getvalue() == ""
    assert str(err.value) == ("a table is held in memory to align it and this one has more than 3 rows; "
                              "use --format jsonl or csv (streamed), or --count")
    assert write_rows(({"a": i} for i in range(5)), ["a"], "jsonl", io.StringIO()) == 5


def test_a_table_of_mechanisms_is_sized_one_loop_earlier_than_a_count():
    """The mechanisms of 14 links (4.27 million, six loops) are refused as a table before any is built;
    their count, and the table of 12 links, are not sized at all."""
    assert synth.worth_sizing(ChainQuery(1, 14), table=True) and not synth.worth_sizing(ChainQuery(1, 14))
    assert not synth.worth_sizing(ChainQuery(1, 12), table=True)
    with pytest.raises(QueryTooLarge, match=r"this listing \(14 links\) is too large for one \(about .* mechanisms"):
        synth.size_check(ChainQuery(1, 14), processes=2, count=False, table=True, mechanisms="mechanisms")
    assert synth.size_check(ChainQuery(1, 14), processes=2, count=False, table=False, mechanisms="mechanisms") is None


def test_a_count_holds_certificates_not_codes_and_a_listing_that_would_hold_gigabytes_is_refused():
    """Issue 37: the h = 2 count of 12 links grew to 4.5 GiB in silence (stage A kept a code's branch
    multigraphs whole, about 800 000 in its largest code); a count now keeps only their certificates
    (0.6 GiB on 2 workers: not even noted) and runs, where the listing, which keeps them whole for its
    order, is refused with the memory it would hold.  (The count's time, about 13 min on 2 workers,
    lies close to the ten minutes above which it is noted.)"""
    note = synth.size_check(ChainQuery(1, 12, h=2), processes=2, count=True, table=False)
    assert "GiB" not in (note or "")
    with pytest.raises(QueryTooLarge) as err:
        synth.size_check(ChainQuery(1, 12, h=2), processes=2, count=False, table=False)
    text = str(err.value)
    assert text.startswith("this query (12 links) would hold too much memory to run unasked: its largest code has about ")
    assert "kept whole until the code is done" in text and "GiB on 2 workers (more than 1.5 GiB)" in text
    assert text.endswith("give force=True to run it anyway")  # (the CLI says --force)
    assert synth.size_check(ChainQuery(1, 16), processes=2, count=True, table=False) is None
