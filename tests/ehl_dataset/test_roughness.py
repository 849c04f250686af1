"""Roughness profiles: the shipped baseline, its statistics, the measured-profile loader, the two moving surfaces."""

import dataclasses
import math

import numpy as np
import pytest

from ehl_dataset.data_files import data_path
from ehl_dataset.model import roughness as rg
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.validation import InputError

BASELINE = rg.baseline_profile()
"""The profile the layout tests were written for (a 2.5 GPa contact needs its long periodic baseline)."""


def test_shipped_baseline_is_regenerated_bit_for_bit():
    """The file in data/roughness/ is exactly what generate_baseline() + profile_text() produce (README claim)."""
    shipped = data_path("roughness", rg.BASELINE_FILE).read_bytes()
    assert rg.baseline_text().encode("ascii") == shipped


def test_baseline_statistics():
    """Rq = 0.5 µm to the file's 1 pm rounding (relative 1e-6), zero mean, β within 3 standard errors of 15 µm
    (standard error from Bartlett's formula, correlation_length_standard_error: 0.17 µm for 131 mm)."""
    base = rg.baseline_profile()
    assert base.z.size == rg.BASELINE_POINTS
    assert base.spacing == pytest.approx(rg.BASELINE_SPACING_M, rel=1e-12)
    assert base.rq == pytest.approx(0.5e-6, rel=1e-6)
    assert abs(base.z.mean()) < 1e-15
    sigma = rg.correlation_length_standard_error(rg.BASELINE_CORRELATION_LENGTH_M, base.length)
    assert 0.1e-6 < sigma < 0.3e-6
    assert abs(base.correlation_length - rg.BASELINE_CORRELATION_LENGTH_M) < 3 * sigma


def test_gaussian_heights():
    """Gaussian process: skewness 0 and kurtosis 3 within 4 sampling standard errors. Heights are correlated over
    ~β, so the effective sample count is L/(β√(π/2)·...) — use the conservative N_eff = L/(2β)."""
    z = rg.baseline_profile().z
    n_eff = rg.baseline_profile().length / (2 * rg.BASELINE_CORRELATION_LENGTH_M)
    s = z.std()
    skew = np.mean(z**3) / s**3
    kurt = np.mean(z**4) / s**4
    assert abs(skew) < 4 * math.sqrt(6 / n_eff)
    assert abs(kurt - 3) < 4 * math.sqrt(24 / n_eff)


def test_correlation_length_standard_error_matches_monte_carlo():
    """The derived sampling error of β̂ (Bartlett) agrees with the spread over 200 independent seeds; the std of a
    200-sample std has relative error 1/√400 = 5 %, so 4 of those = 20 %. The mean is unbiased within 4 σ/√200."""
    n, dx, beta = 2**13, 1e-6, 15e-6
    est = np.array([rg.generate_profile(n, dx, beta, 0.5e-6, seed).correlation_length for seed in range(200)])
    sigma = rg.correlation_length_standard_error(beta, n * dx)
    assert np.std(est, ddof=1) == pytest.approx(sigma, rel=0.20)
    assert abs(est.mean() - beta) < 4 * sigma / math.sqrt(est.size)


@pytest.mark.parametrize("rq", [0.05e-6, 0.4e-6, 1.0e-6])
def test_scaling_gives_exact_rq(rq):
    """The paper obtains each roughness level by multiplying the baseline by a constant: Rq exact, shape kept."""
    base = rg.baseline_profile()
    scaled = base.scaled(rq)
    assert scaled.rq == pytest.approx(rq, rel=1e-12)
    np.testing.assert_allclose(scaled.z / scaled.rq, base.z / base.rq, rtol=0, atol=1e-12)


def test_exponential_acf_variant():
    """ACF exp(−|τ|/β) has ρ(β) = 1/e too: β̂ within 4 standard errors (Gaussian-ACF error, a fair bound)."""
    prof = rg.generate_profile(2**15, 0.5e-6, 12e-6, 0.3e-6, 7, acf="exponential")
    assert prof.rq == pytest.approx(0.3e-6, rel=1e-12)
    assert abs(prof.correlation_length - 12e-6) < 4 * rg.correlation_length_standard_error(12e-6, prof.length) + 0.5e-6


