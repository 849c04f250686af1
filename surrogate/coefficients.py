"""Coefficient files: the portable result of a surrogate fit (JSON, no pickles; docs/explanation/surrogate.md).

Layout (``format = "gearloss.friction_coefficients"``, ``format_version = 2``), all quantities SI:

* ``form``: ``eq9`` (the paper's regression, below) or ``learned`` (an ensemble of small perceptrons,
  :mod:`surrogate.mlp`: ``learned`` holds its weights, scaling and calibrated interval; ``formula`` names it and
  there is no ``branches``). Both forms take the same inputs and record the same ``input_ranges``, ``evaluation``,
  ``lubricant`` and ``cross_validation``, so stage 3 swaps one for the other;
* ``formula``: ``name``, ``version``, ``reference``, ``lambda_threshold`` — must match the term registry in
  :mod:`surrogate.forms`;
* ``branches.mixed`` / ``branches.full_film``: ``terms`` (registry names), ``expressions``, ``params``,
  ``std_errors``, ``covariance`` (of the coefficients, k × k), ``resid_variance``, ``r2``, ``adj_r2``,
  ``resid_std_error``, ``n_obs``, ``df_resid``, condition numbers, ``rank``, ``vif``, ``lambda_range``, ``stable``,
  ``messages`` — ``covariance``, ``resid_variance`` and ``df_resid`` give the prediction interval
  (:mod:`surrogate.intervals`);
* ``offgrid`` (optional): the errors of μ on a seeded random sample of contacts inside the fitted ranges, solved by
  the route of the dataset (:mod:`surrogate.offgrid`), and the coverage of the 90 % intervals there;
* ``interval_calibration`` (optional, Eq. 9 only): ``method``, ``calibration_rows`` and ``score_quantiles``
  ({branch: {coverage: q}}): split-conformal factors that replace Student's t in the statsmodels interval
  (:mod:`surrogate.intervals`), computed on the even rows of the off-grid sample; without it the interval is the
  plain statsmodels one;
* ``evaluation``: ``blend_half_width`` (δ of the λ̄ blend band), ``sr_floor`` (|SR| below it is evaluated at it);
* ``cross_validation`` (k-fold errors of ln μ and μ), ``jump_at_threshold``, ``exclusions``, ``n_input_rows``,
  ``n_used``, ``input_ranges`` ({name: [min, max]} seen in the fitted data), ``stable``;
* ``lubricant`` (the lubricant definition, rebuilt with ``lubricant_from_dict``), ``e_reduced_pa``;
* ``source``: ``path``, ``sha256`` of the dataset file, ``n_points``, ``accuracy_level``, ``description``;
* ``roughness`` (optional): ``name`` and ``sha256`` of the roughness profile of the fitted dataset, copied from its
  HDF5 file (:mod:`ehl_dataset.model.roughness_identity`); absent where the dataset records none (older datasets,
  CSV tables): reports say "not recorded";
* ``package_version``, ``created_utc``;
* ``content_sha256``: SHA-256 of the canonical JSON (sorted keys, compact) of everything else. A file edited
  after writing fails this check; to change a file deliberately, refit.

The statsmodels summaries are written beside the file as ``NAME.summary.txt``.
:func:`load_coefficients` validates everything and raises :class:`InputError` naming the offending field. Files of
format version 1 (no ``form``, no ``covariance``/``resid_variance``) load as Eq. 9 without prediction intervals;
a newer format version than this gearloss reads is refused.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ehl_dataset.model.lubricant import Lubricant, lubricant_from_dict
from ehl_dataset.model.roughness_identity import check_roughness_record
from ehl_dataset.validation import InputError

from .diagnostics import summary_text
from .fit import RANGE_KEYS, SurrogateFit
from .forms import BRANCHES, FORMULAS, Formula

FORMAT = "gearloss.friction_coefficients"
FORMAT_VERSION = 2
READABLE_VERSIONS = (1, 2)
"""Format versions this gearloss reads (1: Eq. 9 without the covariance, so without prediction intervals)."""
FORMS = ("eq9", "learned")
SUMMARY_SUFFIX = ".summary.txt"


def package_version() -> str:
    try:
        from importlib.metadata import version

        return version("gearloss")
    except Exception:  # pragma: no cover - running from a tree without metadata
        return "unknown"


def file_sha256(path: str | Path) -> str:
    """SHA-256 hex digest of a file's bytes (the dataset hash recorded in coefficient files)."""
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _clean(value: Any) -> Any:
    """JSON-safe copy: numpy scalars/arrays → Python, non-finite floats → None."""
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if isinstance(value, np.ndarray):
        return _clean(value.tolist())
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        number = float(value)
        return number if math.isfinite(number) else None
    return value


