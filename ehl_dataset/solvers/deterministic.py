"""Deterministic transient mixed-EHL line contact: the accuracy reference of the rough regime (paper Eq. 1–8;
docs/explanation/mixed-regime.md).

Physics: the paper's unified Reynolds equation with the Eyring flow factor, the film of Eq. 3 with both roughness
profiles moving with their surfaces, the log-kernel deflection (Eq. 4), two-slope viscosity, Dowson–Higginson
density, μ_d·p where asperities touch and the time-averaged μ (Eq. 8). What makes μ converge with the grid:

* asperity contact is a complementarity between the solid contact pressure p_c ≥ 0 and the gap above a physical
  boundary-film (film-breakdown) thickness h_b, with elastic–perfectly-plastic asperities (p_c ≤ hardness); the
  total pressure p = p_f + p_c deflects the surfaces, only the fluid pressure p_f drives flow;
* lubricant mass is conserved exactly: flux-form finite volumes with mass-conserving (Elrod–Adams) cavitation,
  through contacts as everywhere else;
* the grid resolves the roughness and the micro-EHL length ℓ = √(2 R_asp h_b) (:func:`grid_spacing`), the time
  integrator is second order (variable-step BDF2) at Courant 0.25 (:data:`COURANT`; Courant 0.5 and 1 put μ high
  where asperities touch, docs/explanation/mixed-regime.md section "Roughness sweep");
* each time step is a semismooth Newton solve whose linear systems are solved by GMRES with FFT products of the
  deflection and a banded preconditioner (:mod:`ehl_dataset.solvers.krylov`): O(N log N) per iteration.

μ(t) = (1/W')[∫(h/2)∂p_f/∂x dx + ∫θ τ dx + sign(u_s) μ_d ∫p_c dx] with the Eyring shear τ = τ0 asinh(η u_s/(τ0 h))
(h the local film, h_b in contact, θ the filled fraction) and is averaged over time with its autocorrelation-
corrected standard error, the window extended until that error meets the target. The reported film is the
time-averaged film profile over the averaging window (``h_min`` its minimum, ``h_central`` its value at x = 0, the
quantities a homogenised model predicts); the time-averaged minimum of the instantaneous film is
``extra["h_min_local_m"]``.
"""

from __future__ import annotations

import hashlib
import math
import time
from dataclasses import dataclass, field, fields
from typing import Callable

import numpy as np
import scipy.fft
import scipy.linalg

from ..discretisation.deflection import inverse_kernel_band, periodic_kernel_spectrum, uniform_kernel
from ..discretisation.mixed_system import FACE_MEANS, assemble, local_matvec

COUETTE_FLUXES = {"linear": 1.0, "first-order": 0.0, "minmod": 2.0}
"""Couette (shear) flux of the mass rows: minmod-limited linear upwind (the default since det-2026.11-3: second order
where the content is smooth; at a content jump, such as a film closing on a contact, it never carries lubricant
against the flow), linear upwind (unlimited; the scheme of det-2026.11-2, which can drive the film fraction
negative at such jumps), or first-order upwind; docs/explanation/mixed-regime.md."""
from ..model.contact import ContactCase
from ..model.effects import Effects
from ..model.lubricant import LubricantState
from ..model.roughness import RoughnessProfile, default_profile, plan_surfaces, profile_record
from ..model.traction import eyring_shear_stress
from ..validation import InputError, check_range
from .krylov import BandedPreconditioner, gmres
from .levels import get_level, level_settings
from .result import ContactResult
from .steady import ContactScales, dowson_higginson_lambda, moes_h_c, solve_steady
from .time_average import time_mean

START_COARSENING = 3.0
"""Ratio of the continuation grid of the steady smooth solve that starts every run
(:func:`~ehl_dataset.solvers.steady.solve_steady`'s ``coarsening``): the one of det-2026.11-21's results and saved
states, whose fingerprints hash the converged start bit for bit."""

MODEL_VERSION = "det-2026.11-21"
"""Version of the deterministic model's numerics, recorded with its results; bump with any change that can alter a
solved value (what each version changed is listed in CHANGELOG.md, "Solver versions").
:data:`ehl_dataset.solver.SOLVER_VERSION` covers the whole solver."""

FLOOR_STOP_SINCE = "det-2026.11-17"
"""The first model version whose Newton solve may stop at its measured round-off floor above ROUND_OFF_MARGIN × the
tolerance (within ROUND_OFF_STEP_MARGIN ×)."""

CONTINUES = ("det-2026.11-16", "det-2026.11-17", "det-2026.11-18", "det-2026.11-19", "det-2026.11-20")
"""Model versions whose saved run states this version continues (``checkpoint``): they solve the same equations and
differ from it only at round-off stops, and states of det-18 and -19 keep their absolute film offset (film_reference
0), so they go on in their own round-off (a continued run's record names the version and step it continued from, its
``continued_from``)."""

WATCHDOG_STEPS = 5
"""Damped Newton steps a solve of the last attempt at a step may take although the Armijo line search rejected them
(Chamberlain, Powell, Lemarechal & Pedersen, Math. Prog. Study 16 (1982) 1: the watchdog technique); the solve still
has to meet the tolerance or the round-off stops."""

FLOOR_ULPS = 1.0
"""Units in the last place by which :meth:`MixedProblem.round_off_floor` perturbs the state."""

DENSE_KERNEL_NODES = 320
"""Largest grid [nodes] whose deflection K p is a dense product: below about 350 nodes one N × N product costs less
than the zero-padded rfft/irfft pair (1.7 µs against 10 µs at 110 nodes, 8 µs against 24 µs at 300, 18 µs against
13 µs at 400 on the 2-core machine), and the matrix (≤ 0.8 MB) is built once per problem."""


def model_version_key(version: str) -> tuple[int, ...]:
    """A model version det-YYYY.MM-n as (YYYY, MM, n), so that det-2026.11-10 sorts after det-2026.11-9."""
    date, number = version.removeprefix("det-").rsplit("-", 1)
    return (*(int(v) for v in date.split(".")), int(number))


BOUNDARY_FILM_M = 5e-9
"""Default film-breakdown (boundary-film) thickness h_b [m]: below it the surfaces are in solid contact through
their adsorbed/reacted boundary films, which carry load and friction μ_d·p_c. Representative value: adsorbed
friction-modifier layers are a few nm thick, and deterministic mixed-EHL becomes mesh-dependent once films fall
below ~10–20 nm (Liu, Wang, Wang, Hu & Zhu, J. Tribol. 128 (2006) 641); its effect on μ is reported as a
sensitivity (h_b × 0.5, × 2) in docs/explanation/mixed-regime.md."""
FILM_FLOOR = 1e-3
"""The conductance ε reads films below FILM_FLOOR·H_b (interfering asperities) as that floor: a regularisation that
keeps ε > 0 where plastically flattened tips close the gap (``DeterministicOptions.film_floor``; its 10× sensitivity
in docs/validation/deterministic-reference.md, "Time step, thresholds and the boundary film")."""
COURANT = 0.25
"""Default u_r Δt/Δx (det-2026.11-9; 0.5 in det-8, 1.0 before). Measured where asperities carry load, case A's
conditions with Rq 0.5 µm (λ̄ 0.2) at β/16 over 11 paired passes: Courant 0.5 → 0.25 moves μ by −8.9 % ± 6.2 % and
the asperity share from 0.035 to 0.004; 0.25 → 0.125 by −0.20 % ± 0.05 % (share 0.0039). On case A (Rq 0.3 µm) at
β/32 over 40 passes: 1 → 0.5 −3.8 % ± 1.1 %, 0.5 → 0.25 −0.13 % ± 0.03 %. The colliding-asperity events of a longer
step are partly numerical (docs/validation/deterministic-reference.md, "Time step, thresholds and the boundary
film")."""
YIELD_PRESSURE_PA = 6.8e9
"""Hardness of case-hardened gear steel, 60 HRC ≈ 697 HV ≈ 6.8 GPa (ASTM E140): the cap of the solid contact
pressure (elastic–perfectly-plastic asperities; Johnson 1985, §6)."""

