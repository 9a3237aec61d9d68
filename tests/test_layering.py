"""The layers of the house: the engines (synth, balance) never import each other nor the
application (mechsynth); the application imports only names its engines' facades list in
``__all__``, and the benchmarks no module or name that starts with an underscore (the stage
profiler excepted); inside synth no two modules import each other at load time
(a cycle would make the order of imports matter); and ``import synth`` loads nothing but its errors
(and the lazy loader).

(tests/balance/test_bench_and_layout.py holds the same rules for balance.)"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _imports(path: Path, *, top_level_only: bool = False):
    """(module, name) of every import of a file (relative imports resolved), every one or only
    those made when the module loads (not inside a function)."""
    tree = ast.parse(path.read_text())
    package = ".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")
    if path.name != "__init__.py":
        package = package.rsplit(".", 1)[0]
    for node in ast.walk(tree):  # names imported for type checkers only are no dependency at run time
        if isinstance(node, ast.If) and ast.unparse(node.test) in ("TYPE_CHECKING", "typing.TYPE_CHECKING"):
            node.body = []
    nodes = tree.body if top_level_only else ast.walk(tree)
    out = []
    for node in nodes:
        if isinstance(node, ast.Import):
            out += [(a.name, "") for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                module = ".".join(base + ([module] if module else []))
            out += [(module, a.name) for a in node.names]
    return out


def _files(*folders):
    return [f for folder in folders for f in (ROOT / folder).rglob("*.py")]


def test_the_base_imports_neither_engine_nor_the_application():
    """mechbase is what both engines stand on: the error base, TOML reading, ranges, quoting a value."""
    for f in _files("mechbase"):
        for module, _ in _imports(f):
            assert module.split(".")[0] not in ("synth", "balance", "mechsynth"), (f, module)


def test_engines_never_import_each_other_nor_the_application():
    for f in _files("synth"):
        for module, _ in _imports(f):
            assert module.split(".")[0] not in ("balance", "mechsynth"), (f, module)
    for f in _files("balance"):
        for module, _ in _imports(f):
            assert module.split(".")[0] not in ("synth", "mechsynth"), (f, module)


#: the stage profiler wraps the engine's internal stages with timers: reaching inside is its job
_PROFILERS = {"profile_stages.py", "multiple_joint_prune.py",  # they time stage B's own parts
              "memory_by_unit.py",  # it reads the memory of stage A and of each stage-B unit, and sets B's budget
              "stage_a_multiple_joints.py"}  # it runs stage A's kernel against the model and the plain search


def test_the_application_and_the_benchmarks_use_public_names_only():
    """A benchmark measures what a user can call; only the stage profiler reaches inside."""
    files = _files("mechsynth") + [f for f in _files("benchmarks") if f.name not in _PROFILERS]
    for f in files:
        for module, name in _imports(f):
            if module.split(".")[0] in ("synth", "balance"):
                private = [p for p in module.split(".") + [name] if p.startswith("_")]
                assert not private, f"{f.relative_to(ROOT)} imports {module}:{name}"


def _owner_of_private(module: str, name: str) -> str | None:
    """The package a private part of an import belongs to: for ``a.b._c`` (a module) or ``a.b.m:_f``
    (a name of module ``a.b.m``) the package ``a.b``; None when no part is private (dunders such as
    ``__version__`` are public)."""
    parts = module.split(".") + ([name] if name else [])
    for i, part in enumerate(parts[1:], 1):
        if part.startswith("_") and not (part.startswith("__") and part.endswith("__")):
            owner = parts[:i]
            if not (ROOT.joinpath(*owner) / "__init__.py").is_file():
                owner = owner[:-1]  # a name of a module: private to that module's package
            return ".".join(owner)
    return None


def _module_name(path: Path) -> str:
    return ".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")


def test_no_import_of_a_private_name_from_another_package():
    """A name with a leading underscore (a module or an attribute) is private to the package that holds
    it and its sub-packages: ``synth.draw._layout`` may be imported inside ``synth.draw`` only,
    ``synth.structure.chain._helper`` inside ``synth.structure`` only, ``mechsynth._output`` anywhere in
    ``mechsynth``.  Every import counts, at load time or inside a function."""
    wrong = []
    for f in _files("synth", "balance", "mechsynth", "mechbase"):
        me = _module_name(f)
        for module, name in _imports(f):
            if module.split(".")[0] not in ("synth", "balance", "mechsynth", "mechbase"):
                continue
            owner = _owner_of_private(module, name)
            if owner is not None and not (me == owner or me.startswith(owner + ".")):
                wrong.append(f"{f.relative_to(ROOT)} imports {module}:{name}, private to {owner}")
    assert not wrong, "\n".join(wrong)


def test_a_private_import_across_packages_is_seen():
    """The rule above reads modules, names and their packages as intended."""
    assert _owner_of_private("synth.draw._layout", "layout") == "synth.draw"
    assert _owner_of_private("synth.motion._sweep", "_solver") == "synth.motion"
    assert _owner_of_private("synth.structure.chain", "_check") == "synth.structure"
    assert _owner_of_private("synth.structure", "_params") == "synth.structure"
    assert _owner_of_private("mechsynth._output", "emit") == "mechsynth"
    assert _owner_of_private("mechsynth", "__version__") is None
    assert _owner_of_private("synth.draw", "layout") is None


def _facade_names(module: str) -> set[str]:
    """The names an import from ``module`` may take: the ``__all__`` of its engine's facade and,
    for a module of a sub-package of synth with its own facade (``synth.atlas``, ``synth.draw`` …),
    of that facade; balance has one facade."""
    import importlib

    parts = module.split(".")
    names = set(importlib.import_module(parts[0]).__all__)
    if parts[0] == "synth" and len(parts) > 1:
        package = importlib.import_module(".".join(parts[:2]))
        if hasattr(package, "__path__"):
            names |= set(package.__all__)
    return names


def test_the_application_imports_only_names_of_the_engines_facades():
    """mechsynth names what it takes from an engine through the engine's facade (``synth``,
    ``balance``, or a sub-package facade of synth such as ``synth.atlas``): a name missing from the
    facade's ``__all__`` is an engine's inside, whatever module the import reaches it through."""
    wrong = [f"{f.relative_to(ROOT)} imports {module}:{name}"
             for f in _files("mechsynth") for module, name in _imports(f)
             if module.split(".")[0] in ("synth", "balance") and name and name not in _facade_names(module)]
    assert not wrong, "\n".join(wrong)


#: the floors of each engine, lowest first: a module may import its own package, the floors below
#: and (for execution) nothing above the chain types; the package facades stand above everything
FLOORS = {
    "synth": [
        {"synth.errors", "synth._lazy", "synth.schema", "synth.display", "synth.structure"},  # the chain types
        {"synth.execution"},  # running work: a service that imports no floor above the chain types
        {"synth.synthesis"},  # number and type synthesis, and sizing them (planning)
        {"synth.analysis", "synth.gears", "synth.motion", "synth.dimension"},
        {"synth.atlas", "synth.exchange", "synth.draw", "synth.motion_draw"},  # drawings on the top floor
    ],
    "balance": [
        {"balance.errors", "balance.schema", "balance.budget", "balance.extremes"},
        {"balance.model"},
        {"balance.devices"},
        {"balance.problems", "balance.plots"},
    ],
}


def _floor(engine: str, module: str) -> tuple[int, str] | None:
    """(floor, package) of a module of an engine; None for the engine's facade itself."""
    for level, packages in enumerate(FLOORS[engine]):
        for package in packages:
            if module == package or module.startswith(package + "."):
                return level, package
    return None