def content_hash(payload: dict[str, Any]) -> str:
    """SHA-256 of the canonical JSON of ``payload`` without its ``content_sha256`` entry."""
    body = {k: v for k, v in payload.items() if k != "content_sha256"}
    text = json.dumps(body, sort_keys=True, separators=(",", ":"), ensure_ascii=True, allow_nan=False)
    return hashlib.sha256(text.encode("ascii")).hexdigest()


def coefficients_payload(fit, *, source: dict[str, Any] | None = None,
                         offgrid: dict[str, Any] | None = None,
                         roughness: dict[str, str] | None = None) -> dict[str, Any]:
    """The JSON document (as a dict, hash included) describing ``fit``.

    Parameters
    ----------
    fit : SurrogateFit or LearnedFit
        An Eq. 9 fit (:func:`surrogate.fit.fit_surrogate`) or a learned one
        (:func:`surrogate.learned_fit.fit_learned`).
    source : dict, optional
        Provenance of the dataset [-].
    offgrid : dict, optional
        Off-grid validation (:func:`surrogate.offgrid.offgrid_report`) [-].
    roughness : dict, optional
        ``{"name", "sha256"}`` of the dataset's roughness profile, written as the ``roughness`` key (None: no key) [-].

    Returns
    -------
    dict
        The document, ``content_sha256`` included.
    """
    from .learned_fit import LearnedFit

    roughness = check_roughness_record(roughness, "roughness")
    if isinstance(fit, LearnedFit):
        return _finish(_with_roughness(_learned_payload(fit, source, offgrid), roughness))
    branches = {}
    for name, branch in fit.branches.items():
        entry = branch.to_dict()
        entry["expressions"] = [t.expression for t in fit.formula.terms[name]]
        entry["condition"] = (f"lambda_bar <= {fit.formula.lambda_threshold:g}" if name == "mixed"
                              else f"lambda_bar > {fit.formula.lambda_threshold:g}")
        branches[name] = entry
    payload = {
        "format": FORMAT,
        "format_version": FORMAT_VERSION,
        "form": "eq9",
        "formula": {"name": fit.formula.name, "version": fit.formula.version, "reference": fit.formula.reference,
                    "lambda_threshold": fit.formula.lambda_threshold, "response": "ln(mu)"},
        "branches": branches,
        "evaluation": {
            "blend_half_width": fit.blend_half_width,
            "sr_floor": fit.sr_floor,
            "notes": "ln mu blended with a smoothstep over lambda_bar in [1 - d, 1 + d] (d = blend_half_width); "
                     "|SR| below sr_floor is evaluated at sr_floor; inputs outside input_ranges warn",
        },
        "cross_validation": fit.cv,
        "jump_at_threshold": fit.jump,
        "exclusions": fit.exclusions,
        "n_input_rows": fit.n_input_rows,
        "n_used": fit.n_used,
        "input_ranges": fit.input_ranges,
        "stable": fit.stable,
        "lambda_column_max_rel_diff": fit.lambda_column_max_rel_diff,
        "fit_time_s": fit.fit_time_s,
        "lubricant": fit.lubricant,
        "e_reduced_pa": fit.e_reduced,
        "source": source or {},
        "package_version": package_version(),
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    }
    if offgrid is not None:
        payload["offgrid"] = offgrid
    return _finish(_with_roughness(payload, roughness))


def _with_roughness(payload: dict[str, Any], roughness: dict[str, str] | None) -> dict[str, Any]:
    if roughness is not None:
        payload["roughness"] = roughness
    return payload


def _finish(payload: dict[str, Any]) -> dict[str, Any]:
    payload = _clean(payload)
    payload["content_sha256"] = content_hash(payload)
    return payload