INLET_RESOLUTION = 0.1
"""Default largest spacing relative to the inlet length scale a·H_c^(2/3) of the smooth EHL solution (H_c =
h_c r/a², Moes' central film): the heavy-load inlet and outlet zones shrink like H_c^(2/3) (the steady solver's rule,
docs/explanation/ehl-model.md). The ``reference`` level's; ``fast`` and ``standard`` take 0.3 and 0.2
(:data:`ehl_dataset.solvers.levels.REGISTRY`)."""

WIDE_ROUTES = ("auto", "resolve", "windows")
"""How a deterministic run covers the contact (:class:`DeterministicOptions` ``wide``)."""


@dataclass(frozen=True)
class DeterministicOptions:
    """Discretisation and stopping rules of a deterministic run (all physical inputs are in the case and lubricant).

    The averaging window is extended from ``min_average_passes`` until the standard error of the time-averaged μ is
    ≤ ``mu_sem_target``·max(|μ|, 0.01) over ≥ 20 correlation times, or ``max_passes`` is reached; one pass is the
    domain length at u_r.

    Parameters
    ----------
    dx_m : float, optional
        Grid spacing; None: :func:`grid_spacing` with ``points_per_beta``, ``points_per_ell`` and
        ``inlet_resolution`` [m].
    points_per_beta : float
        Grid points per roughness correlation length β [-].
    points_per_ell : float
        Grid points per micro-EHL length [-].
    inlet_resolution : float
        Largest spacing in units of the smooth inlet length a·H_c^(2/3) [-].
    boundary_film_m : float, optional
        Boundary film h_b; None: :data:`BOUNDARY_FILM_M` [m].
    yield_pressure_pa : float
        Contact-pressure cap [Pa].
    courant : float
        Courant number u_r Δt/Δx [-].
    domain : tuple of float
        (x_start, x_end) in units of the Hertz half width a [-].
    ramp_passes : float
        Passes over which the roughness amplitude grows from 0 to 1 [-].
    startup_passes : float
        Passes after the ramp before averaging starts [-].
    min_average_passes : float
        Shortest averaging window, in passes [-].
    max_passes : float
        Longest averaging window, in passes [-].
    layout_passes : float, optional
        Run length in passes the roughness is laid out for; None: ``max_passes``. Where each surface reads the
        profile depends on it, so runs to be compared pairwise (the same roughness at the same times, e.g. at
        different grid spacings with different ``max_passes``) must share it, and it must be ≥ ``max_passes`` [-].
    mu_sem_target : float
        Target standard error of the time-averaged μ relative to max(|μ|, 0.01) [-].
    face_mean : str
        Face mean of the Poiseuille conductance (:data:`ehl_dataset.discretisation.mixed_system.FACE_MEANS`) [-].
    couette_flux : str
        Shear-flux scheme (:data:`COUETTE_FLUXES`) [-].
    band : int
        Half width of the banded inverse kernel in the preconditioner [-].
    newton_tolerance : float
        Largest scaled residual of every step (mass rows relative to the central Couette flux, complementarity rows
        in p_h) [-].
    newton_iterations : int
        Newton iterations per step [-].
    film_floor : float
        The conductance reads films below ``film_floor``·h_b as that floor (interfering asperities) [-].
    max_substeps : int
        Largest split of a time step whose Newton solve failed; reached only by a step that fails every smaller
        split, so converged results do not depend on it [-].
    max_nodes : int
        Largest grid accepted [-].
    wide : str
        How :func:`ehl_dataset.solvers.wide_contact.solve_deterministic_contact` (the entry point of
        ``solve_contact(model="deterministic")``) covers a contact (:data:`WIDE_ROUTES`): ``"resolve"`` solves the
        whole conjunction (:func:`solve_deterministic`, which always does); ``"windows"`` solves ``wide_windows``
        periodic windows of ``window_length_beta`` correlation lengths across the Hertzian zone, fed by the film law;
        ``"auto"`` takes the windows when a/β exceeds :data:`~ehl_dataset.solvers.wide_contact.WIDE_A_OVER_BETA` and
        no ``dx_m`` is given [-].
    wide_windows : int
        Number of periodic windows across a wide contact [-].
    window_length_beta : float
        Window length in correlation lengths β [-].
    clock : callable
        The wall clock, ``time.perf_counter`` [-].
    """

    dx_m: float | None = None
    points_per_beta: float = 32.0
    points_per_ell: float = 2.5
    inlet_resolution: float = INLET_RESOLUTION
    boundary_film_m: float | None = None
    yield_pressure_pa: float = YIELD_PRESSURE_PA
    courant: float = COURANT
    domain: tuple[float, float] = (-2.5, 1.5)
    ramp_passes: float = 0.5
    startup_passes: float = 1.0
    min_average_passes: float = 1.5
    max_passes: float = 12.0
    layout_passes: float | None = None
    mu_sem_target: float = 0.015
    face_mean: str = "kirchhoff"
    couette_flux: str = "minmod"
    band: int = 12
    newton_tolerance: float = 1e-10
    newton_iterations: int = 50
    film_floor: float = FILM_FLOOR
    max_substeps: int = 128
    max_nodes: int = 20000
    wide: str = "auto"
    wide_windows: int = 5
    window_length_beta: float = 8.0
    clock: Callable[[], float] = field(default=time.perf_counter, compare=False)

    def __post_init__(self):
        if self.dx_m is not None:
            check_range("dx_m", self.dx_m, 0.0, 1e-3, low_inclusive=False, unit="m")
        if self.boundary_film_m is not None:
            check_range("boundary_film_m", self.boundary_film_m, 0.0, 1e-6, low_inclusive=False, unit="m")
        check_range("courant", self.courant, 0.0, 8.0, low_inclusive=False)
        check_range("inlet_resolution", self.inlet_resolution, 0.0, 10.0, low_inclusive=False)
        check_range("mu_sem_target", self.mu_sem_target, 0.0, 1.0)
        check_range("film_floor", self.film_floor, 0.0, 1.0, low_inclusive=False, unit="of h_b")
        if self.layout_passes is not None:
            check_range("layout_passes", self.layout_passes, self.max_passes, 1e4, unit="passes")
        if self.face_mean not in FACE_MEANS:
            raise InputError("face_mean", self.face_mean, f"one of {sorted(FACE_MEANS)}")
        if self.couette_flux not in COUETTE_FLUXES:
            raise InputError("couette_flux", self.couette_flux, f"one of {sorted(COUETTE_FLUXES)}")
        if self.wide not in WIDE_ROUTES:
            raise InputError("wide", self.wide, f"one of {list(WIDE_ROUTES)}")
        x_start, x_end = self.domain
        if not (x_start < -1.0 and x_end > 1.0):
            raise InputError("domain", self.domain, "x_start < -1 < 1 < x_end (units of the Hertz half width)")

    @property
    def roughness_layout_passes(self) -> float:
        """The run length [passes] the roughness is laid out for: ``layout_passes``, else ``max_passes``."""
        return float(self.max_passes if self.layout_passes is None else self.layout_passes)


def deterministic_options(level: str = "reference", **overrides) -> DeterministicOptions:
    """The deterministic model's options at an accuracy level.

    Parameters
    ----------
    level : str or AccuracyLevel or Level
        An accuracy level of the registry :data:`ehl_dataset.solvers.levels.REGISTRY`, whose grid rule and averaging
        target (``Level.deterministic``) the options take [-].
    **overrides
        Fields of :class:`DeterministicOptions` to set instead (e.g. ``dx_m``, ``wide``) [-].

    Returns
    -------
    DeterministicOptions
        The options. An unknown level raises :class:`~ehl_dataset.validation.InputError`.
    """
    return DeterministicOptions(**{**level_settings(level).deterministic, **overrides})


def asperity_radius(profile: RoughnessProfile, rq1: float, rq2: float) -> float:
    """Mean summit radius [m] of the composite roughness, 1/√m4 with m4 the fourth spectral moment (mean square
    curvature) of the profile scaled to σ = √(Rq1² + Rq2²); a Gaussian ACF of correlation length β gives
    β²/(√12 σ) (Nayak 1971). Smooth surfaces (σ = 0) have no summits: ∞."""
    sigma = math.hypot(rq1, rq2)
    z = profile.z * (sigma / profile.rq)
    curvature = np.diff(z, 2) / profile.spacing**2
    mean_square = float(np.mean(curvature**2))
    return 1.0 / math.sqrt(mean_square) if mean_square > 0.0 else math.inf


