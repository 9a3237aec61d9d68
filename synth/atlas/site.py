"""An atlas as a static web site: an index of codes with filters, a page per code with every chain drawn.

The site needs no server (open ``index.html`` from disk or put the folder on any web host):
``index.html`` lists the codes by W, h, links, v and code with their counts and filters them in the
browser (W, h, links, v, planar only, a link with I joints); ``codes/<code>-<page>.html`` shows
``page_size`` chains a page, each drawn (SVG) with its code, certificate, planarity,
fractionation, symmetry and its mechanisms (fixed links up to symmetry) on request; a chain's
stable address is ``chain.html#<id>`` with ``id`` the first 12 hex digits of the SHA-1 of its
certificate, which the pages and the lookup files (``lookup/<2 hex>.js``) resolve.  Chains stream
from SQLite in code order, so memory stays bounded by one page and the lookup table.  A planetary
gear train is drawn as its functional schematic (:func:`synth.draw.svg_text`) with its text
form, lever analogue, carriers, rotation graph and the ``mechsynth gears`` commands that list its
mechanisms and draw it.

Example
-------
>>> import os, tempfile
>>> from synth.atlas import run_grid
>>> from synth.atlas.grid import parse_grid
>>> folder = tempfile.mkdtemp()
>>> db = os.path.join(folder, "a.sqlite")
>>> _ = run_grid(parse_grid('dof = 1\\nlinks = "4..8"'), db, workers=1)
>>> write_site(db, os.path.join(folder, "site")).chains
19
"""

from __future__ import annotations

import html
import json
import math
import os
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from mechbase import Row


from .database import AtlasError, _reading, chain_id, open_atlas
from ..execution.executor import Executor
from ..structure.chain import Chain
from ..structure.code import Code
from ..structure.joints import PRISMATIC
from ..draw import svg_inline, svg_text
from ..gears.train import GearTrain
from ..errors import InvalidOption, option

__all__ = ["chain_id", "write_site", "SiteResult", "EmptyAtlas", "MAX_PAGE_SIZE"]

MAX_PAGE_SIZE = 2000  # chains on one page: drawn and held in memory together
_SECONDS_PER_DRAWING = 0.05  # a 12-link chain's layout on one core (docs/atlas.md)


class EmptyAtlas(AtlasError):
    """The atlas holds no chain (a valid atlas, nothing to show)."""

_ORDER = "ORDER BY c.dof, c.h, c.links, c.v, c.code, c.prismatic, c.meshes, c.certificate"
_STYLE = """
body{font:14px/1.4 system-ui,sans-serif;margin:1.5em;color:#1b2733}
a{color:#1f3a5f}h1{font-size:1.4em}table{border-collapse:collapse}
td,th{padding:2px 10px;text-align:right;border-bottom:1px solid #e3e8ee}th{background:#f3f6f9}
td.c,th.c{text-align:left}.filters label{margin-right:1em}.grid{display:flex;flex-wrap:wrap;gap:10px}
figure{margin:0;border:1px solid #dde4ec;border-radius:6px;padding:4px;width:180px;background:#fff}
figure.train{width:240px}figure.train svg{max-width:100%;height:auto}
figure.moving{width:auto;display:inline-block}figure:target{outline:3px solid #c0392b}figcaption{font-size:12px}details{font-size:11px}
code{word-break:break-all;font-size:10px}.nav{margin:1em 0}.total{font-weight:bold}
"""


@dataclass
class SiteResult(Row):
    """What :func:`write_site` wrote: codes, pages, chains and how many of them are drawn."""

    folder: str
    codes: int
    pages: int
    chains: int
    drawn: int


def _slug(group: tuple) -> str:
    dof, h, code, prismatic, meshes = group
    text = f"W{dof}-h{h}-{code}" + (f"-P{prismatic}" if prismatic else "") + (f"-G{meshes}" if meshes else "")
    return re.sub(r"[^A-Za-z0-9.=-]+", "_", text)


