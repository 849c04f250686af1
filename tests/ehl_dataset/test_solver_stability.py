"""Stability over the paper's operating range (the factorial of docs/reference/dataset-format.md)."""

import itertools
import math

import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import solve_contact


@pytest.mark.slow
def test_all_paper_levels_converge_at_sr_1_fast():
    """All 5 × 5 × 6 × 4 = 600 combinations of the paper's p_h, r_eq, u_r and T levels at SR = 1 with the ATF
    (Moes M from 0.5 to 1,500) converge at the fast level with finite outputs, positive films, load balance
    within 1e−4 and 0 ≤ μ ≤ μ_d. (Measured: none fails, ~10 s in total, median 12 ms per case.)"""
    lub = load_lubricant("atf")
    mu_d = lub.mu_d
    failures = []
    for p_h, r_eq, u_r, t in itertools.product([0.5, 1.0, 1.5, 2.0, 2.5], [5, 10, 20, 40, 80],
                                               [1, 2, 5, 10, 15, 20], [25, 50, 75, 100]):
        res = solve_contact(ContactCase.from_engineering(p_h, r_eq, u_r, 1.0, t), lub, "fast",
                            Effects.smooth_steady())
        finite = all(math.isfinite(v) for v in (res.mu, res.h_min, res.h_central, res.p_max))
        if not (res.converged and finite and res.h_min > 0 and abs(res.residuals["load"]) < 1e-4
                and 0.0 <= res.mu <= mu_d):
            failures.append(((p_h, r_eq, u_r, t), res.message, res.mu))
    assert not failures, failures[:5]
