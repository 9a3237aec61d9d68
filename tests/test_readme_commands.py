"""Every command of README.md and of docs/cli.md (the full tour, command by command) works as written.

Each ``mechsynth …`` command of a page's ```bash blocks runs, in the page's order, in one folder of
that page where ``models/`` is this checkout's (the tour writes ``atlas.sqlite`` before it reads it),
and must exit 0; the ``$ mechsynth …`` examples of its output blocks must print what the page
shows (a line ``…`` stands for lines left out).  Commands too long for the default suite are
marked slow, and those that need a running Dask scheduler are skipped: each with its reason.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from mechsynth.cli import main

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
TOUR = ROOT / "docs" / "cli.md"
PAGES = (README, TOUR)  # the README's short tour, then the full one

# why a command is not run in the default suite (matched against the command's text)
SLOW = {
    "--links 16 --count --checkpoint": "counts 19 819 281 chains: about 30 seconds on 2 cores",
    "scene --all models/": "every scene, about 30 CPU seconds: tests/scenes/test_scenes.py runs each of them in the default suite",
    "--db rp.sqlite --html site": "draws 473 chains: about 10 seconds",
    "--db gears.sqlite --html gears_site": "draws 741 gear trains: about 20 seconds",
    "--html moving_site": "moves the mechanisms of three chains, triads among them: about a minute "
                          "(tests/atlas/test_site_motion.py plays a site's moving page in Chromium)",
    "--index-curves --samples 200": "samples 200 crank poses of each 4- and 6-link mechanism: about two CPU minutes "
                                    "(tests/atlas/test_curve_search.py builds a four-bar index in the default suite)",
    "dimension models/dimension_closed_path.csv": "an atlas search with a 60 CPU-second budget on the index above "
                                                  "(tests/atlas/test_curve_search.py finds a four-bar again)",
    "dimension models/dimension_path.csv": "a path synthesis with a 30 CPU-second budget "
                                           "(tests/dimension finds the same points again in the default suite)",
    "dimension models/dimension_half_circle.csv": "six timed points with the frame line free, the default 60 CPU-second "
                                                  "budget (tests/dimension/test_placing.py runs the same command "
                                                  "for two CPU seconds in the default suite)",
    "dimension models/dimension_ce2.csv": "CE2 as its sources state it, a 20 CPU-second budget "
                                          "(tests/dimension/test_placing.py finds it from no guess in the default suite)",
    "dimension models/dimension_slider_crank.csv --db": "an atlas search with a 20 CPU-second budget "
                                                        "(tests/atlas/test_curve_search.py finds a random slider-crank "
                                                        "again in the default suite)",
    "--code 12.2000/6-0 --cranks 3=3": "the translator's query, 21 841 heterogeneous chains: about 13 CPU seconds "
                                       "(tests/synthesis/test_classes_vs_oracle.py runs it in the slow set too)",
    "--code 8310/1 --prismatic 3 --cylinders": "Fig. 6's query, 8 096 mechanisms of 4 617 chains: about 30 CPU seconds",
}
# a slow command's smaller case, run as written but for these words, in the default suite
SMALLER = {"--code 8310/1 --prismatic 3 --cylinders": ("8310/1", "71/1")}
SKIP = {
    "--scheduler tcp://127.0.0.1:8786": "needs the Dask scheduler the README starts by hand "
                                        "(tests/execution runs the same units on a real Dask cluster)",
}
NOT_RUN = {"mechsynth chains --dof 1 --links 20 --count": "runs for half an hour or more by design (the README shows "
                                                          "its first line)"}


def blocks(text: str) -> list[tuple[str, str]]:
    """``(language, body)`` of every fenced block, in order."""
    found, language, body = [], None, []
    for line in text.splitlines():
        if line.startswith("```"):
            if language is None:
                language, body = line[3:].strip(), []
            else:
                found.append((language, "\n".join(body) + "\n"))
                language = None
        elif language is not None:
            body.append(line)
    return found


def bash_commands(text: str) -> list[list[str]]:
    """The ``mechsynth`` commands of the ```bash blocks, as argument lists, in order.

    >>> bash_commands("```bash\\npip install . && mechsynth codes --dof 1 \\\\\\n  --loops 2   # table\\n```\\n")
    [['mechsynth', 'codes', '--dof', '1', '--loops', '2']]
    """
    found = []
    for language, body in blocks(text):
        if language != "bash":
            continue
        for line in body.replace("\\\n", " ").splitlines():
            command: list[str] = []
            for word in [*shlex.split(line, comments=True), "&&"]:
                if word in ("&&", "&", ";"):
                    if command[:1] == ["mechsynth"]:
                        found.append(command)
                    command = []
                else:
                    command.append(word)
    return found


def shown_outputs(text: str) -> list[tuple[str, list[str]]]:
    """``(command, lines shown)`` for every ``$ mechsynth …`` example of a plain ``` block."""
    found = []
    for language, body in blocks(text):
        lines = body.rstrip("\n").splitlines()
        if not language and lines and lines[0].startswith("$ mechsynth "):
            found.append((lines[0][2:], lines[1:]))
    return found


def _read(page: Path) -> str:
    return page.read_text(encoding="utf-8")


COMMANDS = [(page, argv) for page in PAGES for argv in bash_commands(_read(page))]
SHOWN = [(page, command, shown) for page in PAGES for command, shown in shown_outputs(_read(page))]


def _marks(text: str):
    for key, reason in SKIP.items():
        if key in text:
            return [pytest.mark.skip(reason=reason)]
    return [pytest.mark.slow] if any(key in text for key in SLOW) else []


@pytest.fixture(scope="module")
def tours(tmp_path_factory):
    """The folder each page's tour runs in: models/ is the checkout's, files the commands write stay there."""
    folders = {}
    for page in PAGES:
        folders[page] = tmp_path_factory.mktemp(f"tour_{page.stem}")
        (folders[page] / "models").symlink_to(ROOT / "models")
    return folders


@pytest.mark.parametrize("page, argv", [pytest.param(page, c, marks=_marks(shlex.join(c)),
                                                     id=f"{page.stem}:{shlex.join(c[1:4])}")
                                        for page, c in COMMANDS])
def test_readme_command_runs_as_written(page, argv, tours, monkeypatch, capsys):
    monkeypatch.chdir(tours[page])
    status = main(argv[1:])
    out, err = capsys.readouterr()
    assert status == 0, (shlex.join(argv), err[-1500:])
    assert "Traceback" not in err
    assert out.strip() or any(a in argv for a in ("--out", "--animate", "--save", "--html", "--plot", "grid")), shlex.join(argv)


@pytest.mark.parametrize("page, argv", [pytest.param(page, c, id=f"{page.stem}:{shlex.join(c[1:4])}")
                                        for page, c in COMMANDS if any(key in shlex.join(c) for key in SMALLER)])
def test_a_slow_readme_command_runs_on_a_smaller_case(page, argv, tours, monkeypatch, capsys):
    (words, smaller), = [change for key, change in SMALLER.items() if key in shlex.join(argv)]
    assert words in argv
    monkeypatch.chdir(tours[page])
    status = main([smaller if a == words else a for a in argv[1:]])
    out, err = capsys.readouterr()
    assert status == 0 and out.strip() and "Traceback" not in err, (shlex.join(argv), err[-1500:])


_NUMBER = re.compile(r"\d+(?:[ .]\d+)*(?:e[+-]\d+)?(?: (?:s|min|h|days|years)\b)?")
_SIZE = re.compile(r"about (?P<size>\S+ \w+ in [\d ]+ units).*exact counts at (?P<basis>[\d, ]+) links")


def assert_same_sentence(shown: str, printed: str) -> None:
    """A size sentence of the README (a refusal, a long query's note) is the one the command prints:
    the same words, every number in its place; the chains and units the same wherever the estimate
    rests on the same exact counts (the time is measured while sizing, so it is the machine's).

    >>> assert_same_sentence("about 1.3e+11 chains in 2 486 484 units, 36.0 days, extrapolated from the exact "
    ...                      "counts at 8, 10, 12 links", "about 1.3e+11 chains in 2 486 484 units, 11.3 days, "
    ...                      "extrapolated from the exact counts at 8, 10, 12 links")
    """
    shown, printed = (" ".join(text.split()) for text in (shown, printed))
    assert _NUMBER.sub("#", shown) == _NUMBER.sub("#", printed), (shown, printed)
    a, b = _SIZE.search(shown), _SIZE.search(printed)
    if a and b and a["basis"] == b["basis"]:
        assert a["size"] == b["size"], (shown, printed)


@pytest.mark.parametrize("command, shown", [pytest.param(command, shown, id=f"{page.stem}:{command[10:40]}")
                                            for page, command, shown in SHOWN])
def test_readme_output_examples_are_what_the_command_prints(command, shown, capsys):
    if shown and shown[0].startswith("mechsynth: a long query"):  # the note, without the long run
        from synth import ChainQuery, size_check

        argv = shlex.split(command)
        assert argv[1:3] == ["chains", "--dof"] and argv[4] == "--links" and argv[6:] == ["--count"], command
        note = size_check(ChainQuery(int(argv[3]), int(argv[5])), processes=2, count=True, table=False)
        assert_same_sentence(" ".join(shown), f"mechsynth: {note} (give --checkpoint FILE to make it resumable)")
        return
    if command in NOT_RUN:
        pytest.skip(NOT_RUN[command])
    status = main(shlex.split(command)[1:])
    out, err = capsys.readouterr()
    if shown and shown[0].startswith("mechsynth: "):  # a refusal: the whole sentence
        assert status == 2
        assert_same_sentence(" ".join(shown), err)
        return
    assert status == 0, err
    printed = out.rstrip("\n").splitlines()
    position = 0
    for line in shown:  # in order; '…' alone stands for left-out lines
        if line == "…":
            continue
        assert line in printed[position:], (line, out)
        position = printed.index(line, position) + 1


def test_the_readme_has_commands_to_run():
    """The tests above would pass on pages without commands: make sure they see them — the README's short
    tour a command or two of each command, the full tour every command the README's tour held before it
    moved to docs/cli.md (119 besides the quick start's, with 6 output examples)."""
    readme = [argv for page, argv in COMMANDS if page == README]
    tour = [argv for page, argv in COMMANDS if page == TOUR]
    assert len(readme) >= 15 and len(shown_outputs(_read(README))) >= 4
    assert len(tour) >= 119 and len(shown_outputs(_read(TOUR))) >= 6
    for commands in (readme, tour):
        for name in ("codes", "chains", "grid", "identify", "gears", "move", "dimension", "balance"):
            assert any(c[1] == name for c in commands), name


def test_ci_runs_exactly_the_readme_test_command():
    """.ci/run runs the command the README gives for the tests (install with the test extras, then pytest)."""
    text = README.read_text(encoding="utf-8")
    block = re.search(r"one command installs and runs the tests.*?```bash\n(.*?)\n```", text, re.S).group(1)
    script = [line for line in (ROOT / ".ci" / "run").read_text().splitlines()
              if line.strip() and not line.startswith(("#", "set ", "cd "))]
    assert script == [block.strip()]
