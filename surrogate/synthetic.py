"""Synthetic friction tables for tests, benchmarks and demos (no EHL solver involved).

* :func:`factorial_inputs` — the paper's factorial levels (docs/reference/dataset-format.md), or a subset, as a table of SI inputs.
* :func:`toy_mu` — a smooth, *illustrative* μ(λ̄, SR, p_h) with a boundary share μ_d e^{−(λ̄/λ0)²} and a film
  share growing with SR and p_h. It is NOT a physical model; it only supplies realistic magnitudes (0.01–0.1) and a
  two-regime shape so that :func:`reference_coefficients` yields coefficient vectors of plausible size.
* :func:`eq9_table` — a table whose ln μ follows the exact Eq. 9a/9b forms with given coefficients plus Gaussian
  noise of known standard deviation: the ground truth for the coefficient-recovery acceptance test.
"""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd

from .features import compute_features
from .fit import fit_params, prepare_table
from .forms import LI_KAHRAMAN_2009, Formula
from .model import branch_ln_mu

PAPER_LEVELS: dict[str, list] = {
    "p_h_gpa": [0.5, 1.0, 1.5, 2.0, 2.5],
    "r_eq_mm": [5, 10, 20, 40, 80],
    "u_r": [1, 2, 5, 10, 15, 20],
    "sr": [0, 0.05, 0.1, 0.2, 0.4, 0.7, 1.0],
    "temp_c": [25, 50, 75, 100],
    "rq_um": [(0.05, 0.05), (0.1, 0.1), (0.2, 0.2), (0.3, 0.3), (0.4, 0.4), (0.5, 0.5), (0.7, 0.7), (1.0, 1.0),
              (0.2, 0.5), (0.4, 1.0)],
}
"""The paper's factorial (docs/reference/dataset-format.md): 5 × 5 × 6 × 7 × 4 × 10 = 42,000 points."""

SMALL_LEVELS: dict[str, list] = {
    "p_h_gpa": [0.5, 1.5, 2.5],
    "r_eq_mm": [5, 20, 80],
    "u_r": [1, 5, 20],
    "sr": [0, 0.05, 0.2, 0.7, 1.0],
    "temp_c": [25, 75, 100],
    "rq_um": [(0.05, 0.05), (0.2, 0.2), (0.5, 0.5), (1.0, 1.0), (0.2, 0.5), (0.4, 1.0)],
}
"""A 3 × 3 × 3 × 5 × 3 × 6 = 2,430-point subset with the corners of the paper's plan, for tests."""


def factorial_inputs(levels: dict[str, list] | None = None) -> pd.DataFrame:
    """Full-factorial table of SI inputs (columns point, p_h, r_eq, u_r, sr, temperature, rq1, rq2)."""
    levels = levels or PAPER_LEVELS
    rows = list(itertools.product(levels["p_h_gpa"], levels["r_eq_mm"], levels["u_r"], levels["sr"],
                                  levels["temp_c"], levels["rq_um"]))
    arr = np.array([(p, r, u, s, t, q[0], q[1]) for p, r, u, s, t, q in rows], dtype=float)
    return pd.DataFrame({
        "point": np.arange(len(arr)),
        "p_h": arr[:, 0] * 1e9, "r_eq": arr[:, 1] * 1e-3, "u_r": arr[:, 2], "sr": arr[:, 3],
        "temperature": arr[:, 4] + 273.15, "rq1": arr[:, 5] * 1e-6, "rq2": arr[:, 6] * 1e-6,
    })


def toy_mu(features: dict[str, np.ndarray], p_h, mu_d: float = 0.1) -> np.ndarray:
    """Illustrative μ (see module docstring): μ_d e^{−(λ̄/0.7)²} + (1 − e^{−(λ̄/0.7)²}) μ_film,
    μ_film = 0.035 (SR/0.2)^0.25 (p_h/1 GPa)^0.2 λ̄^−0.1 (SR floored at 0.01)."""
    lam = features["lam"]
    share = np.exp(-((lam / 0.7) ** 2))
    sr = np.maximum(features["SR"], 0.01)
    mu_film = 0.035 * (sr / 0.2) ** 0.25 * (np.asarray(p_h) / 1e9) ** 0.2 * lam**-0.1
    return mu_d * share + (1.0 - share) * mu_film