def _learned_payload(fit, source, offgrid) -> dict[str, Any]:
    from .learned_fit import LAMBDA_THRESHOLD, LEARNED_FORMULA_NAME, LEARNED_FORMULA_VERSION

    payload = {
        "format": FORMAT,
        "format_version": FORMAT_VERSION,
        "form": "learned",
        "formula": {"name": LEARNED_FORMULA_NAME, "version": LEARNED_FORMULA_VERSION,
                    "reference": "ensemble of ReLU perceptrons on the Eq. 9 features (surrogate/mlp.py)",
                    "lambda_threshold": LAMBDA_THRESHOLD, "response": "ln(mu)"},
        "learned": fit.ensemble.to_dict() | {"settings": fit.result.settings},
        "evaluation": {
            "blend_half_width": 0.0,
            "sr_floor": fit.sr_floor,
            "notes": "ln mu = mean of the members; |SR| below sr_floor is evaluated at sr_floor; inputs outside "
                     "input_ranges warn (or are clipped)",
        },
        "cross_validation": fit.cv,
        "exclusions": fit.exclusions,
        "n_input_rows": fit.n_input_rows,
        "n_used": fit.n_used,
        "input_ranges": fit.input_ranges,
        "stable": True,
        "fit_time_s": fit.fit_time_s,
        "lubricant": fit.lubricant,
        "e_reduced_pa": fit.e_reduced,
        "source": source or {},
        "package_version": package_version(),
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    }
    if offgrid is not None:
        payload["offgrid"] = offgrid
    return payload


def summary_path(path: str | Path) -> Path:
    path = Path(path)
    return path.with_name(path.stem + SUMMARY_SUFFIX)


def write_coefficients(fit, path: str | Path, *, source: dict[str, Any] | None = None,
                       offgrid: dict[str, Any] | None = None, roughness: dict[str, str] | None = None) -> Path:
    """Write the coefficient file (JSON) and its summary beside it.

    Parameters
    ----------
    fit : SurrogateFit or LearnedFit
        The fit to write [-].
    path : str or Path
        Path of the JSON file, ``NAME.json`` [-].
    source : dict, optional
        Provenance of the dataset [-].
    offgrid : dict, optional
        Off-grid validation of the fit [-].
    roughness : dict, optional
        ``{"name", "sha256"}`` of the dataset's roughness profile (:attr:`surrogate.dataset_io.Dataset.roughness`);
        None: not recorded [-].

    Returns
    -------
    Path
        The JSON path.
    """
    from .learned_fit import LearnedFit, learned_summary_text

    path = Path(path)
    if path.suffix != ".json":
        raise InputError("out", str(path), "a file name ending in .json")
    path.parent.mkdir(parents=True, exist_ok=True)
    payload = coefficients_payload(fit, source=source, offgrid=offgrid, roughness=roughness)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(payload, indent=1, sort_keys=True, allow_nan=False) + "\n", encoding="utf-8")
    tmp.replace(path)
    text = learned_summary_text(fit) if isinstance(fit, LearnedFit) else summary_text(fit)
    summary_path(path).write_text(text + "\n", encoding="utf-8")
    return path


def record_offgrid(path: str | Path, offgrid: dict[str, Any], *, learned_interval: dict | None = None,
                   interval_calibration: dict | None = None) -> Path:
    """Add (or replace) the ``offgrid`` table of an existing coefficient file, re-hashing its content.

    Parameters
    ----------
    path : str or Path
        The coefficient file (validated before and after it is rewritten) [-].
    offgrid : dict
        The off-grid validation (:func:`surrogate.offgrid.offgrid_report`) [-].
    learned_interval : dict, optional
        A learned file's recalibrated ``learned.interval`` table (``workflows.surrogate_stage``) [-].
    interval_calibration : dict, optional
        An Eq. 9 file's ``interval_calibration`` table (:func:`surrogate.offgrid.eq9_interval_calibration`) [-].

    Returns
    -------
    Path
        The path.
    """
    path = Path(path)
    doc = load_coefficients(path).document
    body = {k: v for k, v in doc.items() if k != "content_sha256"}
    if learned_interval is not None:
        body["learned"] = {**body["learned"], "interval": learned_interval}
    if interval_calibration is not None:
        body["interval_calibration"] = interval_calibration
    doc = _finish({**body, "offgrid": offgrid})
    validate_coefficients(doc, str(path))
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(doc, indent=1, sort_keys=True, allow_nan=False) + "\n", encoding="utf-8")
    tmp.replace(path)
    return path


