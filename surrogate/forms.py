"""The paper's two regression forms for ln μ (Li & Kahraman 2009, Eq. 9a and 9b) as design matrices.

Each branch is a list of named *terms*; ln μ = Σ c_k term_k(features), linear in the coefficients, so ordinary
least squares fits it. The reading of the (typeset-garbled) paper equations adopted here, term by term:

Eq. 9a, λ̄ ≤ 1 ("mixed")::

    μ = exp[a0 + a1 λ̄ S̄c + a2 W̄ r̄ + a3 λ̄ W̄ + a4 S̄eq^λ̄]
        · SR^(a5 λ̄) · S̄eq^(a6 λ̄) · S̄c^(a7 SR + a8 V̄ + a9 ln λ̄)
    ln μ = a0 + a1 λ̄S̄c + a2 W̄r̄ + a3 λ̄W̄ + a4 S̄eq^λ̄ + a5 λ̄ ln SR + a6 λ̄ ln S̄eq
           + a7 SR ln S̄c + a8 V̄ ln S̄c + a9 ln λ̄ ln S̄c

Eq. 9b, λ̄ > 1 ("full_film")::

    μ = exp[b0 + λ̄(b1 V̄ + b2 r̄) + b3 V̄^r̄ + b4 ᾱ^W̄ + b5 ᾱ^r̄ + b6 r̄^V̄]
        · λ̄^(b7 + b8 V̄) · SR^(b9 + b10 ln λ̄ + b11 ᾱ) · W̄^(b12 λ̄) · S̄c^(b13 λ̄)
    ln μ = b0 + b1 λ̄V̄ + b2 λ̄r̄ + b3 V̄^r̄ + b4 ᾱ^W̄ + b5 ᾱ^r̄ + b6 r̄^V̄ + b7 ln λ̄ + b8 V̄ ln λ̄
           + b9 ln SR + b10 ln λ̄ ln SR + b11 ᾱ ln SR + b12 λ̄ ln W̄ + b13 λ̄ ln S̄c

The superscripts (S̄eq^λ̄, V̄^r̄, ᾱ^W̄, ᾱ^r̄, r̄^V̄) are read literally as powers, as printed. The names below are
the registry keys stored in coefficient files; a file whose term list differs from the registry is rejected.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

Features = dict[str, np.ndarray]


@dataclass(frozen=True)
class Term:
    """One regressor: registry ``name``, printable ``expression`` and the function that computes its column.

    Parameters
    ----------
    name : str
        Registry name of the term [-].
    expression : str
        Printable expression, e.g. ``ᾱ ln SR`` [-].
    column : callable
        Function of the feature dict that returns the term's column [-].
    """

    name: str
    expression: str
    column: Callable[[Features], np.ndarray]


def _ln(x):
    return np.log(x)


MIXED_TERMS: tuple[Term, ...] = (
    Term("1", "a0", lambda f: np.ones_like(f["lam"])),
    Term("lam*Sc", "a1 λ̄ S̄c", lambda f: f["lam"] * f["Sc"]),
    Term("W*r", "a2 W̄ r̄", lambda f: f["W"] * f["r"]),
    Term("lam*W", "a3 λ̄ W̄", lambda f: f["lam"] * f["W"]),
    Term("Seq**lam", "a4 S̄eq^λ̄", lambda f: f["Seq"] ** f["lam"]),
    Term("lam*ln(SR)", "a5 λ̄ ln SR", lambda f: f["lam"] * _ln(f["SR"])),
    Term("lam*ln(Seq)", "a6 λ̄ ln S̄eq", lambda f: f["lam"] * _ln(f["Seq"])),
    Term("SR*ln(Sc)", "a7 SR ln S̄c", lambda f: f["SR"] * _ln(f["Sc"])),
    Term("V*ln(Sc)", "a8 V̄ ln S̄c", lambda f: f["V"] * _ln(f["Sc"])),
    Term("ln(lam)*ln(Sc)", "a9 ln λ̄ ln S̄c", lambda f: _ln(f["lam"]) * _ln(f["Sc"])),
)
"""Eq. 9a (λ̄ ≤ 1), coefficients a0..a9."""

FULL_FILM_TERMS: tuple[Term, ...] = (
    Term("1", "b0", lambda f: np.ones_like(f["lam"])),
    Term("lam*V", "b1 λ̄ V̄", lambda f: f["lam"] * f["V"]),
    Term("lam*r", "b2 λ̄ r̄", lambda f: f["lam"] * f["r"]),
    Term("V**r", "b3 V̄^r̄", lambda f: f["V"] ** f["r"]),
    Term("alpha**W", "b4 ᾱ^W̄", lambda f: f["alpha"] ** f["W"]),
    Term("alpha**r", "b5 ᾱ^r̄", lambda f: f["alpha"] ** f["r"]),
    Term("r**V", "b6 r̄^V̄", lambda f: f["r"] ** f["V"]),
    Term("ln(lam)", "b7 ln λ̄", lambda f: _ln(f["lam"])),
    Term("V*ln(lam)", "b8 V̄ ln λ̄", lambda f: f["V"] * _ln(f["lam"])),
    Term("ln(SR)", "b9 ln SR", lambda f: _ln(f["SR"])),
    Term("ln(lam)*ln(SR)", "b10 ln λ̄ ln SR", lambda f: _ln(f["lam"]) * _ln(f["SR"])),
    Term("alpha*ln(SR)", "b11 ᾱ ln SR", lambda f: f["alpha"] * _ln(f["SR"])),
    Term("lam*ln(W)", "b12 λ̄ ln W̄", lambda f: f["lam"] * _ln(f["W"])),
    Term("lam*ln(Sc)", "b13 λ̄ ln S̄c", lambda f: f["lam"] * _ln(f["Sc"])),
)
"""Eq. 9b (λ̄ > 1), coefficients b0..b13."""

BRANCHES: tuple[str, ...] = ("mixed", "full_film")
"""Branch names: ``mixed`` is λ̄ ≤ threshold (Eq. 9a), ``full_film`` is λ̄ > threshold (Eq. 9b)."""


@dataclass(frozen=True)
class Formula:
    """A named, versioned pair of branch term lists (paper Eq. 9a and 9b) split at ``lambda_threshold``.

    Parameters
    ----------
    name : str
        Registry name of the form [-].
    version : int
        Version of the form, recorded in coefficient files [-].
    terms : dict of str to tuple of Term
        Regression terms of each branch (``mixed``, ``full_film``) [-].
    lambda_threshold : float
        λ̄ at which the branches meet (1 in the paper) [-].
    reference : str
        Where the form is published [-].
    """

    name: str
    version: int
    terms: dict[str, tuple[Term, ...]]
    lambda_threshold: float = 1.0
    reference: str = ""

    def term_names(self, branch: str) -> list[str]:
        """Names of the terms of one branch, in coefficient order.

        Parameters
        ----------
        branch : str
            ``mixed`` or ``full_film`` [-].

        Returns
        -------
        list of str
            The term names.
        """
        return [t.name for t in self.terms[branch]]


LI_KAHRAMAN_2009 = Formula(
    name="li_kahraman_2009_eq9",
    version=1,
    terms={"mixed": MIXED_TERMS, "full_film": FULL_FILM_TERMS},
    lambda_threshold=1.0,
    reference="Li & Kahraman, J. Adv. Mech. Des. Syst. Manuf. 3 (2009) 146, Eq. 9a/9b "
              "(term reading: surrogate/forms.py)",
)

FORMULAS: dict[tuple[str, int], Formula] = {(LI_KAHRAMAN_2009.name, LI_KAHRAMAN_2009.version): LI_KAHRAMAN_2009}
"""Registry of known formulas by (name, version)."""


def design_matrix(terms: tuple[Term, ...], features: Features) -> np.ndarray:
    """The (n, k) design matrix of ``terms`` evaluated on ``features`` (float64, C order).

    Parameters
    ----------
    terms : tuple of Term
        Regression terms (columns) [-].
    features : dict of str to ndarray
        Features of n rows (:func:`surrogate.features.compute_features`) [-].

    Returns
    -------
    ndarray
        The design matrix, shape (n, k) [-].
    """
    columns = [np.asarray(t.column(features), dtype=float).ravel() for t in terms]
    return np.column_stack(columns) if columns else np.empty((0, 0))
