"""The accuracy-versus-time workflow on a tiny case set: tables, plot, error arithmetic, CLI."""

import json
import math

import pytest

from ehl_dataset.validation import InputError
from workflows import accuracy
from workflows.cli import main

CHEAP = tuple(spec for spec in accuracy.ACCURACY_CASES if spec[0] in ("full-film-9", "corner-thick"))


def test_case_set_spans_the_factorial():
    """≥ 12 cases; every axis of the paper's factorial (docs/reference/dataset-format.md) at both ends; the hardest corner is present."""
    cases = accuracy.ACCURACY_CASES
    assert len(cases) >= 12
    columns = list(zip(*cases))
    assert min(columns[1]) == 0.5 and max(columns[1]) == 2.5      # p_h [GPa]
    assert min(columns[2]) == 5 and max(columns[2]) == 80         # r_eq [mm]
    assert min(columns[3]) == 1 and max(columns[3]) == 20         # u_r [m/s]
    assert min(columns[4]) == 0 and max(columns[4]) == 1          # SR
    assert min(columns[5]) == 25 and max(columns[5]) == 100       # T [°C]
    assert min(columns[7]) == 0.05 and max(columns[7]) == 1.0     # roughness
    assert ("corner-hard-sr1", 2.5, 5.0, 1.0, 1.0, 100.0, 1.0, 1.0) in cases
    assert len({spec[0] for spec in cases}) == len(cases)


def test_observed_order_of_a_known_sequence():
    """f(h) = 1 + h² sampled at h, h/2, h/4 has observed order exactly 2."""
    values = [1 + 0.4**2, 1 + 0.2**2, 1 + 0.1**2]
    assert accuracy.observed_order(values) == pytest.approx(2.0, rel=1e-9)
    assert math.isnan(accuracy.observed_order([1.0, 1.0, 1.0]))


def test_refined_level_scales_the_right_fields():
    from ehl_dataset.solvers.levels import get_level

    base = get_level("standard")
    finer = accuracy.refined_level("standard", "grid", 2.0)
    assert finer.dx_fine == base.dx_fine / 2 and finer.dx_coarse == base.dx_coarse / 2
    assert finer.inlet_resolution == base.inlet_resolution / 2 and finer.tol_residual == base.tol_residual
    with pytest.raises(InputError, match="refinement"):
        accuracy.refined_level("standard", "time_step", 2.0)  # the deleted transient solver's


def test_the_convergence_study_refuses_a_plan_whose_grid_the_level_does_not_set():
    """A rough case with every effect runs the deterministic model, whose spacing is its own grid rule: refining
    the level's fields would change nothing and report a false order, so it is refused with the parameter named."""
    rough = next(spec for spec in accuracy.ACCURACY_CASES if spec[0] == "gear-typical")
    with pytest.raises(InputError, match="effects.*deterministic"):
        accuracy.convergence_study(rough, "grid", base_level="fast", effects="full")


def test_study_against_itself_has_zero_error(tmp_path):
    """The solver is deterministic: a level measured against itself (same effects) has error exactly 0; the report
    files are written and the table lists every case."""
    study = accuracy.run_study(CHEAP, levels=("fast",), reference="fast", reference_effects="auto")
    runs = study.for_level("fast")
    assert len(runs) == 2 * len(CHEAP)
    measured = [r for r in runs if r.effects_mode == "auto"]
    for run in measured:
        assert run.converged, run.message
        assert run.mu_error == 0.0 and run.h_min_error == 0.0
        assert run.wall_time_s > 0
    paths = accuracy.write_report(study, tmp_path)
    text = paths["markdown"].read_text()
    for spec in CHEAP:
        assert spec[0] in text
    assert "| fast |" in text
    png = paths["plot"].read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000
    raw = json.loads(paths["json"].read_text())
    assert raw["summary"]["fast"]["mu_error_max"] == 0.0


def test_cli_writes_report_and_json(tmp_path, capsys):
    """`gearloss accuracy --json` on one cheap case: fast against standard, summary keys with units."""
    code = main(["accuracy", "--only", "full-film-9", "--levels", "fast", "--reference", "standard",
                 "--reference-effects", "auto", "--out-dir", str(tmp_path), "--json"])
    assert code == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["n_cases"] == 1
    row = payload["summary"]["fast"]
    assert row["n_cases"] == 1 and row["converged"] == 1
    assert 0.0 <= row["mu_error_max"] < 0.5 and row["wall_time_mean_s"] > 0
    assert (tmp_path / "accuracy_levels_rough.md").is_file() and (tmp_path / "accuracy_levels_rough.png").is_file()


def test_cli_rejects_bad_options(tmp_path, capsys):
    assert main(["accuracy", "--cases", "0", "--out-dir", str(tmp_path)]) == 2
    assert "--cases" in capsys.readouterr().err
    assert main(["accuracy", "--levels", "ultra", "--out-dir", str(tmp_path)]) == 2
    assert "level" in capsys.readouterr().err
    assert main(["accuracy", "--only", "nope", "--out-dir", str(tmp_path)]) == 2
