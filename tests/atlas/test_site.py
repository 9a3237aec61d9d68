"""The atlas as a static web site: counts on the pages equal the atlas's, stable chain ids,
pagination, refusals, and the pages rendered by headless Chromium."""

from __future__ import annotations

import functools
import html
import json
import math
import os
import re
import shutil
import subprocess

import pytest

from mechsynth.cli import main
from synth.atlas import summary
from synth.atlas.site import chain_id, write_site
from synth.structure.chain import Chain

from .helpers import grid_atlas


@pytest.fixture(scope="module")
def atlas(tmp_path_factory):
    return grid_atlas(tmp_path_factory.mktemp("site") / "a.sqlite", 'dof = "1..2"\nlinks = "4..8"\nv = "0..1"')


def _codes(folder) -> list[dict]:
    text = (folder / "index.html").read_text()
    return json.loads(re.search(r"const CODES=(\[.*?\]);", text).group(1))


def test_pages_show_every_chain_of_the_atlas_once(atlas, tmp_path):
    result = write_site(atlas, tmp_path / "s", page_size=7)
    info = summary(atlas)
    codes = _codes(tmp_path / "s")
    assert result.chains == info["chains"] == sum(c["chains"] for c in codes)
    assert {c["code"]: c["chains"] for c in codes} == info["by_code"]
    seen = []
    for c in codes:
        stem = c["href"][: -len("-1.html")]
        pages = sorted((tmp_path / "s").glob(stem + "-*.html"))
        assert len(pages) == math.ceil(c["chains"] / 7) == c["pages"]
        ids = [i for page in pages for i in re.findall(r'<figure id="([0-9a-f]{12})">', page.read_text())]
        assert len(ids) == c["chains"]
        seen += ids
        last = (tmp_path / "s" / f"{stem}-{c['pages']}.html").read_text()
        assert "next page" not in last and f"of <span class='total' id='count'>{c['chains']}</span>" in last
        planar = sum(Chain.from_dict(r).is_planar() for r in _rows(atlas, c))
        assert c["planar"] == planar
    assert len(seen) == len(set(seen)) == info["chains"]


def _rows(atlas, c):
    from synth.atlas import export

    return [r for r in export(atlas, "chains", where=[f"W={c['W']}", f"n={c['n']}"])
            if r["code"] == c["code"]]


def test_chain_ids_are_stable_and_looked_up(atlas, tmp_path):
    write_site(atlas, tmp_path / "a", page_size=5, draw_limit=3, workers=1)
    write_site(atlas, tmp_path / "b", page_size=5, draw_limit=3, workers=2)  # drawn in two processes: same site
    files = {p.relative_to(tmp_path / "a"): p.read_text() for p in (tmp_path / "a").rglob("*.*")}
    assert files == {p.relative_to(tmp_path / "b"): p.read_text() for p in (tmp_path / "b").rglob("*.*")}
    lookups = {p.name: p.read_text() for p in (tmp_path / "a" / "lookup").iterdir()}
    from synth.atlas import export

    row = next(export(atlas, "chains", where=["n=8"]))
    cid = chain_id(row["certificate"])
    table = json.loads(lookups[cid[:2] + ".js"][len("found("):-2])
    assert f'id="{cid}"' in (tmp_path / "a" / table[cid]).read_text()
    assert (tmp_path / "a" / "index.html").read_text().count("<svg") == 0  # drawings live on code pages
    drawn = sum(p.read_text().count("<svg") for p in (tmp_path / "a" / "codes").iterdir())
    assert drawn == 3


