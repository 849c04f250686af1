"""Standard error of the time mean of an autocorrelated series (ehl_dataset.solvers.time_average)."""

import numpy as np
import pytest
from scipy.signal import lfilter

from ehl_dataset.solvers.time_average import time_mean


def _ar1(phi: float, n: int, seed: int) -> np.ndarray:
    """x_t = φ x_{t−1} + e_t with standard normal e."""
    return lfilter([1.0], [1.0, -phi], np.random.default_rng(seed).standard_normal(n))


@pytest.mark.parametrize("phi", [0.0, 0.5, 0.9])
def test_inefficiency_of_an_ar1_process(phi):
    """For AR(1), g = 1 + 2 Σ φ^k = (1 + φ)/(1 − φ) exactly (1, 3, 19). Sokal's windowed estimate on 2e5 samples
    has a relative standard deviation of about √(20 τ/n) ≈ 1–2 % and a truncation bias of φ^M: asserted 6 %."""
    result = time_mean(_ar1(phi, 200_000, seed=7))
    assert result.inefficiency == pytest.approx((1 + phi) / (1 - phi), rel=0.06)
    assert result.reliable


def test_standard_error_matches_the_spread_of_independent_means():
    """Coverage: over 300 independent AR(1) series (φ = 0.9, n = 3,000) the standard deviation of their means is
    the true standard error √(g/(n(1 − φ²))) = 0.1826; the mean estimated standard error agrees within 10 % (the
    windowed estimator is biased low by a few percent at n/g ≈ 160) and so does the observed spread (sampling
    error of a standard deviation from 300 values ≈ 4 %)."""
    means, errors = [], []
    for seed in range(300):
        result = time_mean(_ar1(0.9, 3000, seed))
        means.append(result.mean)
        errors.append(result.standard_error)
    exact = np.sqrt(19.0 / (3000 * (1 - 0.81)))
    assert np.std(means) == pytest.approx(exact, rel=0.10)
    assert np.mean(errors) == pytest.approx(exact, rel=0.10)


def test_naive_error_understates_a_correlated_mean():
    """σ/√n would claim a mean √g ≈ 4.4 times more precise than it is for φ = 0.9."""
    x = _ar1(0.9, 50_000, seed=3)
    result = time_mean(x)
    assert result.standard_error / (x.std() / np.sqrt(x.size)) == pytest.approx(np.sqrt(19.0), rel=0.1)


def test_short_window_is_not_reliable_but_its_std_bounds_the_error():
    """A window of 100 samples of a process with g = 199 (φ = 0.99) cannot show its own correlation: ``reliable``
    is False. The sample standard deviation is an upper bound of the standard error (g ≤ n)."""
    result = time_mean(_ar1(0.99, 100, seed=1))
    assert not result.reliable
    assert result.standard_error <= result.std
    assert result.within(result.std) and not result.within(0.5 * result.standard_error)


def test_constant_series_is_exact_and_bad_input_raises():
    result = time_mean(np.full(50, 0.03))
    assert result.mean == pytest.approx(0.03) and result.standard_error == 0.0 and result.within(0.0)
    for bad in ([1.0], [1.0, np.nan, 2.0], np.ones((3, 3))):
        with pytest.raises(ValueError, match="1-D series"):
            time_mean(bad)
