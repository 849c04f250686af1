"""The mixed-regime accuracy study (``gearloss accuracy --mixed``): errors against the reference file, resumable
checkpoint, clear errors for a missing or corrupt reference, the report files."""

import json
import math

import pytest

from ehl_dataset.validation import InputError
from workflows import accuracy_mixed
from workflows.cli import main

CASE = {"case": "T", "inputs": {"p_h_gpa": 1.0, "r_eq_mm": 5, "u_r_m_s": 20, "sr": 0.7, "temp_c": 100,
                                "rq1_um": 0.05, "rq2_um": 0.05},
        "lambda_bar": 3.7, "half_width_m": 8.8e-5, "mu_extrapolated": 0.0300, "mu_uncertainty": 0.0003,
        "asperity_load_share_extrapolated": 0.0, "h_central_m": 2.5e-7}


def reference_file(tmp_path, cases=(CASE,)):
    path = tmp_path / "reference.json"
    path.write_text(json.dumps({"cases": list(cases)}))
    return path


class FakeResult:
    def __init__(self, mu):
        self.mu, self.mu_sem, self.h_central, self.asperity_load_share = mu, 0.0, 2.0e-7, 0.1
        self.converged, self.message = True, "converged"


def test_errors_are_measured_against_the_reference_and_runs_resume(tmp_path):
    calls = []

    def solve(case, lubricant, level, effects, **kwargs):
        calls.append((level, kwargs["model"]))
        assert kwargs["roughness"].name == "baseline_synthetic"  # the reference's roughness, not the default
        return FakeResult(0.0330)

    checkpoint = tmp_path / "study.partial.json"
    study = accuracy_mixed.run_mixed_study(["smooth-standard"], reference_file(tmp_path), checkpoint=checkpoint,
                                           solve=solve)
    run = study["runs"][0]
    assert run.mu_error == pytest.approx(0.1, rel=1e-12)           # |0.033 − 0.030|/0.030
    assert run.h_central_error == pytest.approx(0.2, rel=1e-12)    # |200 − 250|/250 nm
    assert run.share_difference == pytest.approx(0.1)
    assert calls == [("standard", "smooth")]
    again = accuracy_mixed.run_mixed_study(["smooth-standard"], reference_file(tmp_path), checkpoint=checkpoint,
                                           solve=solve)
    assert len(calls) == 1 and again["runs"][0].mu == run.mu       # resumed from the checkpoint, not solved again
    # a recomputed reference (e.g. rerun under a new model version): the resumed run is measured against it
    moved = reference_file(tmp_path, [{**CASE, "mu_extrapolated": 0.0275}])
    remeasured = accuracy_mixed.run_mixed_study(["smooth-standard"], moved, checkpoint=checkpoint, solve=solve)
    assert len(calls) == 1 and remeasured["runs"][0].mu_error == pytest.approx(0.2, rel=1e-12)  # |0.033 − 0.0275|/0.0275
    paths = accuracy_mixed.write_mixed_report(study, tmp_path, "gearloss accuracy --mixed")
    assert "| smooth-standard | 1 | 1 | 10 % |" in paths["markdown"].read_text()
    assert paths["plot"].stat().st_size > 0


def test_a_failed_solve_is_a_data_point():
    def solve(*args, **kwargs):
        raise FloatingPointError("overflow")

    row = CASE
    run = accuracy_mixed._run(accuracy_mixed.reference_case(row), "atf", row, "smooth-standard", solve)
    assert not run.converged and "overflow" in run.message and math.isnan(run.mu_error)


