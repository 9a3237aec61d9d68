"""Issue 27 for ``mechsynth balance``: the resource contract, Ctrl-C, and files refused before use."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import psutil
import pytest

from balance import ArmProblem, TooMuchWork, arm_from_dict
from mechsynth.cli import main
from tests.load import allowed_seconds

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"
SPRING = ["spring", "--kind", "compression", "--moment", "100", "--range", "20..160",
          "--r", "0.01..0.5", "--r0", "0.01..1", "--a", "0..1"]


def balance(capsys, argv):
    code = main(["balance", *argv])
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def write(tmp_path, name, text):
    f = tmp_path / name
    f.write_text(text)
    return str(f)


# ------------------------------------------------------------------ the resource contract
def test_samples_beyond_the_limit_are_refused_with_the_estimate_and_the_override(capsys, tmp_path):
    """Issue 27: ``--samples 100000000`` took 24 GB and was killed; now one sentence, before any work."""
    png = tmp_path / "a.png"
    code, out, err = balance(capsys, ["arm", str(MODELS / "arm_base_drives.toml"), "--samples", "100000000",
                                      "--plot", str(png)])
    assert code == 2 and out == "" and err.count("\n") == 1 and not png.exists()
    assert err.startswith("mechsynth: checking 100000000 configurations would take about ")
    assert "µs each, measured here), more than the 30 s a problem may take" in err
    assert err.endswith("; give --force to run it anyway.\n")


@pytest.mark.parametrize("name, table", [
    ("pantograph.toml", "[pantograph]\nl2 = 0.8\nl3 = 1.0\nratio = 4.0\ncheck = { samples = 1000000000 }\n"),
    ("slider.toml", "[slider]\nmass = 2.0\ninertia = 0.1\ncounter_mass = 2.0\nq_max = 0.5\nsamples = 1000000000\n"),
    ("dynamics.toml", "[slider]\nmass = 2.0\ninertia = 0.1\ncounter_mass = 2.0\nq_max = 0.5\n"
                      "dynamics = { samples = 10000000 }\n"),
    ("arm.toml", "[arm]\n[[arm.links]]\nlength = 1.0\nweight = 10.0\n[arm.check]\nsamples = 1000000000\n"),
])
def test_every_scaling_input_of_a_file_is_priced(capsys, tmp_path, name, table):
    code, out, err = balance(capsys, ["solve", write(tmp_path, name, table)])
    assert code == 2 and out == "" and "would take about" in err and "--force" in err


def test_the_limit_is_the_problems_and_none_lifts_it(model):
    arm = arm_from_dict(model("arm_base_drives"))
    with pytest.raises(TooMuchWork, match="^checking 50 configurations would take about") as ei:
        ArmProblem(arm, samples=50, work_limit=1e-9).solve()
    assert ei.value.seconds > ei.value.limit == 1e-9
    assert ArmProblem(arm, samples=50, work_limit=None).solve().check.max_residual < 1e-12


def test_a_urdf_whose_decomposition_would_fill_memory_is_refused(capsys, tmp_path):
    links = ['<link name="l0"/>'] + [f'<link name="l{i}"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" '
                                     f'ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>' for i in range(1, 18)]
    joints = [f'<joint name="j{i}" type="continuous"><parent link="l{i - 1}"/><child link="l{i}"/>'
              f'<origin xyz="0 0 0.1"/><axis xyz="0 1 0"/></joint>' for i in range(1, 18)]
    f = write(tmp_path, "long.urdf", f'<robot name="r">{"".join(links + joints)}</robot>')
    code, _, err = balance(capsys, ["arm", f, "--force"])
    assert code == 2 and "17 revolute joints" in err and "stops at 16 (its grid would fill memory)" in err


def test_a_urdf_arm_whose_harmonic_terms_cost_too_much_is_refused_before_its_decomposition(capsys, tmp_path):
    """Issue 37: a 12-joint URDF arm (up to 265 721 harmonic terms) ran 68 s and took 1.4 GB past its 30 s
    limit, which priced only the decomposition's grid; the terms' check and report are priced too."""
    import numpy as np

    from tests.balance.test_urdf import random_urdf

    f = write(tmp_path, "arm12.urdf", random_urdf(np.random.default_rng(1), 12))
    start = time.perf_counter()
    code, out, err = balance(capsys, ["arm", f])
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "against up to 265721 harmonic terms would take about" in err and "--force" in err
    code, out, err = balance(capsys, ["compare", f])  # the same arm side by side: priced the same way
    assert code == 2 and out == "" and "against up to 265721 harmonic terms would take about" in err
    assert time.perf_counter() - start < allowed_seconds(30)  # seconds, not the hours of the work


# ------------------------------------------------------------------ files refused before use
@pytest.mark.parametrize("name, text, words", [
    ("bin.toml", b"\x00\x01\xff\xfebinary", "bin.toml: not a text file (byte 2 is not UTF-8)."),
    ("t.toml", "arm = 5\n", "t.toml: [arm] must be a table, not 5."),
    ("t.toml", "[arm]\nlinks = 3\n", "t.toml: [arm] key 'links' must be an array, not 3."),
    ("t.toml", "[arm]\n[[arm.links]]\nlength = 1\nweight = true\n",
     "t.toml: [[arm.links]] #1 key 'weight' must be a number, not true."),
    ("t.toml", "[slider]\nmass = \"2\"\n", "t.toml: [slider] key 'mass' must be a number, not '2'."),
    ("t.toml", "[slider]\nmass = 2\n", "t.toml: [slider] needs the key 'counter_mass'."),
    ("t.toml", "[pantograph]\nl2 = 1\nl3 = 1\nratio = 3\nlenght = 2\n",
     "t.toml: [pantograph] has an unknown key 'lenght' (allowed: bar_eb, bar_fb, check, cylinder, elbow_plate, "
     "forearm, l2, l3, parallelogram_bars, parallelogram_offset, payload, range_forearm_deg, range_upper_deg, "
     "ratio, spring, tool, upper, wrist_plate)."),
    ("t.toml", "[spring]\nkind = \"coil\"\n",
     "t.toml: [spring] key 'kind' must be 'tension', 'compression' or 'compression-lever', not 'coil'."),
    ("t.toml", "[arm]\n[arm.check]\nsamples = 0\n", "t.toml: [arm.check] key 'samples' must be ≥ 1, not 0."),
    ("t.toml", "[robot]\n", "t.toml: a balance problem needs exactly one of the tables [arm], [spring], [slider], "
                            "[pantograph] or [compare], not [robot]."),
    ("nan.urdf", '<robot name="r"><link name="a"/><link name="b"><inertial><mass value="nan"/></inertial></link>'
                 '<joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>',
     "nan.urdf: the mass of link 'b' must be a finite number, not 'nan'."),
    ("self.urdf", '<robot name="r"><link name="a"/><joint name="j" type="continuous"><parent link="a"/>'
                  '<child link="a"/></joint></robot>',
     "self.urdf: joint 'j' has the link 'a' as both its parent and its child."),
])
def test_bad_files_one_sentence_naming_the_value(capsys, tmp_path, name, text, words):
    f = tmp_path / name
    f.write_bytes(text) if isinstance(text, bytes) else f.write_text(text)
    before = f.read_bytes()
    code, out, err = balance(capsys, ["arm" if name.endswith(".urdf") else "solve", str(f)])
    assert (code, out) == (2, "") and err == f"mechsynth: {tmp_path / words}\n"
    assert f.read_bytes() == before and sorted(os.listdir(tmp_path)) == [name]  # nothing written, nothing changed


def test_a_urdf_with_a_slide_is_balanced_through_the_cli(capsys, tmp_path):
    """Issue 27: a URDF with a prismatic joint died with KeyError 'rel_error_bound'."""
    f = write(tmp_path, "slide.urdf",
              '<robot name="r"><link name="base"/>'
              '<link name="l1"><inertial><origin xyz="0 0 0.2"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" '
              'iyy="0.01" iyz="0" izz="0.01"/></inertial></link>'
              '<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 1 0"/>'
              '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
              '<link name="l2"><inertial><origin xyz="0 0 0.1"/><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" '
              'iyy="0.01" iyz="0" izz="0.01"/></inertial></link>'
              '<joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.4"/>'
              '<axis xyz="0 0 1"/><limit lower="-0.1" upper="0.1" effort="1" velocity="1"/></joint></robot>')
    code, out, err = balance(capsys, ["arm", f])
    assert code == 0 and err == "" and "prismatic q2 gear ratio k (m/rad)" in out and "relative error bound" in out


# ------------------------------------------------------------------ Ctrl-C
LONG = {  # each runs for minutes unless interrupted
    "spring --pareto": ["balance", *SPRING, "--max-force", "2000", "--max-free-length", "1.5", "--pareto",
                        "--method", "de", "--grid", "50001"],
    "arm": ["balance", "arm", str(MODELS / "arm_base_drives.urdf"), "--samples", "3000000", "--force"],
    "pantograph": ["balance", "pantograph", "PANTOGRAPH", "--force"],
    "solve": ["balance", "solve", "SLIDER", "--force"],
    "compare": ["balance", "compare", str(MODELS / "arm_ur5e.urdf"), "--samples", "2000000", "--force"],
}


@pytest.mark.parametrize("command", LONG)
def test_ctrl_c_stops_every_balance_command(command, tmp_path):
    """SIGINT to the process group, as a terminal sends it, once the command is at work: exit 130,
    'interrupted', and no process left behind."""
    argv = [str(write(tmp_path, "p.toml", "[pantograph]\nl2 = 0.8\nl3 = 1.0\nratio = 4.0\n"
                                          "check = { samples = 20000000 }\n")) if a == "PANTOGRAPH" else
            str(write(tmp_path, "s.toml", "[slider]\nmass = 2.0\ninertia = 0.1\ncounter_mass = 2.0\nq_max = 0.5\n"
                                          "dynamics = { samples = 200000 }\n")) if a == "SLIDER" else a
            for a in LONG[command]]
    proc = subprocess.Popen([sys.executable, "-m", "mechsynth", *argv], cwd=ROOT, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)
    time.sleep(4.0)  # past the imports and the estimate: at work
    assert proc.poll() is None, proc.communicate()
    os.killpg(proc.pid, signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=10)  # a guard against a hang, not a timing
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 130 and err.endswith("mechsynth: interrupted\n") and "Traceback" not in err
    assert not psutil.pid_exists(proc.pid) or psutil.Process(proc.pid).status() == psutil.STATUS_ZOMBIE
