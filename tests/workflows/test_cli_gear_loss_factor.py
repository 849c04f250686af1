"""`gear evaluate`: --load-sharing, the loss factors and the ISO/TR 14179-2 block."""

import json
import math
import subprocess
import sys

import pytest

from efficiency.geometry import GearPair
from efficiency.loss_factor import ohlendorf_loss_factor

FZG_C = ["--teeth1", "16", "--teeth2", "24", "--module-mm", "4.5", "--pressure-angle-deg", "20",
         "--helix-angle-deg", "0", "--face-width-mm", "14", "--shift1", "0.1817", "--shift2", "0.1715",
         "--center-distance-mm", "91.5"]


def run(*args):
    out = subprocess.run([sys.executable, "-m", "workflows.cli", "gear", "evaluate", *FZG_C, *args, "--json"],
                         capture_output=True, text=True, timeout=300)
    return out.returncode, out.stdout, out.stderr


def test_rigid_uniform_reports_ohlendorf_for_a_spur_pair_and_iso14179_block():
    code, stdout, stderr = run("--torque-nm", "200", "--speed-rpm", "1500", "--load-sharing", "rigid-uniform",
                               "--outputs", "", "--iso14179-2", "--oil-temp-c", "60", "--nu40-cst", "32",
                               "--nu100-cst", "5.4", "--ra-um", "0.5")
    assert code == 0, stderr
    payload = json.loads(stdout)
    pair = GearPair(16, 24, 4.5e-3, math.radians(20), 0.0, 0.014, 0.1817, 0.1715, center_distance=0.0915)
    assert payload["load_sharing"] == "rigid-uniform"
    assert payload["loss_factor"] == pytest.approx(ohlendorf_loss_factor(pair), rel=5e-4)
    assert payload["loss_factor_ohlendorf"] == pytest.approx(ohlendorf_loss_factor(pair), rel=1e-12)
    iso = payload["iso14179_2"]
    assert iso["x_l"] == 0.846 and iso["ra_um"] == pytest.approx(0.5)
    assert iso["p_vzp_w"] == pytest.approx(iso["mu_mz"] * iso["loss_factor_ohlendorf"] * iso["input_power_w"])


def test_bad_oil_type_is_one_clear_error():
    code, _, stderr = run("--iso14179-2", "--oil-type", "castor")
    assert code == 2 and "--oil-type" in stderr and "mineral" in stderr


def test_rigid_uniform_json_is_strict_json():
    code, stdout, stderr = run("--load-sharing", "rigid-uniform", "--per-position")
    assert code == 0, stderr
    payload = json.loads(stdout, parse_constant=lambda c: pytest.fail(f"non-standard JSON constant {c}"))
    assert payload["mesh_stiffness_per_width_n_per_m2"] is None and payload["mesh_stiffness_n_per_m"] is None


def test_iso14179_with_a_given_viscosity_reproduces_the_module():
    """--eta-oil-mpas gives the standard's μ_mz for that viscosity (efficiency.iso14179, FZG C, 200 N·m, 1500 rpm)."""
    from efficiency.iso14179 import iso_14179_2_mesh

    code, stdout, stderr = run("--torque-nm", "200", "--speed-rpm", "1500", "--outputs", "", "--iso14179-2",
                               "--eta-oil-mpas", "12.5", "--oil-type", "pao", "--ra-um", "0.4", "0.6")
    assert code == 0, stderr
    iso = json.loads(stdout)["iso14179_2"]
    pair = GearPair(16, 24, 4.5e-3, math.radians(20), 0.0, 0.014, 0.1817, 0.1715, center_distance=0.0915)
    expected = iso_14179_2_mesh(pair, 200.0, 1500 * math.pi / 30, 12.5e-3, 0.4e-6, 0.6e-6, 0.65)
    assert iso["mu_mz"] == pytest.approx(expected["mu_mz"], rel=1e-12)
    assert iso["viscosity_source"] == "eta-oil-mpas"


def test_friction_iso14179_takes_x_l_of_the_oil_type():
    """`--friction iso14179` with --oil-type pao: the loss is 0.65/0.846 of the mineral one (X_L of ISO/TR 14179-2,
    Fernandes et al., Tribol. Int. 88 (2015) 309), the rest of the model unchanged."""
    common = ("--torque-nm", "200", "--speed-rpm", "1500", "--outputs", "", "--positions", "8", "--slices", "5",
              "--friction", "iso14179", "--oil-temp-c", "60")
    code, mineral, stderr = run(*common)
    assert code in (0, 1), stderr
    code, pao, stderr = run(*common, "--oil-type", "pao")
    assert code in (0, 1), stderr
    ratio = json.loads(pao)["power_loss_w"] / json.loads(mineral)["power_loss_w"]
    assert ratio == pytest.approx(0.65 / 0.846, rel=1e-12)


def test_iso14179_block_with_the_viscosity_of_a_lubricant_file():
    """Without --nu40-cst/--eta-oil-mpas the block takes η of --lubricant at --oil-temp-c (the import of that path
    was broken after the lubricant module moved)."""
    from ehl_dataset.model.lubricant import load_lubricant

    code, stdout, stderr = run("--outputs", "", "--positions", "8", "--slices", "5", "--iso14179-2",
                               "--oil-temp-c", "90", "--lubricant", "gear_oil_75w90")
    assert code in (0, 1), stderr
    iso = json.loads(stdout)["iso14179_2"]
    assert iso["viscosity_source"] == "lubricant gear_oil_75w90"
    eta = float(load_lubricant("gear_oil_75w90").dynamic_viscosity(363.15))
    assert iso["eta_oil_mpas"] == pytest.approx(eta * 1e3, rel=1e-12)