def test_sample_interpolates_and_wraps():
    """Linear interpolation hits the samples and the midpoints, and reading is periodic with the profile length."""
    prof = rg.generate_profile(64, 1e-6, 3e-6, 1e-6, 1)
    idx = np.arange(64)
    np.testing.assert_allclose(prof.sample(idx * 1e-6), prof.z, atol=1e-18)
    np.testing.assert_allclose(prof.sample((idx + 0.5) * 1e-6), 0.5 * (prof.z + np.roll(prof.z, -1)), atol=1e-18)
    np.testing.assert_allclose(prof.sample(idx * 1e-6 + prof.length), prof.z, atol=1e-18)
    np.testing.assert_allclose(prof.sample(idx * 1e-6 - 3 * prof.length), prof.z, atol=1e-18)


# ---------------------------------------------------------------------------------------------------------------
# Loader
# ---------------------------------------------------------------------------------------------------------------
def _write(path, x, z, header="# x [um] z [um]\n"):
    path.write_text(header + "".join(f"{a!r} {b!r}\n" for a, b in zip(np.asarray(x).tolist(), np.asarray(z).tolist())))
    return path


def test_detrend_removes_a_line_exactly(tmp_path):
    """A profile plus a + b·x loads as the profile minus its own least-squares line (to round-off)."""
    prof = rg.generate_profile(512, 0.5e-6, 8e-6, 0.4e-6, 3)
    x_um = np.arange(512) * 0.5
    tilted = prof.z * 1e6 + 3.0 - 0.02 * x_um
    loaded = rg.load_profile(_write(tmp_path / "p.txt", x_um, tilted))
    expected = rg.detrend(x_um * 1e-6, prof.z)
    np.testing.assert_allclose(loaded.z, expected, atol=1e-15)
    assert loaded.spacing == pytest.approx(0.5e-6)
    # the least-squares line of the result is zero
    slope = np.polyfit(np.arange(512), loaded.z, 1)
    np.testing.assert_allclose(slope, 0.0, atol=1e-18)


def test_loader_units_resampling_and_target_rq(tmp_path):
    """x in metres, non-uniform sampling (1.25 µm ± 0.5 µm jitter): resampled to a uniform 1 µm grid, Rq scaled
    exactly. A sine of wavelength 50 µm is recovered within the linear-interpolation bound Δx²/8·max|z''|
    = (1.75 µm)²/8·(2π/50 µm)² = 0.6 % of its amplitude (+ the detrending of a sine over whole periods: ~0)."""
    rng = np.random.default_rng(0)
    x = np.arange(800) * 1.25e-6 + rng.uniform(-0.25e-6, 0.25e-6, 800)
    wavelength = 50e-6
    z = 1e-7 * np.sin(2 * np.pi * x / wavelength)
    loaded = rg.load_profile(_write(tmp_path / "m.csv", x, z, header=""), unit="m", spacing_m=1e-6,
                             target_rq_m=0.2e-6)
    assert loaded.spacing == 1e-6
    assert loaded.z.size == int((x[-1] - x[0]) / 1e-6) + 1
    assert loaded.rq == pytest.approx(0.2e-6, rel=1e-12)
    grid = x[0] + 1e-6 * np.arange(loaded.z.size)
    exact = rg.detrend(grid, np.sin(2 * np.pi * grid / wavelength))
    exact *= 0.2e-6 / np.sqrt(np.mean((exact - exact.mean()) ** 2))
    amplitude = 0.2e-6 * math.sqrt(2)
    assert np.max(np.abs(loaded.z - (exact - exact.mean()))) < 0.006 * amplitude


@pytest.mark.parametrize("content, problem", [
    ("0 1\n1 2 3\n", "fields"),
    ("0 1\n1 abc\n", "not numeric"),
    ("0 1\n1 nan\n", "finite"),
    ("".join(f"{i} {i % 3}\n" for i in range(10)), "at least 16"),
    ("".join(f"{i} {i % 3}\n" for i in (list(range(10)) + [9] + list(range(11, 20)))), "increasing"),
    ("".join(f"{i} {2.0 * i + 1}\n" for i in range(40)), "flat"),
])
def test_loader_rejects_malformed_files(tmp_path, content, problem):
    path = tmp_path / "bad.txt"
    path.write_text(content)
    with pytest.raises(InputError, match="roughness file") as info:
        rg.load_profile(path)
    assert problem in str(info.value)
    assert "bad.txt" in str(info.value)


