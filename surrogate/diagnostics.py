"""Diagnostics of a surrogate fit: residuals by branch and by factor level, the text summary written beside the
coefficient file (:func:`summary_text`), and the two standard figures.

Residuals are the *out-of-fold* ones of the k-fold cross-validation (ln μ_predicted − ln μ_computed), so they show
the error a user meets on contacts the fit has not seen.

Figures (matplotlib, Agg backend):

* ``surrogate_mu_vs_lambda.png`` — μ against λ̄ for every usable point with both branches' predictions, on linear
  scales for 0 ≤ λ̄ ≤ 3 as in the paper's Fig. 2, and on a logarithmic λ̄ axis over the whole range;
* ``surrogate_predicted_vs_computed.png`` — cross-validated prediction against computed μ (log–log, 1:1 line).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from .fit import SurrogateFit, branch_masks

FACTORS = {"p_h": ("p_h_gpa", 1e-9), "r_eq": ("r_eq_mm", 1e3), "u_r": ("u_r_m_s", 1.0), "sr": ("sr", 1.0),
           "temperature": ("temp_c", None)}


def _level_label(column: str, value: float) -> str:
    name, scale = FACTORS[column]
    shown = value - 273.15 if scale is None else value * scale
    return f"{shown:.4g}"


def residuals_by_factor(fit: SurrogateFit) -> dict[str, Any]:
    """Out-of-fold ln μ residuals by factor level and branch.

    Factor levels are in engineering units for readability; the roughness factor is the pair 'Rq1/Rq2 µm'.

    Parameters
    ----------
    fit : SurrogateFit
        A fit with its cross-validation predictions [-].

    Returns
    -------
    dict
        {factor: {level: {branch: {n, mean, rms}}}} of the residuals.
    """
    prepared = fit.prepared
    resid = fit.cv_predictions - prepared.ln_mu
    masks = branch_masks(prepared.features["lam"], fit.formula.lambda_threshold)
    table = prepared.table
    keys = {column: np.array([_level_label(column, v) for v in table[column].to_numpy(dtype=float)])
            for column in FACTORS}
    keys["roughness_um"] = np.array([f"{a * 1e6:.3g}/{b * 1e6:.3g}" for a, b in zip(table["rq1"], table["rq2"])])
    out: dict[str, Any] = {}
    for column, labels in keys.items():
        name = FACTORS[column][0] if column in FACTORS else column
        levels: dict[str, Any] = {}
        for level in sorted(set(labels), key=lambda s: float(s.split("/")[0])):
            sel = labels == level
            entry = {}
            for branch, mask in masks.items():
                r = resid[sel & mask]
                entry[branch] = ({"n": int(r.size), "mean": float(r.mean()), "rms": float(np.sqrt(np.mean(r**2)))}
                                 if r.size else {"n": 0})
            levels[level] = entry
        out[name] = levels
    return out


def format_residuals(residuals: dict[str, Any]) -> str:
    lines = ["out-of-fold ln mu residuals: mean / rms (n) per branch"]
    for factor, levels in residuals.items():
        lines.append(f"  {factor}:")
        for level, entry in levels.items():
            cells = []
            for branch, stats in entry.items():
                cells.append(f"{branch} {stats['mean']:+.3f}/{stats['rms']:.3f} ({stats['n']})" if stats["n"]
                             else f"{branch} -")
            lines.append(f"    {level:>10s}: " + "; ".join(cells))
    return "\n".join(lines)


def summary_text(fit: SurrogateFit) -> str:
    """Both statsmodels summaries plus the diagnostics of a fit, as written beside its coefficient file.

    Parameters
    ----------
    fit : SurrogateFit
        The fit [-].

    Returns
    -------
    str
        The text.
    """
    parts = [f"formula {fit.formula.name} v{fit.formula.version}; rows: {fit.n_input_rows} in, "
             f"{fit.n_used} used; excluded: {fit.exclusions}"]
    for b, f in fit.branches.items():
        parts.append(f"\n=== branch {b} ({'lambda <= 1, Eq. 9a' if b == 'mixed' else 'lambda > 1, Eq. 9b'}) ===")
        parts.append(f.summary_text)
        parts.append(f"condition number: raw design {f.condition_number_raw:.4g}, standardised "
                     f"{f.condition_number_standardized:.4g}; rank {f.rank}/{len(f.terms)}; stable={f.stable}")
        parts.append("variance inflation factors: " + ", ".join(f"{k}={v:.4g}" for k, v in f.vif.items()))
        parts.extend(f"note: {m}" for m in f.messages)
    cv = fit.cv["overall"]
    parts.append(f"\n{fit.cv['k']}-fold CV: RMSE ln mu {cv['rmse_ln_mu']:.4g}, mean |rel err mu| "
                 f"{cv['mean_rel_err_mu']:.4g}, p95 {cv['p95_rel_err_mu']:.4g}")
    parts.append(f"jump at lambda = 1: {fit.jump}")
    if fit.prepared is not None and fit.cv_predictions is not None:
        parts.append("\n" + format_residuals(residuals_by_factor(fit)))
    return "\n".join(parts)


def plot_figures(fit: SurrogateFit, out_dir: str | Path, *, prefix: str = "surrogate_", title: str = "") -> list[Path]:
    """Write the two diagnostic figures of a fit (module docstring) into ``out_dir``.

    Parameters
    ----------
    fit : SurrogateFit
        The fit [-].
    out_dir : str or Path
        Output directory [-].
    prefix : str
        File name prefix [-].
    title : str
        Title line of the figures [-].

    Returns
    -------
    list of Path
        The figure paths.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FixedLocator, FormatStrFormatter, NullFormatter

    from .model import predict_ln_mu

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    prepared = fit.prepared
    lam = prepared.features["lam"]
    mu = np.exp(prepared.ln_mu)
    fitted = np.exp(predict_ln_mu(fit.formula, fit.params, prepared.features, fit.blend_half_width))
    masks = branch_masks(lam, fit.formula.lambda_threshold)
    colours = {"mixed": "tab:red", "full_film": "tab:blue"}
    labels = {"mixed": "Eq. 9a (λ̄ ≤ 1)", "full_film": "Eq. 9b (λ̄ > 1)"}
    paths = []

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    for ax, log in zip(axes, (False, True)):
        alpha = float(np.clip(300.0 / max(lam.size, 1), 0.08, 0.8))
        size = float(np.clip(2000.0 / max(lam.size, 1), 2.0, 14.0))
        for branch, mask in masks.items():
            ax.scatter(lam[mask], fitted[mask], s=2 * size, c=colours[branch], alpha=alpha, lw=0,
                       label=labels[branch])
        ax.scatter(lam, mu, s=size, c="k", alpha=alpha, lw=0, label="computed (dataset)")
        ax.axvline(fit.formula.lambda_threshold, c="k", lw=0.8, ls="--")
        ax.set_xlabel("λ̄ = h_min,DH / S_c")
        ax.set_ylabel("μ")
        if log:
            ax.set_xscale("log")
            ax.set_title("whole range (log λ̄)")
        else:
            ax.set_xlim(0, 3)
            ax.set_title("linear scales, λ̄ ≤ 3 (paper Fig. 2)")
        ax.set_ylim(0, max(0.12, float(np.percentile(mu, 99.5)) * 1.1))
    legend = axes[0].legend(loc="upper right", fontsize=8, markerscale=3)
    for handle in legend.legend_handles:
        handle.set_alpha(1.0)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    path = out_dir / f"{prefix}mu_vs_lambda.png"
    fig.savefig(path, dpi=130)
    plt.close(fig)
    paths.append(path)

    predicted = np.exp(fit.cv_predictions)
    fig, ax = plt.subplots(figsize=(5.2, 5))
    for branch, mask in masks.items():
        ax.scatter(mu[mask], predicted[mask], s=float(np.clip(3000.0 / max(mu.size, 1), 5.0, 20.0)),
                   c=colours[branch], alpha=0.6, lw=0,
                   label=f"{labels[branch]}, n = {int(mask.sum())}")
    lo, hi = float(min(mu.min(), predicted.min())) * 0.9, float(max(mu.max(), predicted.max())) * 1.1
    ax.plot([lo, hi], [lo, hi], "k-", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(lo, hi)
    ax.set_ylim(lo, hi)
    ticks = [t for t in (0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5) if lo <= t <= hi]
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(FixedLocator(ticks))
        axis.set_major_formatter(FormatStrFormatter("%g"))
        axis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("computed μ (dataset)")
    ax.set_ylabel(f"predicted μ ({fit.cv['k']}-fold cross-validated)")
    cv = fit.cv["overall"]
    ax.set_title(f"CV RMSE ln μ = {cv['rmse_ln_mu']:.3f}, mean |rel. err| = {cv['mean_rel_err_mu']:.1%}"
                 + (f"\n{title}" if title else ""), fontsize=9)
    ax.legend(loc="upper left", fontsize=8, markerscale=3)
    fig.tight_layout()
    path = out_dir / f"{prefix}predicted_vs_computed.png"
    fig.savefig(path, dpi=130)
    plt.close(fig)
    paths.append(path)
    return paths
