"""The averaging windows of the deterministic validation set (validation/deterministic_sampling_plan.py,
validation/deterministic_validation.py ``WINDOWS``): the multilevel allocation is the least-cost one (Giles, Oper.
Res. 56 (2008) 607, Eq. 3.1–3.2), and every window asked for fits its run's cap and roughness layout."""

import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.roughness import plan_surfaces
from ehl_dataset.solvers.deterministic import DeterministicOptions


@pytest.fixture(scope="module")
def plan(load_benchmark):
    return load_benchmark("deterministic_sampling_plan")


def test_the_allocation_meets_the_variance_budget_at_the_cauchy_schwarz_bound(plan):
    """Σ V_l/N_l = ε² exactly, and the cost Σ N_l c_l equals (Σ √(V_l c_l))²/ε², the Cauchy–Schwarz lower bound of
    every allocation meeting the budget: random feasible allocations all cost more."""
    rng = np.random.default_rng(7)
    for _ in range(20):
        v = 10.0 ** rng.uniform(-8, -3, 4)
        c = 10.0 ** rng.uniform(0, 3.5, 4)
        eps = 10.0 ** rng.uniform(-4, -3)
        passes, cost = plan.optimal_passes(v, c, eps)
        assert np.sum(v / passes) == pytest.approx(eps**2, rel=1e-12)
        assert cost == pytest.approx(np.sum(np.sqrt(v * c)) ** 2 / eps**2, rel=1e-12)
        for _ in range(50):
            other = passes * 10.0 ** rng.uniform(-0.5, 0.5, 4)
            other *= np.sum(v / other) / eps**2  # rescaled onto the budget
            assert np.sum(other * c) >= cost * (1 - 1e-12)


def test_every_window_fits_its_runs_cap_and_layout(plan):
    """A window of WINDOWS plus the start-up fits within the run's pass cap (the long run's cap, a short run's
    cap and layout), and the surfaces read disjoint roughness over it; options_for hands the window to the solver."""
    validation = plan.validation
    defaults = DeterministicOptions()
    startup = defaults.ramp_passes + defaults.startup_passes
    for name, windows in validation.WINDOWS.items():
        middle = validation.spacings(name)[1]
        cap = validation.long_max_passes(name)
        for n, window in windows.items():
            long = n == middle
            options = validation.options_for(n, long, cap, validation.layout_passes(name), window)
            assert options.min_average_passes == window
            assert window + startup <= options.max_passes, (name, n)
            case = ContactCase.from_engineering(*validation.CASES[name])
            a = case.half_width
            x = np.array(defaults.domain) * a
            pass_time = (defaults.domain[1] - defaults.domain[0]) * a / case.u_r
            pair = plan_surfaces(case, x, validation.layout_passes(name) * pass_time, validation.profile_for(name))
            assert pair.disjoint_until((window + startup) * pass_time), (name, n)


def test_the_profile_capacity_matches_the_layout_rule(plan):
    """plan_surfaces needs (x_max − x_min) + |u_i|·t of profile per surface and a gap of 10 β between them (its
    docstring): with the domain 4a and u1 + u2 = 2u_r, a run of P passes (t = 4aP/u_r) needs 8a(1 + P) + 10β, so the
    131 mm baseline holds P = (L − 10β − 8a)/(8a) passes of case B (≈ 375)."""
    validation = plan.validation
    case = ContactCase.from_engineering(*validation.CASES["B"])
    profile = validation.profile_for("B")
    a = case.half_width
    expected = (profile.length - 10 * profile.correlation_length - 8 * a) / (8 * a)
    assert plan.profile_capacity_passes("B") == pytest.approx(expected, rel=1e-6)
