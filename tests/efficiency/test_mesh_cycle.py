"""Mesh-cycle outputs: transmission error, contact and root stresses, friction power (efficiency.mesh_cycle)."""

import dataclasses
import math

import numpy as np
import pytest

from ehl_dataset.model.materials import STEEL, reduced_modulus
from ehl_dataset.validation import InputError
from efficiency import iso6336
from efficiency.geometry import GearPair
from efficiency.kinematics import mesh_kinematics
from efficiency.mesh_cycle import MeshOptions, evaluate_mesh, root_stress, single_pair_outer_points
from efficiency.modifications import Modifications

DEG = math.pi / 180.0


def design_d():
    """The paper's design D (Li & Kahraman 2009, Table 1): N = 32, Φ = 30°, Ψ = 19°, Λ_wd = 2.068, b = 25 mm."""
    return GearPair.from_paper(32, 30 * DEG, 19 * DEG, 2.068)


def spur_c():
    """FZG type C spur gears (gear_cases.md)."""
    return GearPair(16, 24, 4.5e-3, 20 * DEG, 0.0, 0.014, x1=0.1817, x2=0.1715)


@pytest.mark.parametrize("gear", [1, 2])
def test_root_stress_reduces_to_iso_sigma_f0_for_a_uniform_load_at_the_iso_point(gear):
    """ISO 6336-3:2006 method B: σ_F0 = F_t/(b m_n) Y_F Y_S Y_β for the whole tangential load F_t spread uniformly
    over the face and applied at the outer point of single pair contact. Feeding exactly that load case to the
    slice root-stress model must return σ_F0 (efficiency.iso6336.nominal_root_stress) on every slice."""
    pair = design_d()
    torque = 250.0
    kin = mesh_kinematics(pair, positions=1, slices=10)
    rho_d = single_pair_outer_points(pair)[gear - 1]
    length = float(pair.line_of_action_length)
    rho1 = np.full(kin.shape, rho_d if gear == 1 else length - rho_d)
    kin = dataclasses.replace(kin, rho1=rho1, rho2=length - rho1, in_contact=np.ones(kin.shape, bool))
    f_t = iso6336.nominal_tangential_load(pair, torque)
    slice_load = f_t / float(pair.face_width) * kin.slice_width / (
        math.cos(kin.base_helix_angle) * math.cos(float(pair.transverse_pressure_angle)))
    loads = np.zeros(kin.shape)
    loads[:, 0, :] = slice_load
    sigma = root_stress(pair, kin, loads)[gear - 1, :, 0, :]
    assert np.allclose(sigma, iso6336.nominal_root_stress(pair, torque, gear), rtol=1e-12)


def test_spur_contact_pressure_in_single_tooth_contact_matches_iso_hertz_at_the_pitch_point():
    """In single-tooth contact an unmodified spur pair carries W = F_bn uniformly over the face, so
    p² R_n = W E'/(2π b) at every point (Hertz, Johnson §4.3). ISO 6336-2's σ_H0/Z_ε = Z_H Z_E √(F_t(u+1)/(d1 b u)) is
    the same Hertz pressure at the pitch point, so p² R_n = (σ_H0/Z_ε)² R_C with R_C the pitch-point radius."""
    pair = spur_c()
    torque = 150.0
    result = evaluate_mesh(pair, torque, options=MeshOptions(positions=20, slices=6))
    kin = result.kinematics
    single = kin.in_contact.sum(axis=1)[:, 0] == 1
    p = result.contact_pressure[single].max(axis=1)  # the one loaded line of each single-contact position
    r_n = np.where(kin.in_contact[single], kin.r_eq_normal[single], 0).max(axis=1)
    e_red = reduced_modulus(STEEL, STEEL)
    assert np.allclose(p**2 * r_n, result.normal_load * e_red / (2 * math.pi * float(pair.face_width)), rtol=1e-10)
    rb1, rb2 = (float(r) for r in pair.base_radii)
    tan_w = math.tan(float(pair.working_pressure_angle))
    r_c = rb1 * tan_w * rb2 * tan_w / (rb1 * tan_w + rb2 * tan_w)
    z_eps = float(iso6336.contact_ratio_factor(pair.contact_ratio, pair.overlap_ratio))
    sigma_h = iso6336.nominal_contact_stress(pair, torque) / z_eps
    assert np.allclose(p**2 * r_n, sigma_h**2 * r_c, rtol=1e-6)


def test_only_requested_outputs_are_computed():
    """Outputs that were not asked for (TE, stresses) are not computed."""
    pair = design_d()
    none = evaluate_mesh(pair, 250.0, options=MeshOptions(positions=6, slices=10, outputs=frozenset()))
    assert none.transmission_error is None and none.contact_pressure is None and none.root_stress is None
    te_only = evaluate_mesh(pair, 250.0, options=MeshOptions(positions=6, slices=10, outputs=frozenset({"te"})))
    assert te_only.te_peak_to_peak is not None and te_only.sigma_c_max is None
    with pytest.raises(InputError, match="outputs"):
        MeshOptions(outputs=frozenset({"noise"}))


