"""The friction surrogate's 90 % band in ``gearloss report efficiency-map`` and the off-grid validation printed by
``gearloss gear evaluate --offgrid`` (workflows.report, workflows.cli_report, workflows.cli_gear_evaluate).

The band of P is the one of efficiency.power_loss: every loaded contact point at the same end of its μ prediction
interval, P_low = mean_m Σ μ_low W |u_s| and P_high likewise; η's band is 1 − P_high/(T ω) … 1 − P_low/(T ω).
"""

import csv
import json
import math

import numpy as np
import pytest

from workflows import report
from workflows.cli import main

DESIGN_D = ["--teeth", "32", "--pressure-angle-deg", "30", "--helix-angle-deg", "19", "--working-depth", "2.068"]
STUDY_MODS = ["--profile-crown-um", "15", "--lead-crown-um", "12"]
RESOLUTION = ["--positions", "12", "--slices", "12"]
GRID = ["--torques-nm", "150,250", "--speeds-rpm", "2000,4000"]


def _format1_file(tmp_path) -> str:
    """atf_quick.json as a format-1 file: the same Eq. 9 coefficients without what an interval needs (each
    branch's covariance and residual variance, the interval calibration) and without an off-grid table."""
    from surrogate.coefficients import content_hash, load_coefficients

    doc = json.loads(json.dumps(load_coefficients("atf_quick").document))
    for key in ("form", "interval_calibration", "offgrid"):
        doc.pop(key, None)
    for branch in doc["branches"].values():
        for key in ("covariance", "resid_variance"):
            branch.pop(key, None)
    doc["format_version"] = 1
    doc["content_sha256"] = content_hash(doc)
    path = tmp_path / "atf_quick_format1.json"
    path.write_text(json.dumps(doc))
    assert not load_coefficients(str(path)).has_interval
    return str(path)


def _map(tmp_path, capsys, monkeypatch, friction, *extra):
    """Run the 2 × 2 map of design D with ``friction``; return its JSON and the texts of the figure it drew."""
    drawn = {}
    save = report._save

    def recording_save(fig, path, command, note=""):
        drawn["suptitle"] = fig._suptitle.get_text()
        drawn["axes"] = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
        drawn["legends"] = [" ".join(" ".join(t.get_text().split()) for t in ax.get_legend().get_texts())
                            for ax in drawn["axes"] if ax.get_legend() is not None]  # wrapped lines joined
        return save(fig, path, command, note)

    monkeypatch.setattr(report, "_save", recording_save)
    out = tmp_path / "map.png"
    code = main(["report", "efficiency-map", *GRID, *RESOLUTION, "--friction", friction, "--compare",
                 "--out", str(out), "--json", *extra])
    payload = json.loads(capsys.readouterr().out)
    assert out.is_file() and out.stat().st_size > 0
    return code, payload, drawn


