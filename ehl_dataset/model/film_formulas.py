"""Closed-form EHL film thickness formulas for line contacts (SI units).

Dimensionless groups (Hamrock's notation): U = η0 u_r/(E' R), G = α E', W = w'/(E' R), H = h/R, with u_r the
rolling (mean) velocity, w' the load per unit length and E' the reduced modulus 2/[(1 − ν1²)/E1 + (1 − ν2²)/E2].
"""

from __future__ import annotations

import numpy as np


def dimensionless_groups(eta0, u_r, alpha, e_reduced, r_eq, load_per_length):
    """Dimensionless speed, material and load groups of a line contact (rolling-velocity convention).

    U = η0 u_r/(E' R), G = α E', W = w/(E' R).

    Parameters
    ----------
    eta0 : array_like
        Dynamic viscosity at the inlet, ambient pressure [Pa s].
    u_r : array_like
        Rolling (mean) velocity (u1 + u2)/2 [m/s].
    alpha : array_like
        Pressure–viscosity coefficient [1/Pa].
    e_reduced : array_like
        Reduced modulus E' [Pa].
    r_eq : array_like
        Equivalent radius of curvature R [m].
    load_per_length : array_like
        Normal load per unit length w [N/m].

    Returns
    -------
    tuple of ndarray
        (U, G, W) [-].
    """
    u = np.asarray(eta0) * np.asarray(u_r) / (np.asarray(e_reduced) * np.asarray(r_eq))
    g = np.asarray(alpha) * np.asarray(e_reduced)
    w = np.asarray(load_per_length) / (np.asarray(e_reduced) * np.asarray(r_eq))
    return u, g, w


def dowson_higginson_min_film(eta0, u_r, alpha, e_reduced, r_eq, load_per_length):
    """Dowson–Higginson minimum film thickness for a line contact.

    H_min = 2.65 U^0.70 G^0.54 W^−0.13 (Dowson & Higginson, *Elasto-hydrodynamic lubrication*, 1977 SI edition),
    the formula the paper uses for its λ̄ (Li & Kahraman 2009, Sect. 2.1).

    Parameters
    ----------
    eta0 : array_like
        Dynamic viscosity at the inlet, ambient pressure [Pa s].
    u_r : array_like
        Rolling (mean) velocity (u1 + u2)/2 [m/s].
    alpha : array_like
        Pressure–viscosity coefficient [1/Pa].
    e_reduced : array_like
        Reduced modulus E' [Pa].
    r_eq : array_like
        Equivalent radius of curvature R [m].
    load_per_length : array_like
        Normal load per unit length w [N/m].

    Returns
    -------
    ndarray
        h_min [m].
    """
    u, g, w = dimensionless_groups(eta0, u_r, alpha, e_reduced, r_eq, load_per_length)
    return 2.65 * np.asarray(r_eq) * u**0.70 * g**0.54 * w**-0.13


def moes_central_film(eta0, u_r, alpha, e_reduced, r_eq, load_per_length):
    """Moes central film thickness for an isothermal Newtonian line contact.

    Moes (1992), as given by Venner & Lubrecht, *Multilevel Methods in Lubrication* (Elsevier 2000), Ch. 5: with
    the rolling-velocity groups U, G, W of :func:`dimensionless_groups`,
    M = W (2U)^−1/2, L = G (2U)^1/4, H_c = (h_c/R)(2U)^−1/2 and

        H_RI = 3 M^−1,  H_EI = 2.621 M^−1/5,  H_RP = 1.287 L^2/3,  H_EP = 1.311 M^−1/8 L^3/4,
        s = 3/2 [1 + exp(−1.2 H_EI/H_RI)],
        H_c = [ (H_RI^7/3 + H_EI^7/3)^(3s/7) + (H_RP^−7/2 + H_EP^−7/2)^(−2s/7) ]^(1/s).

    A fit to incompressible Newtonian (Barus) numerical solutions covering the rigid/elastic, isoviscous/piezoviscous
    regimes (a compressible solution lies 13–19 % below it: docs/explanation/ehl-model.md, "Validation"). At the
    point U = 1e−11, G = 5000, W = 1e−4 it agrees with Dowson–Toyoda to 2 % (60 % apart with the sum-velocity
    convention), which pins the velocity convention (mean velocity).

    Parameters
    ----------
    eta0 : array_like
        Dynamic viscosity at the inlet, ambient pressure [Pa s].
    u_r : array_like
        Rolling (mean) velocity (u1 + u2)/2 [m/s].
    alpha : array_like
        Pressure–viscosity coefficient [1/Pa].
    e_reduced : array_like
        Reduced modulus E' [Pa].
    r_eq : array_like
        Equivalent radius of curvature R [m].
    load_per_length : array_like
        Normal load per unit length w [N/m].

    Returns
    -------
    ndarray
        h_c [m].
    """
    u, g, w = dimensionless_groups(eta0, u_r, alpha, e_reduced, r_eq, load_per_length)
    two_u = 2.0 * u
    m = w / np.sqrt(two_u)
    l_ = g * two_u**0.25
    h_ri = 3.0 / m
    h_ei = 2.621 * m**-0.2
    h_rp = 1.287 * l_ ** (2.0 / 3.0)
    h_ep = 1.311 * m**-0.125 * l_**0.75
    s = 1.5 * (1.0 + np.exp(-1.2 * h_ei / h_ri))
    rigid = (h_ri ** (7.0 / 3.0) + h_ei ** (7.0 / 3.0)) ** (3.0 * s / 7.0)
    piezo = (h_rp**-3.5 + h_ep**-3.5) ** (-2.0 * s / 7.0)
    h_c = (rigid + piezo) ** (1.0 / s)
    return h_c * np.sqrt(two_u) * np.asarray(r_eq)


