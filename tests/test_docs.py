"""The documentation stands alone: every link of README.md and docs/*.md resolves inside the
repository, and no file points at material a user of the repository does not have (the
developers' theory brief or the source texts it was written from; docs/theory.md is the
project's own account of the theory)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

_FENCE = re.compile(r"^(```|~~~).*?^\1", re.S | re.M)
_CODE_SPAN = re.compile(r"`[^`\n]*`")
_LINK = re.compile(r"!?\[(?P<text>[^\]]*)\]\((?P<target>[^)\s]+)(?:\s+\"[^\"]*\")?\)")
_HEADING = re.compile(r"^#{1,6}\s+(?P<title>.+?)\s*#*\s*$", re.M)


def _prose(text: str) -> str:
    """Markdown without fenced blocks and code spans (links there are not links)."""
    return _CODE_SPAN.sub("", _FENCE.sub("", text))


def anchors(page: Path) -> set[str]:
    """The anchors a Markdown renderer gives the headings of ``page`` (GitHub's rule).

    >>> sorted(anchors(ROOT / "docs" / "theory.md"))[:2]
    ['balanced-manipulator-with-a-pantograph', 'balancing-by-the-potential-function']
    """
    seen: dict[str, int] = {}
    out = set()
    for m in _HEADING.finditer(_FENCE.sub("", page.read_text(encoding="utf-8"))):
        title = _LINK.sub(lambda x: x["text"], m["title"]).replace("`", "")
        slug = re.sub(r"[^\w\- ]", "", title.strip().lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        out.add(slug if n == 0 else f"{slug}-{n}")
    return out


def links(page: Path) -> list[str]:
    return [m["target"] for m in _LINK.finditer(_prose(page.read_text(encoding="utf-8")))]


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_link_resolves_inside_the_repository(page):
    broken = []
    for target in links(page):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # https:, mailto: — outside by definition
            continue
        path, _, anchor = target.partition("#")
        dest = (page.parent / path).resolve() if path else page
        if ROOT not in dest.parents and dest != ROOT:
            broken.append(f"{target}: outside the repository")
        elif not dest.exists():
            broken.append(f"{target}: no such file")
        elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
            broken.append(f"{target}: no heading #{anchor} in {dest.name}")
    assert not broken, f"{page.name}: " + "; ".join(broken)


def test_the_pages_do_link_somewhere():
    """The link test above would pass on pages without links: make sure it sees them."""
    assert len(links(ROOT / "docs" / "theory.md")) > 20
    assert any("docs/theory.md#" in t for t in links(ROOT / "README.md"))


# Spelled in pieces so that this file does not match its own patterns.
_FORBIDDEN = [
    ("the developers' theory brief", re.compile("THEORY" + r"\.md")),
    ("a source text by its file number", re.compile(r"\b" + "seed" + r"s?\s+0\d\d\b|\b" + "seeds" + "/")),
    ("the source texts as 'the seed'", re.compile(r"\b" + "seed" + "'s" + r"\b")),
    ("the shared developer folder", re.compile("/work/" + "shared")),
]
_TEXT = {".py", ".md", ".toml", ".txt", ".cfg", ".ini", ".rst", ".yml", ".yaml", ".json"}
_SKIP = {".git", ".hypothesis", ".pytest_cache", "__pycache__", "out", "build", "dist", ".venv"}


def _repository_files():
    for path in ROOT.rglob("*"):
        rel = path.relative_to(ROOT)
        if any(part in _SKIP or part.endswith(".egg-info") for part in rel.parts):
            continue
        if path.is_file() and (path.suffix in _TEXT or path.parent.name == "benchmarks" and not path.suffix):
            yield path


def test_no_file_cites_material_users_do_not_have():
    hits = []
    for path in _repository_files():
        for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            for what, pattern in _FORBIDDEN:
                if pattern.search(line):
                    hits.append(f"{path.relative_to(ROOT)}:{number} cites {what}")
    assert not hits, "cite docs/theory.md instead: " + "; ".join(hits[:20])


def test_the_forbidden_patterns_catch_what_they_should():
    """The check above must be able to fail."""
    samples = ["see " + "THEORY" + ".md Part A", "seed" + " 001, Fig. 6.2", "the " + "seed" + "'s table", "/work/" + "shared/x"]
    for (what, pattern), sample in zip(_FORBIDDEN, samples):
        assert pattern.search(sample), what
    assert not any(p.search("random seed 0 and seed = 12345") for _, p in _FORBIDDEN)


def test_every_subcommand_is_named_in_the_help_of_its_parent():
    """``mechsynth --help`` names every command, and a command group's line names each of its
    subcommands (``balance compare`` was once missing from it)."""
    import argparse

    from mechsynth._parser import build_parser

    def groups(parser):
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                yield parser, action

    root = build_parser()
    text = root.format_help()
    (_, commands), = groups(root)
    for name, command in commands.choices.items():
        assert re.search(rf"^\s+{re.escape(name)}\s", text, re.M), name
        line = next(a.help for a in commands._choices_actions if a.dest == name)
        for _, inner in groups(command):
            for sub in inner.choices:
                assert re.search(rf"\b{re.escape(sub)}\b", line), f"'{name} {sub}' is missing from '{name}: {line}'"
                assert sub in command.format_help()


_MODEL_BLOCK = re.compile(r"^```toml\n# (?P<path>models/[\w.]+\.toml)\b[^\n]*\n(?P<body>.*?)^```", re.S | re.M)


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_a_toml_block_that_names_a_model_file_shows_what_the_file_holds(page):
    """A ```toml block headed ``# models/NAME.toml`` quotes that file: every key and table it shows is
    in the file with the same value (docs/atlas.md once showed grid_small.toml with a block the file lacks)."""
    import tomllib

    def within(shown, held, where):
        assert isinstance(held, type(shown)), where
        if isinstance(shown, dict):
            for key, value in shown.items():
                assert key in held, f"{where}: '{key}' is not in the file"
                within(value, held[key], f"{where}.{key}")
        else:
            assert shown == held, where

    for m in _MODEL_BLOCK.finditer(page.read_text(encoding="utf-8")):
        within(tomllib.loads(m["body"]), tomllib.loads((ROOT / m["path"]).read_text(encoding="utf-8")), m["path"])


def test_the_model_block_check_catches_a_block_the_file_lacks():
    text = "```toml\n# models/grid_small.toml — x\ndof = \"1..3\"\n[[block]]\ndof = 2\n```\n"
    (m,) = _MODEL_BLOCK.finditer(text)
    assert m["path"] == "models/grid_small.toml" and "[[block]]" in m["body"]