def test_map_with_intervals_carries_a_band_around_every_cell(tmp_path, capsys, monkeypatch):
    """atf_quick.json (format 2, calibrated Eq. 9 intervals): in every cell P_low < P < P_high (μ_low < μ < μ_high
    at every contact point, exp(ln μ ∓ half width) with half width > 0), η_low < η < η_high with
    η_high − η_low = (P_high − P_low)/(T ω) (η = 1 − P/(T ω), Li & Kahraman 2009 Eq. 11b); the CSV table
    holds the same numbers; the figure has the band panel and its legend says what the band is."""
    table = tmp_path / "map.csv"
    code, p, drawn = _map(tmp_path, capsys, monkeypatch, "atf_quick", "--table", str(table))
    assert code == 0
    loss, low, high = (np.array(p[k], dtype=float) for k in ("power_loss_w", "power_loss_low_w",
                                                               "power_loss_high_w"))
    eff, eff_low, eff_high = (np.array(p[k], dtype=float) for k in ("efficiency", "efficiency_low",
                                                                    "efficiency_high"))
    assert loss.shape == low.shape == high.shape == eff_low.shape == (2, 2)
    assert np.array(p["converged"]).all() and np.isfinite(loss).all()
    assert (low < loss).all() and (loss < high).all()
    assert (eff_low < eff).all() and (eff < eff_high).all()
    input_power = np.array(p["torque_nm"])[:, None] * np.array(p["speed_rpm"])[None, :] * math.pi / 30.0
    np.testing.assert_allclose(eff_high - eff_low, (high - low) / input_power, rtol=1e-9)
    np.testing.assert_allclose(eff, 1.0 - loss / input_power, rtol=1e-12)
    assert p["band_coverage"] == 0.9
    assert "90 % prediction band of the friction surrogate, fully correlated over the mesh" in p["band_note"]

    with open(table, newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 4 and float(rows[3]["torque_nm"]) == 250.0 and float(rows[3]["speed_rpm"]) == 4000.0
    assert float(rows[3]["power_loss_low_w"]) == pytest.approx(low[1, 1], rel=1e-12)
    assert float(rows[3]["efficiency_high"]) == pytest.approx(eff_high[1, 1], rel=1e-12)
    assert p["table"] == str(table)

    assert len(drawn["axes"]) == 3
    assert any("90 % prediction band of the friction surrogate, fully correlated over the mesh" in text
               for text in drawn["legends"])
    assert "no band" not in drawn["suptitle"]


def test_map_band_is_the_band_of_gear_evaluate_at_that_cell(tmp_path, capsys, monkeypatch):
    """The cell at 250 N·m, 4000 rpm is the mesh cycle of `gear evaluate` with the same options: the same P band
    (efficiency.power_loss.mesh_power_loss on both paths), to round-off."""
    _, p, _ = _map(tmp_path, capsys, monkeypatch, "atf_quick")
    code = main(["gear", "evaluate", *DESIGN_D, *STUDY_MODS, *RESOLUTION, "--friction", "atf_quick", "--json"])
    assert code in (0, 1)  # 1: flagged outside a validity check, the numbers printed all the same
    direct = json.loads(capsys.readouterr().out)
    assert p["power_loss_w"][1][1] == pytest.approx(direct["power_loss_w"], rel=1e-12)
    assert [p["power_loss_low_w"][1][1], p["power_loss_high_w"][1][1]] == pytest.approx(
        direct["power_loss_band_w"], rel=1e-12)
    assert [p["efficiency_low"][1][1], p["efficiency_high"][1][1]] == pytest.approx(
        direct["efficiency_band"], rel=1e-12)


def test_map_without_intervals_has_no_band_and_says_so(tmp_path, capsys, monkeypatch):
    """A format-1 file (no coefficient covariance): no band in the JSON or the CSV, the figure's title says
    "no band: the friction model has no prediction interval", and the nominal P is that of the same coefficients
    with an interval (the interval does not move μ: exp of the same ln μ)."""
    format1 = _format1_file(tmp_path)
    table = tmp_path / "map.csv"
    code, p, drawn = _map(tmp_path, capsys, monkeypatch, format1, "--table", str(table))
    assert code == 0
    for key in ("power_loss_low_w", "power_loss_high_w", "efficiency_low", "efficiency_high", "band_coverage"):
        assert p[key] is None
    assert p["band_note"] == report.NO_BAND_NOTE == "no band: the friction model has no prediction interval"
    assert np.isfinite(np.array(p["power_loss_w"], dtype=float)).all()
    with open(table, newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 4 and all(row["power_loss_low_w"] == "" for row in rows)
    assert len(drawn["axes"]) == 2
    assert report.NO_BAND_NOTE in drawn["suptitle"]
    monkeypatch.undo()
    _, with_band, _ = _map(tmp_path, capsys, monkeypatch, "atf_quick")
    np.testing.assert_allclose(p["power_loss_w"], with_band["power_loss_w"], rtol=1e-12)
    main(["report", "efficiency-map", *GRID, *RESOLUTION, "--friction", format1, "--compare",
          "--out", str(tmp_path / "m.png")])
    assert report.NO_BAND_NOTE in capsys.readouterr().out


def test_map_table_must_be_csv(tmp_path, capsys):
    code = main(["report", "efficiency-map", *GRID, "--table", str(tmp_path / "map.txt"),
                 "--out", str(tmp_path / "m.png")])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and "table" in err and ".csv" in err


# ---------------------------------------------------------------------- gear evaluate --offgrid
def test_evaluate_offgrid_prints_the_files_validation_per_branch(capsys):
    """`gear evaluate --offgrid` prints the off-grid errors atf_quick.json records (its ``offgrid`` table, made
    by `lubricant fit` on 200 random contacts, seed 2009), per branch with the interval's coverage; the JSON
    carries the table as it is in the file."""
    from surrogate.coefficients import load_coefficients

    recorded = load_coefficients("atf_quick").document["offgrid"]
    argv = ["gear", "evaluate", *DESIGN_D, *STUDY_MODS, *RESOLUTION, "--friction", "atf_quick"]
    main([*argv, "--offgrid"])
    text = capsys.readouterr().out
    for branch in ("overall", "mixed", "full_film"):
        m = recorded[branch]
        assert (f"{branch:9s} n = {m['n']:4d}: |rel err mu| median {m['median_rel_err_mu']:.1%}, 90th percentile "
                f"{m['p90_rel_err_mu']:.1%}, max {m['max_rel_err_mu']:.1%}; 90% interval covers "
                f"{m['coverage']:.1%}") in text
    assert "off-grid validation on 200 random contacts in the fitted ranges (seed 2009" in text
    assert "surrogate off-grid error of μ" not in text  # the one-line summary gives way to the table
    main(argv)
    assert "surrogate off-grid error of μ (200 random contacts" in capsys.readouterr().out
    main([*argv, "--json"])
    payload = json.loads(capsys.readouterr().out)
    assert payload["friction_offgrid"] == recorded


def test_evaluate_offgrid_of_a_model_without_one(tmp_path, capsys):
    """A format-1 file (no off-grid table) and a published formula: friction_offgrid is null in the JSON and
    --offgrid says none is recorded; --offgrid without --friction is one clear error."""
    for model in (_format1_file(tmp_path), "xu2007"):
        main(["gear", "evaluate", *DESIGN_D, *RESOLUTION, "--friction", model, "--json"])
        assert json.loads(capsys.readouterr().out)["friction_offgrid"] is None
        main(["gear", "evaluate", *DESIGN_D, *RESOLUTION, "--friction", model, "--offgrid"])
        assert "off-grid validation: none recorded" in capsys.readouterr().out
    code = main(["gear", "evaluate", *DESIGN_D, *RESOLUTION, "--offgrid"])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and "offgrid" in err and "--friction" in err
