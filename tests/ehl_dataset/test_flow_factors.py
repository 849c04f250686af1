"""Averaged-Reynolds closures (ehl_dataset/model/flow_factors.py): the published Patir–Cheng and Wilson–Marsault
formulas at cited values and limits, the exact 1-D transverse closure against a direct cell average, the isotropic
blend, and the Eyring traction closure."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from ehl_dataset.model import dry_contact as dc
from ehl_dataset.model import flow_factors as ff
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.validation import InputError


def derivative_ok(f, x, h, rel=1e-5):
    value, slope = f(x)
    fd = (f(x + h)[0] - f(x - h)[0]) / (2 * h)
    return np.allclose(fd, slope, rtol=rel, atol=rel * np.max(np.abs(slope)) + 1e-300)


# ---------------------------------------------------------------------------------------------------------------
# Patir & Cheng (1978, 1979), γ = 1 (J. Lubr. Technol. 100 (1978) 12, 101 (1979) 220)
# ---------------------------------------------------------------------------------------------------------------
def test_pc_pressure_flow_factor():
    """φ_x = 1 − 0.90 e^{−0.56H} (Patir & Cheng 1978, γ = 1): φ_x(3) = 0.8322, φ_x(1) = 0.4859, φ_x → 1."""
    assert float(ff.pc_pressure_flow_factor(3.0)[0]) == pytest.approx(0.8322, abs=1e-4)
    assert float(ff.pc_pressure_flow_factor(1.0)[0]) == pytest.approx(0.4859, abs=1e-4)
    assert float(ff.pc_pressure_flow_factor(60.0)[0]) == pytest.approx(1.0, abs=1e-12)
    assert derivative_ok(ff.pc_pressure_flow_factor, np.linspace(0.5, 6, 12), 1e-6)


def test_pc_shear_flow_factor():
    """Φ_s (Patir & Cheng 1979, γ = 1): the two published branches A1 H^α1 e^{−α2H+α3H²} (H ≤ 5) and A2 e^{−H/4}
    (A2 = 1.126) meet at H = 5 to 0.1 % (0.3224 / 0.3226, a check of the tabulated coefficients; the code blends
    them over 4.75–5.25 for C¹); Φ_s(1) = 1.899 e^{−0.87} = 0.7956; Φ_s(8) = 1.126 e^{−2}; Φ_s → 0 as H → ∞."""
    a1, _, a2, a3, big_a2 = ff.PC_SHEAR_FLOW
    low = a1 * 5**0.98 * math.exp(-a2 * 5 + a3 * 25)
    assert low == pytest.approx(big_a2 * math.exp(-1.25), rel=1e-3)
    assert float(ff.pc_shear_flow_factor(1.0)[0]) == pytest.approx(0.7956, abs=1e-4)
    assert float(ff.pc_shear_flow_factor(8.0)[0]) == pytest.approx(1.126 * math.exp(-2.0), rel=1e-12)
    assert float(ff.pc_shear_flow_factor(80.0)[0]) < 1e-8
    assert derivative_ok(ff.pc_shear_flow_factor, np.linspace(0.5, 7.0, 27), 1e-6)


def test_pc_couette_stress_factor_is_the_mean_inverse_gap():
    """φ_f = E[h/h_local] for Patir & Cheng's height density (35/96)(1 − x²/9)³ on |x| ≤ 3: exact for H > 3 (1e-9),
    and for H ≤ 3 with the local gap cut off at 0.01σ (the ln 300(1 + z) term) to 0.5 %; → 1 for large H."""
    density = lambda x: 35 / 96 * (1 - x * x / 9) ** 3  # noqa: E731
    for H, rel in ((4.0, 1e-9), (6.0, 1e-9), (1.0, 5e-3), (2.0, 5e-3), (2.9, 5e-3)):
        exact = quad(lambda x: H / (H - x) * density(x), -3, min(3.0, H - 0.01), limit=200)[0]
        assert float(ff.pc_couette_stress_factor(H)[0]) == pytest.approx(exact, rel=rel)
    assert float(ff.pc_couette_stress_factor(40.0)[0]) == 1.0


def test_pc_shear_stress_factors():
    """Φ_fs = 11.1 H^2.31 e^{−2.38H+0.11H²} (H < 7; 11.1 e^{−2.27} = 1.1472 at H = 1) and φ_fp = 1 − 1.40 e^{−0.66H}
    (γ = 1, Patir & Cheng 1979; both codes A and B)."""
    assert float(ff.pc_shear_stress_factor(1.0)[0]) == pytest.approx(11.1 * math.exp(-2.27), rel=1e-12)
    assert float(ff.pc_shear_stress_factor(8.0)[0]) == 0.0
    assert float(ff.pc_pressure_stress_factor(2.0)[0]) == pytest.approx(1 - 1.4 * math.exp(-1.32), rel=1e-12)
    assert float(ff.pc_pressure_stress_factor(50.0)[0]) == pytest.approx(1.0, abs=1e-12)
    assert derivative_ok(ff.pc_shear_stress_factor, np.linspace(0.5, 6.5, 12), 1e-6)


# ---------------------------------------------------------------------------------------------------------------
# Wilson & Marsault (1998), γ = 1
# ---------------------------------------------------------------------------------------------------------------
def test_wm_pressure_conductance():
    """φ_x H_T³ = a2 (H_T − H_c)² + a3 (H_T − H_c)³ with H_c = 3[1 − 1.47476^−0.25007] = 0.2777, a2 = 0.3774,
    a3 = 1.0019 (γ = 1): zero below the percolation threshold, φ_x → a3 ≈ 1 for large H_T, within 2.5 % of
    Patir & Cheng at H_T = 3 (where the isotropic closure hands over)."""
    assert ff.WM_HC == pytest.approx(0.2777, abs=1e-4)
    assert ff.WM_A2 == pytest.approx(0.3774, abs=1e-4)
    assert float(ff.wm_pressure_conductance(0.2)[0]) == 0.0
    assert float(ff.wm_pressure_conductance(1e4)[0]) / 1e12 == pytest.approx(1.0019, rel=1e-3)
    H, _ = ff.nominal_ratio_from_mean_gap(3.0)
    pc = float(ff.pc_pressure_flow_factor(H)[0]) * float(H) ** 3
    assert float(ff.wm_pressure_conductance(3.0)[0]) == pytest.approx(pc, rel=0.025)
    assert derivative_ok(ff.wm_pressure_conductance, np.linspace(0.4, 6, 12), 1e-6)


def test_wm_shear_flow_factor():
    """The Wilson–Marsault shear-flow fit (γ ≥ 1 branch) is continuous at H_T = 5 with its exponential tail and
    agrees with Patir & Cheng's Φ_s at H_T = 3 to 1 % (0.5517 / 0.5533)."""
    below = float(ff.wm_shear_flow_factor(5.0 - 1e-9)[0])
    above = float(ff.wm_shear_flow_factor(5.0 + 1e-9)[0])
    assert below == pytest.approx(above, rel=1e-7)
    H, _ = ff.nominal_ratio_from_mean_gap(3.0)
    assert float(ff.wm_shear_flow_factor(3.0)[0]) == pytest.approx(float(ff.pc_shear_flow_factor(H)[0]), rel=0.01)
    assert derivative_ok(lambda x: ff.wm_shear_flow_factor(x), np.linspace(0.5, 4.5, 9), 1e-6)
    with pytest.raises(InputError):
        ff.wm_shear_flow_factor(1.0, gamma=0.5)