# ---------------------------------------------------------------------------------------------------------------
# Loading and validation
# ---------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CoefficientSet:
    """A validated coefficient file: what the evaluator needs, plus the raw document.

    Parameters
    ----------
    formula : Formula
        The regression form (terms of both branches, λ̄ threshold) [-].
    params : dict of str to ndarray
        Coefficients per branch (``mixed``, ``full_film``), in the order of the formula's terms [-].
    std_errors : dict of str to ndarray
        Standard errors of the coefficients per branch [-].
    blend_half_width : float
        Half width δ of the λ̄ band over which the evaluator blends the branches (0: the paper's hard switch) [-].
    sr_floor : float
        Smallest |SR| of the fitted data; smaller |SR| is evaluated there [-].
    input_ranges : dict of str to tuple
        Fitted range (low, high) of each input, keyed ``p_h_pa``, ``r_eq_m``, ``u_r_m_s``, ``sr_abs``,
        ``temperature_k``, ``rq1_m``, ``rq2_m`` and ``lambda_bar`` (units in the key) [-].
    lubricant : Lubricant
        The lubricant the coefficients were fitted for [-].
    e_reduced : float
        Reduced modulus E' of the fitted contacts [Pa].
    document : dict
        The whole parsed file [-].
    path : str
        Where the file was read from ("" for a document built in memory) [-].
    form : str
        ``eq9`` (the paper's regression) or ``learned`` [-].
    covariance : dict of str to ndarray, optional
        Coefficient covariance per branch; None for a format-1 file (no prediction interval) [-].
    resid_variance : dict of str to float, optional
        Residual variance of ln μ per branch [-].
    df_resid : dict of str to float, optional
        Residual degrees of freedom per branch [-].
    learned : object, optional
        The learned model of a ``learned`` file [-].
    score_quantiles : dict, optional
        Calibrated interval factors {branch: {coverage: q}} of an Eq. 9 file (``interval_calibration``); None: the
        plain statsmodels interval [-].
    """

    formula: Formula
    params: dict[str, np.ndarray]
    std_errors: dict[str, np.ndarray]
    blend_half_width: float
    sr_floor: float
    input_ranges: dict[str, tuple[float, float]]
    lubricant: Lubricant
    e_reduced: float
    document: dict[str, Any] = field(repr=False, compare=False)
    path: str = ""
    form: str = "eq9"
    covariance: dict[str, np.ndarray] | None = None
    """Coefficient covariance per branch (None: a format-1 file, no prediction interval)."""
    resid_variance: dict[str, float] | None = None
    df_resid: dict[str, float] | None = None
    learned: Any = None
    """The :class:`surrogate.mlp.MlpEnsemble` of a learned file."""
    score_quantiles: dict[str, dict[float, float]] | None = None
    """Split-conformal factors of an Eq. 9 interval (None: plain statsmodels interval)."""

    @property
    def roughness(self) -> dict[str, str] | None:
        """``{"name", "sha256"}`` of the roughness profile of the fitted dataset; None: not recorded."""
        return self.document.get("roughness")

    @property
    def has_interval(self) -> bool:
        """True when the file carries what a prediction interval needs."""
        return self.learned is not None or self.covariance is not None

    @property
    def interval_method(self) -> str:
        """How the file's prediction interval is made, in words (for reports)."""
        if self.learned is not None:
            return "learned ensemble, split-conformal interval"
        if self.covariance is None:
            return "none (format-1 file)"
        if self.score_quantiles is None:
            return "statsmodels OLS prediction interval, not calibrated off the training design"
        return "statsmodels OLS prediction interval, split-conformal factors calibrated off the training design"


