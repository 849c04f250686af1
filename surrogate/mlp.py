"""The learned friction surrogate of a coefficient file: an ensemble of small multilayer perceptrons for ln μ,
fitted with scikit-learn, stored as plain numbers (JSON) and evaluated in numpy.

Model. Inputs are the paper's dimensionless features (:mod:`surrogate.features`) in the columns of
:data:`MLP_FEATURES` — W̄, ᾱ, V̄, ln λ̄, ln SR, ln S̄c, ln S̄eq (r̄ = 2W̄ − log10 2π under Hertz loading carries
nothing more) — standardised with the training mean and standard deviation; the target is ln μ, standardised too.
Each member is ``sklearn.neural_network.MLPRegressor`` with ReLU hidden layers, fitted by L-BFGS with an L2 penalty.
The prediction is the mean of the members' ln μ; the members' standard deviation s(x) is their disagreement.

Ensemble and interval (cross-validation+ with a normalised score; Barber et al., *Ann. Statist.* 49 (2021) 486,
and Lei et al., *J. Am. Stat. Assoc.* 113 (2018) 1094, Sect. 5.2). The rows are split into K folds and member k is
fitted without fold k, so every row has an out-of-fold prediction from the member that did not see it. With the
out-of-fold residuals r_i and the disagreement s_i at the row, the score e_i = |r_i|/(s_i + s₀) (s₀ = median of s_i,
so that a confident ensemble does not get a zero-width interval) is ranked, and its ⌈(n + 1)(1 − α)⌉-th smallest
value q_α is stored for each coverage of :data:`COVERAGES`. The interval of ln μ at a new point is
ln μ̂ ± q_α (s(x) + s₀). Its coverage holds for points drawn like the training rows; whether it holds off the
training design is what the off-grid validation of the file measures.

Evaluation cost. The first layers of all members are one matrix product; the deeper layers a batched product per
member; points are processed in blocks of :data:`BLOCK` so the activations stay in cache.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

from ehl_dataset.validation import InputError

MLP_FEATURES = ("W", "alpha", "V", "ln_lam", "ln_SR", "ln_Sc", "ln_Seq")
"""Input columns of the learned surrogate (the names stored in its coefficient file)."""
COVERAGES = (0.5, 0.68, 0.8, 0.9, 0.95, 0.99)
"""Coverages whose calibrated score quantile a learned coefficient file stores."""
BLOCK = 4096
"""Points per block of the numpy evaluation."""
ACTIVATION = "relu"


def feature_matrix(features: dict[str, np.ndarray]) -> np.ndarray:
    """(n, 7) matrix of :data:`MLP_FEATURES` from a feature dict (:func:`surrogate.features.compute_features`).

    Parameters
    ----------
    features : dict of numpy.ndarray
        Feature arrays [-].

    Returns
    -------
    numpy.ndarray
        Float64 matrix, C order [-].
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        columns = (features["W"], features["alpha"], features["V"], np.log(features["lam"]),
                   np.log(features["SR"]), np.log(features["Sc"]), np.log(features["Seq"]))
    return np.column_stack([np.asarray(c, dtype=float).ravel() for c in columns])