ROUND_OFF_MARGIN = 10.0
ROUND_OFF_STEP = 1e-15
ROUND_OFF_STEP_MARGIN = 1000.0
BALANCE_RETRIES = 3
"""Iterations a Newton solve goes on after a stall at the round-off floor where every scaled row meets the tolerance
and only the global lubricant balance does not (det-2026.11-21): the round-off of the pressures moves that balance
by ±1–3e-11 from one iterate to the next (validation/deterministic_balance_floor.py), so a balance just above the
tolerance is usually met within a few more iterations."""
"""A Newton solve also ends when its scaled residual is within ROUND_OFF_MARGIN × the tolerance and it has
stalled (the last iteration reduced it by less than half, or the line search found no decrease), or within
ROUND_OFF_STEP_MARGIN × the tolerance when its correction is below ROUND_OFF_STEP p_h in every pressure: a few units
in the last place of a pressure of order p_h, which the state cannot take in double precision (MixedProblem.newton).
The attainable balance of a mass row is ≈ (ε/Δ)·1e-16·max P_f, ≈ 1e-10 at the flooded inlet of a heavily loaded
contact (thick film, low viscosity, large conductance ε, reference flux ρ̄H of the thin central film), and grows as
the grid is refined (docs/explanation/mixed-regime.md, "Robustness"). det-2026.11-10 to -14 took ROUND_OFF_STEP = 1e-12
p_h, which is 4,500 units in the last place: a correction of 1e-13 p_h still moves the mass rows (through the
deflection and the storage term, ≈ K·w/(ΔT·ρ̄H)) by more than the tolerance, and the stop accepted steps whose global
balance a further iteration would have met. det-2026.11-15's 1e-15 takes that iteration: over whole short
validation runs (B β/16, D, H, I, L β/8; C β/64) no step exceeds 1e-10 where 1 to 96 did, B β/64 12 of 9,051 steps
where 1,851 did (largest 4.2e-10, was 1.4e-9), at no extra cost (docs/explanation/mixed-regime.md, "Mass balance")."""
STRICT_ROUND_OFF_SINCE = "det-2026.11-15"
"""The first model version whose round-off stop takes ROUND_OFF_STEP = 1e-15 p_h (results record their version: runs
made before it may hold steps that a further iteration would have balanced)."""

REFACTOR_ITERATIONS = 20
"""GMRES iterations of a linear solve at which the stored preconditioner counts as aged: the next solve refactors it
from its own Jacobian first (det-2026.11-14; until det-13 the aged solve itself was repeated with a fresh LU, and its
first iterations were lost). On three 2-pass `fast` runs that saves 6–19 % of the GMRES iterations
(benchmarks/deterministic_linear_cost.py; docs/validation/deterministic-reference.md, "Robustness and cost")."""


def grid_spacing(profile: RoughnessProfile, rq1: float, rq2: float, h_b: float, options: DeterministicOptions,
                 inlet_length: float = math.inf) -> tuple[float, dict]:
    """Grid spacing [m] that resolves the roughness (its resolution length / ``points_per_beta``: the correlation
    length β of a Gaussian-ACF profile, the short cut-off wavelength λ_s of a band-limited one,
    :attr:`~ehl_dataset.model.roughness.RoughnessProfile.resolution_length`), the micro-EHL length
    ℓ = √(2 R_asp h_b) (ℓ/``points_per_ell``) and the smooth inlet length scale ``inlet_length`` [m]
    (``options.inlet_resolution`` of it), and the numbers it came from."""
    beta = profile.correlation_length
    grid_length = profile.resolution_length
    r_asp = asperity_radius(profile, rq1, rq2)
    ell = math.sqrt(2.0 * r_asp * h_b)
    dx = min(grid_length / options.points_per_beta, ell / options.points_per_ell,
             options.inlet_resolution * inlet_length)
    return dx, {"beta_m": beta, "grid_length_m": grid_length, "asperity_radius_m": r_asp, "micro_ehl_length_m": ell,
                "inlet_length_m": inlet_length}


