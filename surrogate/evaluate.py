"""The vectorised friction surrogate μ(p_h, r_eq, u_r, SR, T, Rq1, Rq2) from a coefficient file.

Input policy (documented in docs/explanation/surrogate.md):

* NaN/inf anywhere, p_h ≤ 0, r_eq ≤ 0, u_r ≤ 0, Rq1 ≤ 0 or Rq2 ≤ 0 (Eq. 9 needs rough surfaces: ln S̄c, ln λ̄),
  |SR| > 2, or a temperature outside the lubricant's range → :class:`InputError` naming the input, the first bad
  value, its index and the accepted range.
* The sign of SR is ignored (μ is a magnitude; the friction force opposes sliding). |SR| below the file's
  ``sr_floor`` (the smallest SR in the fitted data) is evaluated at ``sr_floor``: μ stays finite and continuous
  as SR → 0 (Eq. 9 contains ln SR), and the power loss μ W u_s still vanishes at the pitch point because u_s → 0.
* Inputs outside the fitted ranges (and λ̄ outside the fitted λ̄ range) evaluate but emit one
  :class:`SurrogateExtrapolationWarning` per call listing each extrapolated input and how many points.
* With ``clip_to_fitted_ranges=True`` every input is first clipped to the range seen in the fitted data (the
  warning then says "clipped"): Eq. 9's power terms are not extrapolated. Gear contacts leave the factorial's ranges
  routinely (the lightly loaded ends of a contact line lie far below 0.5 GPa), where extrapolation has produced
  μ ≈ 1e14; the gear-side friction factory (:func:`efficiency.friction.friction_from_spec`) therefore clips, and
  :meth:`FrictionSurrogate.last_stats` counts the points moved per input in the last evaluation.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from ehl_dataset.validation import InputError

from .coefficients import CoefficientSet, load_coefficients
from .features import compute_features
from .intervals import DEFAULT_ALPHA, prediction_half_width
from .model import predict_ln_mu


class SurrogateExtrapolationWarning(UserWarning):
    """Inputs outside the ranges the coefficients were fitted on."""


_INPUTS = (("p_h", "Pa", "p_h_pa"), ("r_eq", "m", "r_eq_m"), ("u_r", "m/s", "u_r_m_s"), ("sr", "-", "sr_abs"),
           ("temperature", "K", "temperature_k"), ("rq1", "m", "rq1_m"), ("rq2", "m", "rq2_m"))


def _first_bad(name: str, values: np.ndarray, bad: np.ndarray, accepted: str):
    index = int(np.flatnonzero(bad.ravel())[0])
    raise InputError(name, float(values.ravel()[index]), accepted,
                     f"at index {index}; {int(bad.sum())} of {values.size} values")


class FrictionSurrogate:
    """Friction coefficient μ of the paper's Eq. 9a/9b (or a learned model) from a validated coefficient file.

    Inputs are checked as the module docstring says; :meth:`load` reads a file or a shipped name.

    Parameters
    ----------
    coefficients : CoefficientSet
        The validated coefficient file (:func:`surrogate.coefficients.load_coefficients`) [-].
    clip_to_fitted_ranges : bool
        Clip every input to the range seen in the fitted data before evaluating (Eq. 9's power terms are then never
        extrapolated) [-].
    """

    def __init__(self, coefficients: CoefficientSet, clip_to_fitted_ranges: bool = False):
        self.coefficients = coefficients
        self.clip_to_fitted_ranges = bool(clip_to_fitted_ranges)
        self._stats: dict = {}
        self.formula = coefficients.formula
        self.lubricant = coefficients.lubricant
        self.e_reduced = coefficients.e_reduced
        if coefficients.document.get("stable") is False:
            from .fit import UnstableFitWarning

            warnings.warn(f"coefficient file {coefficients.path} was written from a fit flagged numerically unstable "
                          f"(see its branches.*.messages)", UnstableFitWarning, stacklevel=2)

    @classmethod
    def load(cls, name_or_path: str | Path, clip_to_fitted_ranges: bool = False) -> "FrictionSurrogate":
        """The surrogate of a coefficient file given by path or shipped name (``atf``).

        Parameters
        ----------
        name_or_path : str or Path
            Shipped name (``data/coefficients/NAME.json``) or path of a coefficient file [-].
        clip_to_fitted_ranges : bool
            Clip the inputs to the fitted ranges before evaluating [-].

        Returns
        -------
        FrictionSurrogate
            The evaluator of that file.
        """
        return cls(load_coefficients(name_or_path), clip_to_fitted_ranges)

    def clip(self, arrays: dict[str, np.ndarray]) -> tuple[dict[str, np.ndarray], dict[str, int]]:
        """Inputs clipped to the fitted ranges, and per input the number of points moved.

        |SR| is clipped for SR; its lower end is the SR floor, applied anyway.

        Parameters
        ----------
        arrays : dict of str to ndarray
            Validated inputs keyed ``p_h`` [Pa], ``r_eq`` [m], ``u_r`` [m/s], ``sr`` [-], ``temperature`` [K], ``rq1``,
            ``rq2`` [m] (as :meth:`validate` returns them) [-].

        Returns
        -------
        tuple of (dict, dict)
            The clipped inputs (same keys and units) and {input: number of points moved}.
        """
        ranges = self.coefficients.input_ranges
        out = dict(arrays)
        moved = {}
        for name, _, key in _INPUTS:
            lo, hi = ranges[key]
            raw = np.abs(arrays[name]) if name == "sr" else arrays[name]
            out[name] = np.clip(raw, lo, hi)
            moved[name] = int(np.count_nonzero(out[name] != raw))
        return out, moved

    def last_stats(self) -> dict:
        """What the last evaluation did.

        Returns
        -------
        dict
            ``surrogate_points`` evaluated and, with ``clip_to_fitted_ranges``, ``clipped_inputs`` {input: number of
            points moved to the fitted range} (p_h, r_eq, u_r, sr, temperature, rq1, rq2). Empty before the first
            evaluation.
        """
        return {k: (dict(v) if isinstance(v, dict) else v) for k, v in self._stats.items()}

    def validate(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2) -> dict[str, np.ndarray]:
        """Broadcast and check the inputs (module docstring) and return them as float arrays.

        Parameters
        ----------
        p_h : array_like
            Hertz pressure, > 0 [Pa].
        r_eq : array_like
            Equivalent (reduced) radius of curvature, > 0 [m].
        u_r : array_like
            Rolling (entrainment) velocity (u1 + u2)/2, > 0 [m/s].
        sr : array_like
            Slide-to-roll ratio (u1 − u2)/u_r, |SR| ≤ 2 (sign ignored) [-].
        temperature : array_like
            Inlet temperature, within the lubricant's range [K].
        rq1 : array_like
            RMS roughness of surface 1, > 0 [m].
        rq2 : array_like
            RMS roughness of surface 2, > 0 [m].

        Returns
        -------
        dict of str to ndarray
            The broadcast inputs keyed by parameter name, in the units above.

        Raises
        ------
        InputError
            Naming the first bad input, its value, its index and the accepted range.
        """
        names = ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2")
        arrays = {}
        for name, value in zip(names, (p_h, r_eq, u_r, sr, temperature, rq1, rq2)):
            try:
                arrays[name] = np.asarray(value, dtype=float)
            except (TypeError, ValueError):
                raise InputError(name, value, "numbers or arrays of numbers") from None
        try:
            shaped = np.broadcast_arrays(*arrays.values())
        except ValueError:
            raise InputError("input shapes", {k: v.shape for k, v in arrays.items()}, "broadcastable arrays") from None
        arrays = dict(zip(names, shaped))
        for name, unit, _ in _INPUTS:
            values = arrays[name]
            finite = np.isfinite(values)
            if not finite.all():
                _first_bad(name, values, ~finite, "finite numbers")
        for name, unit in (("p_h", "Pa"), ("r_eq", "m"), ("u_r", "m/s"), ("rq1", "m"), ("rq2", "m")):
            bad = arrays[name] <= 0
            if bad.any():
                _first_bad(name, arrays[name], bad, f"(0, inf) {unit}")
        bad = np.abs(arrays["sr"]) > 2.0
        if bad.any():
            _first_bad("sr", arrays["sr"], bad, "[-2, 2]")
        t_lo, t_hi = self.lubricant.t_min, self.lubricant.t_max
        bad = (arrays["temperature"] < t_lo) | (arrays["temperature"] > t_hi)
        if bad.any():
            _first_bad("temperature", arrays["temperature"], bad, f"[{t_lo:g}, {t_hi:g}] K for {self.lubricant.name}")
        return arrays

    def _warn_extrapolation(self, arrays: dict[str, np.ndarray], lam: np.ndarray) -> None:
        ranges = self.coefficients.input_ranges
        notes = []
        for name, unit, key in _INPUTS:
            lo, hi = ranges[key]
            values = np.abs(arrays[name]) if name == "sr" else arrays[name]
            below = 0 if name == "sr" else int(np.count_nonzero(values < lo * (1 - 1e-9)))
            above = int(np.count_nonzero(values > hi * (1 + 1e-9)))
            if below or above:
                notes.append(f"{name} ({below} below {lo:.4g}, {above} above {hi:.4g} {unit})")
        lo, hi = ranges["lambda_bar"]
        below, above = int(np.count_nonzero(lam < lo * (1 - 1e-9))), int(np.count_nonzero(lam > hi * (1 + 1e-9)))
        if below or above:
            notes.append(f"lambda_bar ({below} below {lo:.4g}, {above} above {hi:.4g})")
        if notes:
            action = "clipped to" if self.clip_to_fitted_ranges else "extrapolates outside"
            warnings.warn(f"friction surrogate {action} its fitted ranges: {'; '.join(notes)}",
                          SurrogateExtrapolationWarning, stacklevel=3)

    def features(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2, *, warn: bool = True) -> dict[str, np.ndarray]:
        """Validated features of the inputs (SR floored at ``sr_floor``), as the regression uses them.

        Parameters
        ----------
        p_h : array_like
            Hertz pressure [Pa].
        r_eq : array_like
            Equivalent radius of curvature [m].
        u_r : array_like
            Rolling velocity [m/s].
        sr : array_like
            Slide-to-roll ratio [-].
        temperature : array_like
            Inlet temperature [K].
        rq1 : array_like
            RMS roughness of surface 1 [m].
        rq2 : array_like
            RMS roughness of surface 2 [m].
        warn : bool
            Emit :class:`SurrogateExtrapolationWarning` for inputs outside the fitted ranges [-].

        Returns
        -------
        dict of str to ndarray
            The features of :func:`surrogate.features.compute_features` (W, alpha, r, V, lam, SR, Sc, Seq [-], plus
            ``h_min_dh`` [m] and ``w_prime`` [N/m]).
        """
        arrays = self.validate(p_h, r_eq, u_r, sr, temperature, rq1, rq2)
        self._stats = {"surrogate_points": int(arrays["p_h"].size)}
        used = arrays
        if self.clip_to_fitted_ranges:
            used, self._stats["clipped_inputs"] = self.clip(arrays)
        sr_eff = np.maximum(np.abs(used["sr"]), self.coefficients.sr_floor)
        feats = compute_features(used["p_h"], used["r_eq"], used["u_r"], sr_eff, used["temperature"],
                                 used["rq1"], used["rq2"], self.lubricant, self.e_reduced)
        if warn:
            self._warn_extrapolation(arrays, feats["lam"])
        return feats

    @property
    def form(self) -> str:
        """``eq9`` or ``learned`` (the form of the coefficient file)."""
        return self.coefficients.form

    @property
    def has_interval(self) -> bool:
        """True when the file gives a prediction interval (a learned file, or an Eq. 9 file of format 2)."""
        return self.coefficients.has_interval

    @property
    def offgrid(self) -> dict | None:
        """The off-grid validation recorded in the file (None if it records none)."""
        return self.coefficients.document.get("offgrid")

    def _ln_mu_features(self, feats: dict[str, np.ndarray],
                        spread: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
        """(ln μ, spread) on features; spread is the members' disagreement of a learned file, else None."""
        with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
            if self.form == "learned":
                from .mlp import feature_matrix

                mean, disagreement = self.coefficients.learned.predict(feature_matrix(feats), spread=spread)
                shape = np.shape(feats["lam"])
                return mean.reshape(shape), None if disagreement is None else disagreement.reshape(shape)
            return predict_ln_mu(self.formula, self.coefficients.params, feats,
                                 self.coefficients.blend_half_width), None

    def ln_mu_interval(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2, *, alpha: float = DEFAULT_ALPHA,
                       warn: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
        """ln μ and the half width of its (1 − α) prediction interval at the inputs.

        Parameters
        ----------
        p_h : array_like
            Hertz pressure [Pa].
        r_eq : array_like
            Equivalent radius of curvature [m].
        u_r : array_like
            Rolling velocity [m/s].
        sr : array_like
            Slide-to-roll ratio [-].
        temperature : array_like
            Inlet temperature [K].
        rq1 : array_like
            RMS roughness of surface 1 [m].
        rq2 : array_like
            RMS roughness of surface 2 [m].
        alpha : float
            1 − coverage of the interval; for a learned file one of its calibrated coverages [-].
        warn : bool
            Warn about inputs outside the fitted ranges [-].

        Returns
        -------
        tuple
            (ln μ, half width of ln μ) [-]; the half width is None for a file without interval data (format 1).
        """
        feats = self.features(p_h, r_eq, u_r, sr, temperature, rq1, rq2, warn=warn)
        out, spread = self._ln_mu_features(feats)
        self._check_finite(out, feats)
        c = self.coefficients
        if self.form == "learned":
            return out, c.learned.half_width(spread, 1.0 - alpha)
        if c.covariance is None:
            return out, None
        with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
            half = prediction_half_width(self.formula, c.covariance, c.resid_variance, c.df_resid, feats,
                                         c.blend_half_width, alpha, score_quantiles=c.score_quantiles)
        return out, half

    def mu_interval(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2, *, alpha: float = DEFAULT_ALPHA,
                    warn: bool = True) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
        """μ and its (1 − α) prediction interval μ_low … μ_high (the exponential of the interval of ln μ).

        Parameters
        ----------
        p_h : array_like
            Hertz pressure [Pa].
        r_eq : array_like
            Equivalent radius of curvature [m].
        u_r : array_like
            Rolling velocity [m/s].
        sr : array_like
            Slide-to-roll ratio [-].
        temperature : array_like
            Inlet temperature [K].
        rq1 : array_like
            RMS roughness of surface 1 [m].
        rq2 : array_like
            RMS roughness of surface 2 [m].
        alpha : float
            1 − coverage of the interval [-].
        warn : bool
            Warn about inputs outside the fitted ranges [-].

        Returns
        -------
        tuple
            (μ, μ_low, μ_high) [-]; the bounds are None for a file without interval data.
        """
        ln_mu, half = self.ln_mu_interval(p_h, r_eq, u_r, sr, temperature, rq1, rq2, alpha=alpha, warn=warn)
        if half is None:
            return np.exp(ln_mu), None, None
        return np.exp(ln_mu), np.exp(ln_mu - half), np.exp(ln_mu + half)

    def _check_finite(self, out: np.ndarray, feats: dict[str, np.ndarray]) -> None:
        bad = ~np.isfinite(out)
        if bad.any():
            index = int(np.flatnonzero(bad.ravel())[0])
            point = {k: float(np.ravel(feats[k])[index]) for k in ("W", "alpha", "r", "V", "lam", "Sc", "Seq")}
            raise InputError("inputs", point, "contact conditions where the regression terms are defined "
                             "(positive W, V, r, alpha)", f"non-finite ln mu at index {index}")

    def ln_mu(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2, *, warn: bool = True) -> np.ndarray:
        """ln μ at the inputs (paper Eq. 9a for λ̄ ≤ 1, Eq. 9b above, blended over the file's band).

        Parameters
        ----------
        p_h : array_like
            Hertz pressure [Pa].
        r_eq : array_like
            Equivalent radius of curvature [m].
        u_r : array_like
            Rolling velocity [m/s].
        sr : array_like
            Slide-to-roll ratio [-].
        temperature : array_like
            Inlet temperature [K].
        rq1 : array_like
            RMS roughness of surface 1 [m].
        rq2 : array_like
            RMS roughness of surface 2 [m].
        warn : bool
            Warn about inputs outside the fitted ranges [-].

        Returns
        -------
        ndarray
            ln μ, shaped like the broadcast inputs [-].

        Raises
        ------
        InputError
            For bad inputs, or where the regression terms are not finite.
        """
        feats = self.features(p_h, r_eq, u_r, sr, temperature, rq1, rq2, warn=warn)
        out, _ = self._ln_mu_features(feats, spread=False)
        self._check_finite(out, feats)
        return out

    def mu(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2, *, warn: bool = True) -> np.ndarray:
        """Friction coefficient μ at the inputs: exp of :meth:`ln_mu`.

        Parameters
        ----------
        p_h : array_like
            Hertz pressure [Pa].
        r_eq : array_like
            Equivalent radius of curvature [m].
        u_r : array_like
            Rolling velocity [m/s].
        sr : array_like
            Slide-to-roll ratio [-].
        temperature : array_like
            Inlet temperature [K].
        rq1 : array_like
            RMS roughness of surface 1 [m].
        rq2 : array_like
            RMS roughness of surface 2 [m].
        warn : bool
            Warn about inputs outside the fitted ranges [-].

        Returns
        -------
        ndarray
            μ, shaped like the broadcast inputs [-].
        """
        return np.exp(self.ln_mu(p_h, r_eq, u_r, sr, temperature, rq1, rq2, warn=warn))

    def __call__(self, *args, **kwargs) -> np.ndarray:
        return self.mu(*args, **kwargs)
