"""``mechsynth gears`` as a user meets it: output paths checked before any work, sheets that never
drop trains silently, captions and link numbers that overprint nothing, a legend, tooth numbers
and the ratio on a design's schematic, rotation counts that add up, large queries sized first,
progress bars on a terminal."""

from __future__ import annotations

import fcntl
import json
import os
import pty
import resource
import select
import struct
import subprocess
import sys
import termios
import time

import pytest

from synth.gears import GearTrain, count_trains, trains
from tests.load import allowed_seconds
from synth.draw import schematic, sheet_figure
from synth.draw._gears import _label_places


def _cli(*args, **kwargs):
    return subprocess.run([sys.executable, "-m", "mechsynth", "gears", *args], capture_output=True, text=True, **kwargs)


# ------------------------------------------------------------------ output paths and sheets
def test_unwritable_out_is_refused_before_any_work(tmp_path):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = _cli("--links", "8", "--out", str(tmp_path / "missing" / "eight.png"))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    assert out.returncode == 2 and out.stdout == "" and "cannot write" in out.stderr
    # CPU time, which load does not stretch: the refusal takes the imports (0.2 s), finding the
    # 6 360 trains takes 3.4 s more
    assert after.ru_utime - before.ru_utime < 2.0
    (tmp_path / "taken.png").mkdir()
    out = _cli("--train", "0-1-2 2-3 0~3i 1~3", "--frame", "0", "--input", "1", "--output", "2", "--ratio", "4.2",
               "--out", str(tmp_path / "taken.png"))
    assert out.returncode == 2 and out.stdout == "" and "is a directory" in out.stderr


@pytest.mark.parametrize("suffix", ["svg", "png"])
def test_the_same_sheet_twice_is_the_same_file(tmp_path, suffix):
    """No date, no random clip ids, no writer's version: two runs give identical bytes (matplotlib alone writes a
    <dc:date> and ids drawn at random into an SVG)."""
    files = [tmp_path / f"{name}.{suffix}" for name in ("first", "second")]
    for path in files:
        out = _cli("--links", "4", "--out", str(path))
        assert out.returncode == 0 and out.stderr == f"{len(out.stdout.splitlines()) - 3} schematics -> {path}\n"
    first = files[0].read_bytes()
    assert first == files[1].read_bytes() and b"Matplotlib" not in first and b"dc:date" not in first


@pytest.mark.parametrize("train,sentence", [
    ("0-1 0~3@1", "link 2 is in no axis and no mesh: every link of a gear train turns on an axis or meshes"),
    ('{"axes": [], "meshes": []}', "the gear train object has no axes and no meshes: give each axis as the links "
                                   "that turn about it and each mesh as its two gears"),
])
def test_a_train_with_a_link_in_nothing_or_nothing_at_all_is_refused(train, sentence):
    out = _cli("--train", train)
    assert (out.returncode, out.stdout, out.stderr) == (2, "", f"mechsynth: {sentence}\n")


def test_a_sheet_beyond_the_limit_is_refused_before_anything_is_printed(tmp_path):
    out = _cli("--links", "6", "--out", str(tmp_path / "six.png"))
    assert out.returncode == 2 and out.stdout == "" and not (tmp_path / "six.png").exists()
    assert "81 gear trains to draw, more than --limit 48" in out.stderr
    out = _cli("--links", "5", "--out", str(tmp_path / "five.png"), "--limit", "12")
    assert out.returncode == 2 and "13 gear trains to draw, more than --limit 12" in out.stderr
    out = _cli("--links", "5", "--out", str(tmp_path / "five.png"), "--limit", "13")
    assert out.returncode == 0 and "13 gear trains" in out.stdout and (tmp_path / "five.png").stat().st_size > 0


def test_sheet_captions_never_overlap_and_link_numbers_clear_every_shaft():
    """Seven-link trains (captions of 40 to 50 characters, wrapped), every tenth: rendered, no two
    captions' boxes meet, no caption meets another drawing, and no link number meets a shaft."""
    fig = sheet_figure(list(trains(1, 7))[::10][:24])
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    titles = [ax.title.get_window_extent(renderer) for ax in fig.axes]
    bodies = [ax.get_window_extent(renderer) for ax in fig.axes]
    for i, box in enumerate(titles):
        assert not any(box.overlaps(other) for j, other in enumerate(titles) if j != i)
        assert not any(box.overlaps(body) for j, body in enumerate(bodies) if j != i)
    for ax in fig.axes:
        numbers = [t.get_window_extent(renderer) for t in ax.texts if t.get_text().isdigit()]
        shafts = [line.get_window_extent(renderer) for line in ax.lines
                  if line.get_linewidth() == 2.2 and len(set(line.get_ydata())) == 1]
        assert numbers and not any(n.overlaps(s) for n in numbers for s in shafts)
        assert not any(a.overlaps(b) for i, a in enumerate(numbers) for b in numbers[i + 1:])
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_link_numbers_stand_left_of_every_shaft():
    train = GearTrain.parse("0-1-4 0-2 0-3 1~2 2~3 3~4", frame=1)
    shafts = schematic(train)["shafts"]
    left = min(s["from"] for s in shafts.values())
    places = _label_places(shafts, left, 0.45)
    assert sorted(x for x, _, _ in places) == list(range(5)) and all(at < left for _, at, _ in places)
    close = [(a, b) for a in places for b in places if a[0] < b[0] and abs(shafts[a[0]]["y"] - shafts[b[0]]["y"]) < 0.45]
    assert close and all(abs(a[2] - b[2]) >= 0.45 - 1e-12 for a, b in close)  # concentric shafts: a line apart