def _module_graph(engine: str) -> dict[str, set[str]]:
    """Every import between an engine's modules, at load time or inside a function."""
    modules = {".".join(f.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__"): f for f in _files(engine)}
    graph: dict[str, set[str]] = {}
    for name, f in modules.items():
        graph[name] = set()
        for module, imported in _imports(f):
            for target in (f"{module}.{imported}", module):
                if target in modules and target != name:
                    graph[name].add(target)
                    break
    return graph


def test_every_import_of_an_engine_names_one_of_its_modules():
    """An import of an engine's module that names no module of it (a relative import left one dot
    short when a module moved into a package) fails only when the function holding it runs."""
    modules = {".".join(f.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")
               for f in _files("synth", "balance", "mechbase")}
    wrong = [f"{f.relative_to(ROOT)} imports {module}"
             for f in _files("synth", "balance", "mechbase", "mechsynth", "benchmarks")
             for module, _ in _imports(f) if module.split(".")[0] in ("synth", "balance", "mechbase")
             and module not in modules]
    assert not wrong, "\n".join(wrong)


@pytest.mark.parametrize("engine", sorted(FLOORS))
def test_every_module_stands_on_a_floor_and_imports_none_above_it(engine):
    """No import — at load time or inside a function — runs up a floor; the execution service imports
    only the chain types; packages on one floor may use each other (without a cycle, below)."""
    graph = _module_graph(engine)
    unplaced = [m for m in graph if m != engine and _floor(engine, m) is None]
    assert not unplaced, f"modules on no floor (add them to FLOORS): {unplaced}"
    wrong = []
    for module, targets in graph.items():
        if module == engine:
            continue
        level, package = _floor(engine, module)
        for target in targets:
            if target == engine:
                wrong.append(f"{module} imports the facade {engine}")
                continue
            to_level, to_package = _floor(engine, target)
            if to_level > level or (package == "synth.execution" and to_level >= 1 and to_package != package):
                wrong.append(f"{module} (floor {level}) imports {target} (floor {to_level})")
    assert not wrong, "\n".join(wrong)


@pytest.mark.parametrize("engine", sorted(FLOORS))
def test_no_import_cycle_between_modules(engine):
    """No two modules of an engine import each other, directly or round a circle, at load time or
    inside a function (a circle makes the order of imports matter and ties the modules into one)."""
    graph = _module_graph(engine)
    state: dict[str, int] = {}

    def visit(node, path):
        state[node] = 1
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                raise AssertionError("import cycle: " + " -> ".join(path + [node, nxt]))
            if nxt not in state:
                visit(nxt, path + [node])
        state[node] = 2

    for node in sorted(graph):
        if node not in state:
            visit(node, [])


def test_import_synth_loads_only_its_errors_and_the_drawing_names():
    code = ("import sys, synth; print(sorted(m for m in sys.modules if m.startswith('synth.')))")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and out.stdout.strip() == (
        "['synth._lazy', 'synth.display', 'synth.errors']"), out


def test_every_public_name_of_synth_resolves():
    import synth

    for name in synth.__all__:
        assert getattr(synth, name) is not None, name


def test_no_public_name_is_also_a_module_of_its_package():
    """A lazily exported function named like a submodule of its package is replaced by that
    module once anything imports it (``synth.gears.mechanisms`` was both): every public name of
    the engines' packages differs from their modules' names."""
    import importlib
    import pkgutil

    for name in ("synth", "synth.atlas", "synth.gears", "balance"):
        package = importlib.import_module(name)
        modules = {m.name for m in pkgutil.iter_modules(package.__path__)}
        assert not modules & set(package.__all__), (name, modules & set(package.__all__))


def test_the_motion_floor_stands_on_the_chain_types_only():
    """synth.motion imports the chain types, the errors, numpy and scipy (and the standard
    library): never synthesis, execution, atlas, exchange, draw, gears or analysis."""
    allowed_synth = ("synth.structure", "synth.errors", "synth._lazy", "synth.display", "synth.motion")
    for f in _files("synth/motion"):
        for module, _ in _imports(f):
            top = module.split(".")[0]
            if top == "synth":
                assert module.startswith(allowed_synth), f"{f.relative_to(ROOT)} imports {module}"
            else:
                assert top in ("numpy", "scipy", "numba", "mechbase") or top in sys.stdlib_module_names, (f, module)


def test_synthesis_over_dimensions_moves_linkages_through_the_motion_layers_public_names():
    """The dimensional synthesis and the atlas (its curve index and search) move candidates through
    ``synth.motion``'s ``__all__`` (``link_poses``, ``sweep``, ``assemble`` …), never its private modules."""
    import synth.motion

    wrong = [f"{f.relative_to(ROOT)} imports {module}:{name}"
             for f in _files("synth/dimension", "synth/atlas") for module, name in _imports(f)
             if module.split(".")[:2] == ["synth", "motion"]
             and (module != "synth.motion" or name not in synth.motion.__all__)]
    assert not wrong, "\n".join(wrong)
