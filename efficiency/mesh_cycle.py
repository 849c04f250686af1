"""Loaded tooth contact over one mesh cycle: load distribution, transmission error, contact and root stresses.

Orchestrates :mod:`efficiency.kinematics` (contact points), :mod:`efficiency.compliance` (tooth, foundation, face
coupling and Hertz compliance), :mod:`efficiency.modifications` (unloaded separations) and
:mod:`efficiency.load_distribution` (the complementarity solve) for a :class:`efficiency.geometry.GearPair` at a
given input torque. Only the outputs asked for are computed (``outputs`` ⊆ {"te", "stresses"}; the loads,
radii and velocities that the power-loss stage needs are always returned).

Definitions (all SI):
- normal load to carry W = T_in / (r_b1 cos ψ_b); the transverse base-circle force is F_bt = T_in / r_b1;
- loaded transmission error at the base circle TE(φ) = δ(φ) / cos ψ_b (δ the rigid-body normal approach; it
  includes the unloaded TE of the modifications), peak-to-peak TE = max − min over the cycle;
- mesh stiffness k(φ) = dF_bt / dTE = cos² ψ_b · dW/dδ on the current active set [N/m]; per unit face width
  c_γ = mean k / b [N/m²] (comparable with ISO 6336-1 c_γα);
- Hertz contact pressure at a point p = √(w E' / (2π R_n)), w = F cos ψ_b / Δz the load per unit length of contact
  line, R_n the normal equivalent radius (Hertz line contact, Johnson 1985 §4.3: W' = 2π r_eq p_h² / E');
- root bending stress of gear i at a point, consistent with ISO 6336-3 (σ_F0 = F_t/(b m_n) Y_F Y_S Y_β):
  σ = (f_t / m_n) · Y_F Y_S Y_β · h(ρ_i)/h(ρ_Di), with f_t = F cos ψ_b cos α_t / Δz the slice's tangential load per
  unit face width at the reference circle, h the bending lever arm of the load about the root section
  (:func:`efficiency.compliance.root_bending_arm`) and ρ_Di the outer point of single pair contact of gear i in the
  transverse section (the ISO load position). A uniform load F_t/b at that point gives exactly σ_F0.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ehl_dataset.model.materials import STEEL, Material, reduced_modulus
from ehl_dataset.validation import InputError, SolverError, check_range

from .compliance import (DEFAULT_HUB_RATIO, centreline_depth, contact_compliance, face_coupling, root_bending_arm,
                         tooth_compliance, weber_log_terms, whole_depth)
from .kinematics import MeshKinematics, choose_positions, mesh_kinematics
from .load_distribution import solve_contact, solve_contact_weber
from .modifications import Modifications, normal_separation

OUTPUTS = frozenset({"te", "stresses"})
LOAD_SHARING = ("elastic", "rigid-uniform", "independent-slices")
DEFAULT_COUPLING_LENGTH_FACTOR = 0.6
"""Face-coupling length ℓ of the tooth (bending, shear, compression) in whole tooth depths. From a 3-D linear-elastic
FE of the FZG H501 teeth (validation/fe_tooth_coupling.py, docs/explanation/gear-model.md): the FE influence of a
concentrated flank load has an effective width of 1.1–1.4 tooth depths at mid-face, and the slice model with
ℓ = 0.6 depth reproduces the FE's loss factor (0.1863 against 0.1864) and its load profile along the path of
contact within 0.02 of the mean. The earlier default, 1 depth, made the ends of partly loaded contact lines too
stiff."""


@dataclass(frozen=True)
class MeshOptions:
    """Resolution and model options of a mesh-cycle evaluation.

    Parameters
    ----------
    positions : int, optional
        Number M of mesh positions per cycle; None: :func:`efficiency.kinematics.choose_positions` (24–48, chosen so
        that the load-sharing breakpoints fall on sampling-cell boundaries) [-].
    slices : int
        Number S of slices across the face width [-].
    outputs : frozenset of str
        Subset of {"te", "stresses"} to compute; loads, radii and velocities are always returned [-].
    coupling_length_factor : float
        Face-coupling length ℓ of the tooth part (bending, shear, compression) in units of the whole tooth depth
        (:data:`DEFAULT_COUPLING_LENGTH_FACTOR`) [-].
    foundation_coupling_length_factor : float, optional
        The same for the gear-body (foundation) part; None: as the tooth part [-].
    load_sharing : str
        ``elastic`` (the complementarity problem with the compliance model), ``rigid-uniform`` (rigid teeth: uniform
        load per unit length over every contact line in contact, the assumption of Wimmer's H_VL and, for spur gears,
        of Ohlendorf's H_V; unmodified flanks only) or ``independent-slices`` (elastic with no face coupling: every
        slice carries load in proportion to its own stiffness, the thin-slice model of ISO 6336-1 and of Marques et
        al., Mech. Mach. Theory 161 (2021) 104320) [-].
    hub_ratio : float
        r_f / r_int of the foundation compliance [-].
    material1 : Material
        Material of gear 1 [-].
    material2 : Material
        Material of gear 2 [-].
    root_stress_factors : tuple of float, optional
        (Y_F Y_S Y_β of gear 1, of gear 2); None: from :mod:`efficiency.iso6336` [-].
    contact_model : str
        ``weber`` (load-dependent Hertz approach, iterated) or ``linear`` (Yang & Lin constant) [-].
    contact_tolerance : float
        Relative change of the secant contact compliance at which the ``weber`` iteration stops [-].
    """

    positions: int | None = None
    slices: int = 30
    outputs: frozenset = OUTPUTS
    coupling_length_factor: float = DEFAULT_COUPLING_LENGTH_FACTOR
    foundation_coupling_length_factor: float | None = None
    load_sharing: str = "elastic"
    hub_ratio: float = DEFAULT_HUB_RATIO
    material1: Material = STEEL
    material2: Material = STEEL
    root_stress_factors: tuple[float, float] | None = None
    contact_model: str = "weber"
    contact_tolerance: float = 1e-4

    def __post_init__(self):
        if self.contact_model not in ("weber", "linear"):
            raise InputError("contact_model", self.contact_model, "'weber' or 'linear'")
        check_range("contact_tolerance", self.contact_tolerance, 0.0, 0.1, low_inclusive=False)
        if self.positions is not None:
            check_range("positions", self.positions, 1, 10000)
        check_range("slices", self.slices, 1, 2000)
        unknown = set(self.outputs) - OUTPUTS
        if unknown:
            raise InputError("outputs", sorted(unknown), f"a subset of {sorted(OUTPUTS)}")
        object.__setattr__(self, "outputs", frozenset(self.outputs))
        check_range("coupling_length_factor", self.coupling_length_factor, 0.0, 100.0, low_inclusive=False)
        if self.foundation_coupling_length_factor is not None:
            check_range("foundation_coupling_length_factor", self.foundation_coupling_length_factor, 0.0, 100.0,
                        low_inclusive=False)
        if self.load_sharing not in LOAD_SHARING:
            raise InputError("load_sharing", self.load_sharing, " or ".join(repr(v) for v in LOAD_SHARING))
        check_range("hub_ratio", self.hub_ratio, 1.0, 10.0, low_inclusive=False)
        if self.root_stress_factors is not None:
            for i, y in enumerate(self.root_stress_factors, start=1):
                check_range(f"root_stress_factor{i}", y, 0.0, 50.0, low_inclusive=False)


@dataclass(frozen=True)
class MeshCycleResult:
    """Loaded mesh over one cycle. Point arrays have shape (M positions, K contact lines, S slices).

    Parameters
    ----------
    kinematics : MeshKinematics
        Contact points, radii of curvature and surface velocities [-].
    torque : float
        Input torque T_in on gear 1 [N·m].
    normal_load : float
        Total normal load W = T_in/(r_b1 cos ψ_b) [N].
    loads : ndarray
        Normal load per contact point, 0 where not loaded or not in contact [N].
    load_per_length : ndarray
        Normal load per unit length of contact line w = F cos ψ_b / Δz [N/m].
    approach : ndarray
        (M,) rigid-body normal approach δ [m].
    mesh_stiffness : ndarray
        (M,) tangent mesh stiffness dF_bt/dTE [N/m].
    mesh_stiffness_per_width : float
        Mean mesh stiffness per face width; 1 N/(mm·µm) = 1e9 N/m² [N/m²].
    converged : bool
        Every position's complementarity problem converged [-].
    iterations : ndarray
        (M,) active-set iterations [-].
    equilibrium_residual : float
        max |ΣF − W|/W over the positions [-].
    max_penetration : float
        Largest penetration over all positions [m].
    min_load : float
        Smallest load of a loaded point [N].
    wall_time_s : float
        Evaluation time [s].
    transmission_error : ndarray, optional
        (M,) loaded transmission error at the base circle δ/cos ψ_b; None unless "te" was asked [m].
    te_peak_to_peak : float, optional
        max − min of the transmission error over the cycle; None unless "te" [m].
    contact_pressure : ndarray, optional
        Hertz pressure per point; None unless "stresses" [Pa].
    sigma_c_max : float, optional
        Largest Hertz pressure σ_c [Pa].
    sigma_c_position : int, optional
        Mesh position index m of ``sigma_c_max`` [-].
    root_stress : ndarray, optional
        (2, M, K, S) root bending stress of gears 1 and 2; None unless "stresses" [Pa].
    sigma_b_max : float, optional
        Largest root stress σ_b [Pa].
    sigma_b_position : tuple of int, optional
        (gear 1 or 2, mesh position m) of ``sigma_b_max`` [-].
    extra : dict
        Further records of the evaluation (contact-model iterations, options used) [-].
    """

    kinematics: MeshKinematics
    torque: float
    normal_load: float
    loads: np.ndarray
    load_per_length: np.ndarray
    approach: np.ndarray
    mesh_stiffness: np.ndarray
    mesh_stiffness_per_width: float
    converged: bool
    iterations: np.ndarray
    equilibrium_residual: float
    max_penetration: float
    min_load: float
    wall_time_s: float
    transmission_error: np.ndarray | None = None
    te_peak_to_peak: float | None = None
    contact_pressure: np.ndarray | None = None
    sigma_c_max: float | None = None
    sigma_c_position: int | None = None
    root_stress: np.ndarray | None = None
    sigma_b_max: float | None = None
    sigma_b_position: tuple[int, int] | None = None
    extra: dict = field(default_factory=dict)

    @property
    def loss_factor(self) -> float:
        """Gear loss factor H_V = P / (μ P_in) of this load distribution for a constant μ [-]: the cycle mean of
        Σ_q W_q |u_s,q| / (T_in ω1) (Ohlendorf 1958; Wimmer 2006's H_VL for rigid uniform load; ISO/TR 14179-2)."""
        return float(self.friction_power(1.0).mean() / (self.torque * self.kinematics.omega1))

    def to_dict(self, per_position: bool = False) -> dict:
        """The loaded mesh as one JSON-ready mapping in SI units, keys named with their unit: the schema of a mesh
        cycle wherever one is printed or tabulated (``gear evaluate``, the design studies, the pipeline, reports).

        Parameters
        ----------
        per_position : bool
            Also return the arrays over the cycle: ``mesh_angle_rad``, ``mesh_stiffness_n_per_m`` (None for rigid
            teeth), ``transmission_error_m`` (with TE) and ``loaded_points`` per position [-].

        Returns
        -------
        dict
            ``torque_nm`` [N·m], ``normal_load_n`` [N], ``positions``, ``slices``, ``loss_factor`` [-],
            ``mesh_stiffness_mean_n_per_m`` [N/m] and ``mesh_stiffness_per_width_n_per_m2`` [N/m²] (None for rigid
            teeth), ``max_load_per_length_n_per_m`` [N/m], ``converged``, ``active_set_iterations``,
            ``equilibrium_residual`` [-], ``max_penetration_m`` [m], ``model_time_s`` [s]; with TE ``te_pp_m`` and
            ``te_mean_m`` [m]; with stresses ``sigma_c_pa`` (the cycle's maximum Hertz pressure) [Pa],
            ``sigma_c_position_rad`` [rad], ``sigma_b_pa`` (the maximum root stress) [Pa], ``sigma_b_gear`` and
            ``sigma_b_position_rad`` [rad].
        """
        kin = self.kinematics
        rigid = not np.isfinite(self.mesh_stiffness_per_width)
        out = {
            "torque_nm": self.torque, "normal_load_n": self.normal_load,
            "positions": int(kin.shape[0]), "slices": int(kin.shape[2]), "loss_factor": self.loss_factor,
            # rigid teeth have no finite mesh stiffness: null in the JSON
            "mesh_stiffness_mean_n_per_m": None if rigid else float(np.mean(self.mesh_stiffness)),
            "mesh_stiffness_per_width_n_per_m2": None if rigid else self.mesh_stiffness_per_width,
            "max_load_per_length_n_per_m": float(self.load_per_length.max()),
            "converged": self.converged, "active_set_iterations": int(self.iterations.sum()),
            "equilibrium_residual": self.equilibrium_residual, "max_penetration_m": self.max_penetration,
            "model_time_s": self.wall_time_s,
        }
        if self.te_peak_to_peak is not None:
            out["te_pp_m"] = self.te_peak_to_peak
            out["te_mean_m"] = float(self.transmission_error.mean())
        if self.sigma_c_max is not None:
            out.update(sigma_c_pa=self.sigma_c_max, sigma_c_position_rad=float(kin.mesh_angle[self.sigma_c_position]),
                       sigma_b_pa=self.sigma_b_max, sigma_b_gear=self.sigma_b_position[0],
                       sigma_b_position_rad=float(kin.mesh_angle[self.sigma_b_position[1]]))
        if per_position:
            out["mesh_angle_rad"] = kin.mesh_angle
            out["mesh_stiffness_n_per_m"] = (self.mesh_stiffness if np.all(np.isfinite(self.mesh_stiffness))
                                             else None)
            if self.transmission_error is not None:
                out["transmission_error_m"] = self.transmission_error
            out["loaded_points"] = (self.loads > 0).sum(axis=(1, 2))
        return out

    def friction_power(self, mu) -> np.ndarray:
        """Instantaneous friction power loss P(φ_m) = Σ_q μ_q W_q |u_s,q| (paper Eq. 11a).

        Parameters
        ----------
        mu : float or array_like
            Friction coefficient, scalar or broadcastable to the point arrays [-].

        Returns
        -------
        ndarray
            (M,) P(φ_m) [W].
        """
        return np.sum(np.asarray(mu) * self.loads * np.abs(self.kinematics.u_s), axis=(1, 2))


def evaluate_mesh(pair, torque: float, speed_rad_s: float = 1.0, modifications: Modifications | None = None,
                  options: MeshOptions | None = None) -> MeshCycleResult:
    """Load distribution, transmission error and stresses of ``pair`` over one mesh cycle (quasi-static).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    torque : float
        Input torque T_in on gear 1 [N·m].
    speed_rad_s : float
        Input angular speed ω1; it only scales the velocities of the kinematics [rad/s].
    modifications : Modifications, optional
        Flank modifications and errors; None: unmodified flanks [-].
    options : MeshOptions, optional
        Resolution and models; None: the :class:`MeshOptions` defaults [-].

    Returns
    -------
    MeshCycleResult
        The loaded mesh; non-convergence is reported in ``converged`` and the residuals.

    Raises
    ------
    InputError
        For bad input.
    """
    started = time.perf_counter()
    modifications = Modifications() if modifications is None else modifications
    options = MeshOptions() if options is None else options
    if not isinstance(modifications, Modifications):
        raise InputError("modifications", type(modifications).__name__, "a Modifications instance or None")
    if not isinstance(options, MeshOptions):
        raise InputError("options", type(options).__name__, "a MeshOptions instance or None")
    if options.load_sharing == "rigid-uniform" and modifications != Modifications():
        raise InputError("modifications", "non-zero", "none with load_sharing 'rigid-uniform' (rigid teeth with "
                         "modified flanks would touch at single points; use 'elastic')")
    torque = check_range("torque", torque, 0.0, 1e7, low_inclusive=False, unit="N·m")
    positions = options.positions or choose_positions(pair, options.slices)
    kin = mesh_kinematics(pair, positions, options.slices, speed_rad_s)
    if float(pair.total_contact_ratio) < 1.0:
        raise InputError("total_contact_ratio", round(float(pair.total_contact_ratio), 6),
                         ">= 1 (below 1 there are mesh positions without any tooth pair in contact)")
    n_pos, n_lines, n_slices = kin.shape
    psi_b = kin.base_helix_angle
    cos_b = math.cos(psi_b)
    rb1 = float(pair.base_radii[0])
    dz = kin.slice_width
    width = float(pair.face_width)
    normal_load = torque / (rb1 * cos_b)

    # Compliance factors at the points in contact (pairs of the √c outer product; gear 2's roll is T1T2 − s).
    inside = kin.in_contact
    # Tooth part (bending, shear, compression) and gear-body part (foundation) are coupled across the face with
    # their own lengths; C_ij = cos²ψ_b Σ_gear Σ_part √(c_i c_j) G_part,ij / Δz (Schur products: SPD).
    parts = []  # (root factors of gear 1, of gear 2, coupling matrix)
    comp1 = _on_path(lambda r: tooth_compliance(pair, 1, r, options.material1, options.hub_ratio),
                     kin.rho1[inside], kin.contact_start, kin.contact_end)
    comp2 = _on_path(lambda r: tooth_compliance(pair, 2, r, options.material2, options.hub_ratio),
                     kin.rho2[inside], kin.line_of_action_length - kin.contact_end,
                     kin.line_of_action_length - kin.contact_start)
    depth = whole_depth(pair, 1)
    if options.load_sharing == "independent-slices":
        lengths = {"tooth": None, "foundation": None}
    else:
        found = options.foundation_coupling_length_factor
        lengths = {"tooth": options.coupling_length_factor * depth,
                   "foundation": (options.coupling_length_factor if found is None else found) * depth}
    for part in ("tooth", "foundation"):
        c1 = np.zeros(kin.shape)
        c2 = np.zeros(kin.shape)
        c1[inside] = comp1["foundation"] if part == "foundation" else comp1["total"] - comp1["foundation"]
        c2[inside] = comp2["foundation"] if part == "foundation" else comp2["total"] - comp2["foundation"]
        length = lengths[part]
        if length is None:
            coupling = np.eye(n_slices)
        elif parts and length == lengths["tooth"]:
            coupling = parts[0][2] * dz
        else:
            coupling = face_coupling(kin.z, width, length)
        parts.append((np.sqrt(c1) * cos_b, np.sqrt(c2) * cos_b, coupling / dz))
    # Contact compliance per point [m/N] = c_H(w) cos ψ_b / Δz (per unit contact-line length → per slice load).
    nominal_w = normal_load * cos_b / (float(pair.contact_ratio) * width)
    scale = cos_b / dz  # load per contact-line length = scale · F; point contact compliance = scale · c_H
    if options.contact_model == "weber":
        depth1 = np.zeros(kin.shape)
        depth2 = np.zeros(kin.shape)
        depth1[inside] = _on_path(lambda r: {"d": centreline_depth(pair, 1, r)}, kin.rho1[inside],
                                  kin.contact_start, kin.contact_end)["d"]
        depth2[inside] = _on_path(lambda r: {"d": centreline_depth(pair, 2, r)}, kin.rho2[inside],
                                  kin.line_of_action_length - kin.contact_end,
                                  kin.line_of_action_length - kin.contact_start)["d"]
        log1, log2, k1, k2, q1, q2 = weber_log_terms(np.where(inside, kin.r_eq_normal, 1.0),
                                                     np.where(inside, depth1, 1.0), np.where(inside, depth2, 1.0),
                                                     options.material1, options.material2)
    else:
        constant = contact_compliance(options.material1, options.material2) * scale

    line = np.broadcast_to(np.arange(n_lines)[:, None], (n_lines, n_slices))
    slc = np.broadcast_to(np.arange(n_slices)[None, :], (n_lines, n_slices))
    separation = normal_separation(modifications, kin.roll, kin.z[None, None, :], line[None], kin.contact_start,
                                   kin.contact_end, width)

    loads = np.zeros(kin.shape)
    approach = np.zeros(n_pos)
    stiffness = np.zeros(n_pos)
    iterations = np.zeros(n_pos, dtype=int)
    converged = True
    equilibrium = 0.0
    penetration = 0.0
    contact_residual = 0.0
    previous = None
    previous_w = np.full(n_lines * n_slices, nominal_w)
    rigid = options.load_sharing == "rigid-uniform"
    for m in range(n_pos):
        flat = np.flatnonzero(inside[m].ravel())
        if rigid:
            out = np.zeros(n_lines * n_slices)
            out[flat] = normal_load / flat.size  # equal slices: uniform load per unit length of contact line
            loads[m] = out.reshape(n_lines, n_slices)
            approach[m] = np.nan
            stiffness[m] = np.inf
            continue
        k_idx = line.ravel()[flat]
        j_idx = slc.ravel()[flat]
        (t1, t2, g_t), (f1, f2, g_f) = parts
        tooth = _tooth_matrix(t1[m].ravel()[flat], t2[m].ravel()[flat], f1[m].ravel()[flat], f2[m].ravel()[flat],
                              j_idx, k_idx, g_t, g_f)
        eps = separation[m].ravel()[flat]
        warm = None if previous is None else previous.ravel()[flat]
        if options.contact_model == "weber":
            terms = (log1[m].ravel()[flat], log2[m].ravel()[flat], k1, k2, q1, q2)
            sol, w, change = solve_contact_weber(tooth, eps, normal_load, terms, scale, previous_w[flat],
                                                 initial_loads=warm, tolerance=options.contact_tolerance)
            previous_w = np.full(n_lines * n_slices, nominal_w)
            previous_w[flat] = w
        else:
            tooth[np.diag_indices_from(tooth)] += constant
            sol = solve_contact(tooth, eps, normal_load, initial_loads=warm)
            change = 0.0
        out = np.zeros(n_lines * n_slices)
        out[flat] = sol.loads
        loads[m] = out.reshape(n_lines, n_slices)
        previous = loads[m]
        approach[m] = sol.approach
        stiffness[m] = sol.stiffness * cos_b**2
        iterations[m] = sol.iterations
        converged &= sol.converged
        equilibrium = max(equilibrium, sol.equilibrium_residual)
        penetration = max(penetration, sol.max_penetration)
        contact_residual = max(contact_residual, change)

    load_per_length = loads * cos_b / dz
    result = dict(
        kinematics=kin, torque=torque, normal_load=normal_load, loads=loads, load_per_length=load_per_length,
        approach=approach, mesh_stiffness=stiffness, mesh_stiffness_per_width=float(stiffness.mean() / width),
        converged=bool(converged), iterations=iterations, equilibrium_residual=float(equilibrium),
        max_penetration=float(penetration), min_load=float(loads.min()),
        extra={"contact_compliance_residual": contact_residual, "load_sharing": options.load_sharing},
    )
    if rigid:
        result["mesh_stiffness_per_width"] = math.inf
    if "te" in options.outputs and not rigid:
        te = approach / cos_b
        result.update(transmission_error=te, te_peak_to_peak=float(te.max() - te.min()))
    if "stresses" in options.outputs:
        e_red = reduced_modulus(options.material1, options.material2)
        with np.errstate(divide="ignore", invalid="ignore"):
            pressure = np.where(inside, np.sqrt(load_per_length * e_red / (2.0 * math.pi * kin.r_eq_normal)), 0.0)
        m_c = int(np.unravel_index(np.argmax(pressure), pressure.shape)[0])
        sigma = root_stress(pair, kin, loads, options.root_stress_factors)
        g_b, m_b = (int(i) for i in np.unravel_index(np.argmax(sigma), sigma.shape)[:2])
        result.update(contact_pressure=pressure, sigma_c_max=float(pressure.max()), sigma_c_position=m_c,
                      root_stress=sigma, sigma_b_max=float(sigma.max()), sigma_b_position=(g_b + 1, m_b))
    result["wall_time_s"] = time.perf_counter() - started
    return MeshCycleResult(**result)


_CHEBYSHEV_NODES = 24
_CHEB_NODES = np.cos(np.pi * (np.arange(_CHEBYSHEV_NODES) + 0.5) / _CHEBYSHEV_NODES)
_CHEB_FIT = np.linalg.inv(np.polynomial.chebyshev.chebvander(_CHEB_NODES, _CHEBYSHEV_NODES - 1))


def _on_path(function, rho, low: float, high: float) -> dict:
    """``function`` (a dict of arrays of ρ) at the points ``rho`` by Chebyshev interpolation from 24 nodes on
    [low, high] (the gear's active profile): the compliances are smooth in ρ, and the interpolation (relative error
    < 1e-7, checked in tests) replaces thousands of quadratures per cycle by 24."""
    rho = np.asarray(rho, dtype=float)
    if rho.size <= _CHEBYSHEV_NODES:
        return function(rho)
    half, mid = 0.5 * (high - low), 0.5 * (high + low)
    values = function(mid + half * _CHEB_NODES)
    t = np.clip((rho - mid) / half, -1.0, 1.0)
    keys = list(values)
    coefficients = _CHEB_FIT @ np.stack([values[k] for k in keys], axis=1)  # exact interpolant at the nodes
    evaluated = np.polynomial.chebyshev.chebval(t, coefficients)
    return {k: evaluated[i] for i, k in enumerate(keys)}


@njit(cache=True)
def _tooth_matrix(t1, t2, f1, f2, j_idx, k_idx, g_t, g_f):
    """C_ij = [(t1_i t1_j + t2_i t2_j) G_t + (f1_i f1_j + f2_i f2_j) G_f]_{slices j_i, j_j} on the same contact line
    (k_i = k_j), 0 between lines (different tooth pairs are not coupled)."""
    n = t1.size
    out = np.zeros((n, n))
    for i in range(n):
        for j in range(i, n):
            if k_idx[i] == k_idx[j]:
                a, b = j_idx[i], j_idx[j]
                v = (t1[i] * t1[j] + t2[i] * t2[j]) * g_t[a, b] + (f1[i] * f1[j] + f2[i] * f2[j]) * g_f[a, b]
                out[i, j] = v
                out[j, i] = v
    return out


def single_pair_outer_points(pair) -> tuple[float, float]:
    """Roll distances of the outer point of single pair contact of gears 1 and 2 in the transverse section.

    ρ_D1 = T1A + p_bt, ρ_D2 = T1T2 − (T1E − p_bt), each from the gear's own tangent point, limited to the active
    profile (for ε_α < 1 the tip).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].

    Returns
    -------
    tuple of float
        (ρ_D1, ρ_D2) [m].
    """
    start, end = float(pair.contact_start), float(pair.contact_end)
    p_bt = float(pair.transverse_base_pitch)
    length = float(pair.line_of_action_length)
    rho_d1 = min(start + p_bt, end)
    rho_d2 = length - max(end - p_bt, start)
    return rho_d1, rho_d2


def root_stress(pair, kin: MeshKinematics, loads: np.ndarray, factors: tuple[float, float] | None = None):
    """Root bending stress of gears 1 and 2 at every contact point (definition in the module docstring).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    kin : MeshKinematics
        The mesh kinematics [-].
    loads : ndarray
        Normal load per contact point [N].
    factors : tuple of float, optional
        (Y_F Y_S Y_β of gear 1, of gear 2); None: :func:`iso_root_stress_factors` [-].

    Returns
    -------
    ndarray
        Shape (2, M, K, S) [Pa].
    """
    if factors is None:
        factors = iso_root_stress_factors(pair)
    cos_b = math.cos(kin.base_helix_angle)
    alpha_t = float(pair.transverse_pressure_angle)
    m_n = float(pair.normal_module)
    f_t = loads * cos_b * math.cos(alpha_t) / kin.slice_width
    out = np.zeros((2,) + loads.shape)
    inside = kin.in_contact
    for i, (rho, rho_d) in enumerate(zip((kin.rho1, kin.rho2), single_pair_outer_points(pair))):
        arm_d = float(root_bending_arm(pair, i + 1, rho_d))
        if not arm_d > 0.0:
            raise SolverError(f"gear {i + 1}: the load at the outer point of single pair contact has no bending "
                              f"lever arm about the root section ({arm_d:.3g} m); root stress undefined")
        ratio = np.zeros(loads.shape)
        ratio[inside] = np.clip(root_bending_arm(pair, i + 1, rho[inside]), 0.0, None) / arm_d
        out[i] = f_t / m_n * factors[i] * ratio
    return out


def iso_root_stress_factors(pair) -> tuple[float, float]:
    """Y_F Y_S Y_β of gears 1 and 2, ISO 6336-3:2006 method B (:mod:`efficiency.iso6336`).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].

    Returns
    -------
    tuple of float
        (Y_F Y_S Y_β of gear 1, of gear 2) [-].
    """
    from . import iso6336

    y_beta = float(iso6336.helix_angle_factor_bending(pair.overlap_ratio, pair.helix_angle))
    out = []
    for gear in (1, 2):
        section = iso6336.root_section(pair, gear)
        out.append(iso6336.tooth_form_factor(pair, gear, section)
                   * iso6336.stress_correction_factor(pair, gear, section) * y_beta)
    return out[0], out[1]
