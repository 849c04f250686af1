"""The averaging window of transient rough runs: standard error of the time-averaged μ, and the window extension
until the level's standard-error target is met (ehl_dataset.solvers.transient, levels.mu_sem_target/max_passes)."""

from dataclasses import replace

import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.levels import LEVELS
from ehl_dataset.solvers.time_average import time_mean
from ehl_dataset.solvers.transient import TransientOptions

CASE = ContactCase.from_engineering(0.5, 5, 10, 0.7, 25, 0.7, 0.7)  # λ̄ ≈ 1.2: asperities pass and touch
SHORT = replace(LEVELS["fast"], name="short", n_passes=1.0, max_steps_rough=60)


def test_fixed_window_reports_its_standard_error():
    """mu_sem_target = 0: the window is the last half of the base run, as before; μ is its mean and mu_sem the
    autocorrelation-corrected standard error of that mean, between σ/√n (independent steps) and σ (one sample)."""
    res = solve_contact(CASE, "atf", replace(SHORT, mu_sem_target=0.0), Effects.full())
    assert res.converged, res.message
    assert res.extra["n_steps"] == res.extra["n_steps_planned"] == 60
    window = res.extra["mu_series"][res.extra["average_from_step"]:]
    assert window.size == 30
    assert res.mu == pytest.approx(window.mean(), rel=1e-12)
    assert res.mu_sem == pytest.approx(time_mean(window).standard_error, rel=1e-12)
    assert window.std() / np.sqrt(window.size) <= res.mu_sem <= window.std()


def test_unmet_target_extends_the_window_to_the_cap_and_says_so():
    """A target no run can meet (1e−6 relative) extends the run with the same time step to max_passes (here 2 × the
    base run) and the converged result says the target was missed; the averaging starts after the base run's
    start-up and runs to the end."""
    level = replace(SHORT, mu_sem_target=1e-6, max_passes=2.0)
    res = solve_contact(CASE, "atf", level, Effects.full())
    assert res.converged and ("above the target" in res.message or "shorter than" in res.message), res.message
    assert res.extra["n_steps"] == res.extra["n_steps_max"] == 120
    assert res.extra["average_from_step"] == 30
    assert res.extra["mu_sem_target_met"] is False
    assert res.extra["averaging_time_s"] == pytest.approx(90 * res.extra["dt_s"], rel=1e-9)


def test_met_target_stops_at_the_base_run():
    """A loose target (100 % of μ: the sample standard deviation of μ over the window is far below μ) is met at
    the end of the base run: no extension, and the message is the plain "converged"."""
    level = replace(SHORT, mu_sem_target=1.0, max_passes=4.0)
    res = solve_contact(CASE, "atf", level, Effects.full())
    assert res.converged and res.message == "converged", res.message
    assert res.extra["n_steps"] == 60 and res.extra["mu_sem_target_met"] is True
    # the roughness is laid out for the base run, so a run that could have been extended but was not is the
    # fixed-window run, bit for bit
    fixed = solve_contact(CASE, "atf", replace(SHORT, mu_sem_target=0.0), Effects.full())
    assert res.mu == fixed.mu and res.h_min == fixed.h_min


def test_fast_level_keeps_its_fixed_window_and_reports_the_error():
    """``fast`` has no standard-error target: its time steps are those of the fixed-window runs of solver version -5 (on which
    its 64-corner stability was measured), now with the standard error reported."""
    assert LEVELS["fast"].mu_sem_target == 0.0
    assert LEVELS["standard"].mu_sem_target > 0.0 and LEVELS["standard"].max_passes > LEVELS["standard"].n_passes


class _StepClock:
    """A wall clock that advances by 1 s per reading (the run reads it once at the start and once before every time
    step), so a budget is a step count, deterministically."""

    def __init__(self):
        self.calls = 0

    def __call__(self):
        self.calls += 1
        return float(self.calls)


def _counting_steps() -> TransientOptions:
    return TransientOptions(clock=_StepClock())


def test_a_budget_that_runs_out_during_the_extension_keeps_the_converged_base_run():
    """The base run (60 steps) is complete when the budget runs out while the window is being extended: the run
    is converged (its time steps all are), averaged from the base start-up on, and its message says that the
    wall-time limit stopped the extension. A budget that runs out before the base run ends is not converged."""
    level = replace(SHORT, mu_sem_target=1e-6, max_passes=2.0)
    res = solve_contact(CASE, "atf", level, Effects.full(), time_limit_s=62.5, transient_options=_counting_steps())
    assert res.converged, res.message
    assert res.extra["n_steps"] == 62 and res.extra["time_limited"] is True
    assert res.extra["average_from_step"] == 30
    assert "wall-time limit of 62.5 s stopped the extension" in res.message
    early = solve_contact(CASE, "atf", level, Effects.full(), time_limit_s=40.5,
                          transient_options=_counting_steps())
    assert not early.converged and "wall-time limit of 40.5 s reached after 40 of 60 time steps" in early.message
