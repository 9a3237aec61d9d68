"""The command-line contract: one sentence and exit 2 for nonsense, 1 when a valid query matches
nothing (in every output form), the same formats everywhere, and --version."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from mechsynth import __version__
from mechsynth.cli import main

REFUSED = [
    # nonsense accepted in silence before
    ("analyze 6301/0 --dof -2", "W must be 0 or more"),
    ("analyze 6301/0 --h 7", "motion space h"),
    ("analyze 6301/0 --f -1", "f must be 0 or more"),
    ("analyze 6301/0 --v 1", "a code carries its own v"),
    ("analyze 0-1,1-2,2-3,3-0 --v 2", "does not apply to a chain"),
    ("codes --dof 1 --loops 3 --max-link-degree 0", "largest link degree must be 2 or more"),
    ("codes --dof 1 --loops 3 --max-link-degree 1", "largest link degree must be 2 or more"),
    ("codes --dof 1 --loops 3 --max-link-degree -5", "largest link degree must be 2 or more"),
    ("codes --dof 1 --loops 3 --h 0", "motion space h"),
    ("chains --code 6301/0 --require 5=0 --count", "asks for n5 = 0"),
    ("chains --code 7201/1 --v 0 --count", "outside the requested v = 0"),
    ("chains --dof 1 --links 8 --workers 100000 --count", "more than the"),
    ("chains --dof 1 --links 10 --cranks 5=5 --require 5=0 --count", "forbids one"),
    # advice names only options the command has
    ("chains --dof 1 --links 10 --require 50=1", "carries at most 5"),
    # old cases that must stay refused
    ("chains --dof 1 --links 11 --count", "no whole number of loops"),
    ("chains --dof 1 --links -4 --count", "1 or more"),
    ("chains --code 63a1/0", "cannot read code"),
    ("analyze '0-1 1-'", "cannot read joint"),
    ("codes --dof 1 --loops 2 --format xml", "invalid choice"),
]


def _run(command: str, capsys) -> tuple[int, str, str]:
    import shlex

    status = main(shlex.split(command))
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize("command,words", REFUSED)
def test_refused_with_one_sentence(command, words, capsys):
    status, out, err = _run(command, capsys)
    assert status == 2, (command, out, err)
    assert err.startswith("mechsynth: ") and err.count("\n") == 1 and words in err, err
    assert "Traceback" not in err and out == ""


def test_advice_does_not_name_missing_options(capsys):
    _, _, err = _run("chains --dof 1 --links 10 --require 50=1", capsys)
    assert "--max-link-degree" not in err


EMPTY = "chains --dof 1 --links 8 --require 4=3"


@pytest.mark.parametrize("form", ["", "--format jsonl", "--format csv", "--format json", "--count",
                                  "--count --format table", "--count --format csv", "--count --format jsonl"])
def test_nothing_matched_exits_1_in_every_form(form, capsys):
    status, out, err = _run(f"{EMPTY} {form} --workers 1", capsys)
    assert status == 1 and err == "mechsynth: no chains satisfy these parameters and conventions\n"


def test_codes_nothing_matched(capsys):
    status, out, err = _run("codes --dof 1 --loops 2 --require 3=0 --require 2=0 --format jsonl", capsys)
    assert (status, out) == (1, "") and err.startswith("mechsynth: no standard code")


@pytest.mark.parametrize("command", ["codes --dof 1 --loops 2", "chains --dof 1 --links 6 --workers 1",
                                     "mechanisms --dof 1 --links 6 --workers 1"])
def test_json_equals_jsonl(command, capsys):
    status, as_json, _ = _run(f"{command} --format json", capsys)
    status2, as_jsonl, _ = _run(f"{command} --format jsonl", capsys)
    assert status == status2 == 0
    rows = [json.loads(line) for line in as_jsonl.splitlines()]
    assert json.loads(as_json) == rows and len(rows) >= 2


def test_count_follows_format(capsys):
    status, out, _ = _run("chains --dof 1 --links 8 --count --workers 1", capsys)
    assert status == 0 and json.loads(out) == {"count": 16, "by_code": {"440/0": 9, "521/0": 5, "602/0": 2}}
    _, out, _ = _run("chains --dof 1 --links 8 --count --format csv --workers 1", capsys)
    assert out.splitlines() == ["code,count", "440/0,9", "521/0,5", "602/0,2"]
    _, out, _ = _run("chains --dof 1 --links 8 --count --format jsonl --workers 1", capsys)
    assert [json.loads(x)["count"] for x in out.splitlines()] == [9, 5, 2]
    _, out, _ = _run("chains --dof 1 --links 8 --count --format table --workers 1", capsys)
    assert out.splitlines()[-1] == "16 in all"


def test_code_with_its_own_v_and_a_range_that_holds_it(capsys):
    for extra in ("", "--v 1", "--v 0..2"):
        status, out, _ = _run(f"chains --code 7201/1 {extra} --count --workers 1", capsys)
        assert status == 0 and json.loads(out)["count"] == 27


def test_analyze_without_dof_prints_no_empty_fields(capsys):
    status, out, _ = _run("analyze 6301/0", capsys)
    assert status == 0 and "None" not in out and not any(line.rstrip() == line.split()[0] for line in out.splitlines())


def test_version(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0 and capsys.readouterr().out.strip() == f"mechsynth {__version__}"


def test_no_traceback_through_the_real_command():
    """The installed entry point (python -m mechsynth) keeps the contract too."""
    env = dict(os.environ)
    p = subprocess.run([sys.executable, "-m", "mechsynth", "analyze", "6301/0", "--dof", "-2"],
                       capture_output=True, text=True, env=env, timeout=60)
    assert p.returncode == 2 and p.stderr.count("\n") == 1 and "Traceback" not in p.stderr


def test_a_command_mounts_only_its_module_and_the_table_names_every_command():
    """The root parser builds one module's commands when argv names one (start-up); the table it
    reads names each command by the module that mounts it, and every command is mounted by one."""
    import argparse
    import importlib

    from mechsynth._parser import COMMANDS, build_parser

    def choices(parser):
        return list(next(a for a in parser._actions if a.dest == "command").choices)

    everything = choices(build_parser())
    assert everything == list(COMMANDS)
    for module in dict.fromkeys(COMMANDS.values()):
        sub = argparse.ArgumentParser().add_subparsers()
        importlib.import_module(f"mechsynth.commands.{module}").add_commands(sub)
        assert list(sub.choices) == [name for name, m in COMMANDS.items() if m == module]
    assert choices(build_parser(["draw", "--code", "42/0"])) == ["draw"]  # one module per command
    assert choices(build_parser(["--help"])) == everything and choices(build_parser(["nonsense"])) == everything


def test_a_command_that_is_not_one_lists_every_command(capsys):
    assert main(["chain", "--dof", "1"]) == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'chain'" in err and "'balance'" in err and err.count("\n") == 1


@pytest.mark.parametrize("argv, command", [
    (["codes", "--dof", "1", "--loops", "4", "--count"], "mechsynth codes"),
    (["balance", "arm", "arm.toml", "--bogus"], "mechsynth balance arm"),
])
def test_an_unknown_option_points_at_its_commands_help(argv, command, capsys):
    """'codes … --count' said 'unrecognized arguments: --count (see 'mechsynth --help')': the root's help,
    which does not list the options of codes."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err == f"mechsynth: unrecognized arguments: {argv[-1]} (see '{command} --help')\n"


