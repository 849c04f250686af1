"""Named accuracy levels of the EHL solver (frozen dataclasses).

A level fixes the discretisation and the stopping rules of the steady solves (smooth, and the smooth part of the
homogenised model); the accuracy-versus-time study measures what each costs. Grid spacings are in units of the
Hertz half width a. The deterministic rough model's grid rule and averaging target per level are its own
(:data:`ehl_dataset.solvers.deterministic.LEVEL_OPTIONS`), chosen by the level's name.

Steady smooth grid: nodes are clustered (spacing ``dx_fine``) in two bands around the Hertz inlet (x ≈ −a) and the
outlet constriction/pressure spike (x ≈ +a), growing linearly over ``transition`` to ``dx_coarse`` elsewhere
(see :func:`ehl_dataset.discretisation.grid.clustered_grid`). A uniform grid would need 1,600–3,200 nodes at
M > 100; the clustered grids reach the same film accuracy with a few hundred (docs/ehl_solver.md, "Numerics").
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..validation import InputError


@dataclass(frozen=True)
class AccuracyLevel:
    """Discretisation and tolerances of one accuracy level.

    Grid (steady): ``x_start``, ``x_end`` domain ends [a]; ``dx_fine``, ``dx_coarse`` spacings [a];
    ``inlet_band``, ``outlet_band`` (start, end) of the fine bands [a]; ``transition`` length over which the spacing
    grows from fine to coarse [a]; ``inlet_resolution`` caps the fine spacing at this fraction of the inlet length
    scale H_c^(2/3) (H_c = h_c r_eq/a², Moes' estimate): at heavy load the inlet meniscus zone and the outlet
    spike shrink like H_c^(2/3), and a fixed spacing would under-resolve them.
    Newton: ``tol_residual`` max relative Reynolds residual (scaled by the Couette flux ρ̄H), ``tol_load`` relative
    load-balance error, ``tol_step`` max pressure correction [p_h]; ``max_iterations`` per continuation stage.
    What each level costs and gives: docs/ehl_solver.md ("Accuracy levels"). (The rough-run fields ``dx_rough``,
    ``courant``, ``n_passes``, ``mu_sem_target``, ... were the deleted transient solver's, removed at ehl-2026.11-15.)
    """

    name: str
    x_start: float = -2.5
    x_end: float = 1.5
    dx_fine: float = 2.5e-3
    dx_coarse: float = 2.5e-2
    inlet_band: tuple[float, float] = (-1.15, -0.9)
    outlet_band: tuple[float, float] = (0.75, 1.06)
    transition: float = 0.25
    inlet_resolution: float = 0.1
    tol_residual: float = 1e-6
    tol_load: float = 1e-6
    tol_step: float = 1e-6
    max_iterations: int = 60

    def with_domain(self, x_start: float, x_end: float) -> "AccuracyLevel":
        """Copy with another domain [x_start, x_end] (in units of a), e.g. −2b…1.5b for the Huang case."""
        if not (x_start < -1.0 and x_end > 1.0):
            raise InputError("domain", (x_start, x_end), "x_start < −1 and x_end > 1 (units of the Hertz half width)")
        return replace(self, x_start=float(x_start), x_end=float(x_end))


LEVELS: dict[str, AccuracyLevel] = {
    "fast": AccuracyLevel("fast", dx_fine=6e-3, dx_coarse=4e-2, inlet_resolution=0.25, tol_residual=1e-5, tol_load=1e-5, tol_step=1e-5,
                          max_iterations=50),
    "standard": AccuracyLevel("standard"),
    "reference": AccuracyLevel("reference", dx_fine=6e-4, dx_coarse=8e-3, transition=0.2, inlet_resolution=0.03,
                               tol_residual=1e-7, tol_load=1e-9, tol_step=1e-7, max_iterations=80),
}
"""The named levels. ``standard`` is the default of :func:`ehl_dataset.solver.solve_contact`."""


def get_level(name: str | AccuracyLevel) -> AccuracyLevel:
    """Return the level called ``name`` (an :class:`AccuracyLevel` is returned as is)."""
    if isinstance(name, AccuracyLevel):
        return name
    try:
        return LEVELS[name]
    except (KeyError, TypeError):
        raise InputError("level", name, f"one of {sorted(LEVELS)}") from None
