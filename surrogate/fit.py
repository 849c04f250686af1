"""Fitting the two-branch ln μ regression (paper Eq. 9a/9b) with statsmodels OLS, with honest diagnostics.

Pipeline (:func:`fit_surrogate`):

1. :func:`prepare_table` computes the features (:mod:`surrogate.features`) and excludes, counting each reason, rows
   that cannot enter a ln μ regression: status other than ``ok``, non-converged solves, μ ≤ 0 or non-finite,
   SR = 0 (ln SR = −∞), smooth surfaces (S_c = 0, λ̄ = ∞) and non-finite features.
2. :func:`fit_branch` fits each branch by OLS on *standardised* columns (zero mean, unit variance; the intercept
   stays 1), which removes the scale part of the ill-conditioning (V̄^r̄ is ~10⁴, ᾱ ln SR ~1), then maps the
   coefficients and their covariance back exactly (β = T β_z, Σ = T Σ_z Tᵀ). It reports the condition number of the
   raw and of the standardised design, the rank (column-pivoted QR), the variance inflation factors and checks that
   the raw-design solve agrees with the standardised one. Rank deficiency raises; a standardised condition number
   above :data:`MAX_STANDARDISED_CONDITION` marks the fit unstable, and :func:`fit_surrogate` refuses to return an
   unstable fit unless ``allow_unstable=True`` (then the flag travels into the coefficient file).
3. k-fold cross-validation of ln μ and μ with the same evaluator the coefficient file uses (including the blend).
4. The jump between the branches at λ̄ = 1 (:func:`branch_jump`).
"""

from __future__ import annotations

import dataclasses

import math
import time
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd
import scipy.linalg
from threadpoolctl import threadpool_limits

from ehl_dataset.validation import InputError, SolverError

from .features import at_lambda_one, compute_features
from .forms import LI_KAHRAMAN_2009, Formula, design_matrix
from .model import branch_ln_mu, predict_ln_mu

MAX_STANDARDISED_CONDITION = 1e8
"""Above this condition number of the standardised design, OLS loses more than 8 of 16 significant digits: unstable."""
HIGH_VIF = 1000.0
"""Variance inflation above this is reported as severe multicollinearity (a warning, not a failure)."""
RAW_AGREEMENT_SE = 1e-2
"""Raw-design and standardised solutions must agree within this many standard errors."""

LAMBDA_COLUMN_RTOL = 1e-3
"""Recomputed and stored λ̄ (same Dowson–Higginson formula) must agree to this relative tolerance, else warn."""

INPUT_COLUMNS = ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2")
RANGE_KEYS = {"p_h": "p_h_pa", "r_eq": "r_eq_m", "u_r": "u_r_m_s", "sr_abs": "sr_abs", "temperature": "temperature_k",
              "rq1": "rq1_m", "rq2": "rq2_m", "lam": "lambda_bar"}
"""Input columns → names of the fitted-range entries in coefficient files (SI units in the suffix)."""


class UnstableFitWarning(UserWarning):
    """The regression is ill-conditioned or severely multicollinear (details in the message)."""


# ---------------------------------------------------------------------------------------------------------------
# Data preparation
# ---------------------------------------------------------------------------------------------------------------
@dataclass
class PreparedTable:
    """Rows usable for the fit, their features, ln μ and the exclusion counts.

    Parameters
    ----------
    table : pandas.DataFrame
        The usable rows [-].
    features : dict of str to ndarray
        Features of those rows (:func:`surrogate.features.compute_features`) [-].
    ln_mu : ndarray
        ln μ of those rows [-].
    exclusions : dict of str to int
        Rows dropped, per reason [-].
    n_input_rows : int
        Rows of the input table [-].
    lambda_column_max_rel_diff : float, optional
        Largest relative difference between the recomputed and the stored λ̄ column [-].
    kept_rows : ndarray, optional
        Positions (0 … n_input_rows − 1) of the usable rows in the input table, in order [-].
    """

    table: pd.DataFrame
    features: dict[str, np.ndarray]
    ln_mu: np.ndarray
    exclusions: dict[str, int]
    n_input_rows: int
    lambda_column_max_rel_diff: float | None = None
    kept_rows: np.ndarray | None = None