def test_loader_rejects_bad_options(tmp_path):
    path = _write(tmp_path / "ok.txt", np.arange(100.0), np.sin(np.arange(100.0)))
    with pytest.raises(InputError, match="unit"):
        rg.load_profile(path, unit="inch")
    with pytest.raises(InputError, match="spacing_m"):
        rg.load_profile(path, spacing_m=50e-6)  # > span/15
    with pytest.raises(InputError, match="roughness file"):
        rg.load_profile(tmp_path / "missing.txt")


# ---------------------------------------------------------------------------------------------------------------
# The two moving surfaces
# ---------------------------------------------------------------------------------------------------------------
def _case(sr=0.5, rq1=0.4e-6, rq2=1.0e-6, r_eq_mm=20.0, p_h_gpa=1.5):
    return ContactCase(p_h_gpa * 1e9, r_eq_mm * 1e-3, 5.0, sr, 353.15, rq1, rq2)


def _grid(case, n=400):
    a = case.half_width
    return np.linspace(-2.5 * a, 1.5 * a, n)


def test_surfaces_move_with_their_own_velocities():
    """Paper Eq. 3: R_i(x, t) = R_i(x − u_i t, 0): shifting x by u_i t reproduces the initial profile."""
    case = _case()
    x = _grid(case)
    t_end = 2 * (x[-1] - x[0]) / case.u_r
    pair = rg.plan_surfaces(case, x, t_end, BASELINE)
    t = 0.37 * t_end
    r1, r2 = pair.at(t)
    r1_0 = pair.profile.sample(x - pair.offset1 - case.u1 * t) * pair.scale1
    np.testing.assert_allclose(r1, r1_0, atol=1e-20)
    # the same material point: R1 at (x + u1 t, t) equals R1 at (x, 0), R2 at (x + u2 t, t) equals R2 at (x, 0)
    shifted1 = dataclasses.replace(pair, x=x + case.u1 * t).at(t)[0]
    np.testing.assert_allclose(shifted1, pair.at(0.0)[0], atol=1e-15)
    shifted2 = dataclasses.replace(pair, x=x + case.u2 * t).at(t)[1]
    np.testing.assert_allclose(shifted2, pair.at(0.0)[1], atol=1e-15)
    assert not np.allclose(r1, pair.at(0.0)[0])
    assert r1.shape == x.shape and r2.shape == x.shape


def test_surface_pair_scaling_and_vectorised_times():
    """Each surface is the baseline times Rq_i/Rq_0 (paper: scaled by a constant); t may be an array."""
    case = _case(rq1=0.2e-6, rq2=0.5e-6)
    x = _grid(case)
    t_end = (x[-1] - x[0]) / case.u_r
    times = np.linspace(0, t_end, 7)
    r1, r2 = rg.surface_pair(case, x, times, t_end, BASELINE)
    assert r1.shape == (7, x.size)
    pair = rg.plan_surfaces(case, x, t_end, BASELINE)
    for k, t in enumerate(times):
        a, b = pair.at(t)
        np.testing.assert_array_equal(a, r1[k])
        np.testing.assert_array_equal(b, r2[k])
    assert pair.scale1 * pair.profile.rq == pytest.approx(0.2e-6, rel=1e-12)
    assert pair.scale2 * pair.profile.rq == pytest.approx(0.5e-6, rel=1e-12)
    smooth = ContactCase(1e9, 0.02, 5.0, 0.5, 353.15)
    z1, z2 = rg.surface_pair(smooth, x, 0.0, t_end, BASELINE)
    assert not z1.any() and not z2.any()