def test_te_of_a_crowned_pair_grows_with_the_crown_at_fixed_torque():
    """At 250 N·m, increasing either crown of design D (from the paper's M_P = 15 µm, M_L = 12 µm) increases the
    peak-to-peak TE (the trend of the paper's Fig. 6(b))."""
    pair = design_d()
    opts = MeshOptions(outputs=frozenset({"te"}))

    def te(mp, ml):
        return evaluate_mesh(pair, 250.0, modifications=Modifications(mp * 1e-6, ml * 1e-6),
                             options=opts).te_peak_to_peak

    profile = [te(mp, 12) for mp in (15, 20, 25, 30)]
    lead = [te(15, ml) for ml in (12, 20, 30)]
    assert np.all(np.diff(profile) > 0)
    assert np.all(np.diff(lead) > 0)


@pytest.mark.parametrize("torque", [50.0, 250.0, 500.0])
def test_stresses_grow_with_the_crowns(torque):
    """The paper's Fig. 6(c, d): at 50, 250 and 500 N·m, σ_c and σ_b of design D increase with M_P (15 → 30 µm at
    M_L = 12 µm) and with M_L (12 → 30 µm at M_P = 15 µm): crowning shrinks the loaded area."""
    pair = design_d()

    def stresses(mp, ml):
        r = evaluate_mesh(pair, torque, modifications=Modifications(mp * 1e-6, ml * 1e-6))
        return r.sigma_c_max, r.sigma_b_max

    for series in ([stresses(mp, 12) for mp in (15, 20, 25, 30)], [stresses(15, ml) for ml in (12, 20, 30)]):
        sigma_c, sigma_b = np.array(series).T
        assert np.all(np.diff(sigma_c) > 0)
        assert np.all(np.diff(sigma_b) > 0)


def test_results_converge_with_resolution():
    """Design D with the paper's crowns: TE, σ_c and σ_b at the default resolution (30 slices, 24 positions) agree
    with a 60 × 48 resolution within 1 % (measured: 0.2 %, 0.1 %, 0.1 %)."""
    pair = design_d()
    coarse = evaluate_mesh(pair, 250.0, modifications=Modifications.paper())
    fine = evaluate_mesh(pair, 250.0, modifications=Modifications.paper(),
                         options=MeshOptions(slices=60, positions=48))
    assert coarse.te_peak_to_peak == pytest.approx(fine.te_peak_to_peak, rel=0.01)
    assert coarse.sigma_c_max == pytest.approx(fine.sigma_c_max, rel=0.01)
    assert coarse.sigma_b_max == pytest.approx(fine.sigma_b_max, rel=0.01)


def test_spur_friction_power_matches_ohlendorf_loss_factor():
    """With a constant μ, the cycle-mean friction power of an unmodified spur pair is μ T ω1 H_V with Ohlendorf's
    loss factor H_V = π(u + 1)/(z1 u cos β_b) (1 − ε_α + ε_1² + ε_2²) (ISO/TR 14179-2:2001; Niemann & Winter).
    H_V assumes equal load sharing in the double-contact zones; the model shares by stiffness, so agreement to a
    few percent is expected (measured 1.4 %)."""
    pair = spur_c()
    torque, omega1, mu = 100.0, 100.0, 0.05
    result = evaluate_mesh(pair, torque, speed_rad_s=omega1,
                           options=MeshOptions(positions=100, slices=4, outputs=frozenset()))
    p_bt = float(pair.transverse_base_pitch)
    eps1 = (float(pair.contact_end) - float(pair.pitch_point)) / p_bt
    eps2 = (float(pair.pitch_point) - float(pair.contact_start)) / p_bt
    u = 24 / 16
    h_v = math.pi * (u + 1) / (16 * u) * (1 - float(pair.contact_ratio) + eps1**2 + eps2**2)
    assert result.friction_power(mu).mean() / (mu * torque * omega1) == pytest.approx(h_v, rel=0.03)


def test_design_d_at_250_nm_is_loaded_beyond_the_iso_nominal_values():
    """Design D with M_P = 15 µm, M_L = 12 µm per gear at 250 N·m: the crowns concentrate the load, so the maximum
    Hertz pressure and root stress exceed ISO's uniform-load nominal σ_H0 and σ_F0 (826 MPa, 193 MPa); all finite,
    converged. Measured: σ_c = 1.36 GPa, σ_b = 323 MPa, TE = 3.8 µm (see the paper comparison below)."""
    pair = design_d()
    result = evaluate_mesh(pair, 250.0, speed_rad_s=4000 * math.pi / 30, modifications=Modifications.paper())
    assert result.converged
    assert result.sigma_c_max > iso6336.nominal_contact_stress(pair, 250.0)
    assert result.sigma_b_max > iso6336.nominal_root_stress(pair, 250.0, 1)
    assert 0.0 < result.te_peak_to_peak < 10e-6