def moes_parameters(eta0, u_r, alpha, e_reduced, r_eq, load_per_length):
    """Moes' load and material parameters (M, L) of :func:`moes_central_film`.

    Parameters
    ----------
    eta0 : array_like
        Dynamic viscosity at the inlet, ambient pressure [Pa s].
    u_r : array_like
        Rolling (mean) velocity (u1 + u2)/2 [m/s].
    alpha : array_like
        Pressure–viscosity coefficient [1/Pa].
    e_reduced : array_like
        Reduced modulus E' [Pa].
    r_eq : array_like
        Equivalent radius of curvature R [m].
    load_per_length : array_like
        Normal load per unit length w [N/m].

    Returns
    -------
    tuple of ndarray
        (M, L) [-].
    """
    u, g, w = dimensionless_groups(eta0, u_r, alpha, e_reduced, r_eq, load_per_length)
    return w / np.sqrt(2.0 * u), g * (2.0 * u) ** 0.25


def dowson_toyoda_central_film(eta0, u_r, alpha, e_reduced, r_eq, load_per_length):
    """Dowson–Toyoda central film thickness: H_c = 3.06 U^0.69 G^0.56 W^−0.10.

    Dowson & Toyoda, "A central film thickness formula for elastohydrodynamic line contacts", Proc. 5th
    Leeds–Lyon Symposium (1979) 60–65; a fit to isothermal Newtonian numerical solutions (U on the mean velocity).

    Parameters
    ----------
    eta0 : array_like
        Dynamic viscosity at the inlet, ambient pressure [Pa s].
    u_r : array_like
        Rolling (mean) velocity (u1 + u2)/2 [m/s].
    alpha : array_like
        Pressure–viscosity coefficient [1/Pa].
    e_reduced : array_like
        Reduced modulus E' [Pa].
    r_eq : array_like
        Equivalent radius of curvature R [m].
    load_per_length : array_like
        Normal load per unit length w [N/m].

    Returns
    -------
    ndarray
        h_c [m].
    """
    u, g, w = dimensionless_groups(eta0, u_r, alpha, e_reduced, r_eq, load_per_length)
    return 3.06 * np.asarray(r_eq) * u**0.69 * g**0.56 * w**-0.10


def pan_hamrock_min_film(eta0, u_r, alpha, e_reduced, r_eq, load_per_length):
    """Pan–Hamrock minimum film thickness: H_min = 1.714 W^−0.128 U^0.694 G^0.568.

    Pan & Hamrock, "Simple formulas for performance parameters used in elastohydrodynamically lubricated line
    contacts", J. Tribol. 111 (1989) 246–251; fit to compressible (Dowson–Higginson) Roelands solutions.

    Parameters
    ----------
    eta0 : array_like
        Dynamic viscosity at the inlet, ambient pressure [Pa s].
    u_r : array_like
        Rolling (mean) velocity (u1 + u2)/2 [m/s].
    alpha : array_like
        Pressure–viscosity coefficient [1/Pa].
    e_reduced : array_like
        Reduced modulus E' [Pa].
    r_eq : array_like
        Equivalent radius of curvature R [m].
    load_per_length : array_like
        Normal load per unit length w [N/m].

    Returns
    -------
    ndarray
        h_min [m].
    """
    u, g, w = dimensionless_groups(eta0, u_r, alpha, e_reduced, r_eq, load_per_length)
    return 1.714 * np.asarray(r_eq) * w**-0.128 * u**0.694 * g**0.568


def pan_hamrock_central_film(eta0, u_r, alpha, e_reduced, r_eq, load_per_length):
    """Pan–Hamrock central film thickness: H_c = 2.922 W^−0.166 U^0.692 G^0.470 (same source as the minimum).

    Parameters
    ----------
    eta0 : array_like
        Dynamic viscosity at the inlet, ambient pressure [Pa s].
    u_r : array_like
        Rolling (mean) velocity (u1 + u2)/2 [m/s].
    alpha : array_like
        Pressure–viscosity coefficient [1/Pa].
    e_reduced : array_like
        Reduced modulus E' [Pa].
    r_eq : array_like
        Equivalent radius of curvature R [m].
    load_per_length : array_like
        Normal load per unit length w [N/m].

    Returns
    -------
    ndarray
        h_c [m].
    """
    u, g, w = dimensionless_groups(eta0, u_r, alpha, e_reduced, r_eq, load_per_length)
    return 2.922 * np.asarray(r_eq) * w**-0.166 * u**0.692 * g**0.470
