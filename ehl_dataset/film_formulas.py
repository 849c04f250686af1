"""Closed-form EHL film thickness formulas for line contacts (SI units).

Dimensionless groups (Hamrock's notation): U = η0 u_r/(E' R), G = α E', W = w'/(E' R), H = h/R, with u_r the
rolling (mean) velocity, w' the load per unit length and E' the reduced modulus 2/[(1 − ν1²)/E1 + (1 − ν2²)/E2].
"""

from __future__ import annotations

import numpy as np


def dimensionless_groups(eta0, u_r, alpha, e_reduced, r_eq, load_per_length):
    """Return (U, G, W) for a line contact."""
    u = np.asarray(eta0) * np.asarray(u_r) / (np.asarray(e_reduced) * np.asarray(r_eq))
    g = np.asarray(alpha) * np.asarray(e_reduced)
    w = np.asarray(load_per_length) / (np.asarray(e_reduced) * np.asarray(r_eq))
    return u, g, w


def dowson_higginson_min_film(eta0, u_r, alpha, e_reduced, r_eq, load_per_length):
    """Dowson–Higginson minimum film thickness [m] for a line contact.

    H_min = 2.65 U^0.70 G^0.54 W^−0.13 (Dowson & Higginson, *Elasto-hydrodynamic lubrication*, 1977 SI edition),
    the formula the paper uses for its λ̄ (Li & Kahraman 2009, Sect. 2.1).
    """
    u, g, w = dimensionless_groups(eta0, u_r, alpha, e_reduced, r_eq, load_per_length)
    return 2.65 * np.asarray(r_eq) * u**0.70 * g**0.54 * w**-0.13
