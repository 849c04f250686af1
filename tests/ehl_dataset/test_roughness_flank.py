"""The flank-like profile (self-affine between a roll-off and a short cut-off), the registry of named profiles, the
PSD-slope estimator, the Johnson S_U height option, and the grid rule that resolves a profile's resolution length."""

import math

import numpy as np
import pytest
from scipy import stats

from ehl_dataset.data_files import data_path
from ehl_dataset.model import roughness as rg
from ehl_dataset.solvers.deterministic import BOUNDARY_FILM_M, asperity_radius, deterministic_options, grid_spacing
from ehl_dataset.validation import InputError


def test_shipped_flank_is_regenerated_bit_for_bit():
    """data/roughness/flank_ground.txt is exactly what generate_flank() + profile_text() produce (README claim)."""
    shipped = data_path("roughness", rg.FLANK_FILE).read_bytes()
    assert rg.flank_text().encode("ascii") == shipped


@pytest.mark.parametrize("name", sorted(rg.PROFILES))
def test_registry_hashes_match_the_shipped_files(name):
    """Every registered name points at a shipped file whose sha256 is the registered one; the profile carries both."""
    entry = rg.PROFILES[name]
    assert rg.file_sha256(data_path("roughness", entry.file)) == entry.sha256
    profile = rg.named_profile(name)
    assert (profile.name, profile.sha256) == (name, entry.sha256)
    assert rg.profile_record(profile)["roughness_sha256"] == entry.sha256


def test_unknown_name_is_one_clear_error():
    with pytest.raises(InputError, match="roughness profile name"):
        rg.named_profile("shaved_gear")


def test_flank_is_the_registered_default_and_the_baseline_unchanged():
    """default_profile() is the registry's default entry, flank_ground; baseline_profile() keeps its source text and
    grid length (β)."""
    assert rg.default_profile().name == rg.DEFAULT_PROFILE == "flank_ground"
    base = rg.baseline_profile()
    assert base.name == rg.BASELINE_NAME == "baseline_synthetic"
    assert base.source == f"shipped baseline {rg.BASELINE_FILE}"
    assert base.grid_length_m is None
    assert base.resolution_length == base.correlation_length


def test_flank_rq_mean_and_length():
    """Rq = 0.5 µm to the file's 1 pm rounding (relative 1e-6), zero mean, the designed sampling."""
    flank = rg.named_profile("flank_ground")
    assert flank.z.size == rg.FLANK_POINTS
    assert flank.spacing == pytest.approx(rg.FLANK_SPACING_M, rel=1e-12)
    assert flank.rq == pytest.approx(rg.FLANK_RQ_M, rel=1e-6)
    assert abs(flank.z.mean()) < 1e-15
    assert flank.resolution_length == rg.FLANK_CUTOFF_WAVELENGTH_M


def test_flank_psd_slope_gives_back_hurst():
    """Log-periodogram regression between λ_s and λ_r: H within 3 of its standard errors (Geweke & Porter-Hudak:
    Var ln of a periodogram ordinate = π²/6) of the design H = 0.85; the standard error is ~0.008 here."""
    fit = rg.psd_slope(rg.named_profile("flank_ground"), rg.FLANK_CUTOFF_WAVELENGTH_M, rg.FLANK_ROLLOFF_WAVELENGTH_M)
    assert fit["hurst_standard_error"] < 0.02
    assert abs(fit["hurst"] - rg.FLANK_HURST) < 3 * fit["hurst_standard_error"]


def test_psd_slope_standard_error_matches_monte_carlo():
    """The stated standard error of the slope agrees with the spread over 100 seeds (relative error of a 100-sample
    std: 1/√200 = 7 %, so 4 of those = 28 %); the mean H is unbiased within 4 σ/√100."""
    fits = [rg.psd_slope(rg.generate_self_affine_profile(2**12, 1e-6, 0.7, 100e-6, 8e-6, 1e-6, seed), 8e-6, 100e-6)
            for seed in range(100)]
    h = np.array([f["hurst"] for f in fits])
    sigma = fits[0]["hurst_standard_error"]
    assert np.std(h, ddof=1) == pytest.approx(sigma, rel=0.28)
    assert abs(h.mean() - 0.7) < 4 * sigma / math.sqrt(h.size)