def _page(title: str, body: str, depth: int = 0) -> str:
    up = "../" * depth
    return (f'<!doctype html><html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>'
            f'<link rel="stylesheet" href="{up}style.css"></head><body>{body}</body></html>')


def _train_card(index: int, chain: Chain, train: tuple, mechanisms, fractionated: bool, draw: bool) -> str:
    """One gear train's figure (HTML): its schematic, numbers and the commands that reproduce it."""
    text, lever, rotation = train
    gears = GearTrain.parse(text)
    cid = chain_id(chain.certificate)
    picture = svg_text(gears) if draw else "<p><i>not drawn</i> (see the site's note)</p>"
    frames = sorted({f for f, i in mechanisms if i < 0})
    quoted = html.escape(text)
    return (f'<figure id="{cid}" class="train">{picture}<figcaption>#{index} <a href="#{cid}">{cid}</a><br>'
            f'lever analogue {html.escape(lever)} · {len(set(gears.carriers))} carrier'
            f'{"s" * (len(set(gears.carriers)) > 1)}<br>rotation graph {chain_id(rotation)}'
            f'{" · fractionated" if fractionated else ""}</figcaption><details>'
            f'<summary>train, certificate, mechanisms</summary>'
            f'train: <code>{quoted}</code><br>carriers per mesh: {", ".join(map(str, gears.carriers))}<br>'
            f'certificate: <code>{html.escape(chain.certificate)}</code><br>'
            f'fixed link up to symmetry: {", ".join(map(str, frames)) or "none stored"}<br>'
            f'<code>mechsynth gears --train "{quoted}" --input-output</code><br>'
            f'<code>mechsynth gears --train "{quoted}" --out train.svg</code></details></figure>')


def _card(job: tuple) -> tuple[str, bool, list[tuple[str, str]]]:
    """One chain's figure (HTML), whether it is planar, and the pages of its mechanisms that move
    (file name, HTML); ``job`` is (index, chain as JSON text, stored mechanisms, fractionated, draw?,
    move?, gear train or None) so that worker processes can build it."""
    index, data, mechanisms, fractionated, draw, move, train = job
    chain = Chain.from_dict(json.loads(data))
    if train is not None:
        return _train_card(index, chain, train, mechanisms, fractionated, draw), chain.is_planar(), []
    cid = chain_id(chain.certificate)
    planar = chain.is_planar()
    picture = svg_inline(chain) if draw else "<p><i>not drawn</i> (see the site's note)</p>"
    frames = sorted({f for f, i in mechanisms if i < 0})
    inputs = sorted((f, i) for f, i in mechanisms if i >= 0)
    order = chain.automorphisms()[1]
    if not frames:  # the atlas stores no mechanisms: the frame choices are the link orbits
        frames = [orbit[0] for orbit in chain.link_orbits]
    mech = f"{len(frames)} with a fixed link (up to symmetry): link " + ", ".join(map(str, frames))
    if inputs:
        mech += "; with an input link: " + ", ".join(f"{f}→{i}" for f, i in inputs)
    pages = [_moving_page(chain, cid, frame) for frame in frames] if move else []
    if pages:
        mech += "<br>moving: " + ", ".join(f'<a href="../moving/{name}">link {frame} fixed</a>' if name else
                                           f"link {frame} fixed: {html.escape(why)}"
                                           for frame, (name, _, why) in zip(frames, pages))
    card = (f'<figure id="{cid}">{picture}<figcaption>#{index} <a href="#{cid}">{cid}</a><br>'
            f'{"planar" if planar else "non-planar"} · |Aut| = {order:g}<br>'
            f'{"fractionated" if fractionated else "not fractionated"}</figcaption><details>'
            f'<summary>chain, certificate, mechanisms</summary>'
            f'joints: <code>{html.escape(chain.compact())}</code><br>certificate: <code>{html.escape(chain.certificate)}'
            f'</code><br>mechanisms: {mech}<br><code>mechsynth draw --chain "{html.escape(chain.compact())}" '
            f'--mechanisms --out m.svg</code></details></figure>')
    return card, planar, [(name, page) for name, page, _ in pages if name]