def test_gaussian_mean_gap():
    """Rigid Gaussian surfaces: H_T(0) = 1/√(2π), H_T(H) → H (3.0004 at H = 3); the inverse round-trips."""
    assert float(ff.gaussian_mean_gap_ratio(0.0)[0]) == pytest.approx(1 / math.sqrt(2 * math.pi), rel=1e-12)
    assert float(ff.gaussian_mean_gap_ratio(3.0)[0]) == pytest.approx(3.0004, abs=1e-4)
    H = np.array([-1.0, 0.0, 0.5, 2.0, 5.0])
    back, _ = ff.nominal_ratio_from_mean_gap(ff.gaussian_mean_gap_ratio(H)[0])
    assert np.allclose(back, H, atol=1e-10)


# ---------------------------------------------------------------------------------------------------------------
# The 1-D transverse closure
# ---------------------------------------------------------------------------------------------------------------
class SinusoidCell:
    """A duck-typed table for the cell gap g = d − a cos θ (no contact for d > a): moments by quadrature."""

    def __init__(self, amplitude, rq1, rq2):
        self.a = amplitude
        self.theta = np.linspace(0, 2 * math.pi, 20000, endpoint=False)
        self.meta = {"rq1_m": rq1, "rq2_m": rq2}
        self.sigma = amplitude / math.sqrt(2)

    def _g(self, d):
        return np.asarray(d, dtype=float)[..., None] - self.a * np.cos(self.theta)

    def gap_moment(self, d, k, h_b, part="all"):
        return np.mean(np.maximum(self._g(d), h_b) ** float(k), axis=-1)

    def d_gap_moment(self, d, k, h_b, part="all"):
        g = self._g(d)
        return np.mean(np.where(g > h_b, k * np.maximum(g, h_b) ** (k - 1.0), 0.0), axis=-1)

    def contact_fraction(self, d):
        return np.zeros(np.shape(d))