def test_flank_cutoffs_where_designed():
    """No power above k_s = 2π/λ_s (only the file's 1 pm rounding: < 1e-9 of the total); power in every ordinate
    just below it; a flat plateau (slope 0 within 3 standard errors) at wavelengths longer than λ_r; Parseval."""
    flank = rg.named_profile("flank_ground")
    k, c = rg.periodogram(flank)
    dk = k[0]
    assert np.sum(c) * dk / (2 * math.pi) == pytest.approx(flank.rq**2, rel=1e-12)
    k_s = 2 * math.pi / rg.FLANK_CUTOFF_WAVELENGTH_M
    above = k > k_s * (1 + 1e-9)
    assert c[above].sum() < 1e-9 * c.sum()
    just_below = (k > 0.9 * k_s) & (k <= k_s)
    assert np.all(c[just_below] > 1e-6 * c[just_below].mean())
    plateau = rg.psd_slope(flank, 1.25 * rg.FLANK_ROLLOFF_WAVELENGTH_M, flank.length)
    assert abs(plateau["slope"]) < 3 * plateau["slope_standard_error"]


def test_flank_heights_are_gaussian():
    """Skewness 0 and kurtosis 3 within 4 sampling standard errors, with the conservative N_eff = L/(2β)."""
    flank = rg.named_profile("flank_ground")
    z = flank.z / flank.z.std()
    n_eff = flank.length / (2 * flank.correlation_length)
    assert abs(np.mean(z**3)) < 4 * math.sqrt(6 / n_eff)
    assert abs(np.mean(z**4) - 3) < 4 * math.sqrt(24 / n_eff)


@pytest.mark.parametrize("skewness, kurtosis", [(-0.5, 4.0), (0.3, 3.5), (-1.0, 6.0)])
def test_johnson_su_transform_gives_the_moments(skewness, kurtosis):
    """The transform of exact normal quantiles (midpoint rule over 1e6 points: the tails beyond ±4.9 σ are left
    out, which lowers a kurtosis of 6 by 0.012) has the requested skewness and kurtosis."""
    n = 10**6
    g = stats.norm.ppf((np.arange(n) + 0.5) / n)
    y = rg.johnson_su_heights(g, skewness, kurtosis)
    y = (y - y.mean()) / y.std()
    assert np.mean(y**3) == pytest.approx(skewness, abs=2e-3)
    assert np.mean(y**4) == pytest.approx(kurtosis, abs=0.02)
    assert np.all(np.diff(y) > 0)  # monotone: the order of heights is kept


def test_johnson_su_outside_its_region_is_an_error():
    """Kurtosis ≤ 3 + 1.5 Rsk² is outside the S_U region: one InputError naming the parameter."""
    with pytest.raises(InputError, match="kurtosis"):
        rg.johnson_su_heights(np.random.RandomState(0).standard_normal(64), 0.0, 2.5)


def test_grid_rule_gaussian_profile_exactly_as_before():
    """For the Gaussian-ACF baseline the grid spacing is min(β/points_per_beta, ℓ/points_per_ell, inlet term)
    bit for bit (the rule before the resolution length existed), at every level."""
    base = rg.baseline_profile()
    for level in ("fast", "standard", "reference"):
        options = deterministic_options(level)
        for rq in (0.1e-6, 0.5e-6, 1.0e-6):
            ell = math.sqrt(2 * asperity_radius(base, rq, rq) * BOUNDARY_FILM_M)
            expected = min(base.correlation_length / options.points_per_beta, ell / options.points_per_ell,
                           options.inlet_resolution * 3e-5)
            dx, rule = grid_spacing(base, rq, rq, BOUNDARY_FILM_M, options, 3e-5)
            assert dx == expected
            assert rule["grid_length_m"] == rule["beta_m"] == base.correlation_length


def test_grid_rule_resolves_the_flank_cutoff():
    """For the flank-like profile the roughness term is λ_s/points_per_beta (not β/points_per_beta, 4× coarser)."""
    flank = rg.named_profile("flank_ground")
    options = deterministic_options("fast", points_per_ell=1e-3)  # the micro-EHL term out of the way
    dx, rule = grid_spacing(flank, 0.2e-6, 0.2e-6, BOUNDARY_FILM_M, options)
    assert dx == rg.FLANK_CUTOFF_WAVELENGTH_M / options.points_per_beta
    assert rule["beta_m"] > 3 * rule["grid_length_m"]