def _with_outputs(inputs: pd.DataFrame, mu: np.ndarray, features: dict[str, np.ndarray]) -> pd.DataFrame:
    table = inputs.copy()
    table["mu"] = mu
    table["mu_std"] = 0.0
    table["lambda_bar"] = features["lam"]
    table["converged"] = True
    table["status"] = "ok"
    table["level"] = "synthetic"
    return table


def toy_table(inputs: pd.DataFrame, lubricant, e_reduced: float, mu_d: float = 0.1) -> pd.DataFrame:
    """Dataset-like table with μ from :func:`toy_mu` (SR = 0 rows get the SR-floored value)."""
    f = compute_features(*(inputs[c].to_numpy() for c in ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2")),
                         lubricant, e_reduced)
    return _with_outputs(inputs, toy_mu(f, inputs["p_h"].to_numpy(), mu_d), f)


def reference_coefficients(lubricant, e_reduced: float, formula: Formula = LI_KAHRAMAN_2009,
                           levels: dict[str, list] | None = None) -> dict[str, np.ndarray]:
    """Coefficients of ``formula`` least-squares fitted to :func:`toy_mu` on a factorial: plausible ground truth."""
    prepared = prepare_table(toy_table(factorial_inputs(levels or SMALL_LEVELS), lubricant, e_reduced), lubricant,
                             e_reduced)
    return fit_params(formula, prepared.features, prepared.ln_mu)


def eq9_table(inputs: pd.DataFrame, params: dict[str, np.ndarray], lubricant, e_reduced: float, *,
              noise_sd: float = 0.05, seed: int = 0, formula: Formula = LI_KAHRAMAN_2009) -> pd.DataFrame:
    """Table with ln μ = Eq. 9a (λ̄ ≤ 1) or Eq. 9b (λ̄ > 1) with ``params`` + N(0, noise_sd²), hard switch.

    Rows with SR = 0 (outside Eq. 9, ln SR = −∞) get the value at the smallest positive SR of the table, like a
    solver that returns a finite rolling friction; the fit must exclude and count them.
    """
    sr = np.abs(inputs["sr"].to_numpy(dtype=float))
    sr_min = sr[sr > 0].min()
    f = compute_features(*(inputs[c].to_numpy() for c in ("p_h", "r_eq", "u_r")), np.maximum(sr, sr_min),
                         *(inputs[c].to_numpy() for c in ("temperature", "rq1", "rq2")), lubricant, e_reduced)
    mixed = f["lam"] <= formula.lambda_threshold
    with np.errstate(divide="ignore", invalid="ignore"):
        ln_mu = np.where(mixed, branch_ln_mu(formula.terms["mixed"], params["mixed"], f),
                         branch_ln_mu(formula.terms["full_film"], params["full_film"], f))
    rng = np.random.default_rng(seed)
    ln_mu = ln_mu + rng.normal(0.0, noise_sd, size=ln_mu.shape)
    return _with_outputs(inputs, np.exp(ln_mu), f)


def write_hdf5(table: pd.DataFrame, path, lubricant, *, name: str = "synthetic", level: str = "synthetic"):
    """Write a synthetic table into a stage-1 HDF5 store (:mod:`ehl_dataset.dataset.store`); rows with non-finite μ are
    recorded as failed. For tests and demos of the dataset → coefficient-file path."""
    import math

    from ehl_dataset.dataset.factorial import POINT_DTYPE, POINT_FIELDS
    from ehl_dataset.dataset.store import FAILED, OK, DatasetStore

    points = np.empty(len(table), dtype=POINT_DTYPE)
    for field in POINT_FIELDS:
        points[field] = table[field].to_numpy(dtype=float)
    factorial = {"name": name, "points_sha256": "", "source": "surrogate.synthetic"}
    solver = {"function": "surrogate.synthetic", "version": "1", "level": level, "effects": "none"}
    with DatasetStore.create(path, points, factorial=factorial, solver=solver, lubricant=lubricant.to_json_dict(),
                             overwrite=True) as store:
        for i, row in enumerate(table.itertuples(index=False)):
            if math.isfinite(row.mu):
                record = {"mu": row.mu, "mu_std": 0.0, "lambda_bar": row.lambda_bar, "converged": bool(row.converged),
                          "iterations": 1, "level": level, "effects": {"synthetic": True}}
                store.record(i, status=OK, record=record)
            else:
                store.record(i, status=FAILED, error="synthetic: no mu")
    return path