def prepare_table(table: pd.DataFrame, lubricant, e_reduced: float) -> PreparedTable:
    """Compute the features and drop, counting each reason, the rows that cannot enter the ln μ regression.

    Reasons in the module docstring.

    Parameters
    ----------
    table : pandas.DataFrame
        Dataset rows with the columns of the HDF5 store (SI units) [-].
    lubricant : Lubricant
        The dataset's lubricant [-].
    e_reduced : float
        Reduced modulus E' [Pa].

    Returns
    -------
    PreparedTable
        The usable rows, their features and ln μ, and the exclusion counts.
    """
    missing = [c for c in (*INPUT_COLUMNS, "mu") if c not in table.columns]
    if missing:
        raise InputError("dataset columns", missing, f"a table with columns {list(INPUT_COLUMNS) + ['mu']}")
    n = len(table)
    keep = np.ones(n, dtype=bool)
    exclusions: dict[str, int] = {}

    def drop(reason: str, bad: np.ndarray):
        bad = np.asarray(bad, dtype=bool) & keep
        exclusions[reason] = int(bad.sum())
        keep[bad] = False

    if "status" in table.columns:
        status = table["status"].astype(str).to_numpy()
        drop("failed", status == "failed")
        drop("not_ok", status != "ok")
    if "converged" in table.columns:
        drop("not_converged", ~table["converged"].astype(bool).to_numpy())
    drop("sr_zero", table["sr"].to_numpy(dtype=float) == 0.0)
    drop("smooth_surfaces", (table["rq1"].to_numpy(dtype=float) <= 0) | (table["rq2"].to_numpy(dtype=float) <= 0))
    mu = table["mu"].to_numpy(dtype=float)
    drop("mu_nonpositive_or_nan", ~(np.isfinite(mu) & (mu > 0)))
    inputs = {c: table[c].to_numpy(dtype=float) for c in INPUT_COLUMNS}
    drop("nonfinite_inputs", ~np.all([np.isfinite(v) for v in inputs.values()], axis=0))
    lo, hi = lubricant.t_min, lubricant.t_max
    drop("temperature_outside_lubricant", (inputs["temperature"] < lo) | (inputs["temperature"] > hi))

    sub = {c: v[keep] for c, v in inputs.items()}
    feats = compute_features(sub["p_h"], sub["r_eq"], sub["u_r"], sub["sr"], sub["temperature"], sub["rq1"],
                             sub["rq2"], lubricant, e_reduced)
    finite = np.all([np.isfinite(feats[k]) for k in ("W", "alpha", "r", "V", "lam", "SR", "Sc", "Seq")], axis=0)
    idx = np.flatnonzero(keep)
    exclusions["nonfinite_features"] = int((~finite).sum())
    keep[idx[~finite]] = False
    feats = {k: v[finite] for k, v in feats.items()}
    used = table.loc[keep].reset_index(drop=True)

    lam_diff = None
    if "lambda_bar" in used.columns and len(used):
        stored = used["lambda_bar"].to_numpy(dtype=float)
        ok = np.isfinite(stored) & (stored > 0)
        if ok.any():
            lam_diff = float(np.max(np.abs(feats["lam"][ok] / stored[ok] - 1.0)))
    return PreparedTable(used, feats, np.log(used["mu"].to_numpy(dtype=float)), exclusions, n, lam_diff,
                         np.flatnonzero(keep))