def _moving_page(chain: Chain, cid: str, frame: int) -> tuple[str | None, str, str]:
    """The page of one mechanism moving in the browser: (file name, HTML, ""), or (None, "", why
    not) when no pose near its drawing moves."""
    from ..errors import MotionError
    from ..motion import joint_name, motion_range, sweep
    from ..motion_draw import PLAYER_SCRIPT, linkage_from_layout, player_svg
    from ..structure.chain import Mechanism

    try:
        linkage = linkage_from_layout(Mechanism(chain, frame), tries=8)
        motion = sweep(linkage, steps=361)
        reach = motion_range(linkage)
        picture = player_svg(motion, size=360, frames=48)
    except MotionError as exc:
        return None, "", str(exc)
    k = linkage.inputs[0]
    if reach.full_rotation:
        moves = "turns fully (a crank)"
    elif reach.limits and linkage.kind(k) == PRISMATIC:  # a slide's limits are lengths, in the drawing's units
        moves = f"slides between {reach.limits[0]:.1f} and {reach.limits[1]:.1f}"
    elif reach.limits:
        moves = f"rocks between {math.degrees(reach.limits[0]):.1f}° and {math.degrees(reach.limits[1]):.1f}°"
    else:
        moves = "does not move"
    worst = min([min(t["min"], math.pi - t["max"]) for t in motion.transmission.values()], default=None)
    rows = [("input", f"joint {joint_name(chain, k)} ({linkage.kind(k)}), {moves}")]
    if reach.grashof:
        rows.append(("Grashof", reach.grashof))
    if worst is not None:
        rows.append(("worst transmission angle", f"{math.degrees(worst):.1f}°"))
    if linkage.note:
        rows.append(("pose", linkage.note))
    compact = html.escape(chain.compact())
    title = f"{chain.compact()} with link {frame} fixed"
    body = (f"<h1>{html.escape(title)}</h1><p class='nav'><a href='../index.html'>index</a> · "
            f"<a href='../chain.html#{cid}'>the chain {cid}</a></p><figure class='moving'>{picture}<figcaption>"
            f"link {frame} fixed (hatched pivots, dashed lines); the input link "
            f"{linkage.input_link(0)} in orange; grey: the paths of the moving pins. A click pauses the drawing."
            "</figcaption></figure>"
            "<table>" + "".join(f"<tr><th class='c'>{html.escape(a)}</th><td class='c'>{html.escape(b)}</td></tr>"
                                for a, b in rows) + "</table>"
            f"<p>Dimensioned by the atlas's drawing (a linkage of size 100). The same in a terminal:<br>"
            f"<code>mechsynth move --chain \"{compact}\" --frame {frame} --range</code><br>"
            f"<code>mechsynth move --chain \"{compact}\" --frame {frame} --animate {cid}-{frame}.gif</code><br>"
            f"<code>mechsynth move --chain \"{compact}\" --frame {frame} --save {cid}-{frame}.json</code> "
            "(its dimensions, to edit)</p>"
            f"<script>{PLAYER_SCRIPT}</script>")
    return f"{cid}-{frame}.html", _page(title, body, 1), ""


def _degrees(code: str) -> list[int]:
    """Link degrees present in a code (all chains of a code share its link assortment)."""
    parsed = Code.parse(code)
    return ([1] if parsed.n1 else []) + [i + 2 for i, n in enumerate(parsed.assortment) if n]


