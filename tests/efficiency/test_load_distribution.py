"""Load distribution: the complementarity solver and the loaded mesh (efficiency.load_distribution, mesh_cycle)."""

import itertools
import math

import numpy as np
import pytest

from efficiency import iso6336
from efficiency.compliance import contact_compliance, face_coupling, tooth_compliance
from efficiency.geometry import GearPair
from efficiency.load_distribution import solve_contact
from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
from efficiency.modifications import Modifications

DEG = math.pi / 180.0


def design_d():
    """The paper's design D (Li & Kahraman 2009, Table 1)."""
    return GearPair.from_paper(32, 30 * DEG, 19 * DEG, 2.068)


def spur_c():
    """FZG type C spur gears (gear_cases.md)."""
    return GearPair(16, 24, 4.5e-3, 20 * DEG, 0.0, 0.014, x1=0.1817, x2=0.1715)


def _random_problem(rng, q):
    a = rng.normal(size=(q, q))
    compliance = (a @ a.T + q * np.eye(q)) * 1e-9
    separation = rng.uniform(0.0, 5e-6, size=q)
    return compliance, separation


def _enumerated_solution(compliance, separation, load):
    """Independent reference: try every active set, keep the one satisfying all KKT conditions (unique for SPD)."""
    q = separation.size
    for size in range(1, q + 1):
        for subset in itertools.combinations(range(q), size):
            idx = np.array(subset)
            sub = compliance[np.ix_(idx, idx)]
            u = np.linalg.solve(sub, np.ones(size))
            v = np.linalg.solve(sub, separation[idx])
            approach = (load + v.sum()) / u.sum()
            x = approach * u - v
            if np.any(x < 0):
                continue
            loads = np.zeros(q)
            loads[idx] = x
            gaps = compliance @ loads + separation - approach
            if gaps.min() >= -1e-15:
                return loads, approach
    raise AssertionError("no KKT point found")


@pytest.mark.parametrize("seed", range(6))
def test_active_set_solver_matches_exhaustive_enumeration(seed):
    """The KKT point of min ½FᵀCF + εᵀF, F ≥ 0, ΣF = W is unique for SPD C; the active-set result must equal the
    one found by trying all 2^Q − 1 active sets (Q = 9)."""
    rng = np.random.default_rng(seed)
    compliance, separation = _random_problem(rng, 9)
    sol = solve_contact(compliance, separation, 1000.0)
    ref_loads, ref_approach = _enumerated_solution(compliance, separation, 1000.0)
    assert sol.converged
    assert np.allclose(sol.loads, ref_loads, rtol=1e-9, atol=1e-9)
    assert sol.approach == pytest.approx(ref_approach, rel=1e-10)
    # complementarity, no tension, no penetration, equilibrium
    assert sol.min_load >= 0.0
    assert sol.max_penetration <= 1e-12
    assert np.max(np.abs(sol.loads * sol.gaps)) <= 1e-12 * 1000.0
    assert sol.equilibrium_residual <= 1e-12


def test_warm_start_gives_the_same_solution():
    rng = np.random.default_rng(11)
    compliance, separation = _random_problem(rng, 40)
    cold = solve_contact(compliance, separation, 500.0)
    warm = solve_contact(compliance, separation, 500.0, initial_loads=rng.uniform(0, 1, 40))
    assert cold.converged and warm.converged
    assert np.allclose(cold.loads, warm.loads, rtol=1e-9, atol=1e-9 * 500.0)


@pytest.mark.parametrize("mods", [Modifications(), Modifications.paper(),
                                  Modifications(profile_crown=5e-6, lead_crown=20e-6, lead_slope=-10e-6,
                                                tip_relief=(10e-6, 5e-6), tip_relief_length=(1e-3, 1.5e-3),
                                                spacing_errors=(0.0, 3e-6))])
def test_equilibrium_no_tension_no_penetration_over_the_cycle(mods):
    """Σ moments of the normal loads about gear 1's axis, Σ F r_b1 cos ψ_b, equals the input torque to 1e-9
    relative at every mesh position (Conry & Seireg 1973 equilibrium); loads ≥ 0; gaps ≥ 0."""
    pair = design_d()
    torque = 250.0
    result = evaluate_mesh(pair, torque, modifications=mods, options=MeshOptions(positions=12, slices=20))
    moments = result.loads.sum(axis=(1, 2)) * float(pair.base_radii[0]) * math.cos(float(pair.base_helix_angle))
    assert np.all(np.abs(moments / torque - 1.0) <= 1e-9)
    assert result.converged
    assert result.min_load >= 0.0
    assert result.max_penetration <= 1e-12
    assert np.all(result.loads[~result.kinematics.in_contact] == 0.0)


