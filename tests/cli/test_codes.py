import json
import subprocess
import sys

import pytest

from mechsynth.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_table_1_command(capsys):
    code, out, _ = run(capsys, "codes", "--dof", "1", "--loops", "1..5")
    assert code == 0 and out.strip().endswith("89 codes (K=1: 1, K=2: 3, K=3: 9, K=4: 23, K=5: 53)")


def test_jsonl_contract(capsys):
    code, out, _ = run(capsys, "codes", "--dof", "1", "--loops", "4", "--require", "5=1..", "--format", "jsonl")
    rows = [json.loads(line) for line in out.splitlines()]
    assert [r["code"] for r in rows][0] == "6301/0" and len(rows) == 7
    assert all({"code", "dof", "loops", "links", "v", "assortment"} <= set(r) for r in rows)


def test_a_link_bound_below_k_plus_1_names_what_it_leaves_out(capsys):
    """The limit K + W holds for chains with W ≥ 1 and no rigid sub-chain: for trusses it drops the
    source's own 32/0 (three-joint links at K = 2), and the command says so on stderr."""
    code, out, err = run(capsys, "codes", "--dof", "0", "--loops", "2", "--max-link-degree", "K+W", "--format", "csv")
    assert code == 0 and out.splitlines()[1:] == ["50/2,5,2,2,5"]
    assert "leaves out 2 codes" in err and "32/0, 41/1" in err and "W ≥ 1" in err
    code, out, err = run(capsys, "codes", "--dof", "2", "--loops", "3", "--max-link-degree", "K+W", "--format", "csv")
    assert code == 0 and err == ""  # K + W above K + 1: nothing left out


def test_csv(capsys):
    code, out, _ = run(capsys, "codes", "--dof", "0", "--links", "5", "--format", "csv")
    assert out.splitlines()[0] == "code,links,loops,v,assortment" and "32/0,5,2,0,3 2" in out


@pytest.mark.parametrize(
    "argv",
    [
        ["codes", "--dof", "1", "--links", "11"],
        ["codes", "--dof", "-1", "--loops", "2"],
        ["codes", "--dof", "1", "--loops", "3", "--v", "9"],
        ["codes", "--dof", "1", "--loops", "3", "--bogus"],
        ["codes", "--dof", "x", "--loops", "3"],
        ["codes", "--dof", "1", "--loops", "3", "--require", "7=1.."],
        ["analyze", "63x1/0"],
        ["frobnicate"],
    ],
)
def test_bad_input_one_sentence(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.startswith("mechsynth: ") and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_console_script_has_no_traceback():
    proc = subprocess.run([sys.executable, "-m", "mechsynth", "codes", "--dof", "1", "--links", "11"],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr and "multiple of h − 1" in proc.stderr


def test_analyze_json(capsys):
    code, out, _ = run(capsys, "analyze", "64200/0", "--dof", "1", "--format", "json")
    data = json.loads(out)
    assert (data["dof"], data["loops"], data["defect"]) == (1, 5, 0)


def test_a_table_of_one_says_one_in_the_singular(capsys):
    """The tables' last lines said '1 codes (K=5: 1)' and '1 chains'."""
    assert main(["codes", "--dof", "1", "--loop-classes", "3=4,5=1", "--v", "6", "--max-link-degree", "3"]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == "1 code (K=5: 1)"
    assert main(["chains", "--dof", "1", "--links", "6", "--h", "5"]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == "1 chain"
    assert main(["mechanisms", "--dof", "1", "--links", "4"]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == "1 mechanism"
