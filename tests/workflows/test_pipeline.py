"""The end-to-end pipeline (workflows.pipeline, `gearloss pipeline`): EHL factorial → Eq. 9 fit → Design D."""

import json
import math
import warnings

import numpy as np
import pytest

from ehl_dataset.dataset.store import read_table
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.materials import STEEL, reduced_modulus
from ehl_dataset.validation import SolverError
from workflows.cli import main
from workflows.pipeline import DATASET_FILE, dataset_stage, design_stage, fit_stage, run_pipeline


# 2 × 1 × 2 × 2 × 2 × 3 = 48 points at light load (p_h ≤ 1 GPa, the cheap solves): a factorial of the paper's levels
# found to determine both branches of Eq. 9 (10 and 14 coefficients) with full rank — 24 rows with
# lambda <= 1 and 24 above; checked with surrogate.synthetic.toy_table on the same inputs (lambda_bar is the same
# Dowson-Higginson number in both).
FITTABLE_FACTORIAL = """
name = "pipeline_test"
description = "48-point light-load subset of paper2009 for the end-to-end pipeline test"
lubricant = "atf"
level = "fast"
effects = "auto"

[axes]
p_h_gpa = [0.5, 1.0]
r_eq_mm = [20.0]
u_r_m_s = [2.0, 20.0]
sr = [0.1, 0.7]
temp_c = [50.0, 100.0]
roughness_um = [[0.05, 0.05], [0.4, 0.4], [0.2, 0.5]]
"""

# Four light-load, smooth (planner: steady smooth solve) points: cheap stage-1 runs for the resume and error tests.
TINY_FACTORIAL = """
name = "tiny"
description = "4 smooth light-load points of paper2009 levels"
lubricant = "atf"
level = "fast"
effects = "auto"

[axes]
p_h_gpa = [0.5]
r_eq_mm = [20.0]
u_r_m_s = [5.0, 20.0]
sr = [0.1, 0.7]
temp_c = [75.0]
roughness_um = [[0.05, 0.05]]
"""


@pytest.fixture()
def tiny(tmp_path):
    path = tmp_path / "tiny.toml"
    path.write_text(TINY_FACTORIAL)
    return path


def _design_d_direct(coefficients_path):
    """Design D at the study point evaluated without the pipeline (reference for the stage's numbers)."""
    from efficiency.design_io import load_study
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
    from efficiency.power_loss import mesh_power_loss
    from surrogate.evaluate import FrictionSurrogate

    study = load_study("paper2009")
    op = study.operating_point
    from efficiency.modifications import Modifications

    mesh = evaluate_mesh(study.design("D"), op.input_torque, op.input_speed,
                         Modifications(profile_crown=op.profile_crown, lead_crown=op.lead_crown), MeshOptions())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        loss = mesh_power_loss(mesh, FrictionSurrogate.load(coefficients_path), op.oil_temperature, op.rq1, op.rq2)
    return mesh, loss


def test_dataset_stage_writes_the_store_and_resumes(tmp_path, tiny):
    """Stage 1 with the real solver on four smooth points: the counts reported equal the file's, μ is finite; a
    second call continues the same file and recomputes exactly the rows that were not ok."""
    first = dataset_stage(tmp_path, tiny, progress="none")
    assert first.artefact == str(tmp_path / DATASET_FILE)
    table = read_table(first.artefact, status=None)
    assert len(table) == first.details["n_points"] == 4
    assert first.details["ok"] == int((table["status"] == "ok").sum()) >= 1
    assert first.details["ok"] + first.details["failed"] + first.details["pending"] == 4
    ok = table[table["status"] == "ok"]
    assert np.all(np.isfinite(ok["mu"])) and np.all((ok["mu"] > 0) & (ok["mu"] < 0.2))
    second = dataset_stage(tmp_path, tiny, progress="none")
    assert second.details["resumed"]
    assert second.details["computed"] == 4 - first.details["ok"]
    assert second.details["ok"] >= first.details["ok"]


def test_pipeline_stops_at_the_fit_when_the_factorial_cannot_determine_eq9(tmp_path, tiny, capsys):
    """Four points cannot determine Eq. 9 (10 + 14 = 24 coefficients; the shipped 16-point smoke factorial cannot
    either). The pipeline keeps the dataset and raises a SolverError naming the fit stage; the CLI (resuming the same
    directory) prints it in one line, exit 3."""
    with pytest.raises(SolverError, match="fit stage"):
        run_pipeline(tmp_path / "run", tiny, progress="none")
    assert (tmp_path / "run" / DATASET_FILE).is_file()
    assert not list((tmp_path / "run").glob("*.json"))
    code = main(["pipeline", "quick", "--out-dir", str(tmp_path / "run"), "--factorial", str(tiny),
                 "--progress", "none", "--json"])
    captured = capsys.readouterr()
    assert code == 3
    error = [line for line in captured.err.splitlines() if "fit stage" in line]
    assert len(error) == 1 and captured.err.strip().splitlines()[-1] == error[0]
    # the error says which rows were usable and what each branch needs
    assert "rows: 4 in the file; excluded: none" in error[0] and "mixed 0 (needs 10)" in error[0]
    assert "full_film 4 (needs 14)" in error[0]
    assert json.loads(captured.out)["error"]["exit_code"] == 3


