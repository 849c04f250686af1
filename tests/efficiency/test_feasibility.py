"""Feasibility limits (efficiency.feasibility): named violations, vectorised screening, the paper's design space."""

import dataclasses
import math

import numpy as np
import pytest

from ehl_dataset.validation import InputError
from efficiency.design_io import load_study, paper_design
from efficiency.feasibility import (CRITERIA, FeasibilityLimits, check_design, count_feasible, feasibility_masks,
                                    paper_design_space)
from efficiency.geometry import GearPair

rad = math.radians


@pytest.fixture(scope="module")
def study():
    return load_study("paper2009")


@pytest.mark.parametrize("name", ["A", "B", "C", "D"])
def test_published_designs_are_feasible(study, name):
    """Designs A–D of Li & Kahraman 2009 Table 1 belong to the paper's feasible set, so they must pass every limit
    (Design A has ε_α = 0.96 < 1: the contact-ratio limit must be on the total contact ratio ε_γ)."""
    report = check_design(study.design(name), study.limits)
    assert report.feasible, str(report)
    if name == "A":
        assert study.design(name).contact_ratio < 1.0 < study.design(name).total_contact_ratio


def test_pointed_teeth_are_reported_by_name():
    """N = 20, Φ = 30°, Λ_wd = 3.376: addendum 1.563 m_n is above the pointed-tip radius of a 30° tooth."""
    report = check_design(paper_design(20, 30.0, 15.0, 3.376))
    assert "pointed_tooth" in report.violated
    v = next(v for v in report.violations if v.name == "pointed_tooth")
    assert v.value < 0 and v.limit == 0 and v.gear in (1, 2)
    assert "pointed_tooth (gear 1)" in str(report)


def test_thin_tip_is_reported_with_value_and_limit():
    """Tip thinner than 0.2 m_n but not pointed is reported as tip_thickness with the 0.2 m_n limit."""
    pair = paper_design(30, 27.5, 20.0, 2.722)
    s = float(pair.tip_normal_thicknesses[0])
    m = float(pair.normal_module)
    assert 0 < s < 0.2 * m
    v = next(v for v in check_design(pair).violations if v.name == "tip_thickness")
    assert v.value == pytest.approx(s) and v.limit == pytest.approx(0.2 * m)


def test_undercut_and_interference_are_reported():
    """N = 20, Φ = 15°, Λ_wd = 3.376: the rack's straight flank reaches 1.56 m_n below the pitch line, far below
    r sin² α_t (undercut); the mating tip then reaches below the form point (interference)."""
    report = check_design(paper_design(20, 15.0, 15.0, 3.376))
    assert {"undercut", "interference"} <= set(report.violated)


def test_interference_below_the_base_circle():
    """A 12-tooth pinion with a 60-tooth standard 20° wheel: the wheel's tip passes beyond T1 (contact_start < 0),
    the classic involute interference of small pinions."""
    pair = GearPair(12, 60, 2e-3, rad(20.0), 0.0, 0.02, thickness_allowance1=5e-5, thickness_allowance2=5e-5)
    assert pair.contact_start < 0
    v = next(v for v in check_design(pair).violations if v.name == "interference" and v.gear == 1)
    assert v.value == pytest.approx(pair.contact_start)


def test_negative_root_clearance_is_reported():
    """A rack with dedendum below the addendum (h_fP = 0.9 < h_aP = 1.0) gives c = −0.1 m_n (tip hits the root)."""
    pair = GearPair(30, 30, 2e-3, rad(20.0), 0.0, 0.02, dedendum_coefficient=0.9, root_fillet_coefficient=0.1,
                    thickness_allowance1=5e-5, thickness_allowance2=5e-5)
    clearance = [v for v in check_design(pair).violations if v.name == "root_clearance"]
    assert len(clearance) == 2
    assert clearance[0].value == pytest.approx(-0.1 * 2e-3, rel=1e-9)