def write_site(db: str | Path, folder: str | Path, *, page_size: int = 60, draw_limit: int = 20000,
               move_limit: int = 0, force: bool = False, progress: bool = False, workers: int | None = None,
               note: Callable[[str], None] | None = None) -> SiteResult:
    """Write the atlas ``db`` as a static site into ``folder`` (see the module docstring).

    ``draw_limit`` bounds the drawings (a layout takes about 50 ms at 12 links): chains beyond
    it are listed with their data but not drawn; ``workers`` processes build a page's figures in
    parallel (default: every core for more than 200 chains, else one; from Python, set
    ``OPENBLAS_NUM_THREADS=1`` before numpy is imported, as the command does, or OpenBLAS threads
    take the cores from the workers).  An existing non-empty folder is refused unless ``force``.
    ``note`` receives a sentence before a long drawing run (how many are drawn, how long it takes).
    ``move_limit`` planar 1-DOF chains (the first drawn ones) get a page per mechanism (fixed link up
    to symmetry) where it moves in the browser, dimensioned by its drawing
    (:func:`synth.motion_draw.linkage_from_layout`); their cards link to those pages.
    """
    if move_limit < 0:
        raise InvalidOption(f"the number of chains whose mechanisms move is at least 0, not {move_limit}")
    if not 1 <= page_size <= MAX_PAGE_SIZE or draw_limit < 0 or (workers is not None and workers < 1):
        raise InvalidOption(f"the page size is 1 … {MAX_PAGE_SIZE} chains (a page is drawn and held in memory "
                            f"at once), workers at least 1 and the drawing limit at least 0, not {page_size}, "
                            f"{workers} and {draw_limit}")
    out = Path(folder)
    if out.exists() and not out.is_dir():
        raise InvalidOption(f"cannot write the site into {out}: it is a file")
    if out.exists() and any(out.iterdir()) and not force:
        raise InvalidOption(f"{out} is not empty; give {option('force')} to write the site over it")
    if not out.parent.is_dir():
        raise InvalidOption(f"cannot write the site into {out}: the directory {out.parent} does not exist")
    conn = open_atlas(db)
    try:
        with _reading(db):
            total = conn.execute("SELECT COUNT(*) FROM chains").fetchone()[0]
    except BaseException:
        conn.close()
        raise
    if total == 0:
        conn.close()
        raise EmptyAtlas(f"the atlas {db} holds no chain: there is no site to write (run 'mechsynth grid' into it "
                         "first)")
    try:
        with _reading(db):
            return _write(conn, out, total, page_size=page_size, draw_limit=draw_limit, move_limit=move_limit,
                          progress=progress, workers=workers, note=note)
    except OSError as exc:
        raise InvalidOption(f"cannot write the site into {out}: {exc.strerror or exc}"
                            + (f" ({exc.filename})" if exc.filename and str(exc.filename) != str(out) else ""))
    finally:
        conn.close()


