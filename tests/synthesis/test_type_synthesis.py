"""Type synthesis against the published counts, itself, and random relabelling."""

import os
import random
import signal
import subprocess
import sys

import pytest

import synth
from synth import Chain, Code, ImpossibleParameters, InvalidOption, MalformedChain
from synth.analysis.chains import analyze_chain

W1_BY_CODE = {
    8: {"440/0": 9, "521/0": 5, "602/0": 2},
    10: {"4600/0": 50, "5410/0": 95, "6220/0": 57, "6301/0": 15, "7030/0": 3, "7111/0": 8, "8002/0": 2},
}


@pytest.mark.parametrize("links, count", [(4, 1), (6, 2), (8, 16), (10, 230), (12, 6856)])
def test_one_dof_simple_joints(links, count):
    result = synth.count_chains(1, links)
    assert result["count"] == count
    if links in W1_BY_CODE:
        assert result["by_code"] == W1_BY_CODE[links]


@pytest.mark.parametrize("links, non_planar", [(10, 11), (12, 938)])
def test_non_planar_chains(links, non_planar):
    total = synth.count_chains(1, links)["count"]
    assert total - synth.count_chains(1, links, planar_only=True)["count"] == non_planar


def test_non_planar_flag_agrees_with_networkx():
    chains = list(synth.type_synthesis(1, 10, planar_only=True, workers=1))
    assert all(c.is_planar() for c in chains)
    assert sum(not c.is_planar() for c in synth.type_synthesis(1, 10, workers=1)) == 11


def test_a_listing_decides_planarity_and_fractionation_once_per_branch_multigraph(monkeypatch):
    """A csv listing shows both for every chain; decided chain by chain they made it 5× slower than jsonl
    (12 links: 6 856 chains on 97 branch multigraphs).  Every chain on one H shares H's answers."""
    import networkx as nx

    calls = {"check_planarity": 0, "is_biconnected": 0}
    for name in calls:
        def counted(*args, _real=getattr(nx, name), _name=name, **kwargs):
            calls[_name] += 1
            return _real(*args, **kwargs)
        monkeypatch.setattr(nx, name, counted)
    listed = list(synth.type_synthesis(0, 9, workers=1))  # trusses: non-planar and fractionated ones among them
    units = len(synth.plan_units(0, 9))
    flags = [(c.is_planar(), c.is_fractionated()) for c in listed]
    assert 0 < calls["check_planarity"] <= units < len(listed) and 0 < calls["is_biconnected"] <= units
    alone = [Chain(c.links, c.joints, c.kinds, c.h) for c in listed]  # the same chains, each on its own graph
    assert flags == [(c.is_planar(), c.is_fractionated()) for c in alone]
    assert {False, True} == {p for p, _ in flags} == {f for _, f in flags}


@pytest.mark.parametrize(
    "dof, links, with_fractionated, without",
    [(2, 5, 1, 1), (2, 7, 4, 3), (2, 9, 40, 35), (3, 6, 1, 1), (3, 8, 7, 5), (3, 10, 98, 74)],
)
def test_multi_dof(dof, links, with_fractionated, without):
    with_f = list(synth.type_synthesis(dof, links))
    without_f = list(synth.type_synthesis(dof, links, fractionated=False))
    assert (len(with_f), len(without_f)) == (with_fractionated, without)
    assert sum(c.is_fractionated() for c in with_f) == with_fractionated - without
    assert not any(c.is_fractionated() for c in without_f)


def test_fractionated_links_exceed_k_plus_one():
    # 3-DOF 8 links, K = 2: the figure-eight has a link with 4 > K + 1 joints
    chains = list(synth.type_synthesis(3, 8))
    assert any(max(c.degrees) == 4 for c in chains)
    assert "701/0" in {str(c.code) for c in chains}