class MixedProblem:
    """The discrete mixed-EHL equations (:mod:`ehl_dataset.discretisation.mixed_system`) on a uniform grid ``x``
    [a], with the film H = H0 + gap + K(P_f + P_c) computed by FFT, and their Newton–Krylov solution."""

    def __init__(self, x: np.ndarray, scales: ContactScales, state: LubricantState, h_b: float, p_yield: float,
                 compressible: bool = True, face_mean: str = "kirchhoff", band: int = 12,
                 couette_flux: str = "minmod", mean_pressure: float | None = None, film_floor: float = FILM_FLOOR):
        """``mean_pressure`` None: the whole contact, loaded with W' (∫P dX = π/2); a number P̄: ``x`` is one
        period of a periodic window (period N Δ) whose mean total pressure is P̄, with the periodic deflection
        (:func:`~ehl_dataset.discretisation.deflection.periodic_kernel_spectrum`; its mean is H0's)."""
        self.x = np.ascontiguousarray(x, dtype=float)
        self.n = n = self.x.size
        self.dx = float(self.x[1] - self.x[0])
        self.periodic = mean_pressure is not None
        self.lam = scales.lam
        self.shear = scales.shear
        self.p_h = scales.p_h
        self.state = state
        self.h_b = h_b
        self.film_floor = film_floor
        self.p_yield = p_yield
        self.compressible = compressible and state.compressible
        self.mean = FACE_MEANS[face_mean]
        self.order = COUETTE_FLUXES[couette_flux]
        self.weights = np.full(n, self.dx)
        if self.periodic:
            self.fft_size = n
            self.kernel_spectrum = periodic_kernel_spectrum(n, self.dx)
            self.kappa = 1.0 / float(scipy.fft.irfft(self.kernel_spectrum, n)[0])
            self.load_target = float(mean_pressure) * n * self.dx
        else:
            kernel = uniform_kernel(n, self.dx)
            # circular convolution of length >= 2N - 1 holds the linear one on the N output nodes (DC-FFT)
            self.fft_size = scipy.fft.next_fast_len(2 * n - 1, real=True)
            wrapped = np.zeros(self.fft_size)
            wrapped[:n] = kernel[n - 1:]
            wrapped[-(n - 1):] = kernel[: n - 1]
            self.kernel_spectrum = scipy.fft.rfft(wrapped)
            self.weights[0] = self.weights[-1] = 0.5 * self.dx
            self.kappa = 1.0 / float(kernel[n - 1])
            self.load_target = 0.5 * math.pi
        self.dense_kernel = None
        self.film_reference = 0.0
        if n <= DENSE_KERNEL_NODES:
            if self.periodic:
                self.dense_kernel = scipy.linalg.circulant(scipy.fft.irfft(self.kernel_spectrum, n))
            else:
                self.dense_kernel = scipy.linalg.toeplitz(kernel[n - 1:], kernel[n - 1::-1])
        self.binv = inverse_kernel_band(band, self.dx)
        self.m_ref = 1.0
        self.preconditioner = None
        self.cost = {"newton_iterations": 0, "gmres_iterations": 0, "factorisations": 0, "round_off_stops": 0,
                     "floor_stops": 0, "watchdog_steps": 0}
        self.last_gmres_iterations = 0

    # -- state --------------------------------------------------------------------------------------------------
    def pack(self, pf, th, pc, h0) -> np.ndarray:
        z = np.empty(3 * self.n + 1)
        z[0:-1:3], z[1:-1:3], z[2:-1:3], z[-1] = pf, th, pc, h0
        return z

    @staticmethod
    def unpack(z):
        return z[0:-1:3], z[1:-1:3], z[2:-1:3], float(z[-1])

    def deflection(self, p: np.ndarray) -> np.ndarray:
        """K p: a dense product on small grids (:data:`DENSE_KERNEL_NODES`), else by zero-padded FFT (DC-FFT)."""
        if self.dense_kernel is not None:
            return self.dense_kernel @ p
        return scipy.fft.irfft(scipy.fft.rfft(p, self.fft_size) * self.kernel_spectrum, self.fft_size)[: self.n]

    def film(self, z, gap) -> np.ndarray:
        pf, _, pc, h0 = self.unpack(z)
        return self._film_of(pf, pc, h0, gap)

    def _film_of(self, pf, pc, h0, gap) -> np.ndarray:
        """H = H0 + gap + K(P_f + P_c); with a film reference (:meth:`rebase_film_offset`) the unknown H0 is the
        offset's change from it, added last: H = (H_ref + gap + K P) + δH0."""
        if self.film_reference == 0.0:
            return h0 + gap + self.deflection(pf + pc)
        return (self.film_reference + gap + self.deflection(pf + pc)) + h0

    def rebase_film_offset(self, z) -> np.ndarray:
        """``z`` with its film offset moved into :attr:`film_reference` (det-2026.11-20): the unknown becomes the
        offset's change δH0, small through a run, so one unit in its last place moves every node's film by far less than
        one of H0 ≈ −0.6 did (which moved the global lubricant balance by up to 0.8 of its 1e-10 target on fine grids of
        heavily loaded contacts; docs/validation/deterministic-reference.md, "Conservation"). The same film to
        round-off."""
        moved = np.array(z, dtype=float)
        self.film_reference += float(moved[-1])
        moved[-1] = 0.0
        return moved

    def conducting_film(self, h):
        """(film the conductance ε reads, max(H, film_floor·H_b); that floor)."""
        floor = self.film_floor * self.h_b
        return np.maximum(h, floor), floor

    def fluid(self, pf, h):
        """ε, ∂ε/∂P_f, ∂ε/∂H, ρ̄, ∂ρ̄/∂P_f at the nodes (negative iterate pressures read as 0)."""
        st = self.state
        positive = pf > 0.0
        pa = np.where(positive, pf, 0.0) * self.p_h
        phi = np.minimum(st.law.exponent(pa), 600.0)
        phi_p = st.law.exponent_derivative(pa) * self.p_h * positive
        if self.compressible:
            rho = st.density(pa) / st.rho0
            rho_p = st.density_derivative(pa) * self.p_h / st.rho0 * positive
        else:
            rho = np.ones_like(pf)
            rho_p = np.zeros_like(pf)
        hp, floor = self.conducting_film(h)
        inv_eta2 = np.exp(-2.0 * phi)
        shear2 = (self.shear / hp) ** 2
        g2 = inv_eta2 + shear2
        eps = rho * hp**3 * np.sqrt(g2) / self.lam
        eps_p = eps * (rho_p / rho - phi_p * inv_eta2 / g2)
        eps_h = np.where(h > floor, eps * (3.0 / hp - shear2 / (hp * g2)), 0.0)
        return eps, eps_p, eps_h, rho, rho_p

    def content(self, z, h) -> np.ndarray:
        """Lubricant content m = ρ̄ θ max(H, H_b) per node (as in :func:`assemble`)."""
        pf, th, _, _ = self.unpack(z)
        return self.fluid(pf, h)[3] * th * np.maximum(h, self.h_b)

    def storage(self, d_t: float | None, ratio: float, m_old, m_older):
        """(w a0/ΔT, w (a1 m^n + a2 m^{n−1})/ΔT): backward Euler for ``ratio`` = 0, variable-step BDF2 with
        ΔT/ΔT_previous = ``ratio`` otherwise; zeros for a steady solve (``d_t`` None)."""
        if d_t is None:
            zero = np.zeros(self.n)
            return zero, zero
        if ratio == 0.0:
            a0, a1, a2 = 1.0, -1.0, 0.0
        else:
            a0, a1, a2 = (1 + 2 * ratio) / (1 + ratio), -(1 + ratio), ratio * ratio / (1 + ratio)
        old = a1 * m_old + (a2 * m_older if a2 else 0.0)
        return self.weights * (a0 / d_t), self.weights * old / d_t

    # -- equations --------------------------------------------------------------------------------------------
    def evaluate(self, z, gap, storage):
        """Residual (3N + 1), film, and the band Jacobians."""
        pf, th, pc, h0 = self.unpack(z)
        h = self._film_of(pf, pc, h0, gap)
        eps, eps_p, eps_h, rho, rho_p = self.fluid(pf, h)
        hp, floor = self.conducting_film(h)
        cube, cube_h = hp**3, np.where(h > floor, 3.0 * hp**2, 0.0)  # the film factor H³ of ε
        res, jac, dfilm = assemble(self.dx, np.ascontiguousarray(pf), np.ascontiguousarray(th),
                                   np.ascontiguousarray(pc), h, eps, eps_p, eps_h, rho, rho_p, self.h_b, self.kappa,
                                   self.p_yield, storage[0], storage[1], self.mean, self.order,
                                   cube, cube_h, self.periodic)
        out = np.empty(3 * self.n + 1)
        out[:-1] = res
        out[-1] = float(self.weights @ (pf + pc)) - self.load_target
        return out, h, jac, dfilm

    @property
    def mass_rows(self) -> slice:
        """The mass rows of the residual: every node's on a periodic window; from node 1 on the whole contact, whose
        node 0 row is the inlet condition θ = 1 (their sum is the global lubricant balance)."""
        return slice(0 if self.periodic else 3, -1, 3)

    def row_scale(self) -> np.ndarray:
        """Mass rows relative to the reference flux ρ̄H at the contact centre; the others in their own units."""
        scale = np.ones(3 * self.n + 1)
        scale[0:-1:3] = 1.0 / self.m_ref
        return scale

    def jacobian_product(self, jac, dfilm, v):
        dp = v[0:-1:3] + v[2:-1:3]
        out = np.empty_like(v)
        out[:-1] = local_matvec(jac, dfilm, v, self.deflection(dp) + v[-1], self.periodic)
        out[-1] = float(self.weights @ dp)
        return out

    def _refactor(self, jac, dfilm):
        self.preconditioner = BandedPreconditioner(jac, dfilm, self.binv, self.weights, self.periodic)
        self.cost["factorisations"] += 1

    def _direction(self, jac, dfilm, scaled_residual, scale, tol):
        if self.preconditioner is None or self.last_gmres_iterations >= REFACTOR_ITERATIONS:
            self._refactor(jac, dfilm)
        matvec = lambda v: self.jacobian_product(jac, dfilm, v) * scale  # noqa: E731
        apply = lambda r: self.preconditioner.apply(r / scale)  # noqa: E731
        step, its, rel = gmres(matvec, apply, -scaled_residual, tol, 40)
        total = its
        if rel > tol:  # the stored LU could not reach the forcing term: refactor with this Jacobian, solve again
            self._refactor(jac, dfilm)
            step, its, rel = gmres(matvec, apply, -scaled_residual, tol, 80)
            total += its
        self.last_gmres_iterations = its
        self.cost["gmres_iterations"] += total
        return step, rel

    def round_off_floor(self, z, gap, storage, seed: int = 0) -> float:
        """The scaled residual's round-off floor at ``z`` [same norm as :meth:`newton`'s]: the largest change of a
        scaled row, or of the sum of the mass rows, when every unknown moves by :data:`FLOOR_ULPS` units in its last
        place (two random sign patterns). No state that double precision can hold is closer to the solution than
        that: fine grids of heavily loaded contacts reach it above ROUND_OFF_MARGIN × the tolerance (B at β/256:
        rows 1.2e-8 for 4 ulps, balance 1.3e-9 at a step where Newton stalls at 1.0e-9)."""
        scale = self.row_scale()
        base = self.evaluate(z, gap, storage)[0] * scale
        signs = np.random.default_rng(seed).choice((-1.0, 1.0), size=(2, z.size))
        floor = 0.0
        for sign in signs:
            moved = self.evaluate(z + FLOOR_ULPS * np.spacing(np.abs(z)) * sign, gap, storage)[0] * scale - base
            floor = max(floor, float(np.max(np.abs(moved))), abs(float(np.sum(moved[self.mass_rows]))))
        return floor

    def newton(self, z, gap, storage, tol: float, max_iterations: int, max_pressure_step: float = 2.0,
               floor_stop: bool = True, watchdog: int = 0):
        """Semismooth Newton from ``z`` with an Armijo line search on ½‖S F‖²; inexact linear solves with the
        Eisenstat–Walker-type forcing term min(0.1, ‖S F‖∞). Converged when every scaled row and the sum of the mass
        rows (the global lubricant balance) are ≤ ``tol``, or, at the round-off floor: when that norm is ≤
        :data:`ROUND_OFF_MARGIN`·``tol`` and the last iteration reduced it by less than half or the line search
        found no decrease, or when it is ≤ :data:`ROUND_OFF_STEP_MARGIN`·``tol`` and the correction is below
        :data:`ROUND_OFF_STEP` in every pressure (counted in ``cost["round_off_stops"]``; the balance reached is
        recorded per step as ever). With ``floor_stop`` (det-2026.11-17) a solve stalled above that margin but
        within ROUND_OFF_STEP_MARGIN·``tol`` also stops where its norm is within the round-off floor
        :meth:`round_off_floor` measures (once per solve, when first needed; counted in ``cost["floor_stops"]``).
        ``watchdog``: damped steps (det-2026.11-18's last attempt, :data:`WATCHDOG_STEPS`) taken although the line
        search rejected them (counted in ``cost["watchdog_steps"]``). Where every scaled row meets ``tol`` and only
        the global balance does not, the line search's merit is that balance squared (det-2026.11-20).
        Returns (z, converged, iterations, that norm)."""
        scale = self.row_scale()
        res, h, jac, dfilm = self.evaluate(z, gap, storage)
        previous = math.inf
        floor = None
        unchecked = watchdog

        def at_floor(z_now, norm_now) -> bool:
            nonlocal floor
            if norm_now <= ROUND_OFF_MARGIN * tol:
                return True
            if not floor_stop or norm_now > ROUND_OFF_STEP_MARGIN * tol:
                return False
            if floor is None:
                floor = self.round_off_floor(z_now, gap, storage)
            return norm_now <= floor

        balance_retries = 0
        for iteration in range(max_iterations):
            scaled = res * scale
            # every row, and the sum of the mass rows (the global lubricant balance, whose terms could add up)
            largest_row, balance = float(np.max(np.abs(scaled))), float(np.sum(scaled[self.mass_rows]))
            norm = max(largest_row, abs(balance))
            if norm <= tol:
                self.last_residual = res
                return z, True, iteration, norm
            if not np.isfinite(norm):
                return z, False, iteration, norm
            if norm > 0.5 * previous and at_floor(z, norm):  # stalled at the round-off floor
                if largest_row <= tol and balance_retries < BALANCE_RETRIES:
                    balance_retries += 1  # only the global balance misses: its round-off moves it by ±3e-11 a step
                else:
                    return self._round_off_stop(z, res, iteration, norm, norm > ROUND_OFF_MARGIN * tol)
            previous = norm
            forcing = min(0.1, max(norm, 1e-3 * tol / norm))
            step, _ = self._direction(jac, dfilm, scaled, scale, forcing)
            largest = max(float(np.max(np.abs(step[0:-1:3]))), float(np.max(np.abs(step[2:-1:3]))), 1e-300)
            if largest <= ROUND_OFF_STEP and norm <= ROUND_OFF_STEP_MARGIN * tol:
                return self._round_off_stop(z, res, iteration, norm)
            omega = min(1.0, max_pressure_step / largest)
            # det-2026.11-20: where every row meets the tolerance and only the global balance does not, the rows'
            # squares are round-off that no step lowers, and the line search measures the balance it must reduce
            balance_only = largest_row <= tol
            merit = balance * balance if balance_only else float(scaled @ scaled)
            accepted = False
            for attempt in range(25):
                if attempt == 1 and forcing > 1e-6:  # a rejected step: an accurate direction with a fresh LU
                    self.preconditioner = None
                    forcing = 1e-6
                    step, _ = self._direction(jac, dfilm, scaled, scale, forcing)
                    largest = max(float(np.max(np.abs(step[0:-1:3]))), float(np.max(np.abs(step[2:-1:3]))), 1e-300)
                    omega = min(1.0, max_pressure_step / largest)
                trial = z + omega * step
                res_t, _, jac_t, dfilm_t = self.evaluate(trial, gap, storage)
                scaled_t = res_t * scale
                merit_t = (float(np.sum(scaled_t[self.mass_rows])) ** 2 if balance_only
                           else float(scaled_t @ scaled_t))
                if np.isfinite(merit_t) and merit_t <= (1.0 - 1e-4 * omega) * merit:
                    accepted = True
                    break
                omega *= 0.5
            self.cost["newton_iterations"] += 1
            if not accepted and unchecked > 0:
                unchecked -= 1
                trial = z + min(1.0, max_pressure_step / largest) * step
                res_t, _, jac_t, dfilm_t = self.evaluate(trial, gap, storage)
                accepted = bool(np.all(np.isfinite(res_t)))
                self.cost["watchdog_steps"] += accepted
            if not accepted:
                if at_floor(z, norm):
                    return self._round_off_stop(z, res, iteration + 1, norm, norm > ROUND_OFF_MARGIN * tol)
                return z, False, iteration + 1, norm
            z, res, jac, dfilm = trial, res_t, jac_t, dfilm_t
        scaled = res * scale
        norm = max(float(np.max(np.abs(scaled))), abs(float(np.sum(scaled[self.mass_rows]))))
        if tol < norm and at_floor(z, norm):
            return self._round_off_stop(z, res, max_iterations, norm, norm > ROUND_OFF_MARGIN * tol)
        self.last_residual = res
        return z, norm <= tol, max_iterations, norm

    def _round_off_stop(self, z, res, iterations, norm, beyond_margin: bool = False):
        self.last_residual = res
        self.cost["round_off_stops"] += 1
        self.cost["floor_stops"] += beyond_margin
        return z, True, iterations, norm

    def mass_balance_error(self) -> float:
        """|Σ_cells (flux in − flux out − storage change)| / reference flux of the last Newton solution: the global
        lubricant balance of the discrete equations (the mass rows summed; interior faces cancel in pairs)."""
        return abs(float(np.sum(self.last_residual[self.mass_rows]))) / self.m_ref