def test_design_schematic_shows_teeth_ratio_and_legend(tmp_path):
    picture = tmp_path / "reducer.svg"
    out = _cli("--train", "0-1-2 2-3 0~3i 1~3", "--frame", "0", "--input", "1", "--output", "2", "--ratio", "4.2",
               "--tolerance", "0.5%", "--teeth", "17..100", "--planets", "3", "--out", str(picture), "--format", "jsonl")
    assert out.returncode == 0 and out.stderr == f"1 schematic -> {picture}\n"  # (it once wrote it in silence)
    best = json.loads(out.stdout.splitlines()[0])
    text = picture.read_text()
    for wheel, z in best["teeth"].items():
        assert f"{wheel}={z}" in text
    assert f"i = ω1/ω2 = {best['ratio']}" in text and "wanted 4.2" in text
    for words in ("gear wheel", "ring gear", "carrier arm", "frame (black, hatched)"):
        assert words in text


# ------------------------------------------------------------------ counts
@pytest.mark.parametrize("dof,links", [(1, 5), (1, 6), (1, 7), (2, 7)])
def test_rotation_counts_by_code_add_up_and_match_the_listing(dof, links):
    found = count_trains(dof, links, graphs="rotation")
    assert sum(found["by_code"].values()) == found["count"]
    listed: dict = {}
    for t in trains(dof, links, graphs="rotation"):
        code = str(t.lever_analogue().code)
        listed[code] = listed.get(code, 0) + 1
    assert listed == found["by_code"]


def test_large_listings_are_sized_first():
    """A table of the 12-link trains (about 2.6e+08 rows) is refused at once, with the estimate."""
    started = time.monotonic()
    out = _cli("--links", "12")
    assert out.returncode == 2 and out.stdout == "" and "use --format jsonl" in out.stderr
    assert "displacement graphs" in out.stderr and "extrapolated from the exact counts" in out.stderr
    assert time.monotonic() - started < allowed_seconds(60)


def test_a_long_count_says_how_long_before_it_starts():
    proc = subprocess.Popen([sys.executable, "-m", "mechsynth", "gears", "--links", "12", "--count"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        line = proc.stderr.readline()
    finally:
        os.killpg(proc.pid, 9)
        proc.wait()
    assert line.startswith("mechsynth: a long query: about ") and " h on 1 worker" in line


# ------------------------------------------------------------------ progress on a terminal
def _on_terminal(args, *wanted: str, seconds: float = 120) -> str:
    """What a command writes to a terminal's stderr until all of ``wanted`` have shown (the command
    is then stopped: a bar is shown by its first redraws, the search need not finish) or ``seconds``
    have passed (a generous bound: a loaded machine draws the bar late, not never)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 120, 0, 0))
    proc = subprocess.Popen([sys.executable, "-m", "mechsynth", "gears", *args], stdout=subprocess.DEVNULL,
                            stderr=slave, start_new_session=True)
    os.close(slave)
    seen, started = b"", time.monotonic()
    try:
        while time.monotonic() - started < seconds and not all(w.encode() in seen for w in wanted):
            ready, _, _ = select.select([master], [], [], 0.2)
            if ready:
                try:
                    chunk = os.read(master, 4096)
                except OSError:
                    break
                if not chunk:
                    break
                seen += chunk
    finally:
        os.killpg(proc.pid, 9)
        proc.wait()
        os.close(master)
    return seen.decode(errors="replace")


def test_long_searches_show_a_progress_bar_on_a_terminal():
    bar = ("gear trains:", "/1540 [", "trees/s")  # 10 links (some 10 CPU s; 9 links now ends before the bar's 1-s delay)
    shown = _on_terminal(["--links", "10", "--count"], *bar)
    assert all(words in shown for words in bar), shown
    bar = ("ratio design:", "/81 [")
    shown = _on_terminal(["--links", "6", "--ratio", "7.3", "--tolerance", "0.5%", "--teeth", "17..80",
                          "--planets", "3"], *bar)
    assert all(words in shown for words in bar), shown
