"""Time-step control of the transient mixed solver: the adaptive sub-step start and the wall-time budget."""

import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers import transient
from ehl_dataset.solvers.transient import RELAX_AFTER, step_attempts, next_start
from ehl_dataset.validation import InputError

BASE = ((1, False), (2, False), (4, False), (1, True), (4, True), (16, True))


def test_a_run_that_never_retries_tries_the_original_sequence():
    """start = 1 is the sequence of solver version ehl-2026.11-4, so a run whose steps all converge at the first
    attempt is unchanged by the controller."""
    assert step_attempts(1) == BASE


@pytest.mark.parametrize("start", [1, 2, 4, 8, 16])
def test_a_raised_start_only_reorders_never_drops_an_attempt(start):
    """Newton's success is not monotone in the step size (measured: a hard 80 mm corner failed at 16 sub-steps
    and converged at 1 and 4 with Couette faces), so every attempt of the base sequence stays available."""
    attempts = step_attempts(start)
    assert attempts[0] == (start, False)
    assert set(BASE) <= set(attempts)
    assert len(attempts) == len(set(attempts))
    assert all(k <= transient.MAX_SUBSTEPS for k, _ in attempts)


def test_start_follows_the_unified_faces_and_relaxes_after_calm_steps():
    assert next_start(1, 4, False, False, 2) == (4, 0)     # unified faces needed 4 sub-steps: begin there
    assert next_start(4, 16, True, False, 0) == (4, 0)     # Couette fallback says nothing about the step size
    start, calm = 4, 0
    for _ in range(RELAX_AFTER - 1):
        start, calm = next_start(start, 4, False, True, calm)
        assert start == 4
    assert next_start(start, 4, False, True, calm) == (2, 0)
    assert next_start(1, 1, False, True, 7) == (1, 8)       # never below one sub-step


def test_time_limit_marks_the_result_not_converged():
    """A spent budget is a result marked not converged with the step reached, never a silent number."""
    case = ContactCase.from_engineering(1.0, 20, 5, 0.2, 90, 0.4, 0.4)
    res = solve_contact(case, "atf", "fast", Effects.full(), time_limit_s=1e-3)
    assert not res.converged
    assert "wall-time limit of 0.001 s" in res.message and "time steps" in res.message
    assert res.extra["time_limited"] is True and res.extra["n_steps"] == 0 and res.extra["n_steps_planned"] > 0


@pytest.mark.parametrize("bad", [0.0, -5.0, float("nan"), float("inf"), True, "10"])
def test_time_limit_must_be_positive_and_finite(bad):
    case = ContactCase.from_engineering(1.0, 20, 5, 0.2, 90, 0.4, 0.4)
    with pytest.raises(InputError, match="time_limit_s"):
        solve_contact(case, "atf", "fast", Effects.full(), time_limit_s=bad)


def test_message_says_when_the_fallback_or_careful_settings_were_needed():
    """A run solved partly with Couette-only contact faces is converged but with other contact-face physics on
    those steps: the message says how many (measured: 246 of 300 steps on 2.5 GPa / 80 mm / 1 m/s / SR 1 / 100 °C /
    Rq 1 µm)."""
    from ehl_dataset.solvers.transient import _message

    assert _message(True, "", 300, 0, 0) == "converged"
    assert _message(True, "", 300, 246, 5) == ("converged (246 of 300 steps with Couette-only contact faces, "
                                               "5 with careful Newton settings)")
    assert _message(False, "time step at t = 1e-3 s did not converge", 12, 3, 0).startswith("not converged: time step")