def local_shear_stress(problem: MixedProblem, case: ContactCase, state: LubricantState, scales: ContactScales, z,
                       h) -> tuple[np.ndarray, np.ndarray]:
    """Per node [Pa]: the fluid shear stress θτ_Eyring + (h/2)∂p_f/∂x (paper Eq. 7, h floored at h_b; the gradient
    periodic on a window) and the boundary friction μ_d p_c sign(u_s) (Eq. 8)."""
    pf, th, pc, _ = problem.unpack(z)
    p_f = pf * case.p_h
    h_m = np.maximum(h, problem.h_b) * scales.film_scale
    if problem.periodic:
        gradient = (np.roll(p_f, -1) - np.roll(p_f, 1)) / (2.0 * problem.dx * scales.a)
    else:
        gradient = np.gradient(p_f, problem.x * scales.a)
    fluid = th * eyring_shear_stress(state.viscosity(p_f), case.u_s, h_m, state.tau0) + 0.5 * h_m * gradient
    sign = math.copysign(1.0, case.u_s) if case.u_s != 0.0 else 0.0
    return fluid, state.mu_d * sign * pc * case.p_h


def _traction(problem: MixedProblem, case: ContactCase, state: LubricantState, scales: ContactScales, z, h,
              local: bool = False):
    """(μ, asperity part of μ, asperity load share, yielded load share) of one state (paper Eq. 7–8); with
    ``local`` also the local shear stress per node [Pa] (:func:`local_shear_stress`, both parts)."""
    _, _, pc, _ = problem.unpack(z)
    fluid, boundary = local_shear_stress(problem, case, state, scales, z, h)
    w = problem.weights * scales.a
    load = case.load_per_length
    asperity = float(w @ boundary) / load
    mu = float(w @ fluid) / load + asperity
    share = float(w @ pc) * case.p_h / load
    yielded = float(w @ (pc * (pc >= (1.0 - 1e-9) * problem.p_yield))) * case.p_h / load
    if local:
        return mu, asperity, share, yielded, fluid + boundary
    return mu, asperity, share, yielded


