"""The joint kinds a chain can have, in one table: what each is, how it is written, counted,
certified and drawn.

=========  ======  ======  =======  ==========  ====  ===========  ==========================
kind       symbol  letter  freedom  loop space  tag   stroke       mark, graph node shape
=========  ======  ======  =======  ==========  ====  ===========  ==========================
revolute   ``-``   R       1        (chain's)         black        pin circle, circle
prismatic  ``=``   P       1        2           p     #1f3a5f      slider block, box
mesh       ``~``   G       2        (chain's)   g     #1e7a46      pitch circles, doublecircle
=========  ======  ======  =======  ==========  ====  ===========  ==========================

* **freedom** — the relative freedoms the pair leaves its two links in the plane.  A pair removes
  h − freedom of the h freedoms of motion space h (:meth:`JointKind.removes`): a pin or a slider
  two of the plane's three, a gear mesh one (the seed writes a mesh as a pair with f = 1 freedom
  *above* one).  A multiple joint is a pin shared by all its links and removes h − 1 per link
  after the first; only a revolute joint may be one (``joins_many``).
* **loop space** — the motion space of a loop made of this kind only, where it is not the
  chain's own: a loop of prismatic pairs cannot use rotation to close, so it is a *wedge loop*
  of h = 2 and gives h − 2 freedoms back to the count.  A loop of pins is of the chain's class;
  a mesh has no loop rule of its own: it counts by its one constraint, as its lever analogue (a
  binary link pinned to both gears) does.
* **planar** — prismatic pairs and meshes are modelled in the plane only (h = 3).

The certificate's dependence
----------------------------
The order of the members is the order of the joint colour cells of a chain's nauty graph, and the
``tag`` letters (with the count of that kind, two hex digits) are the certificate's prefix after
its sizes.  A chain shows the cells and tags of the kinds up to the *last* kind it has: an
all-revolute chain one cell and no tag (``0407…``), a chain with prismatic pairs the revolute and
prismatic cells and ``p02``, a chain with a mesh all three and ``p00g01``.  So a kind appended at
the end leaves the certificate of every chain without it unchanged, while reordering the members,
or changing a tag, changes the certificate — and so the id — of every chain that has a
non-revolute joint: the stored ids of every atlas would point at nothing
(``tests/structure/test_joint_kinds_table.py`` holds such ids).

A member *is* its name (a ``str``): ``JointKind.PRISMATIC == "prismatic"``, it hashes, prints,
compares and writes to JSON as the name, so files and rows never see the class.

>>> JointKind.PRISMATIC == "prismatic", JointKind.PRISMATIC.symbol, JointKind.MESH.removes(3), JointKind.MESH.cell
(True, '=', 1, 2)
>>> JointKind.read("slider"), JointKind.by_symbol("~"), JOINT_KINDS
('prismatic', 'mesh', ('revolute', 'prismatic', 'mesh'))
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

__all__ = ["JointKind", "JOINT_KINDS", "REVOLUTE", "PRISMATIC", "MESH"]


@dataclass(frozen=True)
class _Row:
    symbol: str  # its sign in a joint list: 0-1, 0=1, 0~1
    letter: str  # R, P, G: one letter in tables, matrices and dyad names
    freedom: int  # relative freedoms left in the plane
    loop_space: int | None  # motion space of a loop of this kind only, where not the chain's own
    joins_many: bool  # may join more than two links (a multiple joint)
    planar: bool  # modelled in the plane only (h = 3)
    noun: str  # what an edit of a chain calls it ("move joint 0-1", "move prismatic pair 1=2")
    tag: str  # the certificate's prefix letter before its count ('' for the kind every chain has)
    words: tuple[str, ...]  # other words files use for it (read case-insensitively)
    stroke: str  # the colour its mark is drawn in
    mark: str  # what a drawing shows at it
    graph_shape: str  # the shape of its node in a drawn link–joint graph (DOT)


class JointKind(StrEnum):
    """A joint kind: its name (the str value) and its row of the table above.

    Members are in certificate order; see the module docstring before reordering them.
    """

    REVOLUTE = "revolute", _Row(symbol="-", letter="R", freedom=1, loop_space=None, joins_many=True, planar=False,
                                noun="joint", tag="", words=("pin",), stroke="black", mark="pin circle",
                                graph_shape="circle")
    PRISMATIC = "prismatic", _Row(symbol="=", letter="P", freedom=1, loop_space=2, joins_many=False, planar=True,
                                  noun="prismatic pair", tag="p", words=("slider",), stroke="#1f3a5f",
                                  mark="slider block", graph_shape="box")
    MESH = "mesh", _Row(symbol="~", letter="G", freedom=2, loop_space=None, joins_many=False, planar=True,
                        noun="mesh", tag="g", words=("gear",), stroke="#1e7a46", mark="pitch circles",
                        graph_shape="doublecircle")

    def __new__(cls, name: str, row: _Row):
        member = str.__new__(cls, name)
        member._value_ = name
        member.__dict__.update(vars(row))
        return member

    def __repr__(self) -> str:  # a kind reads as its name, in reprs of tuples and in doctests too
        return repr(self._value_)

    def removes(self, h: int) -> int:
        """Freedoms the pair takes from its two links in motion space ``h``: h − freedom.

        >>> JointKind.REVOLUTE.removes(3), JointKind.REVOLUTE.removes(6), JointKind.PRISMATIC.removes(3)
        (2, 5, 2)
        """
        return h - self.freedom

    @classmethod
    def read(cls, word) -> JointKind | None:
        """The kind a word names — its name, letter, symbol or another word of its row, any case —
        or None.

        >>> JointKind.read("R"), JointKind.read(" Gear "), JointKind.read("="), JointKind.read("crank")
        ('revolute', 'mesh', 'prismatic', None)
        """
        return _WORDS.get(str(word).strip().lower())

    @classmethod
    def by_symbol(cls, symbol: str) -> JointKind:
        """The kind written with ``symbol`` in a joint list (KeyError for another character).

        >>> JointKind.by_symbol("=")
        'prismatic'
        """
        return _BY_SYMBOL[symbol]

    @classmethod
    def symbols(cls) -> str:
        """Every symbol of a joint list, in table order.

        >>> JointKind.symbols()
        '-=~'
        """
        return "".join(kind.symbol for kind in cls)


REVOLUTE, PRISMATIC, MESH = JointKind.REVOLUTE, JointKind.PRISMATIC, JointKind.MESH
for _cell, _kind in enumerate(JointKind):  # its colour cell: the position in the table, the certificate's order
    _kind.cell = _cell
#: the kinds' names in certificate order (the colour cells of a chain's nauty graph)
JOINT_KINDS: tuple[JointKind, ...] = tuple(JointKind)
_BY_SYMBOL = {kind.symbol: kind for kind in JointKind}
_WORDS = {word.lower(): kind for kind in JointKind
          for word in (kind.value, kind.letter, kind.symbol, *kind.words)}