# ---------------------------------------------------------------------------------------------------------------
# One branch
# ---------------------------------------------------------------------------------------------------------------
@dataclass
class BranchFit:
    """OLS fit of one branch. Arrays are in the order of ``terms``; ``vif`` excludes the intercept.

    Parameters
    ----------
    branch : str
        ``mixed`` (λ̄ ≤ threshold, Eq. 9a) or ``full_film`` (Eq. 9b) [-].
    terms : list of str
        Names of the regression terms [-].
    params : ndarray
        Coefficients [-].
    std_errors : ndarray
        Standard errors of the coefficients [-].
    covariance : ndarray
        Covariance matrix of the coefficients [-].
    r2 : float
        Coefficient of determination of ln μ [-].
    adj_r2 : float
        Adjusted R² [-].
    resid_std_error : float
        Residual standard error of ln μ [-].
    n_obs : int
        Number of rows [-].
    df_resid : int
        Residual degrees of freedom [-].
    condition_number_raw : float
        Condition number of the raw design matrix [-].
    condition_number_standardized : float
        Condition number of the standardised design matrix [-].
    rank : int
        Numerical rank of the standardised design [-].
    vif : dict of str to float
        Variance inflation factor of each non-constant term [-].
    raw_vs_standardized_max_dev_se : float
        Largest difference between the raw-design and the standardised solutions, in standard errors [-].
    lambda_range : tuple of float
        Range of λ̄ in the branch's rows [-].
    summary_text : str
        The statsmodels summary [-].
    messages : list of str
        Stability warnings [-].
    stable : bool
        Whether the branch is numerically stable [-].
    fixed_zero : list of str
        Terms fixed at 0 because ᾱ does not vary in the data [-].
    """

    branch: str
    terms: list[str]
    params: np.ndarray
    std_errors: np.ndarray
    covariance: np.ndarray
    r2: float
    adj_r2: float
    resid_std_error: float
    n_obs: int
    df_resid: int
    condition_number_raw: float
    condition_number_standardized: float
    rank: int
    vif: dict[str, float]
    raw_vs_standardized_max_dev_se: float
    lambda_range: tuple[float, float]
    summary_text: str = ""
    messages: list[str] = field(default_factory=list)
    stable: bool = True
    fixed_zero: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """JSON-serialisable form of the fit as stored in coefficient files.

        Returns
        -------
        dict
            Terms, coefficients, standard errors, statistics and stability flags (floats and lists).
        """
        return {
            "terms": list(self.terms),
            "fixed_zero": list(self.fixed_zero),
            "params": [float(v) for v in self.params],
            "std_errors": [float(v) for v in self.std_errors],
            "r2": float(self.r2),
            "adj_r2": float(self.adj_r2),
            "resid_std_error": float(self.resid_std_error),
            "resid_variance": float(self.resid_std_error) ** 2,
            "covariance": [[float(v) for v in row] for row in self.covariance],
            "n_obs": int(self.n_obs),
            "df_resid": int(self.df_resid),
            "condition_number_raw": float(self.condition_number_raw),
            "condition_number_standardized": float(self.condition_number_standardized),
            "rank": int(self.rank),
            "vif": {k: float(v) for k, v in self.vif.items()},
            "raw_vs_standardized_max_dev_se": float(self.raw_vs_standardized_max_dev_se),
            "lambda_range": [float(v) for v in self.lambda_range],
            "stable": bool(self.stable),
            "messages": list(self.messages),
        }


