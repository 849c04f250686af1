"""``gearloss gear evaluate`` (workflows.cli_gear_evaluate), called in process through workflows.cli.main."""

import json
import math
import subprocess
import sys

import pytest

from efficiency import iso6336
from efficiency.geometry import GearPair
from workflows.cli import main

DESIGN_D = ["--teeth", "32", "--pressure-angle-deg", "30", "--helix-angle-deg", "19", "--working-depth", "2.068",
            "--slices", "20", "--positions", "12"]


def run_json(capsys, argv):
    code = main(["gear", "evaluate", *argv, "--json"])
    out = capsys.readouterr().out
    return code, json.loads(out)


def test_evaluate_design_d_json(capsys):
    """Design D with the paper's crowns at 250 N·m: SI keys with unit suffixes, converged, equilibrium, the
    normal load W = T/(r_b1 cos β_b) and ISO nominal values alongside."""
    code, payload = run_json(capsys, [*DESIGN_D, "--torque-nm", "250", "--profile-crown-um", "15",
                                      "--lead-crown-um", "12", "--per-position"])
    assert code == 0
    assert payload["converged"] is True
    assert payload["equilibrium_residual"] <= 1e-9
    for key in ("te_pp_m", "sigma_c_pa", "sigma_b_pa", "mesh_stiffness_per_width_n_per_m2", "wall_time_s"):
        assert math.isfinite(payload[key]) and payload[key] > 0
    pair = GearPair.from_paper(32, math.radians(30), math.radians(19), 2.068)
    expected_w = 250.0 / (float(pair.base_radii[0]) * math.cos(float(pair.base_helix_angle)))
    assert payload["normal_load_n"] == pytest.approx(expected_w, rel=1e-3)  # CLI pair includes backlash thinning
    assert payload["iso6336"]["sigma_h0_pa"] == pytest.approx(iso6336.nominal_contact_stress(pair, 250.0), rel=1e-3)
    assert len(payload["transmission_error_m"]) == 12
    assert max(payload["transmission_error_m"]) - min(payload["transmission_error_m"]) == pytest.approx(
        payload["te_pp_m"], rel=1e-12)


def test_evaluate_general_pair_only_te(capsys):
    """A general pair (FZG H501) with only the TE requested: no stress keys in the output."""
    code, payload = run_json(capsys, ["--teeth1", "20", "--teeth2", "30", "--module-mm", "3.5",
                                      "--pressure-angle-deg", "20", "--helix-angle-deg", "15", "--face-width-mm",
                                      "23", "--shift1", "0.1809", "--shift2", "0.0891", "--outputs", "te",
                                      "--slices", "12", "--positions", "8"])
    assert code == 0
    assert "te_pp_m" in payload and "sigma_c_pa" not in payload


@pytest.mark.parametrize("option,value,name", [("--torque-nm", "-5", "torque-nm"), ("--slices", "0", "slices"),
                                                ("--profile-crown-um", "nan", "profile")])
def test_bad_input_is_one_line_with_exit_status_2(capsys, option, value, name):
    code = main(["gear", "evaluate", *DESIGN_D, option, value])
    err = capsys.readouterr().err
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and name in err


def test_human_output_and_console_script():
    """One real subprocess call of the console entry point (human-readable output)."""
    out = subprocess.run([sys.executable, "-m", "workflows.cli", "gear", "evaluate", *DESIGN_D],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert "transmission error peak-to-peak" in out.stdout and "σ_c" in out.stdout


def test_design_file_with_modifications_table(capsys, tmp_path):
    """``--design FILE.toml`` (efficiency.design_io format) with an optional [modifications] table in µm/mm; an
    explicit option overrides the table. The result equals the in-process model for the same inputs."""
    from efficiency.design_io import design_to_toml
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
    from efficiency.modifications import Modifications

    pair = GearPair.from_paper(32, math.radians(30), math.radians(19), 2.068)
    path = tmp_path / "design_d.toml"
    path.write_text(design_to_toml(pair, "D") + "\n[modifications]\nprofile_crown_um = 15\nlead_crown_um = 30\n")
    code, payload = run_json(capsys, ["--design", str(path), "--lead-crown-um", "12", "--slices", "20",
                                      "--positions", "12"])
    assert code == 0
    assert payload["profile_crown_m"] == pytest.approx(15e-6) and payload["lead_crown_m"] == pytest.approx(12e-6)
    direct = evaluate_mesh(pair, 250.0, speed_rad_s=4000 * math.pi / 30, modifications=Modifications.paper(),
                           options=MeshOptions(slices=20, positions=12))
    assert payload["te_pp_m"] == pytest.approx(direct.te_peak_to_peak, rel=1e-9)
    assert payload["sigma_c_pa"] == pytest.approx(direct.sigma_c_max, rel=1e-9)
    path.write_text(design_to_toml(pair) + "\n[modifications]\ncrown = 3\n")
    assert main(["gear", "evaluate", "--design", str(path)]) == 2
    assert "crown" in capsys.readouterr().err