def test_missing_or_corrupt_reference_is_a_clear_error(tmp_path):
    with pytest.raises(InputError, match="reference"):
        accuracy_mixed.load_reference(tmp_path / "none.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with pytest.raises(InputError, match="reference"):
        accuracy_mixed.load_reference(bad)
    with pytest.raises(InputError, match="models"):
        accuracy_mixed.run_mixed_study(["exact"], reference_file(tmp_path))


def test_cli_runs_the_steady_smooth_model_on_a_reference_case(tmp_path, capsys):
    """A real solve: the smooth model on a full-film case (λ̄ = 3.7) from the CLI, report written."""
    code = main(["accuracy", "--mixed", "--models", "smooth-standard", "--reference-file",
                 str(reference_file(tmp_path)), "--out", str(tmp_path / "out"), "--json"])
    assert code == 0
    payload = json.loads(capsys.readouterr().out)
    row = payload["summary"]["smooth-standard"]
    assert row["converged"] == 1 and math.isfinite(row["mu_error_median"])
    assert (tmp_path / "out" / "accuracy_mixed.md").exists()


def test_a_rescore_measures_only_the_models_asked_for(tmp_path, capsys):
    """``--rescore REPORT --models M``: the runs of the other models are left out of the study and its summary."""
    study = accuracy_mixed.run_mixed_study(["smooth-standard", "homogenised-transverse-standard"],
                                           reference_file(tmp_path), solve=lambda *a, **k: FakeResult(0.0330))
    made = accuracy_mixed.write_mixed_report(study, tmp_path / "made", "gearloss accuracy --mixed (made)")
    assert {run.model for run in study["runs"]} == {"smooth-standard", "homogenised-transverse-standard"}
    only = accuracy_mixed.rescore_study(made["json"], reference_file(tmp_path), ["smooth-standard"])
    assert only["models"] == ["smooth-standard"] and {run.model for run in only["runs"]} == {"smooth-standard"}
    code = main(["accuracy", "--mixed", "--rescore", str(made["json"]), "--models", "smooth-standard",
                 "--reference-file", str(reference_file(tmp_path)), "--out", str(tmp_path / "out"), "--json"])
    assert code == 0
    assert list(json.loads(capsys.readouterr().out)["summary"]) == ["smooth-standard"]
    written = json.loads((tmp_path / "out" / "accuracy_mixed.json").read_text())
    assert written["rescored"]["command"].endswith("--models smooth-standard --reference-file "
                                                   + str(reference_file(tmp_path)))


def test_runs_of_a_report_are_re_measured_against_a_recomputed_reference_without_solving(tmp_path, capsys):
    """``--rescore``: the runs (and their versions) stay, the errors follow the new reference; a report of other
    cases or other inputs is refused."""
    study = accuracy_mixed.run_mixed_study(["smooth-standard"], reference_file(tmp_path),
                                           solve=lambda *a, **k: FakeResult(0.0330))
    made = accuracy_mixed.write_mixed_report(study, tmp_path / "made", "gearloss accuracy --mixed (made)")
    moved = tmp_path / "moved"
    moved.mkdir()
    moved_reference = reference_file(moved, [{**CASE, "mu_extrapolated": 0.0275}])
    again = accuracy_mixed.rescore_study(made["json"], moved_reference)
    run = again["runs"][0]
    assert run.mu == 0.0330 and run.mu_error == pytest.approx(0.2, rel=1e-12)   # |0.033 − 0.0275|/0.0275
    assert again["provenance"]["reference_sha256"] != again["rescored"]["reference_sha256"]
    assert again["runs_command"] == "gearloss accuracy --mixed (made)"

    code = main(["accuracy", "--mixed", "--rescore", str(made["json"]), "--reference-file", str(moved_reference),
                 "--out", str(tmp_path / "out"), "--json"])
    assert code == 0
    assert json.loads(capsys.readouterr().out)["summary"]["smooth-standard"]["mu_error_median"] == \
        pytest.approx(0.2, rel=1e-12)
    written = json.loads((tmp_path / "out" / "accuracy_mixed.json").read_text())
    assert written["command"] == "gearloss accuracy --mixed (made)"      # rescoring again keeps the runs' command
    assert written["rescored"]["command"].startswith("gearloss accuracy --mixed --rescore")
    text = (tmp_path / "out" / "accuracy_mixed.md").read_text()
    assert "gearloss accuracy --mixed (made)" in text and "re-measured" in text

    with pytest.raises(InputError, match="is not in"):
        accuracy_mixed.rescore_study(made["json"], reference_file(moved, [{**CASE, "case": "U"}]))
    with pytest.raises(InputError, match="inputs"):
        accuracy_mixed.rescore_study(made["json"], reference_file(moved, [{**CASE, "inputs": {
            **CASE["inputs"], "sr": 0.5}}]))
    with pytest.raises(InputError, match="models.*smooth-standard"):
        accuracy_mixed.rescore_study(made["json"], moved_reference, ["deterministic-fast"])
    corrupt = tmp_path / "corrupt.json"
    corrupt.write_text('{"runs": [')
    with pytest.raises(InputError, match="report"):
        accuracy_mixed.rescore_study(corrupt, moved_reference)