def test_symmetric_lead_crown_gives_loads_symmetric_across_the_face():
    """A spur pair with a lead crown symmetric about mid-face (and a symmetric compliance model) must carry a load
    distribution that is mirror-symmetric about mid-face."""
    result = evaluate_mesh(spur_c(), 200.0, modifications=Modifications(lead_crown=8e-6),
                           options=MeshOptions(positions=10, slices=21))
    loads = result.loads
    assert np.allclose(loads, loads[..., ::-1], rtol=1e-8, atol=1e-9 * loads.max())
    # the crown concentrates the load at mid-face
    per_slice = loads.sum(axis=(0, 1))
    assert per_slice[10] > per_slice[0]


def test_spur_single_and_double_tooth_load_sharing():
    """Unmodified spur pair: in the single-tooth zone one pair carries the whole load; in the double-tooth zones the
    two pairs share it in proportion to their stiffnesses, F_i/W = (1/c_i)/Σ(1/c_j) with the pair compliance
    c = c_t1(ρ1) + c_t2(ρ2) + c_H (springs in parallel, equal approach). Checked with the load-independent contact
    compliance, for which this ratio is exact."""
    pair = spur_c()
    opts = MeshOptions(positions=40, slices=4, contact_model="linear", outputs=frozenset())
    result = evaluate_mesh(pair, 300.0, options=opts)
    kin = result.kinematics
    w = result.normal_load
    width = float(pair.face_width)
    c_h = contact_compliance()
    single = double = 0
    for m in range(kin.shape[0]):
        lines = np.flatnonzero(kin.in_contact[m, :, 0])
        shares = result.loads[m, lines].sum(axis=1) / w
        if lines.size == 1:
            single += 1
            assert shares[0] == pytest.approx(1.0, rel=1e-12)
        else:
            double += 1
            rho = kin.roll[m, lines, 0]
            c = (tooth_compliance(pair, 1, rho)["total"]
                 + tooth_compliance(pair, 2, float(pair.line_of_action_length) - rho)["total"] + c_h)
            expected = (1 / c) / np.sum(1 / c)
            assert np.allclose(shares, expected, rtol=1e-9)
            # equal approach: per-unit-width deflection c·F/b is the same on both pairs
            assert np.allclose(c * shares * w / width, c[0] * shares[0] * w / width, rtol=1e-9)
    # fraction of positions in double contact = ε_α − 1 (within the sampling 1/M)
    assert double / (single + double) == pytest.approx(float(pair.contact_ratio) - 1.0, abs=1.5 / 40)


GEARS = {
    "FZG C (spur)": lambda: GearPair(16, 24, 4.5e-3, 20 * DEG, 0.0, 0.014, x1=0.1817, x2=0.1715),
    "FZG H501": lambda: GearPair(20, 30, 3.5e-3, 20 * DEG, 15 * DEG, 0.023, x1=0.1809, x2=0.0891),
    "FZG H701": lambda: GearPair(28, 42, 2.5e-3, 20 * DEG, 15 * DEG, 0.017, x1=0.2290, x2=0.1489),
    "ISO/TR 6336-30 ex. 1": lambda: GearPair(17, 103, 8e-3, 20 * DEG, 15.8 * DEG, 0.100, x1=0.145, x2=0.0,
                                             center_distance=0.5, dedendum_coefficient=1.4,
                                             root_fillet_coefficient=0.39),
    "standard spur 30/30": lambda: GearPair(30, 30, 3e-3, 20 * DEG, 0.0, 0.020),
}


@pytest.mark.parametrize("name", list(GEARS))
def test_mesh_stiffness_of_unmodified_gears_is_within_20_percent_of_iso_c_gamma_alpha(name):
    """ISO 6336-1:2006 method B mesh stiffness c_γα = c'(0.75 ε_α + 0.25), c' = c'_th C_M C_R C_B cos β (computed by
    efficiency.iso6336; it reproduces ISO/TR 6336-30 example 1, 17.465 N/(mm·µm)) is an empirical value for
    unmodified solid gears. The model's cycle-mean tangent stiffness per face width (beam + Sainsot foundation +
    Weber contact, no ISO input) must fall within ±20 % of it at a line load of 300 N/mm (measured: 0.84–1.12)."""
    pair = GEARS[name]()
    torque = float(pair.base_radii[0]) * float(pair.face_width) * 300e3
    result = evaluate_mesh(pair, torque, options=MeshOptions(positions=16, slices=16, outputs=frozenset()))
    c_gamma_alpha = iso6336.mesh_stiffness(pair)[0]
    assert result.converged
    assert 0.8 <= result.mesh_stiffness_per_width / c_gamma_alpha <= 1.2


