"""``gearloss gear geometry`` and ``gearloss gear feasibility`` called in process (plus one real subprocess)."""

import json
import subprocess
import sys

import pytest

from efficiency.design_io import load_study
from workflows.cli import main

PAPER_D = ["gear", "geometry", "--teeth", "32", "--pressure-angle-deg", "30", "--helix-angle-deg", "19",
           "--working-depth", "2.068"]


def run_json(capsys, argv):
    code = main(argv + ["--json"])
    out = capsys.readouterr().out
    return code, json.loads(out)


def test_paper_design_d_json(capsys):
    """Design D of Table 1 (Li & Kahraman 2009): d_o = 96.42 mm, root diameter 85.23 mm, m = 2.7036 mm, feasible;
    the JSON keys are SI with unit suffixes."""
    code, p = run_json(capsys, PAPER_D)
    assert code == 0
    assert p["tip_diameter_m"][0] * 1e3 == pytest.approx(96.42, abs=0.005)
    assert p["root_diameter_m"][0] * 1e3 == pytest.approx(85.23, abs=0.005)
    assert p["normal_module_m"] * 1e3 == pytest.approx(2.7036, abs=5e-5)
    assert p["feasible"] is True and p["violations"] == []
    assert p["center_distance_m"] == pytest.approx(0.0915)
    assert p["normal_backlash_m"] >= 0.04e-3
    assert "wall_time_s" in p


def test_general_pair_fzg_c_human_output(capsys):
    """FZG C by options: the printed tip diameters are those of gear_cases.md (82.4567 / 118.3649 mm)."""
    code = main(["gear", "geometry", "--teeth1", "16", "--teeth2", "24", "--module-mm", "4.5",
                 "--pressure-angle-deg", "20", "--face-width-mm", "14", "--shift1", "0.1817", "--shift2", "0.1715",
                 "--thickness-allowance-mm", "0.05"])
    out = capsys.readouterr().out
    assert code == 0
    assert "82.4567 / 118.3649" in out
    assert "ε_α = 1.43766" in out
    assert "verdict: feasible" in out


def test_iso_values_by_torque(capsys):
    """--torque-nm adds the ISO 6336 reference values; σ_H0 and σ_F0 scale with √T and T (ISO 6336-2/-3)."""
    _, low = run_json(capsys, PAPER_D + ["--torque-nm", "100"])
    _, high = run_json(capsys, PAPER_D + ["--torque-nm", "400"])
    assert high["iso6336"]["sigma_h0_pa"] == pytest.approx(2 * low["iso6336"]["sigma_h0_pa"], rel=1e-12)
    assert high["iso6336"]["sigma_f0_1_pa"] == pytest.approx(4 * low["iso6336"]["sigma_f0_1_pa"], rel=1e-12)


def test_design_file(tmp_path, capsys):
    """A design TOML file gives the same geometry as the options."""
    path = tmp_path / "d.toml"
    path.write_text('[design]\nkind = "paper"\nteeth = 32\nnormal_pressure_angle_deg = 30.0\n'
                    'helix_angle_deg = 19.0\nworking_depth = 2.068\n\n[modifications]\nprofile_crown_um = 15\n')
    _, from_file = run_json(capsys, ["gear", "geometry", "--design", str(path)])
    _, from_options = run_json(capsys, PAPER_D)
    for key in ("tip_diameter_m", "root_diameter_m", "contact_ratio", "normal_backlash_m"):
        assert from_file[key] == from_options[key]


def test_bad_designs_reported_by_name(capsys):
    """Pointed teeth: reported by name, value and limit; --strict turns the verdict into exit status 1."""
    argv = ["gear", "geometry", "--teeth", "20", "--pressure-angle-deg", "30", "--helix-angle-deg", "15",
            "--working-depth", "3.376"]
    code, p = run_json(capsys, argv)
    assert code == 0 and p["feasible"] is False
    assert {v["name"] for v in p["violations"]} == {"pointed_tooth"}
    assert all(v["value_m"] < 0 and v["limit_m"] == 0 for v in p["violations"])
    assert main(argv + ["--strict"]) == 1
    assert "pointed_tooth (gear 1)" in capsys.readouterr().out


@pytest.mark.parametrize("argv, parameter", [
    (["--teeth", "32", "--pressure-angle-deg", "30", "--helix-angle-deg", "19"], "working-depth"),
    (["--teeth", "32", "--pressure-angle-deg", "30", "--helix-angle-deg", "50", "--working-depth", "2"],
     "invalid --helix-angle-deg=50: accepted [0, 45) °"),
    (["--teeth", "32", "--teeth1", "20", "--pressure-angle-deg", "30"], "design"),
    (["--teeth1", "20", "--teeth2", "30", "--module-mm", "-2", "--pressure-angle-deg", "20", "--face-width-mm", "10"],
     "invalid --module-mm=-2: accepted (0, 1000] mm"),
    (["--teeth1", "20", "--teeth2", "30", "--module-mm", "2", "--pressure-angle-deg", "20", "--face-width-mm", "10",
      "--center-distance-mm", "40"], "--center-distance-mm"),
])
def test_bad_input_is_one_line_exit_2(capsys, argv, parameter):
    assert main(["gear", "geometry", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and parameter in err


def test_bad_design_file(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text('[design]\nkind = "paper"\nteeth = 32\nnormal_pressure_angle_deg = 30.0\n'
                    'helix_angle_deg = 19.0\nworking_depth = 2.068\ncolour = "red"\n')
    assert main(["gear", "geometry", "--design", str(path)]) == 2
    assert "design.colour" in capsys.readouterr().err
    path.write_text("[design\n")
    assert main(["gear", "geometry", "--design", str(path)]) == 2
    assert main(["gear", "geometry", "--design", str(tmp_path / "missing.toml")]) == 2


def test_feasibility_count_json(capsys):
    """The whole paper space (30,464 designs) is screened; the study's published designs are feasible, so the count
    lies between 4 and 30,464; zero thinning leaves no design with 0.04 mm backlash."""
    code, p = run_json(capsys, ["gear", "feasibility"])
    assert code == 0 and p["total"] == 30464 == load_study().space.size
    assert 4 <= p["feasible"] <= p["satisfied_by_criterion"]["tip_thickness"]
    _, zero = run_json(capsys, ["gear", "feasibility", "--backlash-policy", "constant",
                                "--backlash-policy-value", "0"])
    assert zero["feasible"] == 0 and zero["satisfied_by_criterion"]["backlash"] == 0


def test_console_script_subprocess():
    """One real call of the installed console script."""
    out = subprocess.run([sys.executable, "-m", "workflows.cli", *PAPER_D, "--json"], capture_output=True, text=True,
                         check=True)
    assert json.loads(out.stdout)["feasible"] is True
