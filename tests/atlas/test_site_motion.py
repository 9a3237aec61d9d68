"""The site's moving mechanisms: a page per mechanism whose frames change in a real browser."""

from __future__ import annotations

import re

import pytest

from synth.atlas import run_grid, write_site
from synth.atlas.grid import parse_grid

from .test_site import _browse


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    folder = tmp_path_factory.mktemp("moving")
    db = folder / "a.sqlite"
    run_grid(parse_grid('dof = 1\nlinks = "4..6"'), str(db), workers=1)
    write_site(db, folder / "s", move_limit=1, page_size=1)  # the four-bar only (the first in code order)
    return folder / "s"


def test_cards_link_to_pages_where_their_mechanisms_move(site):
    pages = sorted(p.name for p in (site / "moving").iterdir())
    assert len(pages) == 1  # the four-bar's one mechanism; the six-bars are beyond the limit
    cards = {p.name: p.read_text() for p in (site / "codes").iterdir()}
    linked = [name for name, text in cards.items() if "../moving/" in text]
    assert len(linked) == 1 and f'href="../moving/{pages[0]}"' in cards[linked[0]]
    page = (site / "moving" / pages[0]).read_text()
    assert 'class="moving"' in page and "mechsynth move --chain" in page and "setInterval" in page


def _frame(dom: str) -> tuple[str, str]:
    """The frame number the player shows and the points of the first moving element."""
    svg = re.search(r'<svg[^>]*class="moving"[^>]*>', dom).group(0)
    frame = re.search(r'data-frame="(\d+)"', svg)
    points = re.search(r'<(?:polygon|polyline) points="([^"]+)"[^>]*data-k="0"', dom)
    return (frame.group(1) if frame else ""), (points.group(1) if points else "")


def test_the_frames_change_in_headless_chromium(site):
    page = sorted((site / "moving").iterdir())[0].as_uri()
    early = _browse("--dump-dom", "--virtual-time-budget=400", page).stdout
    late = _browse("--dump-dom", "--virtual-time-budget=1500", page).stdout
    (frame_a, points_a), (frame_b, points_b) = _frame(early), _frame(late)
    assert frame_a and frame_b and frame_a != frame_b
    assert points_a and points_b and points_a != points_b


def test_a_click_pauses_the_player(site, tmp_path):
    page = sorted((site / "moving").iterdir())[0]
    clicked = tmp_path / page.name  # (the style sheet is not needed: the frames are the DOM's)
    clicked.write_text(page.read_text().replace(
        "</body>", "<script>document.querySelector('svg.moving').dispatchEvent(new MouseEvent('click'))</script></body>"))
    frame, _ = _frame(_browse("--dump-dom", "--virtual-time-budget=1500", clicked.as_uri()).stdout)
    assert "</body>" in page.read_text() and frame == ""  # paused before its first tick