def test_face_coupling_reproduces_a_uniform_load_and_is_positive_definite():
    """The image-reflected exponential kernel: rows sum to 1 (uniform line load → uniform deflection), symmetric,
    positive definite (a Green's function of 1 − ℓ² d²/dz²). The self-influence of a cell of width Δz is
    1 − exp(−Δz/2ℓ) in the interior; at a free end the reflected image adds ½[exp(−Δz/2ℓ) − exp(−3Δz/2ℓ)]
    (cell integrals of exp(−|d|/ℓ)/(2ℓ))."""
    width, slices, length = 0.025, 40, 0.001
    dz = width / slices
    z = (np.arange(slices) + 0.5) * dz
    g = face_coupling(z, width, length)
    assert np.allclose(g.sum(axis=1), 1.0, rtol=0, atol=1e-12)
    assert np.allclose(g, g.T, rtol=0, atol=1e-15)
    assert np.linalg.eigvalsh(g).min() > 0
    interior = 1 - math.exp(-dz / (2 * length))
    assert g[20, 20] == pytest.approx(interior, rel=1e-9)
    edge = interior + 0.5 * (math.exp(-dz / (2 * length)) - math.exp(-3 * dz / (2 * length)))
    assert g[0, 0] == pytest.approx(edge, rel=1e-9)


def test_very_low_torque_with_large_crowns_gives_point_like_contact():
    """Hard case: 1 N·m with 30 µm profile and lead crowns: a few loaded points near the middle of
    the face and of the path, converged, finite, equilibrium holds."""
    pair = design_d()
    result = evaluate_mesh(pair, 1.0, modifications=Modifications(profile_crown=30e-6, lead_crown=30e-6))
    assert result.converged and result.equilibrium_residual <= 1e-9
    assert np.all(np.isfinite(result.loads)) and np.isfinite(result.sigma_c_max)
    loaded = (result.loads > 0).sum(axis=(1, 2))
    assert loaded.max() <= 4
    z_loaded = np.broadcast_to(result.kinematics.z, result.loads.shape)[result.loads > 0]
    assert np.all(np.abs(z_loaded - 0.0125) < 0.25 * 0.025)


def test_very_high_torque_loads_the_full_face():
    """Hard case: 5000 N·m (20× the paper's torque) on crowned design D: every point on the path of contact is
    loaded, converged, equilibrium holds."""
    result = evaluate_mesh(design_d(), 5000.0, modifications=Modifications.paper())
    assert result.converged and result.equilibrium_residual <= 1e-9
    assert np.array_equal(result.loads > 0, result.kinematics.in_contact)


def test_misalignment_moves_the_load_to_one_face_end():
    """Hard case: a 60 µm lead slope (opening the z = b end) at 250 N·m: edge contact at z = 0, nothing at z = b,
    converged, equilibrium holds."""
    result = evaluate_mesh(design_d(), 250.0, modifications=Modifications(15e-6, 12e-6, lead_slope=60e-6))
    assert result.converged and result.equilibrium_residual <= 1e-9
    per_slice = result.loads.sum(axis=(0, 1))
    z = result.kinematics.z
    assert np.sum(per_slice * z) / np.sum(per_slice) < 0.3 * 0.025  # centre of load (0.5 b when aligned)
    assert np.all(per_slice[z > 0.75 * 0.025] == 0.0)
    assert per_slice[0] > 0.5 * per_slice.max()
    assert np.all(np.isfinite(result.root_stress))


def test_weber_contact_compliance_log_law_and_fast_form_agree():
    """Weber / Johnson (1985 §5.6) line-contact approach: δ/w = Σ k_i [2 ln(2 d_i/a) − ν_i/(1 − ν_i)] with
    a ∝ √w, so the secant compliance falls by (k1 + k2) ln(w2/w1) from w1 to w2 (k_i = (1 − ν_i²)/(π E_i)); the
    numba form used in the solver returns the same values."""
    from efficiency.compliance import weber_contact_compliance, weber_log_terms, weber_secant

    rng = np.random.default_rng(3)
    r_eq = rng.uniform(5e-3, 20e-3, 50)
    d1, d2 = rng.uniform(1e-3, 4e-3, 50), rng.uniform(1e-3, 4e-3, 50)
    w1, w2 = 1e5, 4e5
    c1 = weber_contact_compliance(w1, r_eq, d1, d2)
    c2 = weber_contact_compliance(w2, r_eq, d1, d2)
    k = (1 - 0.3**2) / (math.pi * 206e9)
    assert np.allclose(c1 - c2, 2 * k * math.log(w2 / w1), rtol=1e-10)
    fast = weber_secant(np.full(50, w1), *weber_log_terms(r_eq, d1, d2))
    assert np.allclose(fast, c1, rtol=1e-12)
    # Weber's compliance is 2-4× the load-independent Yang & Lin value 4/(π E') for gear-tooth proportions
    assert np.all((c1 / contact_compliance() > 2) & (c1 / contact_compliance() < 5))
