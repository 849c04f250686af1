"""A learned alternative to Eq. 9: gradient-boosted trees on the paper's features, predicting ln μ.

Choice: scikit-learn's ``HistGradientBoostingRegressor``. It needs no feature scaling (the features span very
different magnitudes), captures the λ̄-regime change and interactions without a hand-written term list (so no
branch split and no jump at λ̄ = 1), is deterministic with a fixed seed, trains on 42,000 rows in seconds and
predicts vectorised. Inputs: W̄, ᾱ, V̄, ln λ̄, SR, ln S̄c, ln S̄eq (r̄ is omitted: under Hertz loading it is a
function of W̄, see :mod:`surrogate.features`). Target: ln μ, so predictions are always positive.
Trees are piecewise constant: outside the training ranges the prediction is flat, not extrapolated.
Not persisted to coefficient files (no pickles); it is a comparison model (``gearloss surrogate compare``).
"""

from __future__ import annotations

import numpy as np

from threadpoolctl import threadpool_limits

from .features import compute_features

LEARNED_FEATURES = ("W", "alpha", "V", "ln_lam", "SR", "ln_Sc", "ln_Seq")


def feature_matrix(features: dict[str, np.ndarray]) -> np.ndarray:
    """The (n, 7) matrix of the learned model's features (:data:`LEARNED_FEATURES`) from a feature dict.

    Parameters
    ----------
    features : dict of str to ndarray
        Features [-].

    Returns
    -------
    ndarray
        Shape (n, 7) [-].
    """
    cols = {
        "W": features["W"], "alpha": features["alpha"], "V": features["V"], "ln_lam": np.log(features["lam"]),
        "SR": features["SR"], "ln_Sc": np.log(features["Sc"]), "ln_Seq": np.log(features["Seq"]),
    }
    return np.column_stack([np.ravel(cols[name]) for name in LEARNED_FEATURES])


class LearnedFriction:
    """ln μ learned by scikit-learn's ``HistGradientBoostingRegressor`` on the regression's features.

    Parameters
    ----------
    lubricant : Lubricant
        Supplies η0 and α1 of the features [-].
    e_reduced : float
        Reduced modulus E' [Pa].
    max_iter : int
        Boosting iterations [-].
    learning_rate : float
        Boosting learning rate [-].
    max_leaf_nodes : int
        Leaves per tree [-].
    random_state : int
        Seed [-].
    threads : int, optional
        OpenMP threads (1 keeps timings predictable on shared machines; None: all) [-].
    """

    def __init__(self, lubricant, e_reduced: float, *, max_iter: int = 400, learning_rate: float = 0.1,
                 max_leaf_nodes: int = 31, random_state: int = 0, threads: int | None = 1):
        from sklearn.ensemble import HistGradientBoostingRegressor

        self.lubricant = lubricant
        self.threads = threads  # OpenMP threads; 1 keeps timings predictable on shared machines (None: all)
        self.e_reduced = e_reduced
        self.model = HistGradientBoostingRegressor(max_iter=max_iter, learning_rate=learning_rate,
                                                   max_leaf_nodes=max_leaf_nodes, early_stopping=False,
                                                   random_state=random_state)

    def fit_features(self, features: dict[str, np.ndarray], ln_mu: np.ndarray) -> "LearnedFriction":
        """Fit ln μ on feature arrays.

        Parameters
        ----------
        features : dict of str to ndarray
            Features (:func:`surrogate.features.compute_features`) [-].
        ln_mu : ndarray
            ln μ of the rows [-].

        Returns
        -------
        LearnedFriction
            This model, fitted.
        """
        with threadpool_limits(self.threads):
            self.model.fit(feature_matrix(features), np.asarray(ln_mu, dtype=float))
        return self

    def predict_ln_mu_features(self, features: dict[str, np.ndarray]) -> np.ndarray:
        """Predicted ln μ on feature arrays.

        Parameters
        ----------
        features : dict of str to ndarray
            Features [-].

        Returns
        -------
        ndarray
            ln μ [-].
        """
        with threadpool_limits(self.threads):
            return self.model.predict(feature_matrix(features))

    def mu(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2, sr_floor: float = 0.0) -> np.ndarray:
        """Friction coefficient μ at SI inputs (|SR| floored at ``sr_floor``).

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
        sr_floor : float
            Smallest |SR| evaluated [-].

        Returns
        -------
        ndarray
            μ [-].
        """
        sr_eff = np.maximum(np.abs(np.asarray(sr, dtype=float)), sr_floor)
        feats = compute_features(p_h, r_eq, u_r, sr_eff, temperature, rq1, rq2, self.lubricant, self.e_reduced)
        return np.exp(self.predict_ln_mu_features(feats)).reshape(np.shape(feats["lam"]))
