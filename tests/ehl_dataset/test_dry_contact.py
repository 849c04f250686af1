"""Dry elastic–plastic contact of a roughness pair (ehl_dataset/model/dry_contact.py): the periodic solver against
closed forms (Westergaard's wavy surface, Hertz's cylinder, the rigid-plastic limit), exact identities, and the
tables' interpolation, continuation, storage and cache."""

import json
import math

import numpy as np
import pytest

from ehl_dataset.discretisation.deflection import influence_matrix
from ehl_dataset.model import dry_contact as dc
from ehl_dataset.model.roughness import baseline_profile, generate_profile, named_profile
from ehl_dataset.validation import InputError

E = dc.STEEL_E_REDUCED_PA


def wavy(n=512, wavelength=100e-6, amplitude=0.1e-6):
    x = np.arange(n) * wavelength / n
    return x, amplitude * np.cos(2 * math.pi * x / wavelength), wavelength / n


# ---------------------------------------------------------------------------------------------------------------
# Elasticity convention
# ---------------------------------------------------------------------------------------------------------------
def test_periodic_deflection_is_the_projects_log_kernel():
    """V_k = 4 p_k/(E'|k|): a cosine pressure p0 cos(kx) deflects 4 p0/(E'k) cos(kx) (exact for the spectral
    operator), and the project's V = −4/(πE') ∫ ln|x − x'| p dx' (ehl_dataset.discretisation.deflection, piecewise-linear
    elements) over 41 periods gives the same amplitude in the middle period to 0.5 % (truncation ~1/(2πM))."""
    wavelength, p0 = 50e-6, 1e8
    x, _, dx = wavy(256, wavelength)
    k = 2 * math.pi / wavelength
    u = dc.periodic_deflection(p0 * np.cos(k * x), dx, E)
    assert np.max(np.abs(u - 4 * p0 / (E * k) * np.cos(k * x))) < 1e-12 * 4 * p0 / (E * k)
    assert abs(u.mean()) < 1e-20
    periods, per = 41, 32
    xs = np.arange(periods * per + 1) * wavelength / per
    v = influence_matrix(xs, 4.0 / E) @ (p0 * np.cos(k * xs))
    mid = slice(20 * per, 21 * per)
    amplitude = 2 * np.mean((v[mid] - v[mid].mean()) * np.cos(k * xs[mid]))
    assert amplitude == pytest.approx(4 * p0 / (E * k), rel=5e-3)


# ---------------------------------------------------------------------------------------------------------------
# Closed forms
# ---------------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("psi", [0.05, 0.3, 0.7, 0.95])
def test_westergaard_wavy_surface(psi):
    """Johnson (1985) §13.2, z = Δ cos(2πx/λ) on a rigid flat, p* = πE*Δ/λ with E* = E'/2 (full contact at p̄ = p*):
    p̄ = p* sin²(πa/λ) (contact width 2a, to one node of 512), p_max = 2√(p̄ p*) (2e-4), the pressure profile
    p = (2p̄/sin²ψ_a) cos(πx/λ)√(sin²ψ_a − sin²(πx/λ)) (rms error < 0.5 % of p_max), and the mean gap
    ⟨g⟩ = d = Δ(1 − ψ + ψ ln ψ), ψ = p̄/p* (from the energy identity d = −dΠ/dp̄ with Westergaard's
    ⟨p cos θ⟩ = p̄(1 − ψ/2); 2e-4 Δ)."""
    x, z, dx = wavy()
    wavelength, amplitude = 100e-6, 0.1e-6
    p_star = math.pi * (E / 2) * amplitude / wavelength
    sol = dc.solve_contact(z, dx, E, mean_pressure=psi * p_star, hardness=math.inf, tol=1e-12)
    p = sol.pressure[0]
    a = wavelength / math.pi * math.asin(math.sqrt(psi))
    assert abs((p > 0).mean() - 2 * a / wavelength) <= 1.5 / x.size
    assert p.max() == pytest.approx(2 * math.sqrt(psi) * p_star, rel=2e-4)
    xc = np.where(x > wavelength / 2, x - wavelength, x)
    s2 = math.sin(math.pi * a / wavelength) ** 2
    exact = 2 * psi * p_star / s2 * np.cos(math.pi * xc / wavelength) * np.sqrt(
        np.maximum(s2 - np.sin(math.pi * xc / wavelength) ** 2, 0.0))
    assert np.sqrt(np.mean((p - exact) ** 2)) < 5e-3 * p.max()
    closed = amplitude * (1 - psi + psi * math.log(psi))
    assert sol.separation[0] == pytest.approx(closed, abs=2e-4 * amplitude)
    assert sol.gap.mean() == pytest.approx(sol.separation[0], abs=1e-9 * amplitude)
    # Westergaard's first Fourier coefficient used in the derivation, by quadrature of the analytic pressure
    assert np.mean(exact * np.cos(2 * math.pi * x / wavelength)) == pytest.approx(psi * p_star * (1 - psi / 2),
                                                                                   rel=2e-3)


