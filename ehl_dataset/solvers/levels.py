"""Named accuracy levels of the EHL solver (frozen dataclasses).

A level fixes the discretisation and the stopping rules; the accuracy-versus-time study measures what each costs.
Lengths are relative: grid spacings in units of the Hertz half width a (steady smooth solves) and, for rough runs,
also in units of the roughness correlation length.

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
    Transient (phase 2): ``dx_rough`` spacing [roughness correlation length], ``dx_rough_max`` cap [a];
    ``courant`` time step as a fraction of dx/u_r; ``n_passes`` length of the base run in units of the domain
    length / u_r (the time the rolling speed needs to carry the surfaces through the domain); ``average_fraction``
    fraction of the base run's steps used for the time average (the last ones; the rest is the start-up
    transient); ``max_nodes_rough`` upper bound on the grid size; ``max_steps_rough`` upper bound on the number of
    time steps (the time step grows beyond ``courant``·dx when needed; recorded); ``mu_sem_target`` standard error
    of the time-averaged μ, relative to max(|μ|, 0.01), at which the averaging window may stop (once it spans 20
    correlation times, :data:`ehl_dataset.solvers.time_average.RELIABLE_LENGTH`): a run whose μ fluctuates more is
    continued with the same time step, up to ``max_passes`` × the domain length / u_r. ``mu_sem_target`` 0: fixed
    window of ``n_passes``, the standard error still reported (``fast``). Why the window adapts, and what each
    level costs and gives: docs/ehl_solver.md ("Sampling error of μ", "Accuracy levels").
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
    dx_rough: float = 0.5
    dx_rough_max: float = 0.01
    courant: float = 1.0
    n_passes: float = 2.0
    average_fraction: float = 0.5
    max_nodes_rough: int = 1024
    max_steps_rough: int = 600
    mu_sem_target: float = 0.10
    max_passes: float = 12.0

    def with_domain(self, x_start: float, x_end: float) -> "AccuracyLevel":
        """Copy with another domain [x_start, x_end] (in units of a), e.g. −2b…1.5b for the Huang case."""
        if not (x_start < -1.0 and x_end > 1.0):
            raise InputError("domain", (x_start, x_end), "x_start < −1 and x_end > 1 (units of the Hertz half width)")
        return replace(self, x_start=float(x_start), x_end=float(x_end))


LEVELS: dict[str, AccuracyLevel] = {
    "fast": AccuracyLevel("fast", dx_fine=6e-3, dx_coarse=4e-2, inlet_resolution=0.25, tol_residual=1e-5, tol_load=1e-5, tol_step=1e-5,
                          max_iterations=50, dx_rough=1.0, dx_rough_max=0.02, courant=2.0, n_passes=1.5,
                          max_nodes_rough=512, max_steps_rough=300,
                          mu_sem_target=0.0, max_passes=1.5),
    "standard": AccuracyLevel("standard"),
    "reference": AccuracyLevel("reference", dx_fine=6e-4, dx_coarse=8e-3, transition=0.2, inlet_resolution=0.03,
                               tol_residual=1e-7, tol_load=1e-9, tol_step=1e-7, max_iterations=80, dx_rough=0.25, dx_rough_max=0.005,
                               courant=0.5, n_passes=3.0, max_nodes_rough=4096, max_steps_rough=4000,
                               mu_sem_target=0.03, max_passes=40.0),
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