@dataclass(frozen=True)
class MlpEnsemble:
    """Weights of an ensemble of ReLU perceptrons with identical architecture, and their input/output scaling.

    Parameters
    ----------
    weights : tuple of ndarray
        ``weights[l]`` of shape (K, n_in, n_out) for layer l; the last layer has one output [-].
    biases : tuple of ndarray
        ``biases[l]`` of shape (K, n_out) [-].
    x_mean : ndarray
        Mean of each feature of :data:`MLP_FEATURES`, for standardisation [-].
    x_scale : ndarray
        Scale of each feature [-].
    y_mean : float
        Mean of ln μ [-].
    y_scale : float
        Scale of ln μ [-].
    s0 : float
        Floor added to the members' disagreement [-].
    score_quantiles : dict of float to float
        {coverage: q} of the calibrated interval (module docstring) [-].
    """

    weights: tuple[np.ndarray, ...]
    biases: tuple[np.ndarray, ...]
    x_mean: np.ndarray
    x_scale: np.ndarray
    y_mean: float
    y_scale: float
    s0: float
    score_quantiles: dict[float, float]

    @property
    def members(self) -> int:
        return int(self.weights[0].shape[0])

    def member_predictions(self, x: np.ndarray) -> np.ndarray:
        """ln μ of every member at the rows of ``x`` (feature matrix, :func:`feature_matrix`).

        The products run in single precision (float32: ~1e-6 relative in ln μ, far below the model's error) on
        one BLAS thread; the input scaling and the output are double precision.

        Parameters
        ----------
        x : numpy.ndarray
            (n, 7) features [-].

        Returns
        -------
        numpy.ndarray
            (K, n) ln μ [-].
        """
        return self._standardised_members(x) * self.y_scale + self.y_mean

    def _standardised_members(self, x: np.ndarray) -> np.ndarray:
        """(K, n) outputs of the members before the target scaling (ln μ = output·y_scale + y_mean)."""
        x = np.asarray(x, dtype=float)
        n = x.shape[0]
        k = self.members
        out = np.empty((k, n))
        f32 = np.float32
        first_w = np.concatenate(list(self.weights[0]), axis=1).astype(f32)  # all members' first layers at once
        first_b = np.concatenate(list(self.biases[0])).astype(f32)
        h = self.weights[0].shape[2]
        deep = [(w.astype(f32), b.astype(f32)) for w, b in zip(self.weights[1:], self.biases[1:])]
        with threadpool_limits(1):
            for start in range(0, n, BLOCK):
                stop = min(start + BLOCK, n)
                a = ((x[start:stop] - self.x_mean) / self.x_scale).astype(f32) @ first_w
                a += first_b
                np.maximum(a, 0.0, out=a)
                for member in range(k):
                    z = a[:, member * h:(member + 1) * h]
                    for layer, (w, b) in enumerate(deep):
                        z = z @ w[member]
                        z += b[member]
                        if layer < len(deep) - 1:
                            np.maximum(z, 0.0, out=z)
                    out[member, start:stop] = z[:, 0]
        return out

    def predict(self, x: np.ndarray, spread: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
        """Ensemble mean of ln μ and the members' standard deviation s(x) at the rows of ``x``.

        Parameters
        ----------
        x : numpy.ndarray
            (n, 7) features [-].
        spread : bool
            Also compute s(x) (None otherwise) [-].

        Returns
        -------
        tuple of numpy.ndarray
            (mean ln μ, disagreement or None), each (n,) [-].
        """
        members = self._standardised_members(x)
        mean = members.mean(axis=0) * self.y_scale + self.y_mean
        return mean, (members.std(axis=0) * self.y_scale if spread else None)

    def half_width(self, spread: np.ndarray, coverage: float) -> np.ndarray:
        """Half width of the calibrated interval of ln μ, q(coverage)·(s + s₀).

        Parameters
        ----------
        spread : numpy.ndarray
            Disagreement s(x) of the members [-].
        coverage : float
            One of the stored coverages [-].

        Returns
        -------
        numpy.ndarray
            Half width of ln μ [-].
        """
        q = quantile_for(self.score_quantiles, coverage)
        return q * (np.asarray(spread, dtype=float) + self.s0)

    def to_dict(self) -> dict:
        """The JSON form stored under ``learned`` in a coefficient file (plain lists of numbers).

        Returns
        -------
        dict
            Layers, scaling and score quantiles.
        """
        return {
            "features": list(MLP_FEATURES),
            "activation": ACTIVATION,
            "members": self.members,
            "layers": [{"weights": w.tolist(), "biases": b.tolist()} for w, b in zip(self.weights, self.biases)],
            "x_mean": self.x_mean.tolist(), "x_scale": self.x_scale.tolist(),
            "y_mean": float(self.y_mean), "y_scale": float(self.y_scale),
            "interval": {"method": "cross-validation+ with normalised score |r|/(s + s0)", "s0": float(self.s0),
                         "score_quantiles": {f"{c:g}": float(q) for c, q in sorted(self.score_quantiles.items())}},
        }


def quantile_for(quantiles: dict[float, float], coverage: float) -> float:
    """The stored score quantile of ``coverage``.

    Parameters
    ----------
    quantiles : dict of float to float
        {coverage: q} as stored [-].
    coverage : float
        Nominal coverage of the interval [-].

    Returns
    -------
    float
        q [-].

    Raises
    ------
    InputError
        Naming the stored coverages when ``coverage`` is not one of them.
    """
    for c, q in quantiles.items():
        if abs(c - coverage) < 1e-9:
            return q
    raise InputError("coverage", coverage, f"one of the calibrated coverages {sorted(quantiles)}")


def conformal_quantile(scores: np.ndarray, coverage: float) -> float:
    """The ⌈(n + 1)·coverage⌉-th smallest score (split-conformal rank; +inf when n is too small).

    Parameters
    ----------
    scores : numpy.ndarray
        Calibration scores [-].
    coverage : float
        Target coverage in (0, 1) [-].

    Returns
    -------
    float
        The quantile [-].
    """
    scores = np.sort(np.asarray(scores, dtype=float))
    rank = math.ceil((scores.size + 1) * coverage)
    return float(scores[rank - 1]) if rank <= scores.size else math.inf


@dataclass
class MlpFitResult:
    """An ensemble, its out-of-fold predictions and the fit's statistics.

    Parameters
    ----------
    ensemble : MlpEnsemble
        The fitted ensemble [-].
    oof_ln_mu : ndarray
        Out-of-fold ln μ prediction of every row [-].
    spread : ndarray
        Members' disagreement s at every row [-].
    fit_time_s : float
        Wall time of the fit [s].
    settings : dict
        Architecture, penalty, folds and seed [-].
    """

    ensemble: MlpEnsemble
    oof_ln_mu: np.ndarray
    spread: np.ndarray
    fit_time_s: float
    settings: dict


def fit_mlp_ensemble(features: dict[str, np.ndarray], ln_mu: np.ndarray, *, members: int = 5,
                     hidden: tuple[int, ...] = (16, 16), l2: float = 1e-3, max_iter: int = 2000,
                     seed: int = 0, calibration: np.ndarray | None = None) -> MlpFitResult:
    """Fit the ensemble of :class:`MlpEnsemble` by K-fold cross-validation+ (module docstring).

    Parameters
    ----------
    features : dict of numpy.ndarray
        Feature arrays of the training rows [-].
    ln_mu : numpy.ndarray
        ln μ of the rows [-].
    members : int
        K, number of members and of folds (>= 3) [-].
    hidden : tuple of int
        Widths of the hidden layers [-].
    l2 : float
        L2 penalty ``alpha`` of ``MLPRegressor`` (on standardised data) [-].
    max_iter : int
        L-BFGS iterations per member [-].
    seed : int
        Seed of the fold split and of the initial weights [-].
    calibration : numpy.ndarray, optional
        Boolean mask of the rows whose scores set the interval (default: all). Conformal calibration needs rows
        drawn like the points to be predicted: of an adaptive design, only its space-filling start is; the rows
        chosen where the ensemble disagreed are harder than a random point and would widen the interval [-].

    Returns
    -------
    MlpFitResult
        The ensemble with its out-of-fold ln μ, disagreement at the rows and settings.
    """
    from sklearn.model_selection import KFold
    from sklearn.neural_network import MLPRegressor

    if isinstance(members, bool) or not isinstance(members, int) or members < 3:
        raise InputError("members", members, "an integer >= 3")
    x = feature_matrix(features)
    y = np.asarray(ln_mu, dtype=float).ravel()
    n = y.size
    if n < 4 * members or not np.all(np.isfinite(x)) or not np.all(np.isfinite(y)):
        raise InputError("training rows", n, f">= {4 * members} rows with finite features and ln mu")
    started = time.perf_counter()
    x_mean, x_scale = x.mean(axis=0), x.std(axis=0)
    x_scale = np.where(x_scale > 0, x_scale, 1.0)
    y_mean, y_scale = float(y.mean()), float(y.std()) or 1.0
    z, t = (x - x_mean) / x_scale, (y - y_mean) / y_scale
    oof = np.empty(n)
    weights: list[list[np.ndarray]] = []
    biases: list[list[np.ndarray]] = []
    import warnings

    from sklearn.exceptions import ConvergenceWarning

    with threadpool_limits(1), warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        for k, (train, test) in enumerate(KFold(members, shuffle=True, random_state=seed).split(z)):
            model = MLPRegressor(hidden_layer_sizes=hidden, activation=ACTIVATION, solver="lbfgs", alpha=l2,
                                 max_iter=max_iter, max_fun=4 * max_iter, random_state=seed + k, tol=1e-7)
            model.fit(z[train], t[train])
            oof[test] = model.predict(z[test]) * y_scale + y_mean
            weights.append(model.coefs_)
            biases.append(model.intercepts_)
    layers = len(weights[0])
    ensemble = MlpEnsemble(
        weights=tuple(np.stack([w[l] for w in weights]) for l in range(layers)),
        biases=tuple(np.stack([b[l] for b in biases]) for l in range(layers)),
        x_mean=x_mean, x_scale=x_scale, y_mean=y_mean, y_scale=y_scale, s0=0.0, score_quantiles={})
    _, spread = ensemble.predict(x)
    mask = np.ones(n, dtype=bool) if calibration is None else np.asarray(calibration, dtype=bool).ravel()
    if mask.shape != (n,) or not mask.any():
        raise InputError("calibration", f"mask of {mask.size} rows, {int(mask.sum())} set",
                         f"a boolean mask of the {n} rows with at least one set")
    s0 = float(np.median(spread[mask]))
    scores = np.abs(y - oof)[mask] / (spread[mask] + s0)
    quantiles = {c: q for c in COVERAGES if math.isfinite(q := conformal_quantile(scores, c))}  # too few rows: none
    ensemble = MlpEnsemble(ensemble.weights, ensemble.biases, x_mean, x_scale, y_mean, y_scale, s0, quantiles)
    return MlpFitResult(ensemble, oof, spread, time.perf_counter() - started,
                        {"members": members, "hidden": list(hidden), "l2": l2, "max_iter": max_iter, "seed": seed,
                         "calibration_rows": int(mask.sum()),
                         "solver": "lbfgs", "activation": ACTIVATION})


def recalibrate(ensemble: MlpEnsemble, x: np.ndarray, ln_mu: np.ndarray) -> MlpEnsemble:
    """The ensemble with its score quantiles computed on held-out rows (split conformal; Lei et al. 2018, Sect. 2.2):
    q(c) = the ⌈(n + 1) c⌉-th smallest |ln μ − ln μ̂|/(s + s₀) over the rows, for every stored coverage c that the
    number of rows allows. Rows drawn like the points to be predicted (an off-grid sample of the box) give an
    interval of that coverage for such points; the cross-validation+ scores of the training rows come from single
    members fitted on 4/5 of the rows and overstate the error of the five members' mean.

    Parameters
    ----------
    ensemble : MlpEnsemble
        The fitted ensemble.
    x : numpy.ndarray
        (n, 7) features of held-out rows [-].
    ln_mu : numpy.ndarray
        Their solved ln μ [-].

    Returns
    -------
    MlpEnsemble
        Same weights, new ``score_quantiles``.
    """
    mean, spread = ensemble.predict(x)
    scores = np.abs(np.asarray(ln_mu, dtype=float) - mean) / (spread + ensemble.s0)
    quantiles = {c: q for c in COVERAGES if math.isfinite(q := conformal_quantile(scores, c))}
    if 0.9 not in quantiles:
        raise InputError("calibration rows", int(scores.size), ">= 9 held-out rows for a 90 % interval")
    return dataclasses.replace(ensemble, score_quantiles=quantiles)


def ensemble_from_dict(doc: dict, where: str = "learned") -> MlpEnsemble:
    """Validate the ``learned`` table of a coefficient file and build the ensemble.

    Parameters
    ----------
    doc : dict
        The ``learned`` table [-].
    where : str
        Its name in error messages [-].

    Returns
    -------
    MlpEnsemble
        The ensemble.

    Raises
    ------
    InputError
        Naming the first bad field (``learned.layers[1].weights``, ...) and what is accepted.
    """

    def number_array(value, name, shape=None):
        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise InputError(name, "<not numeric>", "nested lists of finite numbers") from None
        if arr.dtype == object or not np.all(np.isfinite(arr)) or (shape is not None and arr.shape != shape):
            raise InputError(name, f"array of shape {arr.shape}",
                             f"finite numbers of shape {shape}" if shape else "finite numbers")
        return arr

    if not isinstance(doc, dict):
        raise InputError(where, type(doc).__name__, "a table with the ensemble's layers")
    if doc.get("features") != list(MLP_FEATURES):
        raise InputError(f"{where}.features", doc.get("features", "<missing>"), f"exactly {list(MLP_FEATURES)}")
    if doc.get("activation") != ACTIVATION:
        raise InputError(f"{where}.activation", doc.get("activation", "<missing>"), f"'{ACTIVATION}'")
    members = doc.get("members")
    if isinstance(members, bool) or not isinstance(members, int) or members < 1:
        raise InputError(f"{where}.members", members, "a positive integer")
    layers = doc.get("layers")
    if not isinstance(layers, list) or len(layers) < 2:
        raise InputError(f"{where}.layers", "<missing>" if layers is None else f"{len(layers)} layers",
                         "a list of >= 2 layers {weights, biases}")
    weights, biases = [], []
    n_in = len(MLP_FEATURES)
    for i, layer in enumerate(layers):
        name = f"{where}.layers[{i}]"
        if not isinstance(layer, dict):
            raise InputError(name, type(layer).__name__, "a table {weights, biases}")
        w = number_array(layer.get("weights"), f"{name}.weights")
        if w.ndim != 3 or w.shape[0] != members or w.shape[1] != n_in:
            raise InputError(f"{name}.weights", f"array of shape {w.shape}", f"shape ({members}, {n_in}, width)")
        weights.append(w)
        biases.append(number_array(layer.get("biases"), f"{name}.biases", (members, w.shape[2])))
        n_in = w.shape[2]
    if n_in != 1:
        raise InputError(f"{where}.layers[{len(layers) - 1}].weights", f"{n_in} outputs", "1 output (ln mu)")
    x_mean = number_array(doc.get("x_mean"), f"{where}.x_mean", (len(MLP_FEATURES),))
    x_scale = number_array(doc.get("x_scale"), f"{where}.x_scale", (len(MLP_FEATURES),))
    if np.any(x_scale <= 0):
        raise InputError(f"{where}.x_scale", x_scale.tolist(), "positive numbers")
    y_mean = float(number_array(doc.get("y_mean"), f"{where}.y_mean", ()))
    y_scale = float(number_array(doc.get("y_scale"), f"{where}.y_scale", ()))
    if y_scale <= 0:
        raise InputError(f"{where}.y_scale", y_scale, "a positive number")
    interval = doc.get("interval")
    if not isinstance(interval, dict):
        raise InputError(f"{where}.interval", "<missing>", "a table {s0, score_quantiles}")
    s0 = float(number_array(interval.get("s0"), f"{where}.interval.s0", ()))
    raw = interval.get("score_quantiles")
    if not isinstance(raw, dict) or not raw:
        raise InputError(f"{where}.interval.score_quantiles", raw, "a table {coverage: quantile}")
    quantiles = {}
    for key, value in raw.items():
        try:
            coverage = float(key)
        except ValueError:
            raise InputError(f"{where}.interval.score_quantiles", key, "coverages in (0, 1) as keys") from None
        if not 0.0 < coverage < 1.0 or isinstance(value, bool) or not isinstance(value, (int, float)) or value < 0:
            raise InputError(f"{where}.interval.score_quantiles.{key}", value,
                             "a non-negative number for a coverage in (0, 1)")
        quantiles[coverage] = float(value)
    if s0 < 0:
        raise InputError(f"{where}.interval.s0", s0, "a non-negative number")
    return MlpEnsemble(tuple(weights), tuple(biases), x_mean, x_scale, y_mean, y_scale, s0, quantiles)
