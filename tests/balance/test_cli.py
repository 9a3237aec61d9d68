"""``mechsynth balance …`` through ``mechsynth.cli.main`` and ``python -m mechsynth balance``."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from mechsynth.cli import main

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"

SPRING = ["spring", "--kind", "compression", "--moment", "100", "--range", "20..160",
          "--r", "0.01..0.5", "--r0", "0.01..1", "--a", "0..1"]


def run(capsys, argv):
    code = main(["balance", *argv])
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def test_arm_json_has_terms_devices_residual(capsys):
    code, out, err = run(capsys, ["arm", str(MODELS / "arm_base_drives.toml"), "--format", "json"])
    assert code == 0 and err == ""
    d = json.loads(out)
    assert {"terms", "devices", "max_residual"} <= d.keys()
    assert sorted(t["amplitude"] for t in d["terms"]) == pytest.approx([15.0, 55.0, 126.0])
    for t in d["terms"]:
        assert {"amplitude", "phase", "form"} <= t.keys()
    assert d["relative_residual"] < 1e-9


def test_arm_table_and_plot(capsys, tmp_path):
    png = tmp_path / "arm.png"
    code, out, err = run(capsys, ["arm", str(MODELS / "arm_prismatic.toml"), "--plot", str(png)])
    assert code == 0 and "gear ratio" in out and png.stat().st_size > 10_000
    assert err == f"plot -> {png}\n"  # where the figure went, as every command that draws says


@pytest.mark.parametrize("extra", [[], ["--norm", "rms"], ["--method", "trf"], ["--method", "nelder-mead"]])
def test_spring_json_fields(capsys, extra):
    code, out, _ = run(capsys, SPRING + extra + ["--format", "json"])
    assert code == 0
    d = json.loads(out)
    for k in ("c", "r", "r0", "a", "max_rel_error", "rms_rel_error", "seconds", "nfev", "active_bounds", "sense"):
        assert k in d
    assert d["max_rel_error"] < 0.0105


def test_spring_negative_range_and_plot(capsys, tmp_path):
    png = tmp_path / "s.png"
    argv = SPRING.copy()
    argv[argv.index("20..160")] = "-90..90"
    code, out, _ = run(capsys, argv + ["--plot", str(png)])
    assert code == 0 and "max relative error" in out and png.exists()


def test_tension_spring_exact(capsys):
    code, out, _ = run(capsys, ["spring", "--kind", "tension", "--moment", "-100", "--range", "0..180",
                                "--r", "0.01..0.5", "--r0", "0.01..1", "--a", "0..1", "--format", "json"])
    d = json.loads(out)
    assert code == 0 and d["method"] == "exact" and d["max_rel_error"] < 1e-13 and d["sense"] == -1


def test_prismatic_json(capsys, tmp_path):
    code, out, _ = run(capsys, ["prismatic", "--mass", "2", "--inertia", "0.1", "--counter-mass", "2",
                                "--stroke", "0.5", "--format", "json", "--plot", str(tmp_path / "p.png")])
    d = json.loads(out)
    assert code == 0 and d["C_min"] == pytest.approx(0.85)
    assert d["max_com_error"] < 1e-12 and d["max_inertia_error"] < 1e-12


def test_pantograph_and_solve(capsys, tmp_path):
    code, out, _ = run(capsys, ["pantograph", str(MODELS / "pantograph.toml"), "--plot", str(tmp_path / "p.png")])
    assert code == 0 and "cylinder force" in out
    for name in ("arm_base_drives", "arm_prismatic", "spring_compression", "pantograph", "slider_countermass"):
        code, out, _ = run(capsys, ["solve", str(MODELS / f"{name}.toml"), "--format", "json"])
        assert code == 0 and json.loads(out)


@pytest.mark.parametrize("argv, words", [
    (["spring", "--kind", "tension", "--moment", "100", "--range", "0..180", "--r", "0.01..0.5",
      "--r0", "0.01..1", "--a", "0..1"], "compression device"),
    (SPRING[:6] + ["160..20"] + SPRING[7:], "inverted"),
    (SPRING[:6] + ["20..20"] + SPRING[7:], "empty"),
    (SPRING[:6] + ["20-160"] + SPRING[7:], "low..high"),
    (SPRING[:-1] + ["0..inf"], "without limit"),
    (SPRING + ["--max-free-length", "0.001"], "free length"),
    (SPRING[:8] + ["-0.1..0.5"] + SPRING[9:], "positive"),
    (["prismatic", "--mass", "-2", "--inertia", "0.1", "--counter-mass", "2", "--stroke", "0.5"], "mass"),
    (["prismatic", "--mass", "2", "--inertia", "0.1", "--counter-mass", "2", "--stroke", "0"], "stroke"),
    (["arm", "/no/such/file.toml"], "no such TOML file"),
    (["spring", "--kind", "coil"], "invalid choice"),
    (["spring", "--kind", "compression"], "required"),
    (["frobnicate"], "invalid choice"),
    (SPRING + ["--grid", "1000000000"], "the fit grid takes 5 to 100001 points"),
    # issue 14: each of these printed a traceback
    (["arm", str(MODELS / "arm_base_drives.toml"), "--samples", "0"], "≥ 1"),
    (["arm", str(MODELS / "arm_base_drives.toml"), "--samples", "-5"], "≥ 1"),
    (["arm", str(MODELS / "arm_base_drives.toml"), "--plot", "x.txt"], "PNG, PDF or SVG"),
    (["prismatic", "--mass", "2", "--inertia", "0.1", "--counter-mass", "2", "--stroke", "0.5",
      "--plot", "p.xyz"], "PNG, PDF or SVG"),
    ([], "required"),
    (SPRING + ["--material", "steel", "--design-spring"], "unknown spring material 'steel'; choose one of music-wire"),
    (SPRING + ["--material", "stainless"], "--material applies only with --design-spring"),
    (SPRING + ["--guided"], "--guided applies only with --design-spring"),
    (SPRING + ["--material", "stainless", "--guided"], "--material and --guided apply only with --design-spring"),
    (SPRING + ["--design-spring", "--max-outer-diameter", "-1"], "outer diameter"),
    (SPRING + ["--design-spring", "--max-outer-diameter", "0.001"], "fits"),
    (SPRING + ["--target-error", "2"], "requested error"),
    (SPRING + ["--target-error", "nan"], "requested error"),
    (["spring", "--kind", "tension", "--moment", "-1", "--range", "0..90", "--r", "0.1..0.2", "--r0", "0.1..0.2",
      "--a", "0..1", "--pareto"], "Pareto front"),
    (["spring", "--kind", "compression-lever", "--moment", "-1", "--range", "0..90", "--r", "0.1..0.2",
      "--r0", "0.1..0.2", "--a", "0.5..1"], "a = r0"),
    (SPRING + ["--spring-ends", "glued", "--design-spring"], "invalid choice"),
    (["spring", "--kind", "tension", "--moment", "-1", "--range", "0..90", "--r", "0.1..0.2", "--r0", "0.1..0.2",
      "--a", "0..1", "--design-spring", "--guided"], "extension spring"),
    (["prismatic", "--mass", "2", "--inertia", "0.1", "--counter-mass", "2", "--stroke", "0.5", "--dynamics",
      "curved"], "invalid choice"),
    (["arm", "/no/such/arm.urdf"], "no such URDF file"),
    (["arm", str(MODELS / "pantograph.toml")], "the file has an unknown table [pantograph]"),
])
def test_bad_input_one_line_exit_2(capsys, argv, words):
    code, out, err = run(capsys, argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and words in err and "Traceback" not in err


def test_range_across_0_and_pi_says_what_the_device_does(capsys):
    argv = SPRING.copy()
    argv[argv.index("20..160")] = "-30..200"
    code, out, err = run(capsys, argv)
    assert code == 0 and err == ""
    assert "dead centres φ = 0° and 180°" in out and "change sign" in out


def test_spring_design_lever_pareto_and_target(capsys, tmp_path):
    png = tmp_path / "s.png"
    code, out, err = run(capsys, SPRING + ["--max-force", "2000", "--max-free-length", "1.5", "--pareto",
                                           "--target-error", "0.03", "--design-spring", "--material", "oil-tempered",
                                           "--format", "json", "--plot", str(png)])
    d = json.loads(out)
    assert code == 1 and err == f"plot -> {png}\n"  # the requested error is missed: a result, a warning, exit 1
    assert d["target_met"] is False and d["pareto"] and png.stat().st_size > 20_000
    for k in ("wire_diameter_m", "mean_diameter_m", "active_coils", "shear_modulus_Pa", "stiffness_N_per_m",
              "max_shear_stress_Pa", "allowed_shear_stress_Pa", "solid_length_m"):
        assert k in d["spring"]
    code, out, _ = run(capsys, ["spring", "--kind", "compression-lever", "--moment", "-100", "--range", "0..180",
                                "--r", "0.05..0.2", "--r0", "0.1..0.4", "--a", "0..1", "--design-spring"])
    assert code == 0 and "lever reach from C" in out and "beyond the farthest pin" in out


def test_bad_arm_file_names_file_and_key(capsys, tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text('[arm]\n[[arm.links]]\njoint = "revolute"\nlength = 1\nweight = 2\nwieght = 3\n')
    code, _, err = run(capsys, ["arm", str(f)])
    assert code == 2 and "bad.toml" in err and "'wieght'" in err
    f.write_text("[arm\n")
    code, _, err = run(capsys, ["arm", str(f)])
    assert code == 2 and "not valid TOML" in err and err.count("\n") == 1


def test_python_m_entry_point():
    p = subprocess.run([sys.executable, "-m", "mechsynth", "balance", "prismatic", "--mass", "1", "--inertia", "0",
                        "--counter-mass", "1", "--stroke", "0.1", "--format", "json"],
                       capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert p.returncode == 0 and json.loads(p.stdout)["C_min"] == pytest.approx(0.015)
    p = subprocess.run([sys.executable, "-m", "mechsynth", "balance", "prismatic", "--mass", "x"],
                       capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert p.returncode == 2 and p.stderr.count("\n") == 1
