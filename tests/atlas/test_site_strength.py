"""The atlas site of a few links, page by page: every code's entry, title, navigation and card against
values worked out by hand (the four-bar's 8 symmetries, Watt's and Stephenson's 4, their 1, 2 and 3
inversions), the lookup of every chain, the moving pages, every refusal's sentence."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from synth.atlas import EmptyAtlas, open_atlas, summary
from synth.atlas import site
from synth.atlas.site import SiteResult, _degrees, _page, _slug, chain_id, write_site
from synth.errors import InvalidOption
from synth.structure.chain import Chain
from .helpers import grid_atlas

GRID = ('input_link = true\ndof = 1\nlinks = "4..6"\n[[block]]\n[[block]]\nlinks = 4\nprismatic = "1..2"\n'
        '[[gears]]\nlinks = 4\n')
FOUR_BAR, WATT, STEPHENSON = (Chain.parse(t) for t in ("0-1 1-2 2-3 3-0", "0-1 1-2 2-3 3-0 0-4 4-5 5-1",
                                                       "0-1 1-2 2-3 3-0 1-4 4-5 5-3"))
#: each code's entry of the index, by hand: (code, P, G, kind, chains, degrees, slug)
CODES = [("22/0 G2", 4, 0, 0, 2, "gears", [2, 3], "W1-h3-22_0-G2"), ("4/0", 4, 0, 0, 0, "chains", [2], "W1-h3-4_0"),
         ("4/0 P1", 4, 0, 1, 0, "chains", [2], "W1-h3-4_0-P1"), ("4/0 P2", 4, 0, 2, 0, "chains", [2], "W1-h3-4_0-P2"),
         ("31/1 G2", 4, 1, 0, 2, "gears", [2, 3], "W1-h3-31_1-G2"), ("42/0", 6, 0, 0, 0, "chains", [2, 3], "W1-h3-42_0")]


@pytest.fixture(scope="module")
def atlas(tmp_path_factory):
    return grid_atlas(tmp_path_factory.mktemp("site") / "a.sqlite", GRID)


@pytest.fixture
def built(atlas, tmp_path):
    """The site written anew in each test (a module fixture would write it once, in the first test, and a mutation
    run maps the writing code to that test alone)."""
    folder = tmp_path / "s"
    result = write_site(atlas, folder, page_size=1, draw_limit=2, workers=1)
    return folder, result


def _codes(folder: Path) -> list[dict]:
    return json.loads(re.search(r"const CODES=(\[.*?\]);", (folder / "index.html").read_text()).group(1))


def _text(page: str) -> str:
    return re.sub(r"<svg.*?</svg>", "<svg/>", page, flags=re.S)


def test_small_pieces_by_hand():
    assert _slug((1, 3, "42/0", 0, 0)) == "W1-h3-42_0"
    assert _slug((2, 4, "2|5/2", 1, 2)) == "W2-h4-2_5_2-P1-G2"
    assert _slug((1, 3, "12.2.0.0.0/6", 0, 0)) == "W1-h3-12.2.0.0.0_6"
    assert _page("a < b", "<p>x</p>") == ('<!doctype html><html lang="en"><head><meta charset="utf-8"><title>a &lt; b'
                                          '</title><link rel="stylesheet" href="style.css"></head><body><p>x</p>'
                                          '</body></html>')
    assert 'href="../../style.css"' in _page("t", "", 2)
    assert _degrees("42/0") == [2, 3] and _degrees("601/0") == [2, 4] and _degrees("2|5/2") == [1, 2]
    assert _degrees("4/0") == [2]


def test_the_index_lists_every_code_by_hand(atlas, built):
    folder, result = built
    assert result == SiteResult(str(folder), 6, 9, 9, 2)
    by_code = summary(atlas)["by_code"]
    expected = []
    for code, n, v, p, g, kind, degrees, slug in CODES:
        chains = {"22/0 G2": 2, "4/0": 1, "4/0 P1": 1, "4/0 P2": 2, "31/1 G2": 1, "42/0": 2}[code]
        expected.append({"code": code, "W": 1, "h": 3, "n": n, "v": v, "P": p, "G": g, "kind": kind, "chains": chains,
                         "planar": chains, "pages": chains, "degrees": degrees, "href": f"codes/{slug}-1.html"})
    assert _codes(folder) == expected
    assert sum(e["chains"] for e in expected) == sum(by_code.values()) == 9
    index = (folder / "index.html").read_text()
    assert "<h1>Atlas: 9 chains in 6 codes</h1>" in index
    assert 'const CODES=[{"code":"22/0 G2","W":1,"h":3,' in index  # compact JSON
    assert not (folder / "moving").exists()  # no moving pages unless asked for
    assert ("<p>The first 2 chains (in code order) are drawn; the others are listed with their data (raise "
            "--draw-limit to draw them).</p>") in index
    assert ('<label>kind <select id="fkind"><option value="">all</option><option>chains</option><option>gears</option>'
            '</select></label>') in index
    assert '<label>n <select id="fn"><option value="">all</option><option>4</option><option>6</option></select>' in index
    assert '<label>v <select id="fv"><option value="">all</option><option>0</option><option>1</option></select>' in index
    assert "shown: <span class='total' id='shown'>9</span> chains in <span id='codes'>6</span> codes" in index
    assert (folder / "style.css").read_text() == site._STYLE
    assert (folder / "chain.html").read_text() == site._LOOKUP_PAGE
    drawn = sum(p.read_text().count("<svg") for p in (folder / "codes").iterdir())
    assert drawn == 2 and sum(p.read_text().count("not drawn") for p in (folder / "codes").iterdir()) == 7


def test_each_code_page_its_title_navigation_and_count(built):
    folder, _ = built
    pages = {p.name: _text(p.read_text()) for p in (folder / "codes").iterdir()}
    assert sorted(pages) == sorted(f"{slug}-{k}.html" for code, *_, slug in CODES
                                   for k in range(1, {"22/0 G2": 2, "4/0 P2": 2, "42/0": 2}.get(code, 1) + 1))
    first, second = pages["W1-h3-42_0-1.html"], pages["W1-h3-42_0-2.html"]
    assert "<title>42/0 — W = 1, h = 3, n = 6, v = 0</title>" in first
    assert all('<link rel="stylesheet" href="../style.css">' in page for page in pages.values())  # one folder down
    nav = "<p class='nav'><a href=\"../index.html\">index</a> · <a href=\"W1-h3-42_0-2.html\">next page</a></p>"
    assert first.count(nav) == 2 and "previous page" not in first
    assert "<p>chains 1–1 of <span class='total' id='count'>2</span></p>" in first
    nav = "<p class='nav'><a href=\"../index.html\">index</a> · <a href=\"W1-h3-42_0-1.html\">previous page</a></p>"
    assert second.count(nav) == 2 and "next page" not in second
    assert "<p>chains 2–2 of <span class='total' id='count'>2</span></p>" in second
    assert "<title>4/0 P1 — W = 1, h = 3, n = 4, v = 0, 1 prismatic pair</title>" in pages["W1-h3-4_0-P1-1.html"]
    assert "<title>4/0 P2 — W = 1, h = 3, n = 4, v = 0, 2 prismatic pairs</title>" in pages["W1-h3-4_0-P2-1.html"]
    assert "<title>31/1 G2 — W = 1, h = 3, n = 4, v = 1, 2 gear meshes</title>" in pages["W1-h3-31_1-G2-1.html"]
    single = pages["W1-h3-4_0-1.html"]
    assert single.count("<p class='nav'><a href=\"../index.html\">index</a></p>") == 2


def _cards(folder: Path) -> dict[str, str]:
    cards = {}
    for page in (folder / "codes").iterdir():
        for card in re.findall(r"<figure id=\"([0-9a-f]{12})\"(.*?)</figure>", _text(page.read_text()), re.S):
            cards[card[0]] = card[1]
    return cards


def test_the_cards_of_the_four_bar_and_the_six_bars_by_hand(built):
    folder, _ = built
    cards = _cards(folder)
    assert len(cards) == 9
    for chain, order, frames in ((FOUR_BAR, 8, 1), (WATT, 4, 2), (STEPHENSON, 4, 3)):
        cid = chain_id(chain.certificate)
        card = cards[cid]
        assert "<figcaption>#" in card and f'<a href="#{cid}">{cid}</a><br>planar · |Aut| = {order}<br>' \
                                             "not fractionated</figcaption>" in card
        assert f"mechanisms: {frames} with a fixed link (up to symmetry): link " in card
        compact = re.search(r"joints: <code>(.*?)</code>", card).group(1)
        assert Chain.parse(compact).certificate == chain.certificate
        assert f'<code>mechsynth draw --chain "{compact}" --mechanisms --out m.svg</code>' in card
        assert f"certificate: <code>{chain.certificate}</code>" in card
    four = cards[chain_id(FOUR_BAR.certificate)]
    assert "mechanisms: 1 with a fixed link (up to symmetry): link 0; with an input link: 0→1<br>" in four


def test_the_gear_train_cards(atlas, built):
    folder, _ = built
    with open_atlas(atlas) as conn:
        trains = conn.execute("SELECT c.certificate, t.train, t.lever_code, t.carriers, t.rotation FROM trains t "
                              "JOIN chains c ON c.id = t.chain").fetchall()
    assert len(trains) == 3
    pages = "".join(_text(p.read_text()) for p in (folder / "codes").glob("*G2*"))
    for certificate, text, lever, carriers, rotation in trains:
        cid = chain_id(certificate)
        card = re.search(rf'<figure id="{cid}" class="train">(.*?)</figure>', pages, re.S).group(1)
        word = "carrier" if carriers == 1 else "carriers"
        assert f"lever analogue {lever} · {carriers} {word}<br>rotation graph {chain_id(rotation)}</figcaption>" in card
        assert f"train: <code>{text}</code>" in card
        assert f'<code>mechsynth gears --train "{text}" --input-output</code>' in card
        assert f'<code>mechsynth gears --train "{text}" --out train.svg</code>' in card
        assert "fixed link up to symmetry: " in card and "none stored" not in card


def test_every_chain_is_looked_up_on_its_page(atlas, built):
    folder, _ = built
    entries = {}
    for path in (folder / "lookup").iterdir():
        text = path.read_text()
        assert text.startswith("found(") and text.endswith(");")
        table = json.loads(text[len("found("):-2])
        assert text == "found(" + json.dumps(table, separators=(",", ":")) + ");"  # compact: no blanks
        assert all(cid[:2] == path.stem for cid in table)
        entries.update(table)
    with open_atlas(atlas) as conn:
        ids = {chain_id(c) for (c,) in conn.execute("SELECT certificate FROM chains")}
    assert set(entries) == ids
    for cid, page in entries.items():
        assert f'<figure id="{cid}"' in (folder / page).read_text()


def test_moving_pages_say_how_the_input_moves(atlas, tmp_path):
    folder = tmp_path / "s"
    write_site(atlas, folder, page_size=60, move_limit=3, workers=1)
    names = sorted(p.name for p in (folder / "moving").iterdir())
    four = chain_id(FOUR_BAR.certificate)
    assert f"{four}-0.html" in names
    page = _text((folder / "moving" / f"{four}-0.html").read_text())
    assert "<title>0-1 0-2 1-3 2-3 with link 0 fixed</title>" in page
    assert f"<a href='../chain.html#{four}'>the chain {four}</a>" in page
    # the drawing's own pose does not turn the four-bar's crank: the page says how it was moved
    assert "<tr><th class='c'>pose</th><td class='c'>the drawing&#x27;s pose does not move well" in page
    assert "<code>mechsynth move --chain \"0-1 0-2 1-3 2-3\" --frame 0 --range</code>" in page
    assert f"--frame 0 --animate {four}-0.gif</code>" in page and f"--frame 0 --save {four}-0.json</code>" in page
    card = _cards(folder)[four]
    assert f'moving: <a href="../moving/{four}-0.html">link 0 fixed</a>' in card
    seen = set()
    for name in names:
        text = (folder / "moving" / name).read_text()
        row = re.search(r"<th class='c'>input</th><td class='c'>joint (\S+) \((\w+)\), (.*?)</td>", text)
        kind, motion = row.group(2), row.group(3)
        seen.add(kind)
        if kind == "prismatic" and motion != "turns fully (a crank)":
            # a slide's limits are lengths: no degrees
            low, high = map(float, re.fullmatch(r"slides between (\S+) and (\S+)", motion).groups())
            assert low < high
        elif motion != "turns fully (a crank)":
            assert re.fullmatch(r"rocks between \S+° and \S+°", motion)
    assert seen == {"revolute", "prismatic"}
    # the first three planar 1-DOF chains without gears move: the four-bar and its two slider variants' orders
    assert len({n[:12] for n in names}) == 3


@pytest.mark.parametrize("options, sentence", [
    (dict(move_limit=-1), "the number of chains whose mechanisms move is at least 0, not -1"),
    (dict(page_size=0), "the page size is 1 … 2000 chains (a page is drawn and held in memory at once), workers at "
                        "least 1 and the drawing limit at least 0, not 0, None and 20000"),
    (dict(page_size=2001), "the page size is 1 … 2000 chains (a page is drawn and held in memory at once), workers "
                           "at least 1 and the drawing limit at least 0, not 2001, None and 20000"),
    (dict(draw_limit=-1, workers=3), "the page size is 1 … 2000 chains (a page is drawn and held in memory at once), "
                                     "workers at least 1 and the drawing limit at least 0, not 60, 3 and -1"),
    (dict(workers=0), "the page size is 1 … 2000 chains (a page is drawn and held in memory at once), workers at "
                      "least 1 and the drawing limit at least 0, not 60, 0 and 20000"),
])
def test_options_are_refused_with_their_sentence(atlas, tmp_path, options, sentence):
    with pytest.raises(InvalidOption) as e:
        write_site(atlas, tmp_path / "s", **options)
    assert str(e.value) == sentence
    assert not (tmp_path / "s").exists()


def test_folders_are_refused_with_their_sentence(atlas, tmp_path):
    (tmp_path / "file").write_text("x")
    with pytest.raises(InvalidOption) as e:
        write_site(atlas, tmp_path / "file")
    assert str(e.value) == f"cannot write the site into {tmp_path / 'file'}: it is a file"
    full = tmp_path / "full"
    full.mkdir()
    (full / "keep.txt").write_text("mine")
    with pytest.raises(InvalidOption) as e:
        write_site(atlas, full)
    assert str(e.value) == f"{full} is not empty; give force=True to write the site over it"
    assert write_site(atlas, full, force=True, draw_limit=0).chains == 9
    assert (full / "keep.txt").read_text() == "mine"
    (tmp_path / "empty").mkdir()
    assert write_site(atlas, tmp_path / "empty", draw_limit=0).drawn == 0
    with pytest.raises(InvalidOption) as e:
        write_site(atlas, tmp_path / "none" / "s")
    assert str(e.value) == f"cannot write the site into {tmp_path / 'none' / 's'}: the directory {tmp_path / 'none'} " \
                           "does not exist"
    blocked = tmp_path / "blocked"
    blocked.mkdir()
    (blocked / "codes").write_text("a file where a folder goes")
    with pytest.raises(InvalidOption) as e:
        write_site(atlas, blocked, force=True, draw_limit=0)
    assert str(e.value) == f"cannot write the site into {blocked}: File exists ({blocked / 'codes'})"


def test_an_empty_atlas_has_no_site(tmp_path):
    db = tmp_path / "a.sqlite"
    open_atlas(db, write=True).close()
    with pytest.raises(EmptyAtlas) as e:
        write_site(db, tmp_path / "s")
    assert str(e.value) == (f"the atlas {db} holds no chain: there is no site to write (run 'mechsynth grid' into it "
                            "first)")


def test_a_long_drawing_run_is_said_first(atlas, tmp_path, monkeypatch, plain_bar):
    monkeypatch.setattr(site, "_SECONDS_PER_DRAWING", 100.0)  # 9 drawings: 900 s on one worker
    said = []
    write_site(atlas, tmp_path / "a", draw_limit=9, workers=1, progress=True, note=said.append)
    assert said == ["9 of the 9 chains are drawn: about 15 min on 1 worker (a lower drawing limit draws fewer)"]
    assert not (tmp_path / "a" / "moving").exists()  # every chain drawn, none moves unless asked for
    said.clear()
    write_site(atlas, tmp_path / "b", draw_limit=6, workers=2, progress=True, note=said.append)
    assert said == ["6 of the 9 chains are drawn: about 5 min on 2 workers (a lower drawing limit draws fewer)"]
    monkeypatch.setattr(site, "_SECONDS_PER_DRAWING", 6.0)  # 9 × 6 s = 54 s: nothing to say
    said.clear()
    write_site(atlas, tmp_path / "c", workers=1, progress=True, note=said.append)
    assert said == []


def test_a_card_says_what_the_atlas_did_not_store():
    from synth.gears.train import GearTrain

    text = "0-1-4 0-2 1-3 0~3 1~2 2~4"  # a train of 5 links whose meshes have two carriers, 1 and 0
    train = GearTrain.parse(text)
    assert sorted(set(train.carriers)) == [0, 1]
    chain = train.to_chain()
    card = site._train_card(4, chain, (text, "x", chain.certificate), [], False, False)
    assert "lever analogue x · 2 carriers<br>" in card and "fixed link up to symmetry: none stored<br>" in card
    assert "<p><i>not drawn</i> (see the site's note)</p>" in card and "#4 " in card
    # a fractionated chain (two four-bars sharing link 0) without stored mechanisms: its link orbits are the frames
    two = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-6 6-0")
    card, planar, pages = site._card((2, json.dumps(two.to_dict()), [], True, False, False, None))
    assert "<br>fractionated</figcaption>" in card and planar and pages == []
    assert f"mechanisms: {len(two.link_orbits)} with a fixed link (up to symmetry): link " in card


def test_the_long_drawing_note_begins_past_a_minute(atlas, tmp_path, monkeypatch, plain_bar):
    said = []
    monkeypatch.setattr(site, "_SECONDS_PER_DRAWING", 10.0)  # 6 drawings: exactly 60 s
    write_site(atlas, tmp_path / "a", draw_limit=6, workers=1, progress=True, note=said.append)
    assert said == []
    monkeypatch.setattr(site, "_SECONDS_PER_DRAWING", 10.1)  # 60.6 s
    write_site(atlas, tmp_path / "b", draw_limit=6, workers=1, progress=True, note=said.append)
    assert said == ["6 of the 9 chains are drawn: about 61 s on 1 worker (a lower drawing limit draws fewer)"]


@pytest.fixture
def plain_bar(monkeypatch):
    """tqdm with a plain thread lock and no monitor thread: its default also makes a multiprocessing lock, which
    hangs in a process forked from a threaded one (mutmut runs each mutant so)."""
    import threading

    import tqdm

    monkeypatch.setattr(tqdm.tqdm, "_lock", threading.RLock(), raising=False)
    monkeypatch.setattr(tqdm.tqdm, "monitor_interval", 0)
