"""Homogenised (two-scale) mixed-EHL line contact: the production model of the rough regime
(docs/explanation/mixed-regime.md).

Where a contact is many roughness correlation lengths wide, the roughness is a statistically homogeneous micro-scale
inside a smooth macro-contact (Patir & Cheng 1978; Johnson, Greenwood & Poon 1972; Gelinck & Schipper 2000; Masjedi &
Khonsari 2012). The macro problem is the steady smooth line contact of :mod:`ehl_dataset.solvers.steady` (same grid,
same Newton solver and continuation) with

* the total pressure P = p_f + p_a(d) as unknown, d = h0 + x²/(2 r_eq) + V(P) the mean gap (macro film);
* p_a(d), the contact fraction and the gap distribution from the dry-contact table of the actual roughness pair
  (:mod:`ehl_dataset.model.dry_contact`: elastic–perfectly-plastic contact of the two profiles);
* the averaged Reynolds equation ∂/∂x(ρ C_p ∂p_f/∂x /(12η)) = ∂/∂x(ρ[u_m h_T + (u1 − u2)/2·S_φ]) with the flow
  factors of :mod:`ehl_dataset.model.flow_factors` (``closure="transverse"``: the exact 1-D cell average of the
  paper's model, no side leakage; ``"isotropic"``: Patir–Cheng / Wilson–Marsault with side leakage — the choice
  that decides the λ̄ → 0 limit) and the Eyring flow factor at the mean gap;
* cavitation p_f ≥ 0 (Reynolds condition, as the smooth steady solver);
* traction: the Eyring shear of the lubricated fraction, the rolling part (h_T/2)∂p_f/∂x, and μ_d·p_a.

μ is a steady value (no time average, no sampling error): the homogenisation takes the ensemble average of the
roughness configurations that a deterministic run samples over time.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .. import names
from ..discretisation.deflection import influence_matrix
from ..discretisation.reynolds import BAND, assemble
from ..model.contact import ContactCase
from ..model.dry_contact import dry_contact_table
from ..model.effects import Effects
from ..model.flow_factors import isotropic_flow_factors, lubricated_shear_stress, transverse_flow_factors
from ..model.lubricant import LubricantState
from ..model.roughness import RoughnessProfile
from ..model.traction import full_film_mask
from ..validation import InputError, check_range
from .asperity_model import solve_asperity
from .film_law_model import solve_film_law
from .levels import AccuracyLevel
from .krylov import WIDE_BAND, WIDE_INVERSE_WIDTH
from .newton import BANDED_MIN_UNKNOWNS, ReynoldsProblem, newton_solve
from .result import ContactResult
from .steady import ContactScales, dowson_higginson_lambda, solve_steady, solve_steady_problem

CLOSURES = names.CLOSURES
"""Closures (:data:`ehl_dataset.names.CLOSURES`): the flow factors ``transverse`` (1-D roughness as in the paper's model, no side leakage) and
``isotropic`` (side leakage around contacts), or ``film_law``: no averaged Reynolds equation, the smooth pressure with
the measured film law of resolved rough contacts and the table's traction
(:mod:`ehl_dataset.solvers.film_law_model`, for wide contacts)."""
BOUNDARY_FILM_M = 5e-9
"""Film-breakdown thickness h_b [m], the floor of the micro gaps in the 1-D flow factors (the deterministic model's
default, :data:`ehl_dataset.solvers.deterministic.BOUNDARY_FILM_M`)."""


@dataclass(frozen=True)
class HomogenisedOptions:
    """Closure choices of a homogenised solve.

    Parameters
    ----------
    closure : str
        Flow-factor closure (:data:`ehl_dataset.names.CLOSURES`) [-].
    boundary_film_m : float
        Floor h_b of the micro gaps in the traction [m].
    flow_floor_sigma : float, optional
        Floor of the micro gaps in the transverse flow factors, in units of σ; None: h_b [-].
    transport : str or float
        Roughness transport weight (:func:`ehl_dataset.model.flow_factors.transport_weight`): a name or the weight of
        surface 1 [-].
    micro_pressure_coefficient : float, optional
        c of the film-law closure's pressure fluctuations σ_p = c·E'Δq/4; None: the calibrated function of the inlet
        length (:func:`ehl_dataset.model.micro_pressure.micro_pressure_coefficient`); 0: off [-].
    fluctuations : str
        Form of that spread where no c is given (:data:`ehl_dataset.names.FLUCTUATIONS`): ``inlet`` (the calibrated
        c(L_in/β)) or ``spectral`` (σ_p = E'Δq_f/4 from the flattened part of the profile's spectrum,
        :func:`ehl_dataset.model.micro_pressure.spectral_pressure_std`) [-].
    """

    closure: str = names.DEFAULT_CLOSURE
    boundary_film_m: float = BOUNDARY_FILM_M
    flow_floor_sigma: float | None = None
    transport: str | float = "variance"
    micro_pressure_coefficient: float | None = None
    fluctuations: str = names.DEFAULT_FLUCTUATIONS

    def __post_init__(self):
        if self.closure not in CLOSURES:
            raise InputError("closure", self.closure, f"one of {list(CLOSURES)}")
        check_range("boundary_film_m", self.boundary_film_m, 0.0, 1e-6, low_inclusive=False, unit="m")
        if self.flow_floor_sigma is not None:
            check_range("flow_floor_sigma", self.flow_floor_sigma, 0.0, 10.0, low_inclusive=False)
        if self.micro_pressure_coefficient is not None:
            check_range("micro_pressure_coefficient", self.micro_pressure_coefficient, 0.0, 1.0)
        if self.fluctuations not in names.FLUCTUATIONS:
            raise InputError("fluctuations", self.fluctuations, f"one of {list(names.FLUCTUATIONS)}")


PSEUDO_DT = 0.3
"""Initial pseudo time step [a/u_r] of the Newton solve started from the smooth solution."""
MAX_ITERATIONS = 300
"""Newton iterations allowed for that solve (the rough film may be several times the smooth one)."""


class HomogenisedProblem(ReynoldsProblem):
    """The steady averaged-Reynolds problem (module docstring) in the interface of
    :class:`~ehl_dataset.solvers.newton.ReynoldsProblem`: the unknown ``p`` is the total pressure P [p_h], the film
    ``h`` the mean gap d [a²/r_eq]; ``cavitation_offset`` makes Newton's cavitation condition act on P − p_a(d)."""

    # exact linear solves (with the wide preconditioner band they need): near film collapse this Newton iteration is
    # sensitive to its iterates; with the forcing term 1 GPa, 5 mm, 0.05 m/s, SR 0.5, 100 °C, Rq 0.5/0.5 µm with the
    # isotropic closure at `fast` stalled
    inexact_newton = False
    preconditioner_widths = (WIDE_INVERSE_WIDTH, WIDE_BAND)
    banded_min_unknowns = BANDED_MIN_UNKNOWNS

    def __init__(self, *args, table=None, film_scale: float = 1.0, sr: float = 0.0, closure: str = "transverse",
                 h_b_m: float = BOUNDARY_FILM_M, transport="variance", flow_floor_m: float | None = None, **kwargs):
        super().__init__(*args, **kwargs)
        self.table = table
        self.film_scale = film_scale
        self.sr = sr
        self.closure = closure
        self.h_b_m = h_b_m
        self.flow_floor_m = h_b_m if flow_floor_m is None else flow_floor_m
        self.transport = transport
        self.film_may_close = True  # the mean gap may close (plastic asperities): no open-film check in Newton

    def asperity(self, h):
        """(p_a [p_h], ∂p_a/∂H) at mean gaps H."""
        d = h * self.film_scale
        return (np.asarray(self.table.asperity_pressure(d)) / self.p_h,
                np.asarray(self.table.d_asperity_pressure(d)) * self.film_scale / self.p_h)

    def cavitation_offset(self, h):
        return self.asperity(h)

    def flow_factors(self, h):
        d = h * self.film_scale
        if self.closure == "transverse":
            return transverse_flow_factors(self.table, d, self.flow_floor_m, self.transport)
        return isotropic_flow_factors(self.table, d, self.transport)

    def fluid(self, p_fluid, h, homotopy: float = 1.0):
        """ε, ∂ε/∂p_f, ∂ε/∂H (at fixed p_f), m = ρ̄(h_T + SR/2·S_φ), ∂m/∂p_f, ∂m/∂H, dimensionless."""
        fs = self.film_scale
        phi, phi_p, rho, rho_p = self.rheology(p_fluid, homotopy)
        ff = self.flow_factors(h)
        cond = np.maximum(ff.conductance / fs**3, 1e-300)
        d_cond = ff.d_conductance / fs**2
        h_t = np.maximum(ff.mean_gap / fs, 1e-12)
        d_h_t = ff.d_mean_gap
        carried = h_t + 0.5 * self.sr * ff.shear_flow / fs
        d_carried = d_h_t + 0.5 * self.sr * ff.d_shear_flow
        inv_eta2 = np.exp(-2.0 * phi)
        shear2 = (self.shear / h_t) ** 2
        g2 = np.maximum(inv_eta2 + shear2, 1e-300)
        g = np.sqrt(g2)
        eps = rho * cond * g / self.lam
        eps_p = eps * (rho_p / rho - phi_p * inv_eta2 / g2)
        eps_h = eps * (d_cond / cond - shear2 * d_h_t / (h_t * g2))
        return eps, eps_p, eps_h, rho * carried, rho_p * carried, rho * d_carried

    def residual(self, p, h, homotopy=1.0):
        """The residual of the averaged Reynolds equation in the fluid pressure p_f = P − p_a(H), with the bands
        ∂R/∂P and ∂R/∂H converted by the chain rule (∂p_f/∂P = 1, ∂p_f/∂H = −p_a'(H))."""
        p_a, p_a_h = self.asperity(h)
        p_fluid = p - p_a
        eps, eps_p, eps_h, m, m_p, m_h = self.fluid(p_fluid, h, homotopy)
        res, dp, dh = assemble(self.x, p_fluid, eps, eps_p, eps_h, m, m_p, m_h, self.squeeze, self.m_old,
                               self.face_order(), self.face_poiseuille())
        n = self.x.size
        nodes = np.arange(n)
        for o in range(BAND):
            j = nodes + o - 2
            valid = (j >= 0) & (j < n)
            dh[valid, o] -= dp[valid, o] * p_a_h[j[valid]]
        return res, dp, dh, (m, m_p, m_h - m_p * p_a_h)


def solve_homogenised(case: ContactCase, state: LubricantState, lvl: AccuracyLevel, plan: Effects,
                      roughness: RoughnessProfile | None = None, options: HomogenisedOptions | None = None,
                      **closure_options) -> ContactResult:
    """Steady homogenised mixed solve of a rough contact (module docstring) on the level's steady grid.

    Smooth surfaces (S_c = 0) return the steady smooth solution with the reason recorded (no roughness to homogenise).

    Parameters
    ----------
    case : ContactCase
        Operating conditions [SI].
    state : LubricantState
        The lubricant at the case's temperature [SI].
    lvl : AccuracyLevel
        Steady grid and tolerances [-].
    plan : Effects
        The effect plan [-].
    roughness : RoughnessProfile, optional
        Shape of both surfaces; None: the default profile (:func:`~ehl_dataset.model.roughness.default_profile`) [-].
    options : HomogenisedOptions, optional
        Closure choices; None: the defaults or ``closure_options`` [-].
    **closure_options
        Fields of :class:`HomogenisedOptions` as keywords (``closure=...``) [-].

    Returns
    -------
    ContactResult
        The result; it says whether the solve converged.
    """
    options = options or HomogenisedOptions(**closure_options)
    closure, h_b_m, transport = options.closure, options.boundary_film_m, options.transport
    start = time.perf_counter()
    if case.s_c == 0.0:
        smooth = solve_steady(case, state, lvl, Effects.smooth_steady(model="homogenised with smooth surfaces "
                                                                            "(S_c = 0): steady smooth solve"))
        smooth.extra["model"] = "homogenised"
        return smooth
    if closure == "film_law":
        return solve_film_law(case, state, lvl, plan, roughness, h_b_m,
                              micro_pressure_coefficient=options.micro_pressure_coefficient,
                              fluctuations=options.fluctuations)
    if closure == "asperity":
        return solve_asperity(case, state, lvl, plan, roughness, h_b_m,
                              micro_pressure_coefficient=options.micro_pressure_coefficient,
                              fluctuations=options.fluctuations)
    table = dry_contact_table(roughness, case.rq1, case.rq2, case.e_reduced)
    scales = ContactScales.of(case, state, plan.shear_thinning)
    smooth_plan = Effects(False, False, plan.shear_thinning, plan.compressibility, plan.mode, {})
    smooth = solve_steady(case, state, lvl, smooth_plan)
    x = smooth.x / scales.a
    problem = HomogenisedProblem(x=x, kmat=influence_matrix(x), gap=0.5 * x**2, lam=scales.lam, p_h=case.p_h,
                                 state=state, compressible=plan.compressibility and state.compressible,
                                 shear=scales.shear, table=table, film_scale=scales.film_scale, sr=case.sr,
                                 closure=closure, h_b_m=h_b_m, transport=transport,
                                 flow_floor_m=None if options.flow_floor_sigma is None
                                 else options.flow_floor_sigma * table.sigma)
    iterations = smooth.iterations
    p0 = smooth.pressure / case.p_h
    h00 = smooth.extra["h0_m"] / scales.film_scale
    # from the smooth solution, globalised by pseudo-time (the rough film grows from the smooth one); the steady
    # solver's continuations if that fails
    outcome = newton_solve(problem, p0, h00, pseudo_dt=PSEUDO_DT, tol_residual=lvl.tol_residual,
                           tol_load=lvl.tol_load, tol_step=lvl.tol_step, max_iterations=MAX_ITERATIONS)
    iterations += outcome.iterations
    if not outcome.converged:
        outcome, its, _ = solve_steady_problem(problem, p0, h00, lvl)
        iterations += its
    return _result(case, state, lvl, plan, scales, problem, outcome, iterations, start, smooth, closure, table)


def _result(case, state, lvl, plan, scales, problem: HomogenisedProblem, outcome, iterations, start, smooth, closure,
            table) -> ContactResult:
    _, lambda_bar = dowson_higginson_lambda(case, state)
    x_m = problem.x * scales.a
    p_total = outcome.p * case.p_h
    d = outcome.h * scales.film_scale
    p_a = np.asarray(table.asperity_pressure(d))
    p_f = np.maximum(p_total - p_a, 0.0)
    ff = problem.flow_factors(outcome.h)
    h_t = np.asarray(ff.mean_gap)
    eta = state.viscosity(p_f)
    film = full_film_mask(p_f)
    shear = np.where(film, lubricated_shear_stress(table, d, eta, case.u_s, state.tau0, problem.h_b_m), 0.0)
    rolling = np.where(film, 0.5 * h_t * np.gradient(p_f, x_m), 0.0)
    asperity = math.copysign(1.0, case.u_s) * (case.u_s != 0.0) * state.mu_d * p_a
    load = case.load_per_length

    def integral(f):
        return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(x_m)))

    parts = {"mu_couette": integral(shear) / load, "mu_poiseuille": integral(rolling) / load,
             "mu_asperity": integral(asperity) / load}
    mu = sum(parts.values())
    converged = bool(outcome.converged) and all(np.isfinite([mu, *d]))
    recorded = plan.to_dict()
    recorded["reasons"] = dict(recorded.get("reasons") or {})
    recorded["reasons"]["model"] = f"homogenised mixed EHL ({closure} flow factors, dry-contact table)"
    recorded["roughness"], recorded["transient"] = True, False  # steady: the ensemble average replaces the time one
    return ContactResult(
        mu=float(mu), h_min=float(np.min(h_t)), h_central=float(np.interp(0.0, x_m, h_t)), p_max=float(np.max(p_total)),
        converged=converged, iterations=int(iterations), wall_time=time.perf_counter() - start, level=lvl.name,
        effects=recorded, lambda_bar=lambda_bar, asperity_load_share=integral(p_a) / load,
        residuals={"reynolds": outcome.residual, "load": outcome.load, "step": outcome.step,
                   "complementarity": outcome.complementarity},
        message=outcome.message if converged else f"not converged: {outcome.message}", x=x_m, pressure=p_total,
        film=h_t,
        extra={"model": "homogenised", "closure": closure, "n_nodes": int(x_m.size), **parts,
               "smooth_mu": smooth.mu, "smooth_h_min_m": smooth.h_min, "boundary_film_m": problem.h_b_m,
               "flow_floor_m": problem.flow_floor_m,
               "contact_fraction_max": float(np.max(table.contact_fraction(d))),
               "dry_contact_table": table.meta.get("key", "")},
    )