def test_ctrl_c_swallowed_by_a_finaliser_still_stops_the_command(monkeypatch, capsys):
    """A Ctrl-C that lands while Python runs a finaliser or a ctypes callback (numba's cache, numpy's
    NpzFile.__del__) is printed as 'Exception ignored … KeyboardInterrupt' and dropped: 'dimension … --budget 60'
    then ran on and exited 0 (2 of 15 SIGINTs at 9–11 s). The command must still stop with 130."""
    import signal
    import time

    import mechsynth.commands.codes as codes

    class Finaliser:
        def __del__(self):
            signal.raise_signal(signal.SIGINT)  # the handler runs here, inside the finaliser

    def run(args):
        Finaliser()  # dropped at once
        for _ in range(300):  # a command that goes on working (3 s at most)
            time.sleep(0.01)
        return 0

    monkeypatch.setattr(codes, "_run_codes", run)
    assert main(["codes", "--dof", "1", "--loops", "1"]) == 130
    err = capsys.readouterr().err
    assert err == "mechsynth: interrupted\n"


@pytest.mark.parametrize("argv, flag", [
    (["identify", "0-1 1-2 2-3 3-0", "--index", "--no-index"], "--index and --no-index"),
    (["chains", "--dof", "1", "--links", "6", "--no-fractionated", "--fractionated"], "--fractionated and --no-fractionated"),
    (["draw", "--chain", "0-1 1-2 2-3 3-0", "--labels", "--no-labels", "--out"], "--labels and --no-labels"),
])
def test_a_flag_and_its_negation_are_refused(argv, flag, capsys, tmp_path):
    """'identify … --index --no-index' ran with the last of the two, as argparse keeps it."""
    if argv[-1] == "--out":
        argv = [*argv, str(tmp_path / "x.svg")]
    assert main(argv) == 2 and not (tmp_path / "x.svg").exists()
    assert f"{flag} contradict each other" in capsys.readouterr().err


