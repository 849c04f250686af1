"""Surface traction and friction coefficient of a line contact (paper Eq. 7–8; docs/explanation/ehl-model.md).

Sign convention: ``mu`` is the friction force that resists the motion of surface 1 relative to surface 2, per unit
load. It is ≥ 0 for u1 > u2 (SR > 0). In the paper's notation the traction on surface 1 is
q = −(h/2) ∂p/∂x − τ with τ the Couette shear stress in the direction of sliding, and μ = −∫q dx / W'. Hence

    μ = (1/W') [ ∫_film (h/2) ∂p/∂x dx + ∫_film τ dx + sign(u_s) μ_d ∫_contact p dx ],

    τ = τ0 asinh(η u_s / (τ0 h))     (exact Eyring shear; Newtonian η u_s/h when τ0 → ∞),

where "film" is the full-film region (the flooded inlet up to the cavitation boundary behind the outlet
constriction; the cavitated region carries no liquid shear) minus the asperity-contact nodes, and "contact" the
nodes where asperities touch (q = μ_d p there, paper after Eq. 7, in the direction opposing sliding: the asperity
friction has the sign of u_s, and vanishes in pure rolling). In pure rolling only the Poiseuille (rolling) part
remains, which rough films can make slightly negative.
"""

from __future__ import annotations

import numpy as np


def eyring_shear_stress(eta, u_s: float, h, tau0: float):
    """Couette shear stress τ = τ0 asinh(η u_s/(τ0 h)), with the sign of u_s.

    Parameters
    ----------
    eta : array_like
        Dynamic viscosity [Pa s].
    u_s : float
        Sliding velocity u1 − u2 [m/s].
    h : array_like
        Film thickness [m].
    tau0 : float
        Eyring stress τ0 [Pa].

    Returns
    -------
    ndarray
        τ [Pa].
    """
    return tau0 * np.arcsinh(np.asarray(eta) * u_s / (tau0 * np.asarray(h)))


CAVITATED_FRACTION = 1e-9
"""A node counts as cavitated when its pressure is at most this fraction of the maximum: the complementarity
solver leaves cavitated nodes at round-off level (±1e-14 p_h), where an exact ``p <= 0`` test would let such a
node extend the full-film region over a cavitated stretch (docs/explanation/ehl-model.md)."""


def full_film_mask(pressure) -> np.ndarray:
    """True from the inlet up to the cavitation boundary: the first node behind the pressure maximum where p = 0
    (to round-off: p ≤ CAVITATED_FRACTION · max p)."""
    p = np.asarray(pressure)
    mask = np.ones(p.size, dtype=bool)
    peak = int(np.argmax(p))
    behind = np.nonzero(p[peak:] <= CAVITATED_FRACTION * max(float(p[peak]), 0.0))[0]
    if behind.size:
        mask[peak + behind[0] + 1:] = False
    return mask


def _integrate(x, f):
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(x)))


def friction_components(x, pressure, film, eta, u_s: float, tau0: float, load_per_length: float,
                        mu_d: float = 0.0, contact=None, couette_stress=None) -> dict[str, float]:
    """Friction coefficient and its parts from the profiles of a solve.

    The pressure gradient is the second-order finite difference on the (non-uniform) nodes.

    Parameters
    ----------
    x : ndarray
        Nodes [m].
    pressure : ndarray
        Pressure at the nodes [Pa].
    film : ndarray
        Film thickness at the nodes [m].
    eta : ndarray
        Viscosity at the nodes [Pa s].
    u_s : float
        Sliding velocity [m/s].
    tau0 : float
        Eyring stress τ0 [Pa].
    load_per_length : float
        Normal load per unit length W' [N/m].
    mu_d : float
        Boundary (dry-contact) friction coefficient of asperity-contact nodes [-].
    contact : ndarray of bool, optional
        Asperity-contact nodes; None: none [-].
    couette_stress : ndarray, optional
        Shear stress at the nodes replacing the isothermal Eyring stress (the thermal correction,
        :func:`ehl_dataset.model.thermal.thermal_couette_traction`); None: isothermal [Pa].

    Returns
    -------
    dict of str to float
        ``mu`` and its parts ``mu_poiseuille`` (rolling, pressure-gradient part), ``mu_couette`` (Eyring shear part)
        and ``mu_asperity`` (μ_d share), all divided by W' [-].
    """
    x = np.asarray(x, dtype=float)
    p = np.asarray(pressure, dtype=float)
    h = np.asarray(film, dtype=float)
    film_region = full_film_mask(p)
    if contact is None:
        contact = np.zeros(x.size, dtype=bool)
    liquid = film_region & ~contact
    dpdx = np.gradient(p, x)
    safe_h = np.where(liquid, np.maximum(h, 1e-300), 1.0)
    poiseuille = np.where(liquid, 0.5 * h * dpdx, 0.0)
    stress = eyring_shear_stress(eta, u_s, safe_h, tau0) if couette_stress is None else np.asarray(couette_stress)
    couette = np.where(liquid, stress, 0.0)
    asperity = np.where(contact, mu_d * np.sign(u_s) * p, 0.0)
    parts = {
        "mu_poiseuille": _integrate(x, poiseuille) / load_per_length,
        "mu_couette": _integrate(x, couette) / load_per_length,
        "mu_asperity": _integrate(x, asperity) / load_per_length,
    }
    parts["mu"] = parts["mu_poiseuille"] + parts["mu_couette"] + parts["mu_asperity"]
    return parts