@pytest.mark.parametrize(
    "links, v_max, by_v",
    [(6, 2, {0: 2, 1: 1, 2: 1}), (8, 4, {0: 16, 1: 20, 2: 18, 3: 4, 4: 2})],
)
def test_multiple_joints(links, v_max, by_v):
    chains = list(synth.type_synthesis(1, links, v=(0, v_max)))
    got = {}
    for c in chains:
        got[c.v] = got.get(c.v, 0) + 1
    assert got == by_v
    assert len({c.certificate for c in chains}) == len(chains)


def test_certificates_survive_random_relabelling():
    rng = random.Random(42)
    chains = list(synth.type_synthesis(1, 8, v=(0, 4))) + list(synth.type_synthesis(3, 8))
    certs = [c.certificate for c in chains]
    assert len(set(certs)) == len(certs)
    for chain in chains:
        perm = list(range(chain.links))
        rng.shuffle(perm)
        assert chain.relabel(perm).certificate == chain.certificate


def test_every_chain_analyses_to_its_own_code():
    for chain in synth.type_synthesis(1, 8, v=(0, 4)):
        a = analyze_chain(chain, dof=1)
        assert (a.code, a.dof, a.subchain_defect) == (str(chain.code), 1, "none")
        assert Code.parse(a.code).dof() == 1
        assert Chain.from_json(chain.to_json()) == chain


def test_worker_count_does_not_change_the_output():
    one = [c.certificate for c in synth.type_synthesis(2, 9, workers=1)]
    two = [c.certificate for c in synth.type_synthesis(2, 9, workers=2)]
    assert one == two


def test_units_partition_the_output():
    units = synth.plan_units(1, 10)
    assert len({u.key for u in units}) == len(units)
    flat = [c.certificate for u in units for c in synth.run_unit(u)]
    assert flat == [c.certificate for c in synth.type_synthesis(1, 10, workers=1)]


def test_locomotive_drive_chains():
    # W = 1, K = 4 (10 links), a frame with 5 joints for five parallel cranks: the seven codes
    constrained = synth.count_chains(1, 10, v=(0, 3), require=["5=1.."])
    seven = {"6301/0", "7111/0", "8002/0", "7201/1", "8011/1", "8101/2", "9001/3"}
    assert {str(Code(Code.parse(k).assortment, Code.parse(k).v)) for k in constrained["by_code"]} <= seven
    # the requirement inside the model gives exactly the filtered unconstrained search
    everything = list(synth.type_synthesis(1, 10, v=(0, 3)))
    filtered = {}
    for c in everything:
        if 5 in c.degrees:
            key = str(Code(c.code.assortment, c.code.v))
            filtered[key] = filtered.get(key, 0) + 1
    got = {}
    for key, n in constrained["by_code"].items():
        plain = str(Code(Code.parse(key).assortment, Code.parse(key).v))
        got[plain] = got.get(plain, 0) + n
    assert got == filtered
    assert got["6301/0"] == 15 and got["8002/0"] == 2


def test_mechanisms_counts():
    assert [sum(1 for _ in synth.mechanisms(1, n)) for n in (4, 6, 8)] == [1, 5, 71]


def test_trusses_allow_rigid_subchains():
    # K = 2: the 3-string truss and the double triangle (32/0), two triangles on one link (401/0)
    assert synth.count_chains(0, 5)["by_code"] == {"32/0": 2, "401/0": 1}
    assert synth.count_chains(0, 5, fractionated=False)["by_code"] == {"32/0": 2}
    # without rigid sub-chains only the 3-string truss is left: no triangle
    only = list(synth.type_synthesis(0, 5, rigid_subchains=False))
    assert len(only) == 1 and sorted(only[0].degrees) == [2, 2, 2, 3, 3]


