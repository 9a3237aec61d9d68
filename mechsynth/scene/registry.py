"""What a scene can compute: one :class:`ComputeKind` per word of ``[scene] compute``.

The runner (:mod:`mechsynth.scene.runner`) knows no computation by name.  Each kind says
which table of the scene holds its problem, how to run it, which ``[expect]`` keys its
result provides and how it is summarised; each table says how it is validated.  To add
a computation, write its function in the module of its family and register it there:

>>> from mechsynth.scene.registry import ComputeKind, Expectation, KINDS
>>> from dataclasses import dataclass
>>> from mechbase import Row
>>> @dataclass(frozen=True)
... class Links(Row):
...     links: int
>>> def _count_links(run):
...     return Links(run.scene.tables["structure"].dof + 1)
>>> kind = ComputeKind("links demo", "W + 1, as an example", table="structure", run=_count_links,
...                    expect={"demo_links": Expectation(int, path=("links",))})
>>> kind.provides("demo_links"), "links demo" in KINDS
(True, False)

(Listed in its module's :class:`Family` and registered by ``mechsynth.scene`` it becomes a word of
``compute``; ``docs/scenes.md`` lists them.)
"""

from __future__ import annotations

import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .compare import equal
from .results import Scene, SceneError

__all__ = ["Expectation", "ComputeKind", "SceneTable", "Run", "KINDS", "TABLES", "Family", "register"]


@dataclass(frozen=True)
class Expectation:
    """One ``[expect]`` key a computation provides.

    Attributes
    ----------
    type : type
        The expected value's type, with the words of its error (``synth.schema`` types or others that say their words with ``mechbase.schema.expect``).
    path : tuple
        Where the actual value sits in the computation's result (default: the key itself).
    compare : callable
        ``compare(expected, actual, rel_tol) -> (met, what differs)``; default
        :func:`~mechsynth.scene.compare.equal`.
    below : bool
        A ``KEY_below = x`` form is allowed: met when the actual value is below x.
    best_of : int
        Rerun the computation up to this many times before calling the key failed (timings).
    """

    type: Any
    path: tuple = ()
    compare: Callable[[Any, Any, float], tuple[bool, str]] = equal
    below: bool = False
    best_of: int = 1


@dataclass(frozen=True)
class ComputeKind:
    """A word of ``[scene] compute``.

    Attributes
    ----------
    name : str
        The word (``"codes"``, ``"balance arm"``).
    summary : str
        One line: what it computes (listed in errors and docs).
    table : str or None
        The scene table that states its problem (``"structure"``, ``"arm"``); required when given.
    run : callable
        ``run(Run) -> result``: the typed result, a frozen dataclass inheriting ``mechbase.Row``,
        printed and checked as its row (``mechbase.as_row``).  It may read the results of kinds registered before it
        (``Run.results``) and share work through ``Run.shared``.
    expect : mapping
        The ``[expect]`` keys its result provides.
    check : callable, optional
        ``check(scene)`` raises ``scene.error(...)`` for a rule across keys or tables.
    report : callable, optional
        ``report(row) -> lines`` of the readable summary, from the result's row (default: the start of its JSON).
    reads : tuple of str
        Optional tables it also reads (``"drawing"``, ``"plot"``).
    """

    name: str
    summary: str
    table: str | None
    run: Callable[[Run], Any]
    expect: Mapping[str, Expectation] = field(default_factory=dict)
    check: Callable[[Scene], None] | None = None
    report: Callable[[dict], list[str]] = lambda result: [json.dumps(result)[:200]]
    reads: tuple[str, ...] = ()

    def provides(self, key: str) -> bool:
        """True when ``key`` (or its ``_below`` form) is one of this kind's expectations."""
        base = key.removesuffix("_below")
        return key in self.expect or (base != key and base in self.expect and self.expect[base].below)


@dataclass(frozen=True)
class SceneTable:
    """A table of a scene file: how it is validated, and what it holds (for the "missing" sentence).

    ``read(raw, path, compute)`` returns the validated table or raises
    :class:`~mechsynth.scene.SceneError`;
    ``compute`` is the set of the scene's computations.
    """

    name: str
    read: Callable[[Any, str, frozenset], Any]
    hint: str

    @classmethod
    def typed(cls, name: str, schema, hint: str) -> "SceneTable":
        """The table ``[name]`` read as ``schema`` (a :class:`mechbase.schema.Table`, its validators given
        the scene's computations as ``compute``), its errors as :class:`~mechsynth.scene.SceneError`.

        >>> from mechbase.schema import Table
        >>> class Steps(Table):
        ...     steps: int = 10
        >>> SceneTable.typed("sweep", Steps, "the number of steps").read({"steps": 5}, "a.toml", frozenset()).steps
        5
        """
        return cls(name, lambda raw, path, compute: schema.read(raw, source=path, where=f"[{name}]", error=SceneError,
                                                                context={"compute": compute}), hint)


@dataclass
class Run:
    """The state of one scene run, passed to every :attr:`ComputeKind.run`."""

    scene: Scene
    out_dir: Path | None = None
    workers: int = 1
    results: dict = field(default_factory=dict)
    _shared: dict = field(default_factory=dict)

    def shared(self, name: str, make: Callable[[], Any]) -> Any:
        """``make()`` once per run: work several kinds use (the chains of count, mechanisms, drawing)."""
        if name not in self._shared:
            self._shared[name] = make()
        return self._shared[name]

    def picture(self, file_name: str) -> Path | None:
        """Where a picture is written: ``out_dir / file_name``, or None when no ``--out`` was given."""
        if self.out_dir is None:
            return None
        self.out_dir.mkdir(parents=True, exist_ok=True)
        return self.out_dir / file_name


#: Every computation, in the order a scene runs them (a kind may use the results of earlier ones).
KINDS: dict[str, ComputeKind] = {}
#: Every table a scene may hold besides ``[scene]`` and ``[expect]``.
TABLES: dict[str, SceneTable] = {}


class Family:
    """The tables and computations of one family of problems (structure, balancing, …), in the
    order its module lists them; :func:`register` makes them words of ``compute``.

    >>> demo = Family("demo"); t = demo.table(SceneTable("demo", lambda raw, path, compute: raw, "a demo"))
    >>> [x.name for x in demo.tables]
    ['demo']
    """

    def __init__(self, name: str):
        self.name = name
        self.tables: list[SceneTable] = []
        self.kinds: list[ComputeKind] = []

    def table(self, table: SceneTable) -> SceneTable:
        self.tables.append(table)
        return table

    def kind(self, kind: ComputeKind) -> ComputeKind:
        self.kinds.append(kind)
        return kind


def register(*families: Family) -> None:
    """Make the families' tables and computations known, in the order given: that is the order a
    scene runs its computations in (``mechsynth.scene`` states it once, whatever order its modules
    were imported in).  A computation's tables must be registered with it or before."""
    for family in families:
        for table in family.tables:
            TABLES[table.name] = table
        for kind in family.kinds:
            for name in (kind.table, *kind.reads):
                if name is not None and name not in TABLES:
                    raise KeyError(f"compute {kind.name!r} reads the unregistered table [{name}]")
            KINDS[kind.name] = kind