def _require(doc: dict, dotted: str, kind: type | tuple[type, ...], accepted: str):
    node: Any = doc
    for part in dotted.split("."):
        if not isinstance(node, dict) or part not in node:
            raise InputError(dotted, "<missing>", accepted, "incomplete coefficient file")
        node = node[part]
    if kind is float:
        ok = isinstance(node, (int, float)) and not isinstance(node, bool) and math.isfinite(node)
    elif kind is int:
        ok = isinstance(node, int) and not isinstance(node, bool)
    else:
        ok = isinstance(node, kind)
    if not ok:
        raise InputError(dotted, node, accepted)
    return node


def _number_list(doc: dict, dotted: str, length: int) -> np.ndarray:
    values = _require(doc, dotted, list, f"a list of {length} finite numbers")
    if len(values) != length or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                        and math.isfinite(v) for v in values):
        raise InputError(dotted, values, f"a list of {length} finite numbers")
    return np.asarray(values, dtype=float)


def validate_coefficients(doc: Any, origin: str = "<dict>") -> CoefficientSet:
    """Validate a parsed coefficient document.

    Parameters
    ----------
    doc : dict
        The parsed JSON document of a coefficient file [-].
    origin : str
        Where the document came from, used in error messages [-].

    Returns
    -------
    CoefficientSet
        The validated coefficients.

    Raises
    ------
    InputError
        Naming the first bad field.
    """
    if not isinstance(doc, dict):
        raise InputError("coefficient file", origin, "a JSON object")
    fmt = doc.get("format", "<missing>")
    if fmt != FORMAT:
        raise InputError("format", fmt, f"'{FORMAT}'")
    version = _require(doc, "format_version", int, f"one of {list(READABLE_VERSIONS)}")
    if version > FORMAT_VERSION:
        raise InputError("format_version", version, f"one of {list(READABLE_VERSIONS)}",
                         f"{origin} was written by a newer gearloss; update gearloss to read it")
    if version not in READABLE_VERSIONS:
        raise InputError("format_version", version, f"one of {list(READABLE_VERSIONS)}")
    form = doc.get("form", "eq9") if version >= 2 else "eq9"
    if version >= 2 and "form" not in doc:
        raise InputError("form", "<missing>", f"one of {list(FORMS)}", "incomplete coefficient file")
    if form not in FORMS:
        raise InputError("form", form, f"one of {list(FORMS)}")
    if form == "learned":
        return _validate_learned(doc, origin)
    name = _require(doc, "formula.name", str, f"one of {sorted({k[0] for k in FORMULAS})}")
    fversion = _require(doc, "formula.version", int, "a formula version number")
    formula = FORMULAS.get((name, fversion))
    if formula is None:
        raise InputError("formula.name/version", f"{name} v{fversion}", f"one of {sorted(FORMULAS)}")
    threshold = _require(doc, "formula.lambda_threshold", float, f"{formula.lambda_threshold}")
    if threshold != formula.lambda_threshold:
        raise InputError("formula.lambda_threshold", threshold, f"{formula.lambda_threshold} for {name}")
    params, errors = {}, {}
    covariances: dict[str, np.ndarray] = {}
    variances: dict[str, float] = {}
    dfs: dict[str, float] = {}
    for branch in BRANCHES:
        expected = formula.term_names(branch)
        terms = _require(doc, f"branches.{branch}.terms", list, f"the term list {expected}")
        if terms != expected:
            raise InputError(f"branches.{branch}.terms", terms, f"exactly {expected} for {name} v{fversion}")
        params[branch] = _number_list(doc, f"branches.{branch}.params", len(expected))
        errors[branch] = _number_list(doc, f"branches.{branch}.std_errors", len(expected))
        if np.any(errors[branch] < 0):
            raise InputError(f"branches.{branch}.std_errors", errors[branch].tolist(), "non-negative numbers")
        n_obs = _require(doc, f"branches.{branch}.n_obs", int, "a positive integer")
        if n_obs <= len(expected):
            raise InputError(f"branches.{branch}.n_obs", n_obs, f"> {len(expected)} (number of coefficients)")
        adj = _require(doc, f"branches.{branch}.adj_r2", float, "a number <= 1")
        if adj > 1.0:
            raise InputError(f"branches.{branch}.adj_r2", adj, "a number <= 1")
        _require(doc, f"branches.{branch}.resid_std_error", float, "a non-negative number")
        if version >= 2:
            k = len(expected)
            cov = _require(doc, f"branches.{branch}.covariance", list, f"a {k} x {k} matrix of finite numbers")
            if len(cov) != k:
                raise InputError(f"branches.{branch}.covariance", f"{len(cov)} rows", f"a {k} x {k} matrix")
            covariance = np.vstack([_row(cov[i], f"branches.{branch}.covariance[{i}]", k) for i in range(k)])
            if not np.allclose(covariance, covariance.T, rtol=1e-9, atol=0.0) or np.any(np.diag(covariance) < 0):
                raise InputError(f"branches.{branch}.covariance", "a non-symmetric matrix or negative variances",
                                 "a symmetric k x k matrix with a non-negative diagonal")
            variance = _require(doc, f"branches.{branch}.resid_variance", float, "a non-negative number")
            df = _require(doc, f"branches.{branch}.df_resid", int, "a positive integer")
            if variance < 0:
                raise InputError(f"branches.{branch}.resid_variance", variance, "a non-negative number")
            if df < 1:
                raise InputError(f"branches.{branch}.df_resid", df, "a positive integer")
            covariances[branch], variances[branch], dfs[branch] = covariance, float(variance), float(df)
    quantiles = _interval_calibration(doc) if "interval_calibration" in doc else None
    if quantiles is not None and not covariances:
        raise InputError("interval_calibration", "present", "only in a file with covariances (format 2)")
    blend, sr_floor, ranges, e_reduced, lubricant = _common_fields(doc, origin)
    return CoefficientSet(formula, params, errors, float(blend), float(sr_floor), ranges, lubricant,
                          float(e_reduced), doc, origin, form="eq9",
                          covariance=covariances or None, resid_variance=variances or None, df_resid=dfs or None,
                          score_quantiles=quantiles)


