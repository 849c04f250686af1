"""Time averages of a stationary but autocorrelated series and their standard error (μ of transient rough runs).

The friction coefficient of a rough line contact fluctuates as asperities pass through the contact: successive
time steps are strongly correlated (an asperity takes ~2a/u_r to cross), so σ/√n badly understates the
uncertainty of the time mean. With the autocovariance γ_k and autocorrelation ρ_k = γ_k/γ_0 of n samples, the
variance of the mean is

    Var(x̄) ≈ γ_0 g / n,      g = 1 + 2 Σ_{k≥1} ρ_k     (the statistical inefficiency; n/g effective samples),

taken ≥ 1 (a short window can sum its ρ_k below zero; the mean is never claimed more precise than for
independent samples),

and g is estimated with Sokal's automatic window: the sum runs to the smallest lag M with M ≥ c·g(M), c = 5
(A. Sokal, "Monte Carlo methods in statistical mechanics: foundations and new algorithms", 1997, §3; the
estimate needs n ≫ g; ``reliable`` reports n ≥ 20 g, :data:`RELIABLE_LENGTH`). For an AR(1) process
x_t = φ x_{t−1} + e_t, g = (1 + φ)/(1 − φ) exactly — the check in the tests.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

SOKAL_WINDOW = 5.0
"""c of Sokal's automatic window (M ≥ c·g(M))."""
RELIABLE_LENGTH = 20.0
"""A series of at least this many statistical inefficiencies g counts as long enough for its standard error (a
shorter one cannot show correlations on its own time scale and underestimates g). The standard error is itself
uncertain by about √(10 g/n) relative (Sokal's variance of the windowed estimate with M ≈ 5τ): ≈ 70 % at n = 20 g,
45 % at n = 50 g (Sokal's recommended minimum)."""


@dataclass(frozen=True)
class TimeMean:
    """Mean of a series, its standard error (same unit as the series), the statistical inefficiency ``g``
    [samples per independent sample], the effective sample count n/g and whether n ≥ RELIABLE_LENGTH·g
    (``reliable``); ``std`` the standard deviation of the samples, an upper bound of the standard error whatever
    the correlation (g ≤ n)."""

    mean: float
    standard_error: float
    inefficiency: float
    effective_samples: float
    reliable: bool
    std: float

    def within(self, tolerance: float) -> bool:
        """True when the mean is known to ``tolerance`` (same unit): a reliable standard error below it, or a
        sample standard deviation below it (which bounds the standard error without any estimate of g)."""
        return (self.reliable and self.standard_error <= tolerance) or self.std <= tolerance


def time_mean(series) -> TimeMean:
    """Mean and standard error of an autocorrelated series (module docstring). Needs at least 2 finite samples;
    a constant series has standard error 0 and g = 1."""
    x = np.asarray(series, dtype=float)
    if x.ndim != 1 or x.size < 2 or not np.all(np.isfinite(x)):
        raise ValueError("time_mean needs a 1-D series of at least 2 finite values")
    n = x.size
    mean = float(x.mean())
    var = float(x.var())
    if var <= 1e-30 * max(mean * mean, 1e-300):
        return TimeMean(mean, 0.0, 1.0, float(n), True, math.sqrt(max(var, 0.0)))
    from statsmodels.tsa.stattools import acf  # statsmodels loads pandas: only where a time mean is taken

    rho = acf(x, nlags=n - 1, fft=True)
    g = 1.0
    for lag in range(1, n):
        g += 2.0 * rho[lag]
        if lag >= SOKAL_WINDOW * g:
            break
    g = max(g, 1.0)  # never more precise than independent samples (short windows can sum ρ_k below 0)
    sem = float(np.sqrt(var * g / n))
    return TimeMean(mean, sem, float(g), float(n / g), bool(n >= RELIABLE_LENGTH * g), math.sqrt(var))
