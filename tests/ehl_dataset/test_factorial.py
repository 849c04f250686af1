"""Factorial plans: the paper's 42,000-point plan, expansion order, hashing and validation of plan files."""

import hashlib
import itertools
import math

import numpy as np
import pytest

from ehl_dataset.dataset.factorial import (AXIS_KEYS, POINT_DTYPE, factorial_from_dict, load_factorial)
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.film_formulas import dowson_higginson_min_film
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.validation import InputError

# Li & Kahraman 2009, Sect. 2.1, with roughness as (Rq1, Rq2) pairs (docs/reference/dataset-format.md).
PAPER_AXES = {
    "p_h_gpa": [0.5, 1.0, 1.5, 2.0, 2.5],
    "r_eq_mm": [5, 10, 20, 40, 80],
    "u_r_m_s": [1, 2, 5, 10, 15, 20],
    "sr": [0, 0.05, 0.1, 0.2, 0.4, 0.7, 1.0],
    "temp_c": [25, 50, 75, 100],
    "roughness_um": [(0.05, 0.05), (0.1, 0.1), (0.2, 0.2), (0.3, 0.3), (0.4, 0.4), (0.5, 0.5), (0.7, 0.7),
                     (1.0, 1.0), (0.2, 0.5), (0.4, 1.0)],
}


def small_plan(**changes):
    data = {"name": "t", "level": "fast", "axes": {"p_h_gpa": [0.5, 1.0], "r_eq_mm": [10.0], "u_r_m_s": [1.0, 5.0],
                                                  "sr": [0.1], "temp_c": [50.0, 100.0],
                                                  "roughness_um": [[0.1, 0.1], [0.2, 0.5]]}}
    for key, value in changes.items():
        if key in AXIS_KEYS:
            data["axes"][key] = value
        else:
            data[key] = value
    return data


def test_paper_plan_is_the_published_5x5x6x7x4x10_factorial():
    """The shipped paper2009.toml lists exactly the levels of Li & Kahraman 2009 (docs/reference/dataset-format.md): 42,000 points."""
    plan = load_factorial("paper2009")
    assert plan.shape == (5, 5, 6, 7, 4, 10)
    assert plan.size == 42_000
    for key, levels in PAPER_AXES.items():
        assert [tuple(v) if isinstance(v, tuple) else v for v in getattr(plan, key)] == \
            [tuple(v) if isinstance(v, tuple) else float(v) for v in levels]
    points = plan.points()
    assert points.dtype == POINT_DTYPE and points.shape == (42_000,)
    assert np.unique(points).size == 42_000  # every point distinct


def test_expansion_order_and_si_units_match_an_independent_product():
    """Row i is the i-th element of the C-order product of the axes (first axis slowest), converted to SI."""
    plan = load_factorial("paper2009")
    expected = np.array(
        [(p * 1e9, r * 1e-3, u, s, t + 273.15, q1 * 1e-6, q2 * 1e-6)
         for p, r, u, s, t, (q1, q2) in itertools.product(*PAPER_AXES.values())], dtype=POINT_DTYPE)
    points = plan.points()
    for name in POINT_DTYPE.names:
        np.testing.assert_array_equal(points[name], expected[name])
    # and the stable hash is the SHA-256 of exactly these bytes (the identity a resumed store checks)
    assert plan.points_hash() == hashlib.sha256(expected.tobytes()).hexdigest()


def test_hash_changes_with_any_level_and_with_order():
    base = factorial_from_dict(small_plan())
    assert base.points_hash() == factorial_from_dict(small_plan(name="renamed")).points_hash()
    assert base.points_hash() != factorial_from_dict(small_plan(temp_c=[50.0, 100.5])).points_hash()
    assert base.points_hash() != factorial_from_dict(small_plan(u_r_m_s=[5.0, 1.0])).points_hash()