def solve_deterministic(case: ContactCase, state: LubricantState, plan: Effects, options: DeterministicOptions,
                        roughness: RoughnessProfile | None = None, time_limit_s: float | None = None,
                        level_name: str = "reference", observer=None, checkpoint=None) -> ContactResult:
    """Solve one rough contact with the deterministic transient model (module docstring).

    ``observer``: None, or called after every accepted time step k = 1, 2, … as ``observer(t_s, p_fluid_pa, film_m,
    fill)`` with the fluid pressure [Pa], the film max(h, h_b) [m] and the fill fraction θ on the nodes ``result.x``
    (for analyses of the fields, e.g. validation/micro_ehl_fluctuations.py; step k is ``result.extra``'s series index
    k − 1).

    ``checkpoint``: None, or an object with ``every_s``, ``load()`` and ``save(state)``
    (:class:`ehl_dataset.dataset.checkpoint.FileCheckpoint`): the run saves its state every ``every_s`` seconds of
    wall time and, given a state saved by the same run (same case, lubricant state, roughness, options and model
    version; anything else is an InputError), continues from it. The result is step for step that of an
    uninterrupted run; its wall time adds up the segments. Runs of hours (validation spacings beyond a session)."""
    clock = options.clock
    start = clock()
    scales = ContactScales.of(case, state, plan.shear_thinning)
    a = scales.a
    profile = roughness if roughness is not None else default_profile()
    h_b_m = options.boundary_film_m if options.boundary_film_m is not None else BOUNDARY_FILM_M
    if options.wide == "windows":
        raise InputError("wide", options.wide, "'auto' or 'resolve' here: solve_deterministic resolves the whole "
                         "contact; the windows are ehl_dataset.solvers.wide_contact.solve_deterministic_contact's")
    rule = {}
    if options.dx_m is not None:
        dx_m = options.dx_m
    else:
        inlet_length = a * moes_h_c(case, state, scales) ** (2.0 / 3.0)
        dx_m, rule = grid_spacing(profile, case.rq1, case.rq2, h_b_m, options, inlet_length)
    x_start, x_end = options.domain
    n = int(round((x_end - x_start) * a / dx_m)) + 1
    if n > options.max_nodes:
        raise InputError("dx_m", dx_m, f">= {(x_end - x_start) * a / (options.max_nodes - 1):.3g} m for this "
                         f"contact (at most {options.max_nodes} nodes; a = {a:.3g} m)")
    x = np.linspace(x_start, x_end, max(n, 9))
    problem = MixedProblem(x, scales, state, h_b_m / scales.film_scale, options.yield_pressure_pa / case.p_h,
                           plan.compressibility, options.face_mean, options.band, options.couette_flux,
                           film_floor=options.film_floor)
    smooth_plan = Effects(False, False, plan.shear_thinning, plan.compressibility, plan.mode, {})
    # the start's continuation grid is the one the run fingerprints (:func:`_fingerprint`, which hashes the converged
    # start) were made with, so that saved states stay valid
    smooth = solve_steady(case, state, get_level("standard"), smooth_plan, coarsening=START_COARSENING)
    if not smooth.converged:
        return _failed(case, state, plan, level_name, start, clock, f"smooth start: {smooth.message}", {})
    p0 = np.interp(x * a, smooth.x, smooth.pressure) / case.p_h
    z = problem.pack(p0, np.ones(x.size), np.zeros(x.size), smooth.extra["h0_m"] / scales.film_scale)
    problem.m_ref = float(np.interp(0.0, smooth.x, smooth.film)) / scales.film_scale
    gap0 = 0.5 * x**2
    steady = problem.storage(None, 0.0, None, None)
    z_start = z
    z, ok, _, norm = problem.newton(z, gap0, steady, options.newton_tolerance, 60)
    if not ok:  # pseudo-transient continuation: smooth time steps from the interpolated state until steady
        z, ok, norm = _settle(problem, z_start, gap0, options)
    if not ok:
        return _failed(case, state, plan, level_name, start, clock,
                       f"steady smooth start on the uniform grid: residual {norm:.2e}", {"residual": norm})
    h = problem.film(z, gap0)
    smooth_mu = _traction(problem, case, state, scales, z, h)[0]
    record = _Record()
    record.smooth = {"mu": smooth_mu, "h_min_m": float(np.min(h)) * scales.film_scale}
    if case.s_c == 0.0:
        return _result(case, state, plan, level_name, options, problem, scales, z, h, record, start, clock, True,
                       "converged (smooth surfaces: steady solution)", rule, dx_m, 0, None)

    passes_dt = (x_end - x_start)  # one pass in units of a/u_r
    d_t = options.courant * problem.dx
    steps_per_pass = passes_dt / d_t
    n_ramp = int(math.ceil(options.ramp_passes * steps_per_pass))
    first_average = n_ramp + int(math.ceil(options.startup_passes * steps_per_pass))
    n_min = first_average + int(math.ceil(options.min_average_passes * steps_per_pass))
    n_max = max(int(math.ceil(options.max_passes * steps_per_pass)), n_min)
    check_every = max(int(0.25 * steps_per_pass), 1)
    time_scale = a / case.u_r
    # laid out for a length in passes, whatever the spacing: runs at different spacings with the same layout read the
    # same roughness at the same times (paired comparisons, docs/explanation/mixed-regime.md)
    surfaces = plan_surfaces(case, x * a, options.roughness_layout_passes * passes_dt * time_scale, profile)

    def gap_at(t):
        r1, r2 = surfaces.at(t * time_scale)
        amplitude = min(1.0, t / (n_ramp * d_t)) if n_ramp else 1.0
        return gap0 - amplitude * (r1 + r2) / scales.film_scale

    z_steady = z
    z = problem.rebase_film_offset(z)
    h = problem.film(z, gap0)
    m = problem.content(z, h)
    state_now = {"z": z, "m": m, "m_prev": m, "z_prev": None, "dt_prev": None}
    message, converged, mu_mean = "", True, None
    time_limited = False
    k = 0
    t = 0.0
    if checkpoint is not None:
        sample_gap = gap_at(0.5 * n_ramp * d_t + d_t)
        fingerprint = _fingerprint(case, state, options, problem, z_steady, sample_gap)
        continued = {_fingerprint(case, state, options, problem, z_steady, sample_gap, version): version
                     for version in CONTINUES}
        saved = checkpoint.load()
        if saved is not None:
            if saved.get("fingerprint") != fingerprint and saved.get("fingerprint") not in continued:
                raise InputError("checkpoint", str(getattr(checkpoint, "path", checkpoint)),
                                 "a state saved by this same run (same case, lubricant, roughness, options and model "
                                 f"version {MODEL_VERSION} or one it continues, {', '.join(CONTINUES)}); this one "
                                 "was saved by another run: delete it or give another path")
            k, t, z, h = saved["k"], saved["t"], saved["z"], saved["h"]
            record = saved["record"] if isinstance(saved["record"], _Record) else _Record.from_state(saved["record"])
            state_now = saved["state_now"]
            problem.film_reference = 0.0  # states saved before det-2026.11-20 hold the absolute H0 (and go on so)
            for name, value in saved["problem"].items():
                setattr(problem, name, value)
            for count in ("floor_stops", "watchdog_steps"):  # states of det-16/-17 lack the newer counts
                problem.cost.setdefault(count, 0)
            if saved["fingerprint"] in continued and getattr(record, "continued_from", None) is None:
                record.continued_from = {"model_version": continued[saved["fingerprint"]], "steps": int(k)}
            start = clock() - saved["elapsed_s"]
        last_save = clock()
    while k < n_max:
        if time_limit_s is not None and clock() - start > time_limit_s:
            converged = k >= n_min
            time_limited = True
            message = f"wall-time limit of {time_limit_s:g} s reached after {k} of at least {n_min} steps"
            break
        outcome = _advance(problem, state_now, gap_at, t, d_t, options)
        if outcome is None:
            converged = False
            message = f"Newton failed at step {k + 1} even with {options.max_substeps} sub-steps"
            save_failure = getattr(checkpoint, "save_failure", None)
            if save_failure is not None:
                kept = save_failure(_saved_state(fingerprint, k, t, z, h, record, state_now, clock() - start,
                                                 problem, checkpoint))
                message += f"; the state before that step is kept in {kept} (hand it to the same run to replay it)"
            break
        z, h, g, substeps = outcome
        k += 1
        t = k * d_t
        record.add(problem, case, state, scales, z, h, g, substeps, t * time_scale)
        if observer is not None:
            p_fluid, fill, _, _ = problem.unpack(z)
            observer(t * time_scale, p_fluid * case.p_h, np.maximum(h, problem.h_b) * scales.film_scale, fill.copy())
        if k > first_average:
            record.accumulate()
        if k >= n_min and (k - n_min) % check_every == 0:
            mu_mean = time_mean(record.mu[first_average:])
            tolerance = options.mu_sem_target * max(abs(mu_mean.mean), 0.01)
            if mu_mean.within(tolerance):
                break
        if checkpoint is not None and clock() - last_save >= checkpoint.every_s:
            checkpoint.save(_saved_state(fingerprint, k, t, z, h, record, state_now, clock() - start, problem,
                                         checkpoint))
            last_save = clock()
    if converged and k < n_min:
        converged = False
    if k > first_average + 1:
        mu_mean = time_mean(record.mu[first_average:])
    if converged:
        target = options.mu_sem_target * max(abs(mu_mean.mean), 0.01)
        message = "converged" + ("" if mu_mean.within(target) else
                                 f"; standard error of mu {mu_mean.standard_error:.2g} above the target "
                                 f"{target:.2g} after the cap of {options.max_passes:g} passes") + message
    result = _result(case, state, plan, level_name, options, problem, scales, z, h, record, start, clock, converged,
                     message, rule, dx_m, first_average, mu_mean, time_limited)
    result.extra.update(profile_record(profile))
    return result