def test_zero_backlash_is_reported():
    """Un-thinned teeth at the zero-backlash centre distance have j = 0 < 0.04 mm."""
    report = check_design(GearPair(30, 30, 2e-3, rad(20.0), 0.0, 0.02))
    assert report.violated == ("backlash",)
    assert abs(report.violations[0].value) < 1e-12
    assert report.violations[0].as_dict()["limit_m"] == pytest.approx(0.04e-3)


def test_vectorised_masks_agree_with_the_scalar_check(study):
    """feasibility_masks on the whole space equals check_design design by design (a random sample of 150)."""
    space = study.space
    masks = feasibility_masks(space.pairs(), study.limits)
    phi, psi, n, wd = space.grid()
    rng = np.random.default_rng(7)
    for flat in rng.choice(phi.size, size=150, replace=False):
        idx = np.unravel_index(flat, phi.shape)
        one = paper_design(int(n[idx]), math.degrees(phi[idx]), math.degrees(psi[idx]), float(wd[idx]),
                           root_fillet_coefficient=space.root_fillet_coefficient)
        report = check_design(one, study.limits)
        assert masks["feasible"][idx] == report.feasible
        for name in CRITERIA:
            # a pointed tooth is reported once (pointed_tooth) but fails the tip-thickness mask as well
            failed = name in report.violated or (name == "tip_thickness" and "pointed_tooth" in report.violated)
            assert masks[name][idx] == (not failed), name


def test_paper_space_size_and_backlash_sensitivity(study):
    """7 × 16 × 34 × 8 = 30,464 combinations. At the standard centre distance backlash exists only through tooth
    thinning: without it no design reaches 0.04 mm; thinning both gears by A_sn gives j_bn = 2 A_sn cos α_n, so
    A_sn = 0.0231 mm (≥ 0.04/(2 cos 30°)) passes every design; the count then falls slowly as the tips thin."""
    space = study.space
    assert space.size == 30464
    zero = count_feasible(dataclasses.replace(space, backlash_policy="constant", backlash_policy_value=0.0))
    assert zero["total"] == 30464 and zero["backlash"] == 0 and zero["feasible"] == 0
    thin = count_feasible(dataclasses.replace(space, backlash_policy="constant", backlash_policy_value=0.0232e-3))
    thick = count_feasible(dataclasses.replace(space, backlash_policy="constant", backlash_policy_value=0.1e-3))
    assert thin["backlash"] == thick["backlash"] == 30464
    assert thin["feasible"] >= thick["feasible"] > 0
    # without the backlash limit the count is bounded by the geometric criteria alone
    geometric = feasibility_masks(dataclasses.replace(space, backlash_policy="constant",
                                                      backlash_policy_value=0.0).pairs())
    only_geometry = np.ones(geometric["feasible"].shape, bool)
    for name in CRITERIA:
        if name != "backlash":
            only_geometry &= geometric[name]
    assert thin["feasible"] <= int(only_geometry.sum())


def test_count_is_monotone_in_the_tip_thickness_limit(study):
    """A stricter tip-thickness limit can only remove designs."""
    counts = [count_feasible(study.space, dataclasses.replace(study.limits, min_tip_thickness=t))["feasible"]
              for t in (0.1, 0.2, 0.3, 0.4)]
    assert counts == sorted(counts, reverse=True) and counts[0] > counts[-1]


def test_root_clearance_of_the_paper_parametrisation_is_always_025_module():
    """ISO 53 rack: dedendum = addendum + 0.25 m_n at the standard centre distance → c = 0.25 m_n for every design,
    so the paper's 0.2 m_n clearance limit never binds in this parametrisation."""
    pairs = paper_design_space().pairs()
    assert np.allclose(pairs.root_clearances[0], 0.25 * pairs.normal_module, rtol=1e-9)


def test_bad_limits_are_rejected():
    with pytest.raises(InputError, match="backlash_kind"):
        FeasibilityLimits(backlash_kind="radial")
    with pytest.raises(InputError, match="min_tip_thickness"):
        FeasibilityLimits(min_tip_thickness=-1.0)
    with pytest.raises(InputError, match="backlash_policy"):
        paper_design_space(backlash_policy="guess").pairs()
