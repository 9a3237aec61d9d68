"""Installed as users install it: a wheel built from the sources, put into a fresh virtual environment
(not editable), runs a smoke command of every subcommand from outside the source tree.

A hand-kept package list once left ``mechsynth.scene`` out of ``pip install .`` while the editable
install of the test run saw every package; this test sees what a user gets.  The wheel is built
without build isolation and installed without dependencies (they come from the environment the
suite runs in, as plain path entries): the test needs no network.
"""

from __future__ import annotations

import os
import shutil
import site
import subprocess
import sys
import sysconfig
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MODELS = ROOT / "models"
PACKAGES = ("mechbase", "synth", "balance", "mechsynth")  # every package pyproject.toml installs

# every subcommand of `mechsynth --help`, each with a small real job (paths are absolute: cwd is elsewhere)
SMOKE = [
    ["--version"],
    ["codes", "--dof", "1", "--loops", "2", "--format", "csv"],
    ["analyze", "6301/0", "--dof", "1"],
    ["chains", "--dof", "1", "--links", "8", "--count", "--workers", "1"],
    ["mechanisms", "--dof", "1", "--links", "6", "--count", "--workers", "1"],
    ["grid", "{tmp}/grid.toml", "--db", "{tmp}/atlas.sqlite", "--workers", "1"],
    ["atlas", "--db", "{tmp}/atlas.sqlite"],
    ["atlas", "--db", "{tmp}/atlas.sqlite", "--html", "{tmp}/site", "--workers", "1"],
    ["draw", "--chain", "0-1 1-2 2-3 3-0 0-4 4-5 5-1", "--out", "{tmp}/watt.svg"],
    ["identify", "0-1 1-2 2-3 3-0 0-4 4-5 5-1"],
    ["compare", str(MODELS / "atlas_8_links_damaged.txt"), "--dof", "1", "--links", "8", "--workers", "1"],
    ["scene", str(MODELS / "locomotive_drive.toml")],
    ["planetary", "--satellites", "2..3"],
    ["move", str(MODELS / "motion_four_bar.toml"), "--steps", "5", "--format", "csv"],
    ["dimension", str(MODELS / "dimension_function.csv"), "--mechanism", "0-1 1-2 2-3 3-0", "--frame", "0",
     "--budget", "5", "--format", "json"],
    ["gears", "--dof", "1", "--links", "5", "--count"],
    ["balance", "prismatic", "--mass", "2", "--inertia", "0.1", "--counter-mass", "2", "--stroke", "0.5"],
    ["balance", "arm", str(MODELS / "arm_base_drives.toml")],
]


def _copy_sources(dest: Path) -> None:
    """What a clone holds for building (the build writes build/ and *.egg-info next to the sources)."""
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(ROOT / name, dest / name)
    for package in PACKAGES:
        shutil.copytree(ROOT / package, dest / package, ignore=shutil.ignore_patterns("__pycache__"))


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """The ``mechsynth`` script of a fresh virtual environment holding the wheel, and the environment to run it."""
    work = tmp_path_factory.mktemp("install")
    source, wheels, env_dir = work / "source", work / "wheels", work / "venv"
    source.mkdir()
    _copy_sources(source)
    clean = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PIP_REQUIRE_VIRTUALENV")}
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "--quiet",
                    "--wheel-dir", str(wheels), str(source)], check=True, env=clean, cwd=work, timeout=300,
                   capture_output=True)
    (wheel,) = wheels.glob("mechsynth-*.whl")
    venv.create(env_dir, with_pip=True)
    python = env_dir / "bin" / "python"
    # the dependencies: this interpreter's site-packages, as --system-site-packages would give them, less
    # an editable install of this checkout (its import hook would stand in for a package the wheel lacks)
    purelib = Path(subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                                  capture_output=True, text=True, check=True).stdout.strip())
    dirs = [d for d in dict.fromkeys([*site.getsitepackages(), sysconfig.get_paths()["purelib"],
                                      sysconfig.get_paths()["platlib"]]) if os.path.isdir(d)]
    (purelib / "_dependencies.py").write_text(
        "import os, site, sys\n"
        f"for folder in {dirs!r}:\n"
        "    sys.path.append(folder)\n"
        "    for name in sorted(os.listdir(folder)):\n"
        "        if name.endswith('.pth') and not name.startswith('__editable__'):\n"
        "            site.addpackage(folder, name, set(sys.path))\n")
    (purelib / "_dependencies.pth").write_text("import _dependencies\n")
    subprocess.run([str(python), "-m", "pip", "install", "--no-deps", "--no-index", "--quiet", str(wheel)],
                   check=True, env=clean, cwd=work, timeout=300, capture_output=True)
    return env_dir / "bin" / "mechsynth", python, clean, work


def test_the_wheel_holds_every_package_of_the_sources(installed):
    _, python, env, work = installed
    found = subprocess.run([str(python), "-c", "import mechsynth, synth, balance; "
                            "print(mechsynth.__file__); print(synth.__file__); print(balance.__file__)"],
                           capture_output=True, text=True, env=env, cwd=work, check=True).stdout.split()
    assert all(str(work / "venv") in path for path in found), found  # the wheel's copy, not the checkout
    packages = sorted(str(p.parent.relative_to(ROOT)).replace(os.sep, ".")
                      for top in PACKAGES for p in (ROOT / top).rglob("__init__.py"))
    missing = subprocess.run([str(python), "-c", "import importlib, sys\n"
                              "for name in sys.argv[1:]:\n"
                              "    try: importlib.import_module(name)\n"
                              "    except ModuleNotFoundError: print(name)", *packages],
                             capture_output=True, text=True, env=env, cwd=work, check=True).stdout.split()
    assert len(packages) > 10 and missing == []


@pytest.mark.parametrize("argv", SMOKE, ids=lambda argv: " ".join(argv[:2]))
def test_every_subcommand_runs_from_the_wheel(installed, argv):
    script, _, env, work = installed
    (work / "grid.toml").write_text('dof = 1\nlinks = "4..8"\n')
    args = [a.replace("{tmp}", str(work)) for a in argv]
    done = subprocess.run([str(script), *args], capture_output=True, text=True, env=env, cwd=work, timeout=300)
    assert done.returncode == 0, (args, done.stderr[-2000:])
    assert "Traceback" not in done.stderr
    assert done.stdout.strip() or args[0] in ("draw", "grid") or "--html" in args


def test_the_smoke_list_names_every_subcommand():
    from mechsynth._parser import build_parser

    parser = build_parser()
    commands = set(next(a for a in parser._actions if a.dest == "command").choices)
    assert commands == {argv[0] for argv in SMOKE if not argv[0].startswith("-")}