def direct_cell_flux(cell, d, dpdx, eta, u1, u2):
    """Time-averaged flux at a fixed point for a rough surface 1 (gap d − a cos(k(x − u1 t))) and a smooth
    surface 2, from the lab-frame Reynolds equation ∂q/∂x = −∂g/∂t = −u1 ∂g/∂x ⇒ q = C(t) + u1 g, with C fixed
    by a mean pressure gradient dpdx over the period; averaged over one passage of the roughness."""
    g = d - cell.a * np.cos(cell.theta)
    # −g³/(12η) p' + (u1 + u2)/2 g = C + u1 g  and  ⟨p'⟩ = dpdx
    c = ((0.5 * (u1 + u2) - u1) * np.mean(g**-2.0) - dpdx / (12 * eta)) / np.mean(g**-3.0)
    return np.mean(c + u1 * g)


def test_transverse_closure_reproduces_the_cell_average():
    """One rough surface (Rq2 = 0 → weight w = 1 with the variance transport): the closure's q̄ equals the direct
    time average of the cell flux (1e-10), for pressure-driven, Couette and mixed cases; C_p = 1/⟨g⁻³⟩ ≤ h_T³
    (Hölder) and 0 ≤ S_φ ≤ h_T."""
    cell = SinusoidCell(0.5e-6, 0.5e-6, 0.0)
    d, eta = 0.8e-6, 0.01
    f = ff.transverse_flow_factors(cell, d, h_b=1e-12)
    for dpdx, u1, u2 in ((1e9, 0.0, 0.0), (0.0, 3.0, 1.0), (-2e8, 1.0, 4.0)):
        assert float(f.flux(dpdx, eta, u1, u2)) == pytest.approx(direct_cell_flux(cell, d, dpdx, eta, u1, u2),
                                                                  rel=1e-10)
    assert float(f.conductance) <= float(f.mean_gap) ** 3
    assert 0 <= float(f.shear_flow) <= float(f.mean_gap)


def test_transverse_closure_transport_options():
    """Equal speeds: the gap is steady in the common frame, q̄ = −p̄'/(12η⟨g⁻³⟩) + u⟨g⟩ whatever the transport weight;
    equal Rq with the variance weight gives no shear flow (φ_s = 0); swapping the rough surface flips S_φ."""
    cell = SinusoidCell(0.5e-6, 0.4e-6, 0.4e-6)
    d, eta = 0.9e-6, 0.02
    exact = -5e8 / (12 * eta * float(cell.gap_moment(d, -3, 1e-12))) + 2.0 * float(cell.gap_moment(d, 1, 1e-12))
    for transport in ("variance", "mean", "surface1", "surface2", 0.3):
        f = ff.transverse_flow_factors(cell, d, 1e-12, transport)
        assert float(f.flux(5e8, eta, 2.0, 2.0)) == pytest.approx(exact, rel=1e-12)
    assert float(ff.transverse_flow_factors(cell, d, 1e-12).shear_flow) == 0.0
    s1 = float(ff.transverse_flow_factors(cell, d, 1e-12, "surface1").shear_flow)
    s2 = float(ff.transverse_flow_factors(cell, d, 1e-12, "surface2").shear_flow)
    assert s1 > 0 and s2 == pytest.approx(-s1)
    with pytest.raises(InputError):
        ff.transverse_flow_factors(cell, d, 1e-12, "upwind")