@pytest.mark.xfail(strict=True, reason="known deviation: with M_P, M_L applied per gear this model gives "
                   "σ_c = 1.27 GPa, σ_b = 281 MPa, TE = 3.47 µm for design D (with the face coupling); see "
                   "docs/explanation/gear-model.md")
def test_design_d_meets_the_papers_limits():
    """Li & Kahraman 2009 §3: design D satisfies σ_b < 235 MPa, σ_c < 1.175 GPa and TE < 0.25 µm at 250 N·m."""
    result = evaluate_mesh(design_d(), 250.0, modifications=Modifications.paper())
    assert result.sigma_c_max < 1.175e9
    assert result.sigma_b_max < 235e6
    assert result.te_peak_to_peak < 0.25e-6


def test_bad_designs_are_reported_by_name():
    """A pair whose total contact ratio is below 1 cannot carry the load at every position; a vectorised pair is
    not a single design."""
    short = GearPair(30, 30, 3e-3, 20 * DEG, 0.0, 0.02, addendum_coefficient=0.4)
    with pytest.raises(InputError, match="total_contact_ratio"):
        evaluate_mesh(short, 100.0)
    with pytest.raises(InputError, match="pair"):
        evaluate_mesh(GearPair(np.array([30, 31]), 30, 3e-3, 20 * DEG, 0.0, 0.02), 100.0)
    with pytest.raises(InputError, match="torque"):
        evaluate_mesh(design_d(), float("nan"))


def test_tip_relief_reduces_spur_transmission_error():
    """Harris (1958) / Munro: linear 'long' tip relief over the double-contact zone, of an amount up to the tooth
    pair deflection, flattens the loaded TE of a spur pair. FZG C at 150 N·m (single-pair deflection ≈ 23 µm):
    TE_pp falls monotonically as C_a grows from 0 to 15 µm, while the maximum contact pressure (single-tooth contact
    near the pitch point) is unchanged."""
    pair = spur_c()
    length = (float(pair.contact_ratio) - 1.0) * float(pair.transverse_base_pitch)
    opts = MeshOptions(positions=48, slices=4)
    results = [evaluate_mesh(pair, 150.0, modifications=Modifications(tip_relief=(ca * 1e-6,) * 2,
                                                                      tip_relief_length=(length,) * 2),
                             options=opts) for ca in (0, 5, 10, 15)]
    te = [r.te_peak_to_peak for r in results]
    assert np.all(np.diff(te) < 0)
    assert te[-1] < 0.6 * te[0]
    assert np.allclose([r.sigma_c_max for r in results], results[0].sigma_c_max, rtol=1e-9)


def test_to_dict_is_the_one_schema_of_a_mesh_cycle():
    """``MeshCycleResult.to_dict``: the maxima by their definitions (σ_c the largest Hertz pressure of the cycle, σ_b
    the largest root stress of either gear, TE p-p = max − min of the loaded TE, paper §3), the mean mesh stiffness
    per face width, the positions at which the maxima occur, and the optional arrays only when asked for; the design
    studies' rows carry the same keys and values (one σ_c key, ``sigma_c_pa``, everywhere)."""
    import json

    from efficiency.friction import ConstantFriction
    from efficiency.studies import StudyPoint, evaluate_design

    pair = design_d()
    options = MeshOptions(positions=6, slices=10)
    result = evaluate_mesh(pair, 250.0, 4000 * math.pi / 30, options=options)
    d = result.to_dict()
    assert d["sigma_c_pa"] == np.max(result.contact_pressure)
    assert d["sigma_b_pa"] == np.max(result.root_stress)
    assert d["te_pp_m"] == np.max(result.transmission_error) - np.min(result.transmission_error)
    assert d["mesh_stiffness_per_width_n_per_m2"] == pytest.approx(
        np.mean(result.mesh_stiffness) / pair.face_width, rel=1e-12)
    position = int(np.argmax(np.max(result.contact_pressure, axis=(1, 2))))
    assert d["sigma_c_position_rad"] == result.kinematics.mesh_angle[position]
    assert d["torque_nm"] == 250.0 and (d["positions"], d["slices"]) == (6, 10)
    assert "mesh_angle_rad" not in d and len(result.to_dict(per_position=True)["mesh_angle_rad"]) == 6
    json.dumps(d)
    row = evaluate_design(pair, ConstantFriction(0.05), StudyPoint(250.0, 4000 * math.pi / 30, 363.15, 4e-7, 4e-7),
                          options)
    assert {k: row[k] for k in ("te_pp_m", "sigma_c_pa", "sigma_b_pa")} == {
        k: d[k] for k in ("te_pp_m", "sigma_c_pa", "sigma_b_pa")}