@pytest.mark.parametrize("argv, option", [
    (["chains", "--dof", "1", "--links", "8", "--links", "9", "--count"], "--links"),
    (["chains", "--dof", "1", "--li", "8", "--links", "9", "--count"], "--links"),  # an abbreviation is the option
    (["chains", "--dof", "1", "--links", "6", "--count", "--count"], "--count"),
    (["codes", "--dof", "1", "--loops", "2", "--format", "csv", "--format=json"], "--format"),
    (["draw", "--chain", "0-1 1-2 2-3 3-0", "--no-labels", "--no-labels", "--out"], "--no-labels"),
    (["balance", "spring", "--kind", "compression", "--kind", "tension", "--moment", "1"], "--kind"),
    (["move", "models/motion_four_bar.toml", "--steps", "3", "--steps", "4"], "--steps"),
    (["dimension", "models/dimension_path.csv", "--mechanism", "0-1 1-2 2-3 3-0", "--frame", "0", "--budget", "1",
      "--budget", "2"], "--budget"),
])
def test_an_option_of_one_value_given_twice_is_refused(argv, option, capsys, tmp_path):
    """'chains --links 8 --links 9' counted 9 links, as argparse keeps the last value: every option that holds
    one value is refused when given twice, by one mechanism of the parser (mechsynth._argtypes.GivenOnce)."""
    if argv[-1] == "--out":
        argv = [*argv, str(tmp_path / "x.svg")]
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(Path(__file__).resolve().parents[2])
        assert main(argv) == 2 and not (tmp_path / "x.svg").exists()
    err = capsys.readouterr().err
    assert err.startswith(f"mechsynth: {option} is given twice: give it once") and err.count("\n") == 1


def test_options_that_collect_values_stay_repeatable(capsys):
    """--require (action="append") is given once per bound: two of them are one query, not a refusal."""
    assert main(["chains", "--dof", "1", "--links", "8", "--require", "3=2", "--require", "4=1", "--count"]) == 0
    assert json.loads(capsys.readouterr().out)["by_code"] == {"521/0": 5}


def _commands(parser=None, words=("mechsynth",)):
    """(words, parser) of the root parser and of every command and sub-command under it."""
    import argparse

    from mechsynth._parser import build_parser

    parser = parser or build_parser()
    yield list(words), parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _commands(sub, [*words, name])


def test_every_option_of_every_command_says_what_it_is():
    """--help of 'balance prismatic' listed --mass m, --inertia I and --counter-mass M without a word or a unit;
    22 options and arguments (each command's --format among them) had no help."""
    import argparse

    silent = [f"{' '.join(words)} {action.option_strings or action.dest}" for words, parser in _commands()
              for action in parser._actions if not isinstance(action, argparse._SubParsersAction) and not action.help]
    assert silent == []


WRITERS = [words[1:] for words, parser in _commands() if "--out" in parser._option_string_actions]


def test_o_writes_a_drawing_and_means_nothing_else(tmp_path):
    assert WRITERS and ["draw"] in WRITERS  # the parametrised test below runs over something
    assert not [w for w, p in _commands() if "-o" in p._option_string_actions and "--out" not in p._option_string_actions]
    assert main(["draw", "--chain", "0-1 1-2 2-3 3-0", "-o", str(tmp_path / "x.svg")]) == 0
    assert (tmp_path / "x.svg").read_text().lstrip().startswith("<?xml")


@pytest.mark.parametrize("words", WRITERS, ids=" ".join)
def test_o_is_the_short_form_of_out(words):
    """'draw --chain … -o x.png' was read as a LINKAGE_FILE and refused against it: -o is --out on every command
    that has --out, and no command takes -o for anything else."""
    parser = dict((tuple(w[1:]), p) for w, p in _commands())[tuple(words)]
    assert parser._option_string_actions["-o"] is parser._option_string_actions["--out"]


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full to stand for a full disk")
@pytest.mark.parametrize("argv", [["analyze", "6301/0"], ["codes", "--dof", "1", "--loops", "1..5"],
                                  ["chains", "--dof", "1", "--links", "10", "--format", "jsonl", "--workers", "1"]])
def test_a_full_disk_under_stdout_is_one_sentence_and_exit_2(argv, tmp_path):
    """`mechsynth … > file` on a full disk (/dev/full): one sentence and exit 2, no traceback, no second error from
    the interpreter's last flush, nothing left running (each ended with a traceback before)."""
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[2])}
    with open("/dev/full", "w") as full:
        p = subprocess.Popen([sys.executable, "-m", "mechsynth", *argv], stdout=full, stderr=subprocess.PIPE,
                             text=True, env=env, start_new_session=True)
        _, err = p.communicate(timeout=120)
    assert p.returncode == 2, err[-800:]
    assert err == "mechsynth: cannot write the output: No space left on device\n"
    left = subprocess.run(["pgrep", "-g", str(p.pid)], capture_output=True, text=True).stdout.split()
    assert left == [], left