@pytest.fixture(scope="module")
def table():
    settings = dc.DryContactSettings(window_correlation_lengths=64, n_windows=2, points_per_correlation_length=16)
    return dc.compute_dry_contact_table(baseline_profile(), 0.2e-6, 0.5e-6, settings=settings)


def test_transverse_closure_on_a_table(table):
    """On a rough pair (0.2/0.5 µm): the d-derivatives agree with centred differences (1e-4), C_p ≤ h_T³, the shear
    flow has the sign of w − ½ (here negative: surface 2 is the rougher) and |S_φ| ≤ h_T, all finite from −2σ to 6σ;
    far from contact (H = d/σ = 20) the moments come from the top row's open gaps shifted by d − d_max (a 24-point
    quadrature that keeps ~80 % of the height variance) and tend to the small-roughness limits of Tripp (1983) for
    transverse roughness (γ = 0), φ_x = C_p/d³ = 1 − 6/H² and φ_s = 3/H (× (2w − 1)): checked to a factor 4 in
    1 − φ_x and 30 % in φ_s (σ here is the windows' rms height)."""
    s = table.sigma
    d = np.linspace(-2 * s, 6 * s, 41)
    f = ff.transverse_flow_factors(table, d, 1e-9)
    for v in (f.mean_gap, f.conductance, f.shear_flow, f.phi_f, f.phi_fs, f.phi_fp, f.lubricated_fraction):
        assert np.all(np.isfinite(v))
    assert np.all(f.conductance <= f.mean_gap**3 * (1 + 1e-4))  # Hölder, up to the interpolation of the moments
    assert np.all(f.shear_flow <= 1e-3 * 1e-9) and np.all(-f.shear_flow <= f.mean_gap)  # round-off at full contact
    h = 1e-7 * s
    plus, minus = ff.transverse_flow_factors(table, d + h, 1e-9), ff.transverse_flow_factors(table, d - h, 1e-9)
    for name in ("mean_gap", "conductance", "shear_flow"):
        fd = (getattr(plus, name) - getattr(minus, name)) / (2 * h)
        an = getattr(f, "d_" + name)
        assert np.allclose(fd, an, rtol=1e-4, atol=1e-4 * np.abs(an).max())
    rms = table.meta["window_rms_m"]
    H = 20 * s / rms
    far = ff.transverse_flow_factors(table, 20 * s, 1e-9)
    w = 0.2**2 / (0.2**2 + 0.5**2)
    assert 0.25 * 6 / H**2 < 1 - float(far.conductance) / (20 * s) ** 3 < 6 / H**2
    assert float(far.shear_flow) / rms == pytest.approx((2 * w - 1) * 3 / H, rel=0.3)


def test_transverse_contacts_block_the_pressure_flow(table):
    """In a 1-D cell every contact spot is a wall: with contact, ⟨max(g, h_b)⁻³⟩ ≥ cf·h_b⁻³, so C_p ≤ h_b³/cf and
    the pressure flow is governed by the floor (C_p ∝ h_b³ when the contact atom dominates)."""
    s = table.sigma
    d = 0.5 * s
    cf = float(table.contact_fraction(d))
    f1 = ff.transverse_flow_factors(table, d, 1e-9)
    f2 = ff.transverse_flow_factors(table, d, 2e-9)
    assert float(f1.conductance) <= (1e-9) ** 3 / cf
    assert float(f2.conductance) / float(f1.conductance) == pytest.approx(8.0, rel=0.05)