def _write(conn, out: Path, total: int, *, page_size: int, draw_limit: int, move_limit: int, progress: bool,
           workers: int | None, note: Callable[[str], None] | None) -> SiteResult:
    """The body of :func:`write_site` on an open atlas with ``total`` chains."""
    if workers is None:
        workers = (os.cpu_count() or 1) if total > 200 else 1
    executor, bar = Executor(workers), None  # its workers leave Ctrl-C to this process, which ends them
    try:
        (out / "codes").mkdir(parents=True, exist_ok=True)
        (out / "lookup").mkdir(exist_ok=True)
        if move_limit:
            (out / "moving").mkdir(exist_ok=True)
        (out / "style.css").write_text(_STYLE)
        groups: list[dict] = []
        lookup: dict[str, dict[str, str]] = {}
        pages = drawn = moved = 0
        if progress:
            from ..execution.progress import Progress
            from ..execution.sizes import describe_seconds

            seconds = min(draw_limit, total) * _SECONDS_PER_DRAWING / workers
            if seconds > 60 and note is not None:
                note(f"{min(draw_limit, total)} of the {total} chains are drawn: about {describe_seconds(seconds)} "
                     f"on {workers} worker{'s' * (workers > 1)} (a lower drawing limit draws fewer)")
            bar = Progress(total, "chains", desc="site")
        rows = conn.execute(f"SELECT c.id, c.dof, c.h, c.links, c.v, c.code, c.prismatic, c.meshes, c.fractionated, "
                            f"c.chain, c.certificate, t.train, t.lever_code, t.rotation "
                            f"FROM chains c LEFT JOIN trains t ON t.chain = c.id {_ORDER}")
        current, buffer = None, []

        def flush(final: bool) -> None:
            nonlocal pages, drawn, moved
            if not buffer:
                return
            info = groups[-1]
            number = info["pages"] + 1
            slug = _slug(current)
            jobs = []
            for index, data, mechs, frac, cid, train in buffer:
                move = (moved < move_limit and drawn < draw_limit and train is None and current[0] == 1
                        and current[1] == 3 and not current[4])  # planar 1-DOF linkages, no gear trains
                jobs.append((index, data, mechs, frac, drawn < draw_limit, move, train))
                drawn += drawn < draw_limit
                moved += move
                lookup.setdefault(cid[:2], {})[cid] = f"codes/{slug}-{number}.html"
            cards = list(executor.map(_card, jobs, chunk=4))
            info["planar"] += sum(planar for _, planar, _ in cards)
            for _, _, moving in cards:
                for file_name, page in moving:
                    (out / "moving" / file_name).write_text(page)
            name = f"{slug}-{number}.html"
            nav = ['<a href="../index.html">index</a>']
            if number > 1:
                nav.append(f'<a href="{slug}-{number - 1}.html">previous page</a>')
            if not final:
                nav.append(f'<a href="{slug}-{number + 1}.html">next page</a>')
            first, last = buffer[0][0], buffer[-1][0]
            title = (f"{info['code']} — W = {info['W']}, h = {info['h']}, n = {info['n']}, v = {info['v']}"
                     + (f", {info['P']} prismatic pair{'s' if info['P'] > 1 else ''}" if info["P"] else "")
                     + (f", {info['G']} gear meshes" if info["G"] else ""))
            body = (f"<h1>{html.escape(title)}</h1><p class='nav'>{' · '.join(nav)}</p>"
                    f"<p>chains {first}–{last} of <span class='total' id='count'>{{TOTAL}}</span></p>"
                    f"<div class='grid'>{''.join(card for card, _, _ in cards)}</div><p class='nav'>{' · '.join(nav)}</p>")
            (out / "codes" / name).write_text(_page(title, body, 1))
            info["pages"] = number
            pages += 1
            buffer.clear()

        for key, dof, h, links, v, code, prismatic, meshes, fractionated, data, certificate, *train in rows:
            group = (dof, h, code, prismatic, meshes)
            if group != current:
                flush(True)
                current = group
                groups.append({"code": code + (f" P{prismatic}" if prismatic else "") + (f" G{meshes}" if meshes else ""),
                               "W": dof, "h": h, "n": links, "v": v, "P": prismatic, "G": meshes,
                               "kind": "gears" if train[0] is not None else "chains", "chains": 0, "planar": 0,
                               "pages": 0, "degrees": _degrees(code), "href": f"codes/{_slug(group)}-1.html"})
            mechs = conn.execute("SELECT frame, input_link FROM mechanisms WHERE chain = ?", (key,)).fetchall()
            info = groups[-1]
            info["chains"] += 1
            if len(buffer) == page_size:  # a full page with more to come: it links to the next one
                flush(False)
            buffer.append((info["chains"], data, mechs, bool(fractionated), chain_id(certificate),
                           None if train[0] is None else tuple(train)))
            if bar is not None:
                bar.update()
        flush(True)
    finally:
        executor.close()  # Ctrl-C or an error: no worker goes on drawing
        if bar is not None:
            bar.close()
    _fill_totals(out, groups)
    for prefix, entries in lookup.items():
        (out / "lookup" / f"{prefix}.js").write_text(f"found({json.dumps(entries, separators=(',', ':'))});")
    (out / "index.html").write_text(_index(groups, total, drawn))
    (out / "chain.html").write_text(_LOOKUP_PAGE)
    return SiteResult(str(out), len(groups), pages, total, min(drawn, total))