def test_unequal_roughness_pairs_break_the_collinearity_of_sc_and_seq():
    """With equal pairs S_eq = S_c/(2√2) exactly (rank 2 with the intercept); the unequal pairs make it rank 3."""
    def rank(pairs):
        q = np.asarray(pairs)
        s_c = np.hypot(q[:, 0], q[:, 1])
        s_eq = q[:, 0] * q[:, 1] / (q[:, 0] + q[:, 1])
        return np.linalg.matrix_rank(np.column_stack([np.ones_like(s_c), s_c, s_eq]), tol=1e-9)

    pairs = load_factorial("paper2009").roughness_um
    assert rank([p for p in pairs if p[0] == p[1]]) == 2
    assert rank(pairs) == 3


def test_quick_plan_is_a_subset_spanning_both_regression_branches():
    """quick.toml: a few hundred points on paper levels, with Dowson–Higginson λ̄ both below and above 1
    (paper Eq. 9a/9b branches), estimated with the Dowson–Higginson formula the paper uses for λ̄."""
    quick, paper = load_factorial("quick"), load_factorial("paper2009")
    assert 100 <= quick.size <= 500
    for key in AXIS_KEYS:
        assert set(getattr(quick, key)) <= set(getattr(paper, key)), key
    lub = load_lubricant(quick.lubricant)
    lambdas = []
    for p in quick.points():
        case = ContactCase(*[float(v) for v in p])
        state = lub.state(case.temperature)
        h = dowson_higginson_min_film(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                      case.load_per_length)
        lambdas.append(h / case.s_c)
    lambdas = np.asarray(lambdas)
    assert (lambdas < 1).sum() >= 30 and (lambdas > 1).sum() >= 30


@pytest.mark.parametrize("changes, field", [
    ({"p_h_gpa": [-1.0]}, "axes.p_h_gpa[0]"),
    ({"p_h_gpa": []}, "axes.p_h_gpa"),
    ({"sr": [0.1, 0.1]}, "axes.sr"),
    ({"temp_c": [float("nan")]}, "axes.temp_c[0]"),
    ({"u_r_m_s": [True]}, "axes.u_r_m_s[0]"),
    ({"roughness_um": [[0.1]]}, "axes.roughness_um[0]"),
    ({"roughness_um": [[0.1, -0.2]]}, "axes.roughness_um[0][1]"),
    ({"effects": "sometimes"}, "effects"),
    ({"name": ""}, "name"),
    ({"lubricant": 3}, "lubricant"),
    ({"temperature": 3}, "factorial key 'temperature'"),
])
def test_bad_plans_name_the_field(changes, field):
    with pytest.raises(InputError) as info:
        factorial_from_dict(small_plan(**changes))
    assert info.value.parameter == field


def test_missing_and_misspelt_axes_are_rejected():
    data = small_plan()
    del data["axes"]["sr"]
    with pytest.raises(InputError, match="axes.sr"):
        factorial_from_dict(data)
    data = small_plan()
    data["axes"]["slide_roll"] = [0.1]
    with pytest.raises(InputError, match="axes.slide_roll"):
        factorial_from_dict(data)


def test_files_load_by_path_and_bad_toml_is_a_clear_error(tmp_path):
    good = tmp_path / "mine.toml"
    good.write_text('name = "mine"\n[axes]\np_h_gpa = [1.0]\nr_eq_mm = [10]\nu_r_m_s = [5]\nsr = [0.2]\n'
                    'temp_c = [80]\nroughness_um = [[0.3, 0.3]]\n')
    plan = load_factorial(good)
    assert plan.size == 1 and plan.level == "standard" and plan.effects == "auto"
    point = plan.points()[0]
    assert point["p_h"] == 1e9 and point["temperature"] == pytest.approx(353.15) and math.isclose(point["rq2"], 3e-7)
    bad = tmp_path / "bad.toml"
    bad.write_text("name = \n")
    with pytest.raises(InputError, match="factorial file"):
        load_factorial(bad)
    with pytest.raises(InputError, match="factorial"):
        load_factorial("no_such_plan")


def test_to_dict_round_trips_and_checks_its_hash():
    plan = load_factorial("quick")
    data = plan.to_dict()
    again = factorial_from_dict(data)
    assert again == plan and again.points_hash() == data["points_sha256"]
    data["axes"]["sr"] = [0.05, 0.2, 0.75]
    with pytest.raises(InputError, match="points_sha256"):
        factorial_from_dict(data)