# ---------------------------------------------------------------------------------------------------------------
# Isotropic closure
# ---------------------------------------------------------------------------------------------------------------
def test_isotropic_closure(table):
    """Wilson–Marsault below H_T = 2.5, Patir–Cheng above 3.5, C¹ in between (derivatives agree with centred
    differences across the blend edges), no pressure flow below the percolation threshold, φ_x, φ_f, φ_fp → 1 far
    away (Couette shear η Δu/h on both walls)."""
    s = table.sigma
    d = np.linspace(-1 * s, 8 * s, 181)
    f = ff.isotropic_flow_factors(table, d)
    ratio = f.mean_gap / s
    wm = ff.wm_pressure_conductance(ratio)[0] * s**3
    assert np.allclose(f.conductance[ratio <= 2.5], wm[ratio <= 2.5], rtol=1e-12)
    H, _ = ff.nominal_ratio_from_mean_gap(ratio[ratio >= 3.5])
    pc = ff.pc_pressure_flow_factor(H)[0] * (H * s) ** 3
    assert np.allclose(f.conductance[ratio >= 3.5], pc, rtol=1e-10)
    assert np.all(f.conductance[ratio < ff.WM_HC] == 0)
    h = 1e-7 * s
    plus, minus = ff.isotropic_flow_factors(table, d + h), ff.isotropic_flow_factors(table, d - h)
    for name in ("conductance", "shear_flow", "mean_gap"):
        fd = (getattr(plus, name) - getattr(minus, name)) / (2 * h)
        an = getattr(f, "d_" + name)
        assert np.allclose(fd, an, rtol=1e-4, atol=1e-5 * np.abs(an).max())
    far = ff.isotropic_flow_factors(table, 40 * s)
    assert float(far.phi_x) == pytest.approx(1.0, abs=1e-3)
    assert float(far.phi_f) == pytest.approx(1.0, abs=1e-3) and float(far.phi_fp) == pytest.approx(1.0, abs=1e-3)
    tau1, tau2 = far.shear_stresses(0.0, 0.01, 1.0, 3.0)  # plain Couette between smooth walls
    assert float(tau1) == pytest.approx(0.01 * 2.0 / float(far.mean_gap), rel=1e-3)
    assert float(tau2) == pytest.approx(-float(tau1), rel=1e-6)
    with pytest.raises(InputError):
        ff.isotropic_flow_factors(table, s, blend=(3.0, 2.0))


# ---------------------------------------------------------------------------------------------------------------
# Traction
# ---------------------------------------------------------------------------------------------------------------
def test_traction(table):
    """Newtonian limit (τ0 = ∞): the lubricated shear is η u_s ⟨max(g, h_b)⁻¹·1[g > 0]⟩ (5 %, quantile quadrature
    against the tabulated open moment); the Eyring shear is smaller; traction adds μ_d p_a; no sliding, no
    traction; per-d viscosities broadcast."""
    s = table.sigma
    d = np.array([0.3, 0.8, 1.2]) * s
    eta, u_s, h_b = 0.01, 1.0, 1e-8
    newton = ff.lubricated_shear_stress(table, d, eta, u_s, math.inf, h_b)
    exact = eta * u_s * table.gap_moment(d, -1, h_b, part="open")
    assert np.allclose(newton, exact, rtol=0.05)
    eyring = ff.lubricated_shear_stress(table, d, eta, u_s, 5e6, h_b)
    assert np.all(eyring < newton) and np.all(eyring > 0)
    total = ff.traction(table, d, eta, u_s, 5e6, 0.1, h_b)
    assert np.allclose(total, eyring + 0.1 * table.asperity_pressure(d), rtol=1e-12)
    assert np.all(ff.traction(table, d, eta, 0.0, 5e6, 0.1, h_b) == 0)
    per_d = ff.lubricated_shear_stress(table, d, np.array([0.01, 0.02, 0.03]), u_s, math.inf, h_b)
    assert np.allclose(per_d, newton * np.array([1, 2, 3]), rtol=1e-12)