def test_wavy_surface_reaches_full_contact_at_p_star():
    """As d → 0⁺ the mean pressure tends to p* = πE'Δ/(2λ) and the pressure to p*(1 + cos kx): at d = 1e-6 Δ,
    p̄ = p*(1 − √(2·1e-6)) (closed form above, to 1e-4)."""
    x, z, dx = wavy()
    p_star = math.pi * E * 0.1e-6 / (2 * 100e-6)
    sol = dc.solve_contact(z, dx, E, 1e-6 * 0.1e-6, hardness=math.inf, tol=1e-12)
    assert sol.pressure.mean() / p_star == pytest.approx(1 - math.sqrt(2e-6), abs=1e-4)
    assert (sol.pressure > 0).mean() > 0.95  # pockets of mean depth 1e-6 Δ remain at the troughs


def test_hertz_line_contact():
    """A cylinder z = −x²/(2R) (R = 10 mm) in a periodic window 40 contact half-widths long: b = √(8WR/(πE')) and
    p0 = 2W/(πb) (Hertz, plane strain, W load per length) to 0.5 %."""
    radius, n, length = 10e-3, 8192, 2e-3
    x = (np.arange(n) - n // 2) * length / n
    z = -x**2 / (2 * radius)
    b = length / 40
    load = math.pi * E * b**2 / (8 * radius)
    sol = dc.solve_contact(z, length / n, E, mean_pressure=load / length, hardness=math.inf)
    p = sol.pressure[0]
    width = (p > 0).sum() * length / n
    assert width / 2 == pytest.approx(b, rel=5e-3)
    assert p.max() == pytest.approx(2 * load / (math.pi * b), rel=5e-3)


def test_rigid_plastic_limit():
    """With E' → ∞ (1e18 Pa) the asperities only flow plastically: contact fraction = plastic fraction = p̄/H
    (within 2 nodes), p ≤ H everywhere, and d is the height exceeded on that fraction of the window."""
    profile = baseline_profile().scaled(0.5e-6)
    z = profile.z[:4096] - profile.z[:4096].mean()
    hardness, p_mean = 1e9, 0.3e9
    sol = dc.solve_contact(z, profile.spacing, 1e18, mean_pressure=p_mean, hardness=hardness)
    p = sol.pressure[0]
    assert p.max() <= hardness
    assert (p > 0).mean() == pytest.approx(p_mean / hardness, abs=2 / z.size)
    assert (p >= hardness).mean() == pytest.approx(p_mean / hardness, abs=2 / z.size)
    assert np.mean(z > sol.separation[0]) == pytest.approx(p_mean / hardness, abs=2 / z.size)


# ---------------------------------------------------------------------------------------------------------------
# Identities and scaling on rough windows
# ---------------------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def small_windows():
    settings = dc.DryContactSettings(window_correlation_lengths=64, n_windows=2, points_per_correlation_length=16)
    z, spacing = dc.composite_windows(baseline_profile(), 0.4e-6, 0.4e-6, settings)
    return z, spacing, settings


def test_composite_windows(small_windows):
    """Two independent periodic windows of 64β at β/16 (1024 nodes each), zero mean, rms ≈ σ = √2·0.4 µm (sampling
    error of 64β windows ~10 %), no jump at the wrap larger than the largest jump inside (the cross-fade)."""
    z, spacing, _ = small_windows
    assert z.shape == (2, 1024)
    beta = baseline_profile().correlation_length
    assert spacing == pytest.approx(beta / 16, rel=2e-3)
    assert np.allclose(z.mean(axis=1), 0.0, atol=1e-20)
    assert np.sqrt(np.mean(z**2)) == pytest.approx(math.sqrt(2) * 0.4e-6, rel=0.2)
    jumps = np.abs(np.diff(z, axis=1)).max(axis=1)
    wrap = np.abs(z[:, 0] - z[:, -1])
    assert np.all(wrap <= jumps)


def test_contact_conditions_and_volume_identity(small_windows):
    """At d = 0.5σ, H = 6.8 GPa: 0 ≤ p ≤ H, p·g = 0, contact conditions to 1e-9·rms, ⟨u_e⟩ = 0 and the exact
    volume identity ⟨g⟩ = d − ⟨z⟩ + ⟨u_p⟩ per window (to 1e-9 σ)."""
    z, spacing, _ = small_windows
    sigma = math.sqrt(2) * 0.4e-6
    sol = dc.solve_contact(z, spacing, E, 0.5 * sigma)
    assert sol.residual <= 1e-9 * np.sqrt(np.mean(z**2))
    assert sol.pressure.min() >= 0 and sol.pressure.max() <= dc.DEFAULT_HARDNESS_PA
    assert np.all(sol.pressure * sol.gap == 0)
    assert np.allclose(sol.deflection.mean(axis=1), 0.0, atol=1e-12 * sigma)
    lhs = sol.gap.mean(axis=1)
    rhs = sol.separation - z.mean(axis=1) + sol.plastic.mean(axis=1)
    assert np.allclose(lhs, rhs, atol=1e-9 * sigma)


def test_elastic_scaling(small_windows):
    """Elastic contact is linear-homogeneous: heights ×2 at d ×2 doubles p; E' ×3 triples p (so p_a/(E'σ/β) is a
    function of d/σ only; plasticity breaks it, which is why tables are keyed on the dimensional values)."""
    z, spacing, _ = small_windows
    d = 0.3e-6
    base = dc.solve_contact(z, spacing, E, d, hardness=math.inf, tol=1e-12).pressure
    doubled = dc.solve_contact(2 * z, spacing, E, 2 * d, hardness=math.inf, tol=1e-12).pressure
    stiffer = dc.solve_contact(z, spacing, 3 * E, d, hardness=math.inf, tol=1e-12).pressure
    assert np.allclose(doubled, 2 * base, rtol=1e-7, atol=1e-7 * base.max())
    assert np.allclose(stiffer, 3 * base, rtol=1e-7, atol=1e-7 * base.max())


def test_load_control_matches_displacement_control(small_windows):
    """The separation found under load control reproduces the load under displacement control."""
    z, spacing, _ = small_windows
    sol = dc.solve_contact(z, spacing, E, mean_pressure=0.5e9)
    assert np.allclose(sol.pressure.mean(axis=1), 0.5e9, rtol=1e-9)
    again = dc.solve_contact(z, spacing, E, sol.separation)
    assert np.allclose(again.pressure.mean(axis=1), 0.5e9, rtol=1e-7)


def test_solver_input_errors(small_windows):
    z, spacing, _ = small_windows
    with pytest.raises(InputError):
        dc.solve_contact(z, spacing, E)  # neither d nor p̄
    with pytest.raises(InputError):
        dc.solve_contact(z, spacing, E, 0.1e-6, mean_pressure=1e8)
    with pytest.raises(InputError):
        dc.solve_contact(z, spacing, -1.0, 0.1e-6)
    with pytest.raises(InputError):
        dc.composite_windows(generate_profile(1024, 1e-6, 15e-6, 0.5e-6, 1), 0.1e-6, 0.1e-6)  # too short


# ---------------------------------------------------------------------------------------------------------------
# Tables
# ---------------------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def table(small_windows):
    _, _, settings = small_windows
    return dc.compute_dry_contact_table(baseline_profile(), 0.4e-6, 0.4e-6, settings=settings)


def test_table_rows(table):
    """Rows: d strictly decreasing, p_a and the contact fraction increasing, plastic ≤ contact fraction, the
    volume identity ⟨g⟩ = d + ⟨u_p⟩ (zero-mean windows) to 1e-6 σ, the ladder ends at 3 GPa or full contact."""
    s = table.sigma
    assert np.all(np.diff(table.tab_separation) < 0)
    assert np.all(np.diff(table.tab_pressure) > 0)
    assert np.all(np.diff(table.tab_contact_fraction) >= 0)
    assert np.all(table.tab_plastic_fraction <= table.tab_contact_fraction)
    assert np.allclose(table.tab_mean_gap, table.tab_separation + table.tab_mean_plastic, atol=1e-6 * s)
    assert table.tab_pressure[-1] >= 3e9 or table.tab_contact_fraction[-1] >= 0.995
    assert table.tab_separation[0] / s > 1.0  # starts where 64 nodes (here 3 % of 2048) touch


def test_interpolation_is_monotone_c1_and_never_nan(table):
    """On d ∈ [−10σ, 20σ]: finite everywhere, p_a and the contact fraction non-increasing, derivatives agree with
    centred differences (1e-5 relative) including across both table ends, fractions in [0, 1]."""
    s = table.sigma
    d = np.linspace(-10 * s, 20 * s, 3001)
    for f in (table.asperity_pressure, table.d_asperity_pressure, table.contact_fraction, table.plastic_fraction,
              table.mean_gap, lambda x: table.gap_moment(x, -3, 1e-9), lambda x: table.gap_moment(x, 1, 1e-9)):
        assert np.all(np.isfinite(f(d)))
    assert np.all(np.diff(table.asperity_pressure(d)) <= 0)
    assert np.all(np.diff(table.contact_fraction(d)) <= 1e-15)
    cf = table.contact_fraction(d)
    assert cf.min() >= 0 and cf.max() <= 1
    lo, hi = table.d_range
    h = 1e-7 * s
    for x0 in (lo, hi, 0.5 * (lo + hi), lo - s, hi + s):
        for f, df in ((table.asperity_pressure, table.d_asperity_pressure),
                      (table.contact_fraction, table.d_contact_fraction), (table.mean_gap, table.d_mean_gap),
                      (lambda x: table.gap_moment(x, -3, 1e-9), lambda x: table.d_gap_moment(x, -3, 1e-9))):
            for x in (x0 - 2 * h, x0 + 2 * h):
                fd = (f(x + h) - f(x - h)) / (2 * h)
                roundoff = 1e-14 * abs(f(x)) / h  # cancellation in the difference quotient
                assert fd == pytest.approx(df(x), rel=1e-4, abs=roundoff + 1e-300)


def test_continuations(table):
    """Above the table p_a decays like a Gaussian tail (ln p_a has the constant second difference −1 in units of σ),
    ⟨g⟩ continues with slope 1 (no contact:
    ⟨g⟩ = d); below it p_a is linear (zero second difference), the contact fraction → 1, ⟨max(g, h_b)^-3⟩ →
    h_b^-3 and ⟨g⟩ → 0."""
    s = table.sigma
    lo, hi = table.d_range
    p = table.asperity_pressure(np.array([hi + s, hi + 2 * s, hi + 3 * s]))
    lp = np.log(p)
    assert lp[0] - 2 * lp[1] + lp[2] == pytest.approx(-1.0, rel=1e-9) and p[1] < p[0]
    assert table.d_mean_gap(hi + 5 * s) == pytest.approx(1.0, abs=0.02)
    q = table.asperity_pressure(np.array([lo - 3 * s, lo - 2 * s, lo - s]))
    assert q[0] - 2 * q[1] + q[2] == pytest.approx(0.0, abs=1e-9 * q[0])
    assert table.contact_fraction(lo - 20 * s) == pytest.approx(1.0, abs=1e-6)
    assert table.gap_moment(lo - 20 * s, -3, 1e-9) == pytest.approx(1e27, rel=1e-6)
    assert table.mean_gap(lo - 20 * s) < 1e-6 * s


def test_moments(table):
    """⟨max(g, h)⟩ → ⟨g⟩ for small h and ≥ h; the moments are ordered by the floor; the full moment is the open
    moment + contact fraction·h^k at the rows; the 24-point quantile quadrature agrees with the exact moments
    (⟨g⟩ 0.5 %, ⟨g⁻³⟩ floored at 10 nm 10 %) inside the table."""
    s = table.sigma
    d = np.linspace(*table.d_range, 9)[1:-1]
    assert np.allclose(table.gap_moment(d, 1, 1e-5 * s), table.mean_gap(d), rtol=1e-3, atol=1e-4 * s)
    assert np.all(table.gap_moment(d, -3, 1e-9) > table.gap_moment(d, -3, 1e-8))
    rows = table.tab_separation[1:-1]  # the split is exact at the rows (the interpolants in d differ between them)
    full = table.gap_moment(rows, -2, 1e-8)
    split = table.gap_moment(rows, -2, 1e-8, part="open") + table.contact_fraction(rows) * 1e-8**-2
    assert np.allclose(full, split, rtol=1e-6)
    quad1 = table.gap_expectation(d, lambda g: g, 0.0)
    assert np.allclose(quad1, table.mean_gap(d), rtol=5e-3)
    quad3 = table.gap_expectation(d, lambda g: g**-3.0, 1e-8)
    assert np.allclose(quad3, table.gap_moment(d, -3, 1e-8), rtol=0.1)


def test_separation_at_pressure_inverts(table):
    s = table.sigma
    d = np.linspace(table.d_range[0] - s, table.d_range[1] + s, 11)
    assert np.allclose(table.separation_at_pressure(table.asperity_pressure(d)), d, atol=1e-9 * s)


def test_save_load_and_keys(table, tmp_path):
    """Round trip through .npz (CDF and quantiles in float32); the key depends on Rq, E', H and the settings."""
    path = table.save(tmp_path / "t.npz")
    back = dc.DryContactTable.load(path)
    d = np.linspace(*table.d_range, 7)
    assert np.allclose(back.asperity_pressure(d), table.asperity_pressure(d), rtol=1e-12)
    assert np.allclose(back.gap_moment(d, -3, 1e-9), table.gap_moment(d, -3, 1e-9), rtol=1e-6)
    prof = baseline_profile()
    keys = {dc.table_key(prof, 0.4e-6, 0.4e-6, E, 6.8e9), dc.table_key(prof, 0.4e-6, 0.5e-6, E, 6.8e9),
            dc.table_key(prof, 0.4e-6, 0.4e-6, 1.1 * E, 6.8e9), dc.table_key(prof, 0.4e-6, 0.4e-6, E, 6e9),
            dc.table_key(prof, 0.4e-6, 0.4e-6, E, 6.8e9, dc.DryContactSettings(n_windows=2))}
    assert len(keys) == 5


def test_cache_computes_once(tmp_path, monkeypatch, table):
    """dry_contact_table computes a missing table once, writes it to the cache directory, then reads it back."""
    calls = []

    def fake_compute(*args, **kwargs):
        calls.append(args)
        return table

    monkeypatch.setattr(dc, "compute_dry_contact_table", fake_compute)
    monkeypatch.setenv(dc.CACHE_ENV, str(tmp_path))
    settings = dc.DryContactSettings(n_windows=3)
    first = dc.dry_contact_table(None, 0.33e-6, 0.33e-6, settings=settings)  # a pair no shipped table has
    second = dc.dry_contact_table(None, 0.33e-6, 0.33e-6, settings=settings)
    assert len(calls) == 1
    assert list((tmp_path / "dry_contact").glob("*.npz"))
    assert second.asperity_pressure(first.d_range[0]) == pytest.approx(first.asperity_pressure(first.d_range[0]))


def test_input_errors(table):
    with pytest.raises(InputError):
        table.gap_moment(0.0, -4, 1e-9)
    with pytest.raises(InputError):
        table.gap_moment(0.0, -3, 0.0)
    with pytest.raises(InputError):
        table.separation_at_pressure(-1.0)
    with pytest.raises(InputError):
        dc.DryContactSettings(n_windows=0)


# ---------------------------------------------------------------------------------------------------------------
# Shipped tables
# ---------------------------------------------------------------------------------------------------------------
def test_shipped_tables():
    """The tables of the paper's ten Rq pairs ship for both shipped profiles (< 1 MB in all), are found by their key
    with the windows the homogenised models ask for, rise monotonically to ≥ 3 GPa or full contact, and satisfy
    ⟨g⟩ = d + ⟨u_p⟩."""
    folder = dc.data_path(*dc.SHIPPED_DIR)
    index = json.loads((folder / "index.json").read_text())
    assert set(index["profiles"]) == set(dc.SHIPPED_TABLE_PROFILES)
    assert sum(f.stat().st_size for f in folder.iterdir()) < 1_000_000
    for name in dc.SHIPPED_TABLE_PROFILES:
        prof = named_profile(name)
        rows = [row for row in index["tables"] if row["profile"] == name]
        assert {tuple(row["rq_um"]) for row in rows} == {tuple(p) for p in dc.PAPER_RQ_PAIRS_UM}
        assert index["profiles"][name]["sha256"] == dc.profile_hash(prof)
        settings = dc.windows_that_fit(prof)
        for row in rows:
            rq1, rq2 = (v * 1e-6 for v in row["rq_um"])
            assert row["key"] == dc.table_key(prof, rq1, rq2, E, dc.DEFAULT_HARDNESS_PA, settings)
            t = dc.DryContactTable.load(folder / f"{row['key']}.npz")
            assert np.all(np.diff(t.tab_pressure) > 0)
            assert t.tab_pressure[-1] >= 3e9 or t.tab_contact_fraction[-1] >= 0.995
            assert np.allclose(t.tab_mean_gap, t.tab_separation + t.tab_mean_plastic, atol=1e-6 * t.sigma)


def test_without_settings_a_short_profile_gets_the_windows_that_fit_and_its_shipped_table():
    """flank_ground holds fewer than the default 8 windows of 512 β: with no settings the table is the one of the
    windows that fit (the shipped table, found without computing), and the baseline keeps the defaults."""
    flank = named_profile("flank_ground")
    assert dc.windows_that_fit(flank) != dc.DryContactSettings()
    assert dc.windows_that_fit(baseline_profile()) == dc.DryContactSettings()
    table = dc.dry_contact_table(flank, 0.4e-6, 0.4e-6, E, cache=False)
    assert table.meta["key"] == dc.table_key(flank, 0.4e-6, 0.4e-6, E, dc.DEFAULT_HARDNESS_PA,
                                             dc.windows_that_fit(flank))
    assert dc.data_path(*dc.SHIPPED_DIR, f"{table.meta['key']}.npz").is_file()


@pytest.mark.slow
def test_resolution_convergence():
    """β/32 against β/64 on the same windows (0.4/0.4 µm, d = σ): p_a within 0.1 %, contact fraction within 3 %
    (first-order: nodes are counted), ⟨max(g, 1 nm)^-3⟩ within 2 %."""
    out = {}
    for points in (32.0, 64.0):
        settings = dc.DryContactSettings(window_correlation_lengths=128, n_windows=2,
                                         points_per_correlation_length=points)
        z, spacing = dc.composite_windows(baseline_profile(), 0.4e-6, 0.4e-6, settings)
        sol = dc.solve_contact(z, spacing, E, math.sqrt(2) * 0.4e-6)
        out[points] = (sol.pressure.mean(), (sol.pressure > 0).mean(), np.mean(np.maximum(sol.gap, 1e-9) ** -3.0))
    assert out[32.0][0] == pytest.approx(out[64.0][0], rel=1e-3)
    assert out[32.0][1] == pytest.approx(out[64.0][1], rel=3e-2)
    assert out[32.0][2] == pytest.approx(out[64.0][2], rel=2e-2)


def test_a_pair_without_its_own_table_scales_the_nearest_shipped_one(tmp_path, monkeypatch):
    """Elastic similarity (Johnson, Contact Mechanics, 1985, §13): heights scaled by k give p_a(d) = k·p_a0(d/k)
    and A(d) = A0(d/k). A pair of the shipped pairs' mixing angle that ships no table of its own, Rq 0.15/0.15 µm on
    flank_ground, takes the nearest shipped one in composite roughness, 0.2/0.2 µm, at scale 0.75, and reproduces the
    pair's own computed table where neither is plastic (to 1e-4: the tables' interpolation), and within 1 % down to
    d = 0.5σ, where the plastic cap (H for the pair, 0.75·H as scaled) touches up to 1.7 % of the contact area
    (measured −0.6 % at 0.5σ; at d = 0, in heavy plastic contact, −25 %). A shipped pair is its own table at scale 1;
    a user's profile without shipped tables gets its own computed table."""
    monkeypatch.setenv(dc.CACHE_ENV, str(tmp_path))
    flank = named_profile("flank_ground")
    settings = dc.windows_that_fit(flank)
    table, scale, pair = dc.similar_dry_contact_table(flank, 0.15e-6, 0.15e-6, E)
    assert pair == pytest.approx((0.2e-6, 0.2e-6)) and scale == pytest.approx(0.75, rel=1e-12)
    own = dc.compute_dry_contact_table(flank, 0.15e-6, 0.15e-6, E, settings=settings)
    d = np.linspace(0.5, 3.5, 13) * own.sigma
    scaled, exact = scale * table.asperity_pressure(d / scale), own.asperity_pressure(d)
    elastic = (own.plastic_fraction(d) == 0.0) & (table.plastic_fraction(d / scale) == 0.0)
    assert elastic.sum() >= 5
    np.testing.assert_allclose(scaled[elastic], exact[elastic], rtol=1e-4)
    np.testing.assert_allclose(table.contact_fraction(d / scale)[elastic], own.contact_fraction(d)[elastic], rtol=1e-4)
    np.testing.assert_allclose(scaled, exact, rtol=0.01)
    same, unit, same_pair = dc.similar_dry_contact_table(flank, 0.2e-6, 0.5e-6, E)
    assert unit == 1.0 and same_pair == (0.2e-6, 0.5e-6)
    assert same.meta["key"] == dc.table_key(flank, 0.2e-6, 0.5e-6, E, dc.DEFAULT_HARDNESS_PA, settings)
    users = generate_profile(1 << 15, 0.5e-6, 15e-6, 0.5e-6, seed=11)
    small = dc.DryContactSettings(n_windows=1, window_correlation_lengths=64)
    mine, one, mine_pair = dc.similar_dry_contact_table(users, 0.3e-6, 0.3e-6, E, settings=small)
    assert one == 1.0 and mine_pair == (0.3e-6, 0.3e-6) and (dc.cache_directory() / f"{mine.meta['key']}.npz").is_file()