def _fill_totals(out: Path, groups: list[dict]) -> None:
    """Each code's pages say 'chains a–b of N': N is known once the code has streamed by."""
    for info in groups:
        stem = info["href"][len("codes/"):-len("-1.html")]
        for number in range(1, info["pages"] + 1):
            path = out / "codes" / f"{stem}-{number}.html"
            path.write_text(path.read_text().replace("{TOTAL}", str(info["chains"]), 1))


def _index(groups: list[dict], total: int, drawn: int) -> str:
    options = {key: sorted({g[key] for g in groups}) for key in ("kind", "W", "h", "n", "v")}
    selects = "".join(
        f'<label>{key} <select id="f{key}"><option value="">all</option>'
        + "".join(f'<option>{value}</option>' for value in values) + "</select></label>"
        for key, values in options.items())
    note = "" if drawn >= total else (f"<p>The first {drawn} chains (in code order) are drawn; the others are listed "
                                      "with their data (raise --draw-limit to draw them).</p>")
    body = (f"<h1>Atlas: {total} chains in {len(groups)} codes</h1>{note}"
            f"<div class='filters'>{selects}<label><input type='checkbox' id='fplanar'> planar only</label>"
            f"<label>a link with <input type='number' id='fdeg' min='1' max='99' style='width:4em'> joints</label>"
            f"<label>chain id <input id='fid' size='14' placeholder='12 hex digits'></label></div>"
            f"<p>shown: <span class='total' id='shown'>{total}</span> chains in <span id='codes'>{len(groups)}</span> "
            f"codes</p><table><thead><tr><th class='c'>code</th><th>W</th><th>h</th><th>n</th><th>v</th>"
            f"<th>chains</th><th>planar</th></tr></thead><tbody id='rows'></tbody></table>"
            f"<script>const CODES={json.dumps(groups, separators=(',', ':'))};{_INDEX_JS}</script>")
    return _page("mechsynth atlas", body)


_INDEX_JS = """
const $=id=>document.getElementById(id);
function show(){
  const f={kind:$('fkind').value,W:$('fW').value,h:$('fh').value,n:$('fn').value,v:$('fv').value};
  const planar=$('fplanar').checked, deg=parseInt($('fdeg').value);
  let rows='',chains=0,codes=0;
  for(const c of CODES){
    if(Object.keys(f).some(k=>f[k]!==''&&String(c[k])!==f[k]))continue;
    if(!isNaN(deg)&&!c.degrees.includes(deg))continue;
    const n=planar?c.planar:c.chains; if(n===0)continue;
    chains+=n;codes+=1;
    rows+=`<tr><td class="c"><a href="${c.href}">${c.code}</a></td><td>${c.W}</td><td>${c.h}</td><td>${c.n}</td>`+
          `<td>${c.v}</td><td>${c.chains}</td><td>${c.planar}</td></tr>`;
  }
  $('rows').innerHTML=rows;$('shown').textContent=chains;$('codes').textContent=codes;
}
for(const id of ['fkind','fW','fh','fn','fv','fplanar','fdeg'])$(id).addEventListener('input',show);
$('fid').addEventListener('change',()=>{location.href='chain.html#'+$('fid').value.trim().toLowerCase();});
show();
"""

_LOOKUP_PAGE = _page("chain lookup", """<p id="msg">Looking up the chain…</p>
<script>
const id=location.hash.slice(1).toLowerCase();
function found(table){
  if(table[id]){location.replace(table[id]+'#'+id);}
  else{document.getElementById('msg').textContent='No chain '+id+' in this atlas.';}
}
if(!/^[0-9a-f]{12}$/.test(id)){document.getElementById('msg').textContent='Give a chain id: chain.html#<12 hex digits>.';}
else{const s=document.createElement('script');s.src='lookup/'+id.slice(0,2)+'.js';
  s.onerror=()=>{document.getElementById('msg').textContent='No chain '+id+' in this atlas.';};
  document.head.appendChild(s);}
</script><p><a href="index.html">index</a></p>""")