@pytest.mark.parametrize("sr", [0.0, 1.0, 2.0])
def test_segments_are_disjoint_and_independent(sr):
    """The two surfaces read disjoint stretches separated by 10β, and their sampled heights are uncorrelated:
    the sample cross-correlation of the two surfaces over the run stays within 4 standard errors of 0
    (standard error of a correlation of N_eff = stretch/(2β) effectively independent pairs: 1/√N_eff)."""
    case = _case(sr=sr, r_eq_mm=40, p_h_gpa=2.0)
    x = _grid(case, 800)
    t_end = 3 * (x[-1] - x[0]) / case.u_r
    pair = rg.plan_surfaces(case, x, t_end, BASELINE)
    assert pair.independent
    (a1, b1), (a2, b2) = pair.stretches()
    assert a1 == pytest.approx(0.0, abs=1e-12)
    beta = pair.profile.correlation_length
    assert a2 - b1 == pytest.approx(rg.SEGMENT_GAP_CORRELATION_LENGTHS * beta, rel=1e-9)
    assert b2 <= pair.profile.length
    times = np.linspace(0, t_end, 60)
    r1, r2 = pair.at(times)
    corr = np.corrcoef(r1.ravel(), r2.ravel())[0, 1]
    n_eff = min(b1 - a1, b2 - a2) / (2 * beta)
    assert abs(corr) < 4 / math.sqrt(n_eff)


def test_too_long_run_is_flagged_not_hidden():
    """A run longer than the profile can serve with disjoint stretches is marked independent=False."""
    case = _case(r_eq_mm=80, p_h_gpa=2.5)
    x = _grid(case)
    span = x[-1] - x[0]
    assert rg.plan_surfaces(case, x, 3.5 * span / case.u_r, BASELINE).independent
    assert not rg.plan_surfaces(case, x, 5 * span / case.u_r, BASELINE).independent


def test_a_run_shorter_than_its_layout_is_checked_over_its_own_length():
    """disjoint_until checks the stretches read up to the given time, not the layout's end: a run laid out for
    more than the profile can serve still reads disjoint roughness while it is short enough."""
    case = _case(r_eq_mm=80, p_h_gpa=2.5)
    x = _grid(case)
    span = x[-1] - x[0]
    pair = rg.plan_surfaces(case, x, 5 * span / case.u_r, BASELINE)
    assert not pair.independent
    assert not pair.disjoint_until(5 * span / case.u_r)
    assert pair.disjoint_until(1 * span / case.u_r)


def test_the_long_baseline_is_the_baselines_process_over_more_samples():
    """long_baseline_profile(2^18): Rq 0.5 µm to the 1 pm rounding, zero mean, β within 3 Bartlett standard errors
    of 15 µm (0.12 µm over 262 mm), Gaussian heights (skewness, kurtosis as in test_gaussian_heights); another
    realisation, not the baseline repeated; lengths that are not a power of two above the baseline are refused."""
    long = rg.long_baseline_profile(2**18)
    base = rg.baseline_profile()
    assert long.z.size == 2**18 and long.spacing == rg.BASELINE_SPACING_M
    assert long.length == pytest.approx(2 * base.length, rel=1e-9)
    assert long.rq == pytest.approx(rg.BASELINE_RQ_M, rel=1e-6)
    assert abs(long.z.mean()) < 1e-15
    sigma = rg.correlation_length_standard_error(rg.BASELINE_CORRELATION_LENGTH_M, long.length)
    assert abs(long.correlation_length - rg.BASELINE_CORRELATION_LENGTH_M) < 3 * sigma
    n_eff = long.length / (2 * rg.BASELINE_CORRELATION_LENGTH_M)
    s = long.z.std()
    assert abs(np.mean(long.z**3) / s**3) < 4 * math.sqrt(6 / n_eff)
    assert abs(np.mean(long.z**4) / s**4 - 3) < 4 * math.sqrt(24 / n_eff)
    first_half = long.z[: base.z.size]
    assert abs(np.corrcoef(first_half, base.z)[0, 1]) < 4 / math.sqrt(base.length / (2 * rg.BASELINE_CORRELATION_LENGTH_M))
    for bad in (rg.BASELINE_POINTS, 3 * 2**16, 2**16):
        with pytest.raises(InputError, match="n_points"):
            rg.long_baseline_profile(bad)


def test_surface_pair_rejects_bad_grid():
    case = _case()
    with pytest.raises(InputError, match="x_m"):
        rg.plan_surfaces(case, np.array([0.0, np.nan]), 1e-3, BASELINE)
    with pytest.raises(InputError, match="t_end_s"):
        rg.plan_surfaces(case, np.linspace(0, 1e-3, 10), -1.0, BASELINE)