@pytest.mark.parametrize(
    "call, exc",
    [
        (lambda: list(synth.type_synthesis(1, 9)), ImpossibleParameters),
        (lambda: list(synth.type_synthesis(1, code="8310/1")), ImpossibleParameters),
        (lambda: list(synth.type_synthesis(1, 8, workers=0)), InvalidOption),
        (lambda: Chain.from_json('{"joints": [[0, 1], [1'), MalformedChain),
        (lambda: Chain.from_json('{"joints": [[0, 0]]}'), MalformedChain),
        (lambda: Chain.parse("0-1 1-x"), MalformedChain),
        (lambda: list(synth.type_synthesis(-1, 8)), ImpossibleParameters),
    ],
)
def test_bad_input(call, exc):
    with pytest.raises(exc):
        call()


@pytest.mark.parametrize(
    "argv",
    [
        ["chains", "--dof", "1", "--links", "9"],
        ["chains", "--dof", "1", "--code", "8310/1"],
        ["chains", "--dof", "1", "--links", "8", "--workers", "0"],
        ["chains", "--dof", "1", "--code", "72x1/1"],
        ["analyze", '{"joints": [[0, 1], [1'],
    ],
)
def test_cli_bad_input(capsys, argv):
    from mechsynth.cli import main

    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.strip().splitlines()) == 1 and err.startswith("mechsynth: ")


def test_cli_count_contract(capsys):
    from mechsynth.cli import main

    assert main(["chains", "--dof", "1", "--links", "10", "--count"]) == 0
    import json

    data = json.loads(capsys.readouterr().out)
    assert data == {"count": 230, "by_code": W1_BY_CODE[10]}


def _read_until(fd: int, marker: bytes, limit_s: float = 600.0) -> bytes:
    """Read a pty until the regular expression ``marker`` matches or it closes (``limit_s`` only
    guards against a hang)."""
    import re
    import select

    data = b""
    while not re.search(marker, data):
        ready, _, _ = select.select([fd], [], [], limit_s)
        if not ready:
            break
        try:
            chunk = os.read(fd, 4096)
        except OSError:  # the other end closed
            break
        if not chunk:
            break
        data += chunk
    return data


def test_ctrl_c_stops_cleanly():
    """SIGINT once the run says it is working (its progress bar on a terminal): exit 130, one line."""
    import fcntl
    import pty
    import struct
    import termios

    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # a 0-column terminal hides the bar
    proc = subprocess.Popen([sys.executable, "-m", "mechsynth", "chains", "--dof", "1", "--links", "14", "--count"],
                            stdout=subprocess.PIPE, stderr=slave, text=True)
    os.close(slave)
    try:
        # the bar shows done/total codes once the run works (inline first, then on the pool: a
        # Ctrl-C while the pool forks must not be lost either)
        started = _read_until(master, rb"\d+/\d+ \[")
        proc.send_signal(signal.SIGINT)
        out, _ = proc.communicate(timeout=600)
        err = (started + _read_until(master, rb"\0")).decode(errors="replace")
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        os.close(master)
    assert proc.returncode == 130 and out == "", err
    lines = [x.strip() for x in err.replace("\r", "\n").splitlines() if x.strip()]
    assert "Traceback" not in err and "mechsynth: interrupted" in lines[-1], err
    assert all("/s]" in x or "/s," in x for x in lines[:-1]), err  # nothing but the progress bar before it


@pytest.mark.slow
def test_fourteen_links():
    assert synth.count_chains(1, 14)["count"] == 318162


def _carries_cranks(chain, joints_on_link, count):
    deg = chain.degrees
    for u in range(chain.links):
        if deg[u] != joints_on_link:
            continue
        cranks = sum(1 for j in chain.joints if len(j) == 2 and u in j and deg[j[0] + j[1] - u] == 2)
        if cranks >= count:
            return True
    return False


@pytest.mark.parametrize("links, v, joints_on_link, count", [(10, (0, 3), 5, 5), (10, (0, 3), 5, 3), (8, (0, 4), 3, 2),
                                                             (9, (0, 2), 4, 4)])
def test_crank_substructure_equals_filter(links, v, joints_on_link, count):
    dof = 1 if links % 2 == 0 else 2
    constrained = [c.certificate for c in synth.type_synthesis(dof, links, v=v, cranks={joints_on_link: count})]
    filtered = [c.certificate for c in synth.type_synthesis(dof, links, v=v) if _carries_cranks(c, joints_on_link, count)]
    assert constrained == filtered and constrained