def _saved_state(fingerprint, k, t, z, h, record, state_now, elapsed_s, problem, checkpoint=None) -> dict:
    """What a checkpoint keeps of a run after step ``k`` (:func:`solve_deterministic` continues from it): plain data
    but the factorised preconditioner, which a ``portable`` checkpoint leaves out (the next step rebuilds it)."""
    kept = {name: getattr(problem, name) for name in _PROBLEM_STATE}
    if getattr(checkpoint, "portable", False):
        kept["preconditioner"] = None
    return {"fingerprint": fingerprint, "k": k, "t": t, "z": z, "h": h, "record": record.to_state(),
            "state_now": {key: value for key, value in state_now.items() if key != "last_storage"},
            "elapsed_s": elapsed_s, "problem": kept}


_PROBLEM_STATE = ("m_ref", "preconditioner", "cost", "last_residual", "last_gmres_iterations", "film_reference")
"""The attributes of a :class:`MixedProblem` that change during a run (a checkpoint saves them; the rest is built
from the inputs)."""


def _fingerprint(case: ContactCase, state: LubricantState, options: DeterministicOptions, problem: MixedProblem,
                 z_start: np.ndarray, gap: np.ndarray, version: str = MODEL_VERSION) -> str:
    """A digest of everything that determines a run: the model ``version``, the case, the lubricant state, the
    options (but the clock), the grid, the steady start ``z_start`` and a gap of the rough surfaces ``gap``."""
    options_text = repr({f.name: getattr(options, f.name) for f in fields(options) if f.name != "clock"})
    digest = hashlib.sha256()
    for text in (version, repr(case), repr(state), options_text, repr((problem.n, problem.dx))):
        digest.update(text.encode())
    for array in (z_start, gap):
        digest.update(np.ascontiguousarray(array, dtype=float).tobytes())
    return digest.hexdigest()


def _settle(problem: MixedProblem, z, gap, options: DeterministicOptions, passes: float = 4.0):
    """Time steps with smooth surfaces (Courant ``options.courant``) from ``z`` until the steady equations hold:
    the physical transient as a globalisation of the steady solve. Returns (z, converged, steady residual)."""
    steady = problem.storage(None, 0.0, None, None)
    d_t = options.courant * problem.dx
    h = problem.film(z, gap)
    s = {"z": z, "m": problem.content(z, h), "m_prev": problem.content(z, h), "z_prev": None, "dt_prev": None}
    n_steps = int(math.ceil(passes * (problem.x[-1] - problem.x[0]) / d_t))
    norm = math.inf
    for k in range(n_steps):
        if _advance(problem, s, lambda t: gap, k * d_t, d_t, options) is None:
            break
        if k % 10 == 9:
            z, ok, _, norm = problem.newton(s["z"], gap, steady, options.newton_tolerance, 10)
            if ok:
                return z, True, norm
    return s["z"], False, norm


MAX_STEP_RATIO = 2.0
"""Largest ratio ΔT_n/ΔT_{n−1} of consecutive BDF2 steps. Variable-step BDF2 is zero-stable only for ratios below
1 + √2 ≈ 2.41 (Grigorieff 1983); at a ratio of 16, as after a time step split into sub-steps, its history term
amplifies the content differences of the sub-steps sixteen-fold and Newton cannot converge
(docs/validation/deterministic-reference.md, "Robustness and cost")."""


def substep_sizes(d_t: float, parts: int, dt_prev: float | None, growth: float = MAX_STEP_RATIO) -> list[float]:
    """Sub-steps covering ``d_t``: none longer than ``d_t``/``parts``, each at most ``growth`` × the one before
    (the first relative to ``dt_prev``), the last merged with a remainder that would be shorter than a quarter of
    it as long as the merged step keeps that ratio. Sums to ``d_t``."""
    sizes: list[float] = []
    target = d_t / parts
    previous = dt_prev if dt_prev else math.inf
    remaining = d_t
    while remaining > 1e-12 * d_t:
        size = min(target, growth * previous, remaining)
        rest = remaining - size
        if rest < 0.25 * size and remaining <= growth * previous:
            size = remaining
        elif 0.0 < rest < 1e-9 * d_t:
            size = remaining
        sizes.append(size)
        remaining -= size
        previous = size
    sizes[-1] += remaining
    return sizes


def _advance(problem: MixedProblem, s: dict, gap_at, t: float, d_t: float, options: DeterministicOptions):
    """One time step from t to t + d_t in sub-steps (:func:`substep_sizes`: after a split step the steps grow back
    by at most :data:`MAX_STEP_RATIO`), split into 2, 4, … parts while Newton fails; None if every
    split up to ``options.max_substeps`` fails even with the watchdog steps of the last attempt (det-2026.11-18).
    Updates ``s``; returns (z, h, gap, number of sub-steps) or None."""
    outcome = _advance_split(problem, s, gap_at, t, d_t, options, 0)
    if outcome is None:
        outcome = _advance_split(problem, s, gap_at, t, d_t, options, WATCHDOG_STEPS)
    return outcome


def _advance_split(problem: MixedProblem, s: dict, gap_at, t: float, d_t: float, options: DeterministicOptions,
                   watchdog: int):
    parts = 1
    while parts <= options.max_substeps:
        saved = dict(s)
        ok = True
        sizes = substep_sizes(d_t, parts, s["dt_prev"])
        elapsed = 0.0
        for j, step in enumerate(sizes):
            elapsed = d_t if j == len(sizes) - 1 else elapsed + step
            gap = gap_at(t + elapsed)
            ratio = step / s["dt_prev"] if s["dt_prev"] else 0.0
            storage = problem.storage(step, ratio, s["m"], s["m_prev"])
            guesses = [s["z"]]
            if s["z_prev"] is not None and ratio:
                extrapolated = s["z"] + ratio * (s["z"] - s["z_prev"])
                extrapolated[0:-1:3] = np.maximum(extrapolated[0:-1:3], 0.0)
                extrapolated[1:-1:3] = np.clip(extrapolated[1:-1:3], 0.0, 1.0)
                extrapolated[2:-1:3] = np.maximum(extrapolated[2:-1:3], 0.0)
                scale = problem.row_scale()
                if (np.max(np.abs(problem.evaluate(extrapolated, gap, storage)[0] * scale))
                        < np.max(np.abs(problem.evaluate(s["z"], gap, storage)[0] * scale))):
                    guesses.insert(0, extrapolated)
            for guess in guesses:  # the extrapolation can predict a wrong contact set: then the last state
                z, converged, _, _ = problem.newton(guess, gap, storage, options.newton_tolerance,
                                                    options.newton_iterations, watchdog=watchdog)
                if converged:
                    break
                problem.preconditioner = None
            if not converged:
                ok = False
                break
            h = problem.film(z, gap)
            s["m_prev"], s["m"] = s["m"], problem.content(z, h)
            s["z_prev"], s["z"] = s["z"], z
            s["dt_prev"] = step
            s["last_storage"] = storage
        if ok:
            return s["z"], h, gap, len(sizes)
        s.clear()
        s.update(saved)
        problem.preconditioner = None
        parts *= 2
    return None


