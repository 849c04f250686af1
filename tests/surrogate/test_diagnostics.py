"""Diagnostics: residual tables account for every fitted row; figures are written."""

import pytest

from surrogate.diagnostics import format_residuals, plot_figures, residuals_by_factor


def test_residuals_by_factor_cover_every_row_once_per_factor(eq9_fit):
    table = residuals_by_factor(eq9_fit)
    assert set(table) == {"p_h_gpa", "r_eq_mm", "u_r_m_s", "sr", "temp_c", "roughness_um"}
    for factor, levels in table.items():
        n = sum(stats["n"] for entry in levels.values() for stats in entry.values())
        assert n == eq9_fit.n_used, factor
    # exact-form data: no factor level may carry a systematic bias beyond ~4 standard errors of its mean
    for levels in table.values():
        for entry in levels.values():
            for stats in entry.values():
                if stats["n"] >= 30:
                    assert abs(stats["mean"]) < 4 * 0.05 / stats["n"] ** 0.5 + 0.01
    assert "temp_c" in format_residuals(table)


def test_figures_are_written(eq9_fit, tmp_path):
    pytest.importorskip("matplotlib")
    paths = plot_figures(eq9_fit, tmp_path)
    assert [p.name for p in paths] == ["surrogate_mu_vs_lambda.png", "surrogate_predicted_vs_computed.png"]
    for p in paths:
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and p.stat().st_size > 10_000