@pytest.mark.parametrize("dof, links, v, input_link", [(1, 8, (0, 4), False), (3, 8, 0, True), (0, 7, (0, 2), False)])
def test_counts_made_in_workers_equal_the_streamed_results(dof, links, v, input_link):
    chains = list(synth.type_synthesis(dof, links, v=v, workers=2))
    tally = {}
    for c in chains:
        tally[str(c.code)] = tally.get(str(c.code), 0) + 1
    assert synth.count_chains(dof, links, v=v, workers=2).to_dict() == {"count": len(chains), "by_code": tally}
    mechs = list(synth.mechanisms(dof, links, v=v, input_link=input_link, workers=1))
    assert synth.count_mechanisms(dof, links, v=v, input_link=input_link, workers=2)["count"] == len(mechs)


@pytest.mark.parametrize("v, require, message", [
    ("0", None, "code 7201/1 has v = 1, outside the requested v = 0"),
    ("2..", None, "code 7201/1 has v = 1, outside the requested v = 2.."),
    ("2..3", None, "code 7201/1 has v = 1, outside the requested v = 2..3"),
    (None, ["4=1"], "code 7201/1 has 0 link(s) with 4 joints, but the requirement asks for n4 = 1"),
    (None, ["2=8.."], "code 7201/1 has 7 link(s) with 2 joints, but the requirement asks for n2 = 8.."),
    (None, ["2=0..6"], "code 7201/1 has 7 link(s) with 2 joints, but the requirement asks for n2 = 0..6"),
    ("x", None, "v must be a whole number or a range A..B, not 'x'"),
])
def test_a_code_contradicting_its_query_is_refused_with_the_numbers(v, require, message):
    from synth.synthesis.type_synthesis import plan_units

    with pytest.raises((ImpossibleParameters, InvalidOption)) as refused:
        plan_units(1, code="7201/1", v=v, require=require, workers=1)
    assert str(refused.value) == message


@pytest.mark.parametrize("v, require", [("1", None), ("0..1", None), ("1..", None), (None, ["2=7"]), (None, ["2=7.."]),
                                        (None, ["2=0..7"]), ("0..", ["3=2", "4=0"])])
def test_a_code_on_the_edge_of_its_query_is_accepted(v, require):
    """v and n_i exactly at a range's ends, and open ranges, admit the code 7201/1 (n2 = 7, n3 = 2, v = 1)."""
    from synth.synthesis.type_synthesis import plan_units

    assert {str(u.code) for u in plan_units(1, code="7201/1", v=v, require=require, workers=1)} == {"7201/1"}


def test_progress_bar_on_a_terminal_counts_codes_and_chains(monkeypatch):
    """On a terminal the bar counts codes (of the total) and shows the chains found so far; it is
    cleared at the end. Elsewhere (a pipe, a file) nothing is written."""
    import io
    import threading

    import tqdm

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    class Eager(tqdm.tqdm):  # every update drawn, so the test sees each state
        monitor_interval = 0  # no monitor thread: a process forked later (mutmut) must not inherit its lock

        def __init__(self, *args, **kwargs):
            super().__init__(*args, mininterval=0, **kwargs)

    # a plain thread lock: tqdm's default also makes a multiprocessing lock, which hangs in a
    # process forked from a threaded one (mutmut runs each mutant so)
    monkeypatch.setattr(Eager, "_lock", threading.RLock(), raising=False)
    monkeypatch.setattr(tqdm, "tqdm", Eager)
    for run, total, found in [(lambda: list(synth.type_synthesis(1, 8, workers=1, progress=True)), "3/3", "chains=16"),
                              (lambda: synth.count_chains(1, 10, workers=1, progress=True), "7/7", "chains=230")]:
        err = Terminal()
        monkeypatch.setattr(sys, "stderr", err)
        run()
        frames = err.getvalue().split("\r")
        shown = [f for f in frames if "codes/s" in f]
        assert shown and total in shown[-1] and found in shown[-1], shown[-1:]
        assert frames[-1] == "" and frames[-2] and frames[-2].strip() == ""  # cleared at the end, not left
    pipe = io.StringIO()
    monkeypatch.setattr(sys, "stderr", pipe)
    synth.count_chains(1, 8, workers=1, progress=True)
    assert pipe.getvalue() == ""
    quiet = Terminal()  # no bar unless asked
    monkeypatch.setattr(sys, "stderr", quiet)
    synth.count_chains(1, 8, workers=1), list(synth.type_synthesis(1, 8, workers=1)), synth.count_mechanisms(1, 8, workers=1)
    assert quiet.getvalue() == ""