@pytest.mark.parametrize("extra, message", [
    (["--where", "n=8"], "does not go with --where"),
    (["--count"], "does not go with --count"),
    (["--draw-limit", "-1"], "--draw-limit"),
])
def test_cli_refusals(atlas, tmp_path, capsys, extra, message):
    assert main(["atlas", "--db", str(atlas), "--html", str(tmp_path / "s"), *extra]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechsynth:") and message in err and err.count("\n") == 1


def test_cli_folder_rules(atlas, tmp_path, capsys):
    (tmp_path / "file").write_text("x")
    assert main(["atlas", "--db", str(atlas), "--html", str(tmp_path / "file")]) == 2
    assert "is a file" in capsys.readouterr().err
    assert main(["atlas", "--db", str(atlas), "--html", str(tmp_path / "s"), "--draw-limit", "0"]) == 0
    assert main(["atlas", "--db", str(atlas), "--html", str(tmp_path / "s"), "--draw-limit", "0"]) == 2
    assert "--force" in capsys.readouterr().err
    assert main(["atlas", "--db", str(atlas), "--html", str(tmp_path / "s"), "--draw-limit", "0", "--force"]) == 0
    assert main(["atlas", "--db", str(tmp_path / "none.sqlite"), "--html", str(tmp_path / "t")]) == 2
    assert main(["atlas", "--db", str(atlas), "--page-size", "9"]) == 2
    assert main(["atlas", "--db", str(atlas), "--workers", "1"]) == 2
    assert "go with --html" in capsys.readouterr().err
    assert main(["atlas", "--db", str(atlas), "--draw-limit", "20000"]) == 2  # the default value, still refused
    assert "go with --html" in capsys.readouterr().err


_BROWSERS = ("chromium", "chromium-browser", "google-chrome")


@functools.cache
def _installed_chromium() -> str | None:
    """A headless browser on PATH; on a Debian machine where the tests run as root (a CI clone),
    Debian's ``chromium`` is installed first (about a minute, once a session)."""
    if not any(shutil.which(name) for name in _BROWSERS) and shutil.which("apt-get") and os.geteuid() == 0:
        env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
        for step in (["install"], ["update"], ["install"]):  # stale package lists: update, then again
            done = subprocess.run(["apt-get", *step, "-y", "-q", *(["chromium"] if step == ["install"] else [])],
                                  capture_output=True, timeout=600, env=env)
            if step == ["install"] and done.returncode == 0:
                break
    return next((name for name in _BROWSERS if shutil.which(name)), None)


def _chromium() -> str:
    name = _installed_chromium()
    if name is None:
        pytest.skip("no chromium, and it could not be installed here (Debian: apt-get install chromium)")
    return name


def _browse(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([_chromium(), "--headless", "--no-sandbox", "--disable-gpu", "--window-size=1200,900",
                           *args], capture_output=True, text=True, timeout=120)


def test_site_in_headless_chromium(atlas, tmp_path):
    """The index's script runs and shows the atlas's total; a code page renders its drawings."""
    write_site(atlas, tmp_path / "s", page_size=30)
    dom = _browse("--dump-dom", (tmp_path / "s" / "index.html").as_uri()).stdout
    total = summary(atlas)["chains"]
    assert f'<span class="total" id="shown">{total}</span>' in dom
    rows = re.search(r'<tbody id="rows">(.*?)</tbody>', dom, re.S).group(1)
    assert rows.count("<tr>") == len(summary(atlas)["by_code"])  # one row a code, written by the script
    page = tmp_path / "s" / _codes(tmp_path / "s")[-1]["href"]
    shot = tmp_path / "code_page.png"
    _browse(f"--screenshot={shot}", page.as_uri())
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and shot.stat().st_size > 5000


def test_each_card_lists_one_mechanism_per_link_orbit(atlas, tmp_path):
    """The frame choices shown for a chain are its link orbits (the atlas's stored mechanisms)."""
    write_site(atlas, tmp_path / "s", page_size=100, draw_limit=0)
    cards = [card for page in (tmp_path / "s" / "codes").iterdir()
             for card in page.read_text().split("<figure")[1:]]
    assert cards
    for card in cards:
        joints = re.search(r"joints: <code>(.*?)</code>", card).group(1)
        shown = int(re.search(r"mechanisms: (\d+) with a fixed link", card).group(1))
        assert shown == len(Chain.parse(html.unescape(joints)).link_orbits)


def test_the_sites_progress_in_a_log_is_no_bar(atlas, tmp_path, capsys):
    """`atlas --html` with stderr to a file: no tqdm bar (a '\\r' redraw per chain drawn), only the result line."""
    assert main(["atlas", "--db", str(atlas), "--html", str(tmp_path / "s"), "--draw-limit", "3",
                 "--workers", "1"]) == 0
    err = capsys.readouterr().err
    assert "\r" not in err and "chain/s" not in err