class _Record:
    """Per-step history of a run."""

    def __init__(self):
        self.mu, self.asperity, self.share, self.yielded, self.h_min, self.h_c = [], [], [], [], [], []
        self.t = []
        self.mass, self.load = [], []
        self.film_sum = None
        self.film_count = 0
        self.profile_sums = {}
        self.substep_steps = 0
        self.continued_from = None
        self.smooth = {}

    _SERIES = ("mu", "asperity", "share", "yielded", "h_min", "h_c", "t", "mass", "load")

    def to_state(self) -> dict:
        """The record as plain data (series as float64 arrays) for a checkpoint; :meth:`from_state` inverts it."""
        state = {name: np.asarray(getattr(self, name), dtype=float) for name in self._SERIES}
        state.update(film_sum=self.film_sum, film_count=self.film_count, profile_sums=dict(self.profile_sums),
                     substep_steps=int(self.substep_steps), continued_from=self.continued_from,
                     smooth=dict(self.smooth))
        return state

    @classmethod
    def from_state(cls, state: dict) -> "_Record":
        """The record :meth:`to_state` saved (series back to lists of floats: the same values)."""
        record = cls()
        for name in cls._SERIES:
            setattr(record, name, np.asarray(state[name], dtype=float).tolist())
        record.film_sum = state["film_sum"]
        record.film_count = int(state["film_count"])
        record.profile_sums = dict(state["profile_sums"] or {})
        record.substep_steps = int(state["substep_steps"])
        record.continued_from = state["continued_from"]
        record.smooth = dict(state["smooth"] or {})
        return record

    def accumulate(self):
        """Add the last state's profiles to the sums of the averaging window."""
        self.film_sum = self.last_film.copy() if self.film_sum is None else self.film_sum + self.last_film
        self.film_count += 1
        for key, value in self.last_profiles.items():
            self.profile_sums[key] = value.copy() if key not in self.profile_sums else self.profile_sums[key] + value

    def mean_profiles(self) -> dict:
        """Time-averaged profiles over the averaging window [SI], named as in the result's ``extra``."""
        if not self.film_count:
            return {}
        return {key: value / self.film_count for key, value in self.profile_sums.items()}

    def add(self, problem, case, state, scales, z, h, gap, substeps, t_s):
        mu, asperity, share, yielded, local = _traction(problem, case, state, scales, z, h, local=True)
        self.t.append(t_s)
        self.mu.append(mu)
        self.asperity.append(asperity)
        self.share.append(share)
        self.yielded.append(yielded)
        self.h_min.append(float(np.min(h)) * scales.film_scale)
        self.h_c.append(float(np.interp(0.0, problem.x, h)) * scales.film_scale)
        pf, th, pc, _ = problem.unpack(z)
        self.load.append(float(problem.weights @ (pf + pc)) / (0.5 * math.pi) - 1.0)
        self.mass.append(problem.mass_balance_error())
        self.last_film = h * scales.film_scale
        self.last_profiles = {"mean_shear_stress_profile_pa": local, "mean_contact_pressure_profile_pa": pc * case.p_h,
                              "mean_pressure_profile_pa": (pf + pc) * case.p_h,
                              "mean_content_film_profile_m": th * np.maximum(h, problem.h_b) * scales.film_scale}
        self.substep_steps += substeps > 1


def _window_mean(values) -> float:
    """Mean of an averaging window's values; NaN (without numpy's empty-slice warning) for a run stopped before its
    window began (a wall-time budget spent in the start-up)."""
    return float(np.mean(values)) if len(values) else math.nan


def _result(case, state, plan, level_name, options, problem, scales, z, h, record, start, clock, converged, message,
            rule, dx_m, first_average, mu_mean, time_limited=False) -> ContactResult:
    _, lambda_bar = dowson_higginson_lambda(case, state)
    pf, th, pc, h0 = problem.unpack(z)
    x_m = problem.x * scales.a
    if record.mu:
        window = slice(first_average, None)
        mu = mu_mean.mean if mu_mean is not None else _window_mean(record.mu[window])
        sem = mu_mean.standard_error if mu_mean is not None else math.nan
        share = _window_mean(record.share[window])
        share_sem = time_mean(record.share[window]).standard_error if len(record.share[window]) > 1 else math.nan
        mean_film = record.film_sum / record.film_count if record.film_count else h * scales.film_scale
        h_min = float(np.min(mean_film))
        h_c = float(np.interp(0.0, problem.x, mean_film))
        local_min = _window_mean(record.h_min[window])
        mu_std = float(np.std(record.mu[window])) if len(record.mu[window]) else math.nan
        yielded = _window_mean(record.yielded[window])
    else:
        mu = record.smooth["mu"]
        sem = share = mu_std = yielded = 0.0
        share_sem = 0.0
        mean_film = h * scales.film_scale
        h_min = local_min = float(np.min(h)) * scales.film_scale
        h_c = float(np.interp(0.0, problem.x, h)) * scales.film_scale
    recorded = recorded_effects(plan, case.s_c > 0.0)
    n_steps = len(record.mu)
    return ContactResult(
        mu=float(mu), h_min=h_min, h_central=h_c, p_max=float(np.max(pf + pc)) * case.p_h, converged=bool(converged),
        iterations=int(problem.cost["newton_iterations"]), wall_time=clock() - start, level=level_name,
        effects=recorded, mu_std=mu_std, mu_sem=float(sem), lambda_bar=lambda_bar, asperity_load_share=share,
        residuals={"max_load_error": float(np.max(np.abs(record.load))) if record.load else 0.0,
                   "max_mass_error": float(np.max(record.mass)) if record.mass else 0.0},
        message=message, x=x_m, pressure=(pf + pc) * case.p_h, film=mean_film,
        extra={"model": "deterministic", "route": "resolve", "model_version": MODEL_VERSION, "dx_m": float(problem.dx * scales.a), "n_nodes": int(problem.n),
               "n_steps": n_steps, "average_from_step": int(first_average), "courant": options.courant,
               "boundary_film_m": float(problem.h_b * scales.film_scale),
               "yield_pressure_pa": float(problem.p_yield * case.p_h), "asperity_load_share_sem": float(share_sem),
               "yielded_load_share": yielded, "substep_steps": int(record.substep_steps),
               "continued_from": getattr(record, "continued_from", None),
               "smooth_mu": record.smooth.get("mu"), "smooth_h_min_m": record.smooth.get("h_min_m"),
               "mu_series": np.asarray(record.mu), "share_series": np.asarray(record.share),
               "t_series_s": np.asarray(record.t), "h_min_local_m": local_min,
               "h_min_local_series_m": np.asarray(record.h_min), "mass_error_series": np.asarray(record.mass),
               "face_mean": options.face_mean, "layout_passes": options.roughness_layout_passes,
               "couette_flux": options.couette_flux, "time_limited": bool(time_limited), **record.mean_profiles(),
               **problem.cost, **rule},
    )


def recorded_effects(plan: Effects, rough: bool) -> dict:
    """The effects a deterministic run records: ``plan`` with roughness and the transient on for rough surfaces
    (``rough``: S_c > 0; the model time-steps the moving roughness whatever the plan says) and off for smooth ones
    (the steady smooth start is the solution), and the model named in its reasons."""
    recorded = plan.to_dict()
    recorded["reasons"] = dict(recorded.get("reasons") or {})
    recorded["reasons"]["model"] = "deterministic transient mixed EHL (contact complementarity, mass-conserving)"
    recorded["roughness"] = recorded["transient"] = bool(rough)
    return recorded


def _failed(case, state, plan, level_name, start, clock, message, residuals) -> ContactResult:
    _, lambda_bar = dowson_higginson_lambda(case, state)
    nan = math.nan
    return ContactResult(mu=nan, h_min=nan, h_central=nan, p_max=nan, converged=False, iterations=0,
                         wall_time=clock() - start, level=level_name,
                         effects=recorded_effects(plan, case.s_c > 0.0), lambda_bar=lambda_bar,
                         residuals=dict(residuals), message=f"not converged: {message}",
                         extra={"model": "deterministic", "time_limited": False})