def test_the_limit_theorem_is_a_default_only_where_it_holds():
    """W = 3, 8 links: fractionated chains may have a joint of 4 links (K + 1 = 3 would drop 80/0-1),
    so there the default has no limit; an explicit --max-multiplicity is obeyed; a code keeps its own."""
    full = synth.count_chains(3, 8, v=(0, 16), workers=1)
    assert full["count"] == 16 and full["by_code"]["80/0-1"] == 1
    assert synth.count_chains(3, 8, v=(0, 16), max_multiplicity=3, workers=1)["count"] == 15
    assert synth.count_chains(3, 8, v=(0, 16), max_multiplicity=8, workers=1)["count"] == 16
    for code in ("80/0-1", Code.parse("80/0-1")):
        assert synth.count_chains(3, code=code, workers=1)["count"] == 1


@pytest.mark.parametrize("h", [2, 3, 4, 5, 6])
def test_single_loops_are_chains_of_their_motion_space(h):
    """The single loop of h + 1 links, built without a solver, is a chain of space h (W = 1)."""
    chains = list(synth.type_synthesis(1, h + 1, h=h, workers=1))
    assert [(c.links, c.h, c.dof) for c in chains] == [(h + 1, h, 1)]


def test_a_two_link_loop_is_no_chain():
    """h = 2, W = 0 gives the code 2/0: two joints on the same two links, which is one joint, so no chain."""
    assert [str(u.code) for u in synth.plan_units(0, 2, h=2)] == ["2/0"]
    assert list(synth.type_synthesis(0, 2, h=2, workers=1)) == []
    assert synth.count_chains(0, 2, h=2, workers=1)["count"] == 0


@pytest.mark.parametrize("kwargs, message", [
    (dict(dof=4, code="2|5/2", n1=1), "code 2|5/2 has n1 = 2, not the requested n1 = 1"),
    (dict(dof=4, code="2|5/2", n1="3..4"), "code 2|5/2 has n1 = 2, not the requested n1 = 3..4"),
    (dict(dof=1, code="2|5/2"), "code 2|5/2 gives W = 4 with h = 3, not the requested W = 1"),
    (dict(dof=4, links=8, code="2|5/2"), "code 2|5/2 has 7 links, not 8"),
])
def test_a_code_and_its_query_disagree(kwargs, message):
    with pytest.raises(ImpossibleParameters) as refused:
        synth.plan_units(**kwargs)
    assert str(refused.value) == message


def test_a_code_and_its_query_agree():
    """The same numbers given twice (n1, links) are no contradiction; a code keeps exactly its own
    assortment (6220/0 and 6301/0 share n2 = 6 and their loops and v)."""
    for kwargs in (dict(n1=2), dict(n1="2..2"), dict(links=7), dict(n1=2, links=7)):
        assert {str(u.code) for u in synth.plan_units(4, code="2|5/2", **kwargs)} == {"2|5/0-1", "2|5/2"}
    assert synth.count_chains(1, code="6220/0", workers=1)["by_code"] == {"6220/0": 57}
    assert synth.count_chains(1, code="7201/1", workers=1)["by_code"].keys() == {"7201/1"}