def test_pipeline_cli_rejects_bad_input(tmp_path, capsys):
    assert main(["pipeline", "quick", "--out-dir", str(tmp_path), "--workers", "0"]) == 2
    assert "workers" in capsys.readouterr().err
    assert main(["pipeline", "quick", "--out-dir", str(tmp_path), "--factorial", "no_such_factorial"]) == 2
    assert not (tmp_path / DATASET_FILE).exists()
    capsys.readouterr()
    for value in ("0", "-1", "nan", "inf"):
        assert main(["pipeline", "quick", "--out-dir", str(tmp_path / "run"), "--time-limit-s", value]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and "invalid --time-limit-s=" in err, err
        assert not (tmp_path / "run").exists()


def test_dataset_stage_passes_the_time_limit_and_reports_it(tmp_path, tiny):
    """Stage 1 with a budget: the 4 smooth points ignore it (steady solves), the session records it."""
    from ehl_dataset.dataset.store import read_metadata

    stage = dataset_stage(tmp_path, tiny, workers=0, progress="none", time_limit_s=30)
    assert stage.details["time_limit_s"] == 30.0 and stage.details["ok"] == 4
    assert read_metadata(stage.artefact)["sessions"][0]["time_limit_s"] == 30.0


@pytest.fixture(scope="module")
def synthetic_store(tmp_path_factory):
    """A stage-1 file holding the toy μ table of surrogate.synthetic on the quick factorial's inputs (324 rows):
    stands in for the EHL solver so that stages 2-3 are tested on their own."""
    from surrogate.synthetic import factorial_inputs, toy_table, write_hdf5

    atf = load_lubricant("atf")
    levels = dict(p_h_gpa=[0.5, 1.5, 2.5], r_eq_mm=[10, 40], u_r=[1, 5, 20], sr=[0.05, 0.2, 0.7], temp_c=[50, 100],
                  rq_um=[(0.1, 0.1), (0.4, 0.4), (0.2, 0.5)])
    table = toy_table(factorial_inputs(levels), atf, reduced_modulus(STEEL, STEEL))
    return write_hdf5(table, tmp_path_factory.mktemp("stage1") / DATASET_FILE, atf, name="quick")


def test_fit_and_design_stages_on_a_stage1_file(synthetic_store, tmp_path):
    """Stage 2 writes a valid coefficient file and its summary; stage 3 gives Design D's P, η, TE, σ_c, σ_b equal to
    a direct evaluation with the same file (η = 1 − P/(T ω), 0.9 < η < 1)."""
    from surrogate.coefficients import load_coefficients

    fit = fit_stage(synthetic_store, tmp_path / "atf_quick.json")
    assert fit.artefact == str(tmp_path / "atf_quick.json")
    coefficients = load_coefficients(fit.artefact)
    assert coefficients.lubricant.name == "atf"
    assert (tmp_path / "atf_quick.summary.txt").is_file()
    assert fit.details["n_used"] == sum(b["n_obs"] for b in fit.details["branches"].values())
    assert fit.details["exclusions"]["sr_zero"] == 0 and fit.details["n_used"] == 324

    design = design_stage(fit.artefact, clip_to_fitted_ranges=False)
    d = design.details
    mesh, loss = _design_d_direct(fit.artefact)
    assert d["power_loss_w"] == pytest.approx(loss.power_loss, rel=1e-12)
    assert d["te_pp_m"] == pytest.approx(mesh.te_peak_to_peak, rel=1e-12)
    assert d["sigma_c_pa"] == pytest.approx(mesh.sigma_c_max, rel=1e-12)
    assert d["sigma_b_pa"] == pytest.approx(mesh.sigma_b_max, rel=1e-12)
    assert d["efficiency"] == pytest.approx(1.0 - d["power_loss_w"] / d["input_power_w"], rel=1e-14)
    assert d["input_power_w"] == pytest.approx(250.0 * 4000.0 * math.pi / 30.0, rel=1e-12)
    assert 0.9 < d["efficiency"] < 1.0 and math.isfinite(d["efficiency"])
    assert d["converged"]
    assert any("extrapolates" in w for w in d["warnings"])

    clipped = design_stage(fit.artefact).details  # default: inputs held inside the fitted ranges
    counts = clipped["clipped_to_fitted_range"]
    assert counts["p_h"] > 0  # the lightly loaded tooth ends lie below the factorial's 0.5 GPa
    assert counts["contact_points"] == int((mesh.loads > 0).sum())
    assert not any("extrapolates" in w for w in clipped["warnings"])
    assert 0.9 < clipped["efficiency"] < 1.0
    assert clipped["te_pp_m"] == d["te_pp_m"]


@pytest.mark.slow
def test_pipeline_end_to_end_with_the_ehl_solver(tmp_path, capsys):
    """All three stages with the real solver through the CLI, on a 48-point factorial passed as a file: every
    artefact exists and is consistent, and Design D's efficiency is finite and in (0.9, 1)."""
    factorial = tmp_path / "pipeline_test.toml"
    factorial.write_text(FITTABLE_FACTORIAL)
    out = tmp_path / "run"
    code = main(["pipeline", "quick", "--out-dir", str(out), "--factorial", str(factorial), "--workers", "2",
                 "--progress", "none", "--json"])
    captured = capsys.readouterr()
    rows = read_table(out / DATASET_FILE, status=None)
    bad = rows[(rows["status"] != "ok") | ~rows["converged"].astype(bool)]
    assert len(bad) == 0, bad[["lambda_bar", "status", "error"]].to_string()
    payload = json.loads(captured.out)
    # exit 1 when design D lies outside the fit's validity (this factorial has r_eq 20 mm only; design D's contacts
    # are at 12-13 mm, so their r_eq is clipped: docs/reference/cli.md "Validity")
    assert code == (0 if payload["valid"] else 1), f"pipeline exit {code}: {captured.err.strip()}"
    assert payload["valid"] or "r_eq" in payload["stages"]["design"]["not_valid_because"]
    stages = payload["stages"]
    assert stages["dataset"]["n_points"] == 48 and stages["dataset"]["artefact"] == str(out / DATASET_FILE)
    assert stages["dataset"]["ok"] == len(read_table(out / DATASET_FILE))
    assert stages["fit"]["artefact"] == str(out / "atf_pipeline_test.json")
    assert (out / "atf_pipeline_test.json").is_file() and (out / "atf_pipeline_test.summary.txt").is_file()
    assert 0.9 < payload["efficiency"] < 1.0 and math.isfinite(payload["power_loss_w"])
    for name in ("dataset", "fit", "design"):
        assert stages[name]["wall_time_s"] > 0.0


def test_stage1_runs_isothermal_on_request_and_a_run_keeps_its_effect_plan(tmp_path, tiny):
    """``effects="isothermal"`` (the data the paper's Eq. 9 was fitted to): the planner's plan without the thermal
    correction. Rows whose automatic plan corrects the traction get a higher μ (shear heating only lowers the
    viscosity, docs/explanation/ehl-model.md), the others the same μ; the file records the plan, the default directory names it,
    and a run directory is not resumed under the other plan."""
    from ehl_dataset.dataset.store import read_metadata
    from ehl_dataset.validation import InputError
    from workflows.pipeline import check_inputs, default_out_dir

    auto = dataset_stage(tmp_path / "auto", tiny, progress="none")
    iso = dataset_stage(tmp_path / "iso", tiny, progress="none", effects="isothermal")
    assert iso.details["effects"] == "isothermal" and auto.details["effects"] == "auto"
    assert read_metadata(iso.artefact)["solver"]["effects"] == "isothermal"
    a, b = read_table(auto.artefact), read_table(iso.artefact)
    thermal = np.array([json.loads(e)["thermal"] for e in a["effects"]])
    assert thermal.any()
    assert not any(json.loads(e)["thermal"] for e in b["effects"])
    assert np.all(b["mu"].to_numpy()[thermal] > a["mu"].to_numpy()[thermal] * 1.001)
    np.testing.assert_allclose(b["mu"].to_numpy()[~thermal], a["mu"].to_numpy()[~thermal], rtol=1e-12)
    assert default_out_dir("quick", "fast", effects="isothermal") == "gearloss_quick_fast_isothermal"
    with pytest.raises(InputError, match="effects"):
        check_inputs(tiny, out_dir=tmp_path / "auto", effects="isothermal", design=None)
    with pytest.raises(InputError, match="effects"):
        check_inputs(tiny, effects="warm", design=None)


def test_the_cli_effect_choices_are_the_store_s():
    from ehl_dataset.dataset.factorial import EFFECTS_MODES
    from workflows.cli_help import EFFECTS_CHOICES

    assert EFFECTS_CHOICES == EFFECTS_MODES