def _interval_calibration(doc: dict) -> dict[str, dict[float, float]]:
    """The validated ``interval_calibration.score_quantiles`` of an Eq. 9 file as {branch: {coverage: q}}."""
    _require(doc, "interval_calibration", dict, "the interval calibration table")
    _require(doc, "interval_calibration.method", str, "a description of the calibration")
    out = {}
    for branch in BRANCHES:
        name = f"interval_calibration.score_quantiles.{branch}"
        table = _require(doc, name, dict, "{coverage: positive factor} including '0.9'")
        quantiles = {}
        for key, value in table.items():
            try:
                coverage = float(key)
            except ValueError:
                raise InputError(name, key, "coverages in (0, 1) as keys") from None
            if not 0.0 < coverage < 1.0:
                raise InputError(name, key, "coverages in (0, 1) as keys")
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
                    or value <= 0:
                raise InputError(f"{name}.{key}", value, "a positive finite factor")
            quantiles[coverage] = float(value)
        if 0.9 not in quantiles:
            raise InputError(name, sorted(table), "{coverage: positive factor} including '0.9'")
        out[branch] = quantiles
    return out


def _row(values: Any, name: str, length: int) -> np.ndarray:
    if (not isinstance(values, list) or len(values) != length
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values)):
        raise InputError(name, values if not isinstance(values, list) else f"{len(values)} values",
                         f"a list of {length} finite numbers")
    return np.asarray(values, dtype=float)


def _validate_learned(doc: dict, origin: str) -> CoefficientSet:
    from .learned_fit import LAMBDA_THRESHOLD, LEARNED_FORMULA_NAME, LEARNED_FORMULA_VERSION
    from .mlp import ensemble_from_dict

    name = _require(doc, "formula.name", str, f"'{LEARNED_FORMULA_NAME}'")
    version = _require(doc, "formula.version", int, f"{LEARNED_FORMULA_VERSION}")
    if (name, version) != (LEARNED_FORMULA_NAME, LEARNED_FORMULA_VERSION):
        raise InputError("formula.name/version", f"{name} v{version}",
                         f"{LEARNED_FORMULA_NAME} v{LEARNED_FORMULA_VERSION} for form 'learned'")
    ensemble = ensemble_from_dict(_require(doc, "learned", dict, "the ensemble table"), "learned")
    blend, sr_floor, ranges, e_reduced, lubricant = _common_fields(doc, origin)
    formula = Formula(LEARNED_FORMULA_NAME, LEARNED_FORMULA_VERSION, {}, LAMBDA_THRESHOLD,
                      doc["formula"].get("reference", ""))
    return CoefficientSet(formula, {}, {}, float(blend), float(sr_floor), ranges, lubricant, float(e_reduced), doc,
                          origin, form="learned", learned=ensemble)


