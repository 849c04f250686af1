"""The roughness layouts of the deterministic validation set (validation/deterministic_validation.py): every run of a
case reads the two surfaces from disjoint stretches of its profile, so μ's standard error counts independent
roughness (docs/explanation/mixed-regime.md, "Standard error of the long run")."""


import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.roughness import BASELINE_POINTS, plan_surfaces
from ehl_dataset.solvers.deterministic import DeterministicOptions



@pytest.fixture(scope="module")
def validation(load_benchmark):
    return load_benchmark("deterministic_validation")


def _surfaces(validation, name):
    case = ContactCase.from_engineering(*validation.CASES[name])
    domain = DeterministicOptions().domain
    a = case.half_width
    x = np.array(domain) * a
    pass_time = (domain[1] - domain[0]) * a / case.u_r
    layout = validation.layout_passes(name)
    return plan_surfaces(case, x, layout * pass_time, validation.profile_for(name)), pass_time


def test_every_validation_run_reads_disjoint_roughness_up_to_its_cap(validation):
    """Up to the long run's cap (the longest any run of the case can last), surfaces 1 and 2 read disjoint stretches
    of the case's profile, so the runs never see the same roughness twice."""
    for name in validation.CASES:
        pair, pass_time = _surfaces(validation, name)
        cap = max(validation.long_max_passes(name), validation.MAX_PASSES)
        assert pair.disjoint_until(cap * pass_time), name


def test_the_long_layouts_fit_their_profiles(validation):
    """The cases given a long run (LONG_RUNS) are laid out within their profile: the whole layout is independent.
    G's 300 passes need more than the 131 mm baseline holds (1.63 of it) and read the 262 mm long profile (0.81)."""
    for name in validation.LONG_RUNS:
        pair, _ = _surfaces(validation, name)
        assert pair.independent, name
    for name in validation.PROFILE_POINTS:
        pair, _ = _surfaces(validation, name)
        assert pair.profile.z.size == validation.profile_points(name) > BASELINE_POINTS
        assert pair.required_length > pair.profile.length / 2
