"""A pair given by its manufacturing data, and feasibility limits that belong to the
paper's study only.

Reference: the Ohio State unity-ratio spur pair of Petry-Johnson, Kahraman, Anderson & Chase, J. Mech. Des. 130
(2008) 062601 (its gear table): z = 40/40, pitch diameter 92.74 mm
(m = 2.3185 mm; "2.32" printed), α = 28°, base diameter 81.89 mm, outside diameter 95.95 mm, root diameter
85.90 mm, start of active profile 87.73 mm, circular tooth thickness 2.925 mm, fillet radius 0.83 mm, face width
26.7 mm, centre distance 91.5 mm.
"""

import json
import math
import subprocess
import sys

import pytest

from ehl_dataset.validation import InputError
from efficiency.feasibility import FeasibilityLimits, check_design
from efficiency.geometry import GearPair

DEG = math.pi / 180


def osu_pair(**overrides):
    kwargs = dict(z1=40, z2=40, normal_module=92.74e-3 / 40, normal_pressure_angle=28 * DEG, helix_angle=0.0,
                  face_width=26.7e-3, center_distance=91.5e-3, root_fillet_coefficient=0.83 / 2.3185,
                  tip_diameters=(95.95e-3, 95.95e-3), root_diameters_given=(85.90e-3, 85.90e-3),
                  normal_thicknesses_given=(2.925e-3, 2.925e-3))
    kwargs.update(overrides)
    return GearPair(**kwargs)


def test_osu_pair_from_manufacturing_data_reproduces_the_published_diameters():
    pair = osu_pair()
    assert 2 * pair.base_radii[0] == pytest.approx(81.89e-3, abs=0.01e-3)
    assert pair.root_diameters[0] == pytest.approx(85.90e-3, rel=1e-12)
    assert pair.tip_diameters_m[0] == pytest.approx(95.95e-3, rel=1e-12)
    assert pair.normal_thicknesses[0] == pytest.approx(2.925e-3, rel=1e-12)
    # start of active profile: published 87.73 mm (the mate's tip circle on the line of action)
    assert 2 * pair.sap_radii[0] == pytest.approx(87.73e-3, abs=0.1e-3)
    assert check_design(pair, FeasibilityLimits.physical()).feasible


def test_thickness_given_sets_the_allowance():
    pair = osu_pair()
    nominal = pair.normal_module * math.pi / 2
    assert pair.thickness_allowance1 == pytest.approx(nominal - 2.925e-3, rel=1e-12)


def test_given_root_moves_the_form_point_below_the_active_profile():
    """The basic-rack dedendum 1.25 m_n would put the form circle above the SAP (interference); the real root
    (dedendum 1.47 m_n) is cut deeper and the involute reaches below the SAP."""
    assert osu_pair().form_radii[0] < osu_pair().sap_radii[0]
    basic = osu_pair(root_diameters_given=None)
    assert basic.form_radii[0] > basic.sap_radii[0]


def test_fzg_pairs_are_feasible_outside_the_paper_study_but_not_with_its_limits():
    """FZG H501 at a = 91.5 mm has zero backlash (the printed shifts give −0.2 µm): a real test pair, so the
    physical limits accept it; the paper study's 0.04 mm minimum backlash would not."""
    pair = GearPair(20, 30, 3.5e-3, 20 * DEG, 15 * DEG, 23e-3, 0.1809, 0.0891, center_distance=0.0915)
    assert check_design(pair, FeasibilityLimits.physical()).feasible
    assert not check_design(pair, FeasibilityLimits()).feasible


def test_gear_geometry_cli_uses_physical_limits_for_a_general_pair():
    args = ["--teeth1", "16", "--teeth2", "24", "--module-mm", "4.5", "--pressure-angle-deg", "20",
            "--helix-angle-deg", "0", "--face-width-mm", "14", "--shift1", "0.1817", "--shift2", "0.1715",
            "--center-distance-mm", "91.5", "--json"]
    out = subprocess.run([sys.executable, "-m", "workflows.cli", "gear", "geometry", *args], capture_output=True,
                         text=True, timeout=120)
    payload = json.loads(out.stdout)
    assert payload["feasibility_limits"] == "physical" and payload["feasible"] is True
    out = subprocess.run([sys.executable, "-m", "workflows.cli", "gear", "geometry", *args, "--study-limits"],
                         capture_output=True, text=True, timeout=120)
    assert json.loads(out.stdout)["feasible"] is False


def test_bad_manufacturing_data_names_the_parameter():
    with pytest.raises(InputError, match="root_diameter1"):
        osu_pair(root_diameters_given=(-1.0, 85.9e-3))
    with pytest.raises(InputError, match="normal_thickness2"):
        osu_pair(normal_thicknesses_given=(2.9e-3, 0.0))