def _common_fields(doc: dict, origin: str):
    """The fields both forms share: evaluation, cross-validation, input ranges, lubricant, E', source, hash."""
    blend = _require(doc, "evaluation.blend_half_width", float, "a number in [0, 0.5)")
    if not 0.0 <= blend < 0.5:
        raise InputError("evaluation.blend_half_width", blend, "[0, 0.5)")
    sr_floor = _require(doc, "evaluation.sr_floor", float, "a number in (0, 2]")
    if not 0.0 < sr_floor <= 2.0:
        raise InputError("evaluation.sr_floor", sr_floor, "(0, 2]")
    _require(doc, "cross_validation.overall.rmse_ln_mu", float, "the k-fold CV RMSE of ln mu")
    ranges = {}
    for key in RANGE_KEYS.values():
        pair = _require(doc, f"input_ranges.{key}", list, "[min, max] with finite min <= max")
        if (len(pair) != 2 or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                                      for v in pair) or pair[0] > pair[1]):
            raise InputError(f"input_ranges.{key}", pair, "[min, max] with finite min <= max")
        ranges[key] = (float(pair[0]), float(pair[1]))
    e_reduced = _require(doc, "e_reduced_pa", float, "a positive number [Pa]")
    if e_reduced <= 0:
        raise InputError("e_reduced_pa", e_reduced, "(0, inf) Pa")
    lub_doc = _require(doc, "lubricant", dict, "the lubricant definition table")
    try:
        lubricant = lubricant_from_dict(lub_doc, origin=f"{origin} [lubricant]")
    except InputError as err:
        raise InputError(f"lubricant.{err.parameter}", err.value, err.accepted) from None
    _require(doc, "source", dict, "a table describing the source dataset")
    check_roughness_record(doc.get("roughness"), "roughness")
    if "offgrid" in doc:
        _require(doc, "offgrid", dict, "the off-grid validation table")
    _require(doc, "package_version", str, "the gearloss version that wrote the file")
    stored = _require(doc, "content_sha256", str, "the SHA-256 of the file content")
    try:
        actual = content_hash(doc)
    except ValueError as err:
        raise InputError("coefficient file", origin, "JSON without NaN/Infinity", str(err)) from None
    if stored != actual:
        raise InputError("content_sha256", stored, "the SHA-256 of the file's content",
                         f"content hashes to {actual[:12]}...; the file was modified after it was written — refit "
                         f"instead of editing coefficients")
    return blend, sr_floor, ranges, e_reduced, lubricant


def load_coefficients(name_or_path: str | Path) -> CoefficientSet:
    """Load and validate a coefficient file by path or by shipped name.

    Parameters
    ----------
    name_or_path : str or Path
        Shipped name (``data/coefficients/NAME.json``, e.g. ``atf``) or path of a coefficient file [-].

    Returns
    -------
    CoefficientSet
        The validated coefficients.

    Raises
    ------
    InputError
        For a missing file or the first bad field of the document.
    """
    from ehl_dataset.data_files import resolve_named_file

    path = resolve_named_file("coefficients", name_or_path, ".json")
    try:
        doc = json.loads(Path(path).read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as err:
        raise InputError("coefficient file", str(path), "a valid JSON coefficient file", str(err)) from None
    try:
        return validate_coefficients(doc, origin=str(path))
    except InputError as err:
        if str(path) in str(err):
            raise
        base = f"invalid {err.parameter}={err.value!r}: accepted {err.accepted}"
        extra = str(err)[len(base) + 2:-1] if len(str(err)) > len(base) else ""
        raise InputError(err.parameter, err.value, err.accepted,
                         f"in coefficient file {path}" + (f"; {extra}" if extra else "")) from None