def _standardise(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Columns scaled to zero mean, unit std; returns (Z, mean, scale) with Z = (X − mean)/scale.

    Constant columns (the intercept) are only scaled by their magnitude (mean 0), and nothing is centred when the
    design has no intercept, so that the back-transformation to raw coefficients is exact.
    """
    mean = x.mean(axis=0)
    scale = x.std(axis=0)
    constant = scale <= 1e-14 * np.maximum(np.abs(mean), 1.0)
    magnitude = np.abs(x[0]) if x.shape[0] else np.ones(x.shape[1])
    scale = np.where(constant, np.where(magnitude > 0, magnitude, 1.0), scale)
    mean = np.where(constant, 0.0, mean)
    if _intercept_column(x) is None:
        mean = np.zeros_like(mean)
    return (x - mean) / scale, mean, scale


def _back_transform(mean: np.ndarray, scale: np.ndarray, intercept_col: int | None) -> np.ndarray:
    """Matrix T with β_raw = T β_z for the model y = Z β_z, Z = (X − m)/s (intercept column stays 1)."""
    k = mean.size
    t = np.diag(1.0 / scale)
    if intercept_col is not None:
        t[intercept_col, intercept_col] = 1.0
        for j in range(k):
            if j != intercept_col:
                t[intercept_col, j] = -mean[j] / scale[j]
    return t


def rank_and_dependent_terms(z: np.ndarray, names: list[str], rtol: float = 1e-10) -> tuple[int, list[str]]:
    """Numerical rank of the standardised design by column-pivoted QR and the terms that are linearly dependent."""
    _, r, piv = scipy.linalg.qr(z, mode="economic", pivoting=True)
    diag = np.abs(np.diag(r))
    rank = int(np.sum(diag > rtol * diag[0]))
    return rank, [names[i] for i in piv[rank:]]


def variance_inflation(z: np.ndarray, names: list[str]) -> dict[str, float]:
    """VIF_j = 1/(1 − R_j²) of each non-constant column, from the diagonal of the inverse correlation matrix.

    Equivalent to statsmodels' ``variance_inflation_factor`` on a design that includes the intercept.
    """
    cols = [j for j in range(z.shape[1]) if np.std(z[:, j]) > 0]
    if len(cols) < 2:
        return {names[j]: 1.0 for j in cols}
    corr = np.corrcoef(z[:, cols], rowvar=False)
    inv = np.linalg.pinv(corr, hermitian=True)
    return {names[j]: float(inv[i, i]) for i, j in enumerate(cols)}


def solve_standardised(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Least-squares coefficients of the raw design solved on standardised columns (fast path for CV)."""
    z, mean, scale = _standardise(x)
    intercept = _intercept_column(x)
    beta_z, *_ = np.linalg.lstsq(z, y, rcond=None)
    return _back_transform(mean, scale, intercept) @ beta_z


def _intercept_column(x: np.ndarray) -> int | None:
    hits = [j for j in range(x.shape[1]) if np.all(x[:, j] == 1.0)]
    return hits[0] if hits else None


def fit_branch(x: np.ndarray, y: np.ndarray, names: list[str], branch: str, lam: np.ndarray | None = None,
               max_condition: float = MAX_STANDARDISED_CONDITION, fixed_zero: tuple[str, ...] = ()) -> BranchFit:
    """OLS fit of ln μ on one branch's design matrix with statsmodels (see module docstring for the checks).
    ``max_condition``: condition number of the standardised design above which the branch is unstable.
    ``fixed_zero``: terms whose coefficient is fixed at 0 (not fitted; :func:`alpha_terms_to_fix`): they are left
    out of the regression and reported with coefficient and standard error 0.

    BLAS runs single-threaded here: the matrices are thin (n × 10–14) and multi-threaded SVDs were measured 10×
    slower on a loaded 2-core machine.
    """
    keep = [j for j, name in enumerate(names) if name not in fixed_zero]
    with threadpool_limits(1):
        fit = _fit_branch(x[:, keep], y, [names[j] for j in keep], branch, lam, max_condition)
    if len(keep) == len(names):
        return fit
    k = len(names)
    params, errors, cov = np.zeros(k), np.zeros(k), np.zeros((k, k))
    params[keep], errors[keep] = fit.params, fit.std_errors
    cov[np.ix_(keep, keep)] = fit.covariance
    return dataclasses.replace(fit, terms=list(names), params=params, std_errors=errors, covariance=cov,
                               fixed_zero=[n for n in names if n in fixed_zero])


ALPHA_CONSTANT_RTOL = 1e-9
"""Relative spread of ᾱ over a dataset below which the lubricant's α1 is taken as temperature independent."""


def alpha_terms_to_fix(formula: Formula, branch: str, features: dict[str, np.ndarray]) -> tuple[str, ...]:
    """Terms of ``branch`` to fix at 0 because ᾱ does not vary: with ᾱ constant over the dataset (a lubricant whose
    α1 does not depend on temperature, e.g. one Barus α) the terms that contain it lose their own variable —
    ᾱ ln SR is a multiple of ln SR whatever the factorial, ᾱ^W̄ and ᾱ^r̄ are functions of W̄ and r̄ alone, which the
    factorial's levels may not separate from the other terms (Eq. 9b). Each such term that adds no rank to the
    standardised design (column-pivoted QR, the α terms added one by one after the others) is fixed at 0: the
    fitted function is unchanged, its coefficients become identifiable. Empty when ᾱ varies; a dependent term
    without ᾱ still stops the fit (:func:`fit_branch`)."""
    alpha = np.asarray(features["alpha"], dtype=float)
    if alpha.size == 0 or np.ptp(alpha) > ALPHA_CONSTANT_RTOL * max(float(np.max(np.abs(alpha))), 1e-300):
        return ()
    names = formula.term_names(branch)
    alpha_terms = [n for n in names if "alpha" in n]
    if not alpha_terms:
        return ()
    others = [n for n in names if n not in alpha_terms]
    z, _, _ = _standardise(design_matrix(formula.terms[branch], features))
    order = [names.index(n) for n in others + alpha_terms]
    fixed = []
    for count in range(len(alpha_terms)):  # add the α terms one by one; fix each that adds no rank
        kept = [j for j in order[: len(others) + count + 1] if names[j] not in fixed]
        rank, _ = rank_and_dependent_terms(z[:, kept], [names[j] for j in kept])
        if rank < len(kept):
            fixed.append(alpha_terms[count])
    return tuple(fixed)


def _fit_branch(x, y, names, branch, lam, max_condition) -> BranchFit:
    import statsmodels.api as sm

    n, k = x.shape
    if n <= k:
        raise SolverError(f"branch {branch}: {n} usable rows for {k} coefficients; need more data in this branch")
    z, mean, scale = _standardise(x)
    intercept = _intercept_column(x)
    rank, dependent = rank_and_dependent_terms(z, names)
    if rank < k:
        raise SolverError(f"branch {branch}: design matrix has rank {rank} < {k}; the data cannot separate the "
                          f"terms {dependent} from the others (add factorial levels or drop terms)")
    result_z = sm.OLS(y, z).fit()
    t = _back_transform(mean, scale, intercept)
    params = t @ result_z.params
    cov = t @ result_z.cov_params() @ t.T
    std_errors = np.sqrt(np.diag(cov))
    cond_raw = float(np.linalg.cond(x))
    cond_z = float(np.linalg.cond(z))
    vif = variance_inflation(z, names)

    result_raw = sm.OLS(y, x).fit()
    deviation = float(np.max(np.abs(result_raw.params - params) / std_errors))
    try:
        summary = result_raw.summary(xname=names, yname="ln(mu)", title=f"ln mu regression, branch {branch}")
        summary_text = summary.as_text()
    except Exception as err:  # statsmodels summary can fail on pathological data; the fit itself stands
        summary_text = f"(statsmodels summary unavailable: {err})"

    messages = []
    stable = True
    if cond_z > max_condition:
        stable = False
        messages.append(f"condition number of the standardised design {cond_z:.3g} > "
                        f"{max_condition:.0e}: coefficients are numerically unreliable")
    if deviation > RAW_AGREEMENT_SE:
        stable = False
        messages.append(f"raw-design and standardised solutions differ by {deviation:.3g} standard errors")
    severe = {name: v for name, v in vif.items() if v > HIGH_VIF}
    if severe:
        worst = max(severe, key=severe.get)
        messages.append(f"severe multicollinearity: {len(severe)} terms with VIF > {HIGH_VIF:g} "
                        f"(worst {worst}: {severe[worst]:.3g}); individual coefficients are poorly determined "
                        f"although predictions may be fine")
    lam_range = (float(np.min(lam)), float(np.max(lam))) if lam is not None and len(lam) else (math.nan, math.nan)
    return BranchFit(
        branch=branch, terms=list(names), params=params, std_errors=std_errors, covariance=cov,
        r2=float(result_z.rsquared), adj_r2=float(result_z.rsquared_adj),
        resid_std_error=float(np.sqrt(result_z.scale)), n_obs=int(n), df_resid=int(result_z.df_resid),
        condition_number_raw=cond_raw, condition_number_standardized=cond_z, rank=rank, vif=vif,
        raw_vs_standardized_max_dev_se=deviation, lambda_range=lam_range, summary_text=summary_text,
        messages=messages, stable=stable,
    )


# ---------------------------------------------------------------------------------------------------------------
# Metrics, cross-validation and the jump at λ̄ = 1
# ---------------------------------------------------------------------------------------------------------------
def error_metrics(ln_mu_true: np.ndarray, ln_mu_pred: np.ndarray) -> dict[str, float]:
    """Errors of predicted ln μ and μ against the true values.

    Parameters
    ----------
    ln_mu_true : ndarray
        True ln μ [-].
    ln_mu_pred : ndarray
        Predicted ln μ [-].

    Returns
    -------
    dict of str to float
        ``n``; RMSE, MAE and bias of ln μ; R² of ln μ; RMSE of μ; mean, median and 95th-percentile relative error
        of μ.
    """
    ln_mu_true = np.asarray(ln_mu_true, dtype=float)
    ln_mu_pred = np.asarray(ln_mu_pred, dtype=float)
    resid = ln_mu_pred - ln_mu_true
    mu_t, mu_p = np.exp(ln_mu_true), np.exp(ln_mu_pred)
    rel = np.abs(mu_p / mu_t - 1.0)
    ss_tot = float(np.sum((ln_mu_true - ln_mu_true.mean()) ** 2))
    return {
        "n": int(resid.size),
        "rmse_ln_mu": float(np.sqrt(np.mean(resid**2))),
        "mae_ln_mu": float(np.mean(np.abs(resid))),
        "bias_ln_mu": float(np.mean(resid)),
        "r2_ln_mu": float(1.0 - np.sum(resid**2) / ss_tot) if ss_tot > 0 else math.nan,
        "rmse_mu": float(np.sqrt(np.mean((mu_p - mu_t) ** 2))),
        "mean_rel_err_mu": float(np.mean(rel)),
        "median_rel_err_mu": float(np.median(rel)),
        "p95_rel_err_mu": float(np.percentile(rel, 95)),
    }


def branch_masks(lam: np.ndarray, threshold: float) -> dict[str, np.ndarray]:
    """Row masks of the two branches (λ̄ ≤ threshold: mixed, λ̄ > threshold: full film)."""
    return {"mixed": lam <= threshold, "full_film": lam > threshold}


def fit_params(formula: Formula, features: dict[str, np.ndarray], ln_mu: np.ndarray) -> dict[str, np.ndarray]:
    """Least-squares coefficients of both branches (fast path without statistics; used inside CV)."""
    with threadpool_limits(1):
        return _fit_params(formula, features, ln_mu)


def _fit_params(formula, features, ln_mu):
    masks = branch_masks(features["lam"], formula.lambda_threshold)
    out = {}
    for branch, mask in masks.items():
        sub = {k: v[mask] for k, v in features.items()}
        x = design_matrix(formula.terms[branch], sub)
        if x.shape[0] <= x.shape[1]:
            raise SolverError(f"branch {branch}: {x.shape[0]} rows for {x.shape[1]} coefficients in a CV fold")
        out[branch] = solve_standardised(x, ln_mu[mask])
    return out


def cross_validate(formula: Formula, features: dict[str, np.ndarray], ln_mu: np.ndarray, *, k_folds: int = 5,
                   seed: int = 0, blend_half_width: float = 0.0) -> dict[str, Any]:
    """k-fold cross-validation of the two-branch model: out-of-fold ln μ predictions and their errors.

    Parameters
    ----------
    formula : Formula
        Regression form [-].
    features : dict of str to ndarray
        Features of the rows [-].
    ln_mu : ndarray
        ln μ of the rows [-].
    k_folds : int
        Number of folds (rows shuffled with ``seed``) [-].
    seed : int
        Seed of the shuffle [-].
    blend_half_width : float
        Half width δ of the branch blend band in λ̄, as the evaluator uses it [-].

    Returns
    -------
    dict
        :func:`error_metrics` overall and per branch (``mixed``, ``full_film``), and the out-of-fold predictions
        under ``_predictions``.
    """
    from sklearn.model_selection import KFold

    n = ln_mu.size
    if k_folds < 2 or n < 2 * k_folds:
        raise InputError("k_folds", k_folds, f"an integer in [2, {max(2, n // 2)}] for {n} rows")
    pred = np.empty(n)
    for train, test in KFold(k_folds, shuffle=True, random_state=seed).split(np.arange(n)):
        params = fit_params(formula, {k: v[train] for k, v in features.items()}, ln_mu[train])
        pred[test] = predict_ln_mu(formula, params, {k: v[test] for k, v in features.items()}, blend_half_width)
    out = {"k": int(k_folds), "seed": int(seed), "blend_half_width": float(blend_half_width),
           "overall": error_metrics(ln_mu, pred)}
    for branch, mask in branch_masks(features["lam"], formula.lambda_threshold).items():
        out[branch] = error_metrics(ln_mu[mask], pred[mask]) if mask.any() else {"n": 0}
    return out | {"_predictions": pred}


def branch_jump(formula: Formula, params: dict[str, np.ndarray], features: dict[str, np.ndarray],
                lambda_window: tuple[float, float] = (0.5, 2.0)) -> dict[str, float]:
    """Jump Δ = ln μ_9b − ln μ_9a at λ̄ = 1 over the fitted conditions.

    Each row with λ̄ in ``lambda_window`` (so its roughness needs scaling by at most ×2 to reach λ̄ = 1, staying near
    the data) is moved to λ̄ = 1 (:func:`surrogate.features.at_lambda_one`) and both branches are evaluated there.

    Parameters
    ----------
    formula : Formula
        Regression form [-].
    params : dict of str to ndarray
        Coefficients per branch [-].
    features : dict of str to ndarray
        Features of the fitted rows [-].
    lambda_window : tuple of float
        λ̄ range of the rows moved to λ̄ = 1 [-].

    Returns
    -------
    dict of str to float
        ``n`` rows used and statistics of |Δ| (median, 95th percentile, maximum, mean Δ) with the corresponding
        ratio μ_9b/μ_9a.
    """
    lam = features["lam"]
    sel = (lam >= lambda_window[0]) & (lam <= lambda_window[1])
    if not sel.any():
        return {"n": 0}
    at_one = at_lambda_one({k: v[sel] for k, v in features.items()})
    delta = (branch_ln_mu(formula.terms["full_film"], params["full_film"], at_one)
             - branch_ln_mu(formula.terms["mixed"], params["mixed"], at_one))
    mag = np.abs(delta)
    return {
        "n": int(sel.sum()),
        "lambda_window": [float(v) for v in lambda_window],
        "median_abs_delta_ln_mu": float(np.median(mag)),
        "p95_abs_delta_ln_mu": float(np.percentile(mag, 95)),
        "max_abs_delta_ln_mu": float(np.max(mag)),
        "mean_delta_ln_mu": float(np.mean(delta)),
        "median_abs_rel_jump_mu": float(np.median(np.abs(np.expm1(delta)))),
        "p95_abs_rel_jump_mu": float(np.percentile(np.abs(np.expm1(delta)), 95)),
    }


# ---------------------------------------------------------------------------------------------------------------
# The whole surrogate
# ---------------------------------------------------------------------------------------------------------------
@dataclass
class SurrogateFit:
    """Result of :func:`fit_surrogate`: both branch fits plus everything a coefficient file records.

    Parameters
    ----------
    formula : Formula
        The fitted regression form [-].
    branches : dict of str to BranchFit
        Fit of each branch (``mixed``, ``full_film``) [-].
    exclusions : dict of str to int
        Rows excluded from the fit, per reason [-].
    n_input_rows : int
        Rows of the input table [-].
    n_used : int
        Rows used by the fit [-].
    input_ranges : dict of str to list
        Fitted (low, high) of each input, keyed with the unit in the name (``p_h_pa``, ...) [-].
    sr_floor : float
        Smallest |SR| of the fitted rows [-].
    blend_half_width : float
        Half width δ of the branch blend band in λ̄ [-].
    cv : dict
        Cross-validation errors (:func:`cross_validate`) [-].
    jump : dict of str to float
        Jump between the branches at λ̄ = 1 (:func:`branch_jump`) [-].
    fit_time_s : float
        Wall time of the fit [s].
    e_reduced : float
        Reduced modulus E' of the dataset [Pa].
    lubricant : dict
        The lubricant's definition (provenance) [-].
    stable : bool
        Whether both branches are numerically stable [-].
    lambda_column_max_rel_diff : float, optional
        Largest relative difference between the recomputed and the stored λ̄ column [-].
    prepared : PreparedTable, optional
        The prepared table the fit used [-].
    cv_predictions : ndarray, optional
        Out-of-fold ln μ predictions of the used rows [-].
    """

    formula: Formula
    branches: dict[str, BranchFit]
    exclusions: dict[str, int]
    n_input_rows: int
    n_used: int
    input_ranges: dict[str, list[float]]
    sr_floor: float
    blend_half_width: float
    cv: dict[str, Any]
    jump: dict[str, float]
    fit_time_s: float
    e_reduced: float
    lubricant: dict[str, Any]
    stable: bool
    lambda_column_max_rel_diff: float | None = None
    prepared: PreparedTable | None = field(default=None, repr=False)
    cv_predictions: np.ndarray | None = field(default=None, repr=False)
    """Out-of-fold ln μ predictions for the rows of ``prepared`` (diagnostics)."""

    @property
    def params(self) -> dict[str, np.ndarray]:
        return {b: f.params for b, f in self.branches.items()}



def fit_surrogate(table: pd.DataFrame, lubricant, e_reduced: float, *, formula: Formula = LI_KAHRAMAN_2009,
                  k_folds: int = 5, seed: int = 0, blend_half_width: float = 0.1,
                  allow_unstable: bool = False, max_condition: float = MAX_STANDARDISED_CONDITION) -> SurrogateFit:
    """Fit both branches of ``formula`` (paper Eq. 9a/9b) on a dataset table by OLS, with cross-validation.

    Steps in the module docstring. Always emits :class:`UnstableFitWarning` with the reasons when a branch is
    ill-conditioned or severely multicollinear.

    Parameters
    ----------
    table : pandas.DataFrame
        Dataset rows with the columns of the HDF5 store (SI units: ``p_h`` [Pa], ``r_eq`` [m], ``u_r`` [m/s], ``sr``,
        ``temperature`` [K], ``rq1``, ``rq2`` [m], ``mu``, ``status``, ``converged``) [-].
    lubricant : Lubricant
        The lubricant of the dataset (η0 and α1 of the features) [-].
    e_reduced : float
        Reduced modulus E' of the dataset's contacts [Pa].
    formula : Formula
        Regression form; default the paper's Eq. 9a/9b [-].
    k_folds : int
        Number of cross-validation folds [-].
    seed : int
        Seed of the fold shuffle [-].
    blend_half_width : float
        Half width δ of the λ̄ band in which the evaluator blends the branches (0: the paper's hard switch) [-].
    allow_unstable : bool
        Return an unstable fit (flagged) instead of raising [-].
    max_condition : float
        Largest accepted condition number of a standardised design [-].

    Returns
    -------
    SurrogateFit
        Both branch fits, cross-validation errors, the branch jump and everything a coefficient file records.

    Raises
    ------
    SolverError
        For a rank-deficient branch, or an unstable one unless ``allow_unstable``.
    """
    if not 0.0 <= blend_half_width < 0.5:
        raise InputError("blend_half_width", blend_half_width, "[0, 0.5)")
    start = time.perf_counter()
    prepared = prepare_table(table, lubricant, e_reduced)
    feats, ln_mu = prepared.features, prepared.ln_mu
    masks = branch_masks(feats["lam"], formula.lambda_threshold)
    branches = {}
    for branch, mask in masks.items():
        sub = {k: v[mask] for k, v in feats.items()}
        x = design_matrix(formula.terms[branch], sub)
        fixed = alpha_terms_to_fix(formula, branch, sub)
        if fixed:
            warnings.warn(f"branch {branch}: the pressure-viscosity coefficient is the same at every temperature of "
                          f"the dataset, so the terms {list(fixed)} are multiples of the others: fixed at 0",
                          UserWarning, stacklevel=2)
        branches[branch] = fit_branch(x, ln_mu[mask], formula.term_names(branch), branch, sub["lam"], max_condition,
                                      fixed)
    stable = all(f.stable for f in branches.values())
    if prepared.lambda_column_max_rel_diff is not None and prepared.lambda_column_max_rel_diff > LAMBDA_COLUMN_RTOL:
        warnings.warn(f"lambda_bar recomputed from the inputs differs from the dataset's lambda_bar column by up to "
                      f"{prepared.lambda_column_max_rel_diff:.2%}: is the lubricant or E' the one the dataset was "
                      f"computed with?", UserWarning, stacklevel=2)
    for f in branches.values():
        if f.messages:
            warnings.warn(f"branch {f.branch}: " + "; ".join(f.messages), UnstableFitWarning, stacklevel=2)
    if not stable and not allow_unstable:
        reasons = "; ".join(f"{f.branch}: {m}" for f in branches.values() for m in f.messages)
        raise SolverError(f"unstable regression ({reasons}); pass allow_unstable=True (--allow-unstable) to keep it")
    fit_time = time.perf_counter() - start
    params = {b: f.params for b, f in branches.items()}
    cv = cross_validate(formula, feats, ln_mu, k_folds=k_folds, seed=seed, blend_half_width=blend_half_width)
    cv_predictions = cv.pop("_predictions")
    jump = branch_jump(formula, params, feats)
    used = prepared.table
    ranges = {}
    for column, key in RANGE_KEYS.items():
        values = (np.abs(used["sr"].to_numpy(dtype=float)) if column == "sr_abs"
                  else feats["lam"] if column == "lam" else used[column].to_numpy(dtype=float))
        ranges[key] = [float(np.min(values)), float(np.max(values))]
    return SurrogateFit(
        formula=formula, branches=branches, exclusions=prepared.exclusions, n_input_rows=prepared.n_input_rows,
        n_used=int(ln_mu.size), input_ranges=ranges, sr_floor=ranges["sr_abs"][0],
        blend_half_width=float(blend_half_width), cv=cv, jump=jump, fit_time_s=fit_time, e_reduced=float(e_reduced),
        lubricant=lubricant.to_json_dict(), stable=stable,
        lambda_column_max_rel_diff=prepared.lambda_column_max_rel_diff, prepared=prepared,
        cv_predictions=cv_predictions,
    )
