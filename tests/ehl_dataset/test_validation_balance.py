"""Conservation over the deterministic validation set (data/reference/deterministic_validation.json, written by
``python validation/deterministic_validation.py --summarise`` from every run's per-step series; docs/explanation/mixed-regime.md,
"Mass balance"): what the recorded runs balanced, against the conservation laws and the solver's own stop rule."""

import json
from pathlib import Path

import pytest

from ehl_dataset.solvers.deterministic import (DeterministicOptions, ROUND_OFF_MARGIN, ROUND_OFF_STEP_MARGIN,
                                               FLOOR_STOP_SINCE, STRICT_ROUND_OFF_SINCE,
                                               model_version_key)

REFERENCE = Path(__file__).resolve().parents[2] / "data" / "reference" / "deterministic_validation.json"


@pytest.fixture(scope="module")
def cases():
    return [c for c in json.loads(REFERENCE.read_text())["cases"] if "mass_error_max" in c]


def test_every_validation_case_records_its_balance_at_every_spacing(cases):
    """Each of the 12 cases carries the balance of each spacing it was solved at (at least 12 cases)."""
    assert len(cases) >= 12
    for case in cases:
        assert set(case["mass_error_max"]) == set(case["wall_time_s"]), case["case"]
        assert all(case["steps"][k] > 0 for k in case["steps"]), case["case"]


def test_the_load_is_balanced_to_1e_10_at_every_step_of_every_validation_run(cases):
    """The conservation target for the load: ∫p dx = W' to ≤ 1e-10 (relative) at every step."""
    for case in cases:
        assert max(case["load_error_max"].values()) <= 1e-10, case["case"]


def test_no_validation_step_was_accepted_beyond_the_solvers_round_off_bound(cases):
    """The mass balance of a step exceeds the Newton tolerance only at a round-off stop, which accepts at most
    ROUND_OFF_STEP_MARGIN × the tolerance (the correction below ROUND_OFF_STEP p_h: 1e-12 until det-2026.11-14,
    1e-15 since det-2026.11-15). A larger error would be a step accepted unconverged. Where it exceeds the issue's
    1e-10 is reported, not asserted away (docs/validation/deterministic_validation.md counts the steps)."""
    bound = ROUND_OFF_STEP_MARGIN * DeterministicOptions().newton_tolerance
    for case in cases:
        for spacing, error in case["mass_error_max"].items():
            assert error <= bound, (case["case"], spacing, error)
        over = sum(case["mass_error_steps_over_target"].values())
        assert 0 <= over <= sum(case["steps"].values())


def test_runs_under_the_strict_round_off_stop_stay_within_its_stall_margin(cases):
    """Under det-2026.11-15 and -16 a step ends above the tolerance only at the round-off floor: stalled within
    ROUND_OFF_MARGIN (10×) the tolerance, or with a correction below 1e-15 p_h (a few units in the last place).
    Measured on the validation runs made under it (run_versions in the data): every step within the 10× margin; at
    the floor of double precision B at β/64 reaches 4.2e-10 on 12 of 9,051 steps and G's long run 8.3e-10 on 9 of
    263,900 (docs/explanation/mixed-regime.md, "Robustness" item 8, "Mass balance"). The runs made before it accepted up
    to 1000× (5.3e-8)."""
    bound = ROUND_OFF_MARGIN * DeterministicOptions().newton_tolerance
    checked = 0
    for case in cases:
        for spacing, version in case["run_versions"].items():
            # det-17 also stops at a measured floor above the margin (within ROUND_OFF_STEP_MARGIN: the test above)
            if (model_version_key(STRICT_ROUND_OFF_SINCE) <= model_version_key(version)
                    < model_version_key(FLOOR_STOP_SINCE)):
                assert case["mass_error_max"][spacing] <= bound, (case["case"], spacing)
                checked += 1
    assert checked >= 8
