"""Contact case: Hertz line-contact relations and input validation."""

import math

import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.materials import STEEL, reduced_modulus
from ehl_dataset.validation import InputError


def test_reduced_modulus_of_steel_pair():
    # E' = E/(1 − ν²) for identical materials
    assert reduced_modulus(STEEL, STEEL) == pytest.approx(206e9 / (1 - 0.09))


def test_hertz_line_contact_relations():
    """Hertz (Johnson, Contact Mechanics, Eq. 4.45): p_h = 2W'/(π a) and a² = 4 W' R/(π E'/2)... in E' form a² = 8W'R/(πE')."""
    case = ContactCase(1.2e9, 0.02, 5.0, 0.3, 353.15)
    w, a = case.load_per_length, case.half_width
    assert case.p_h == pytest.approx(2 * w / (math.pi * a))
    assert a**2 == pytest.approx(8 * w * case.r_eq / (math.pi * case.e_reduced))
    assert case.u1 - case.u2 == pytest.approx(case.u_s)
    assert (case.u1 + case.u2) / 2 == pytest.approx(case.u_r)


@pytest.mark.parametrize("field, value", [("p_h", -1.0), ("p_h", float("nan")), ("r_eq", 0.0), ("u_r", -2.0),
                                          ("sr", 3.0), ("rq1", -1e-7)])
def test_bad_inputs_name_the_parameter(field, value):
    kwargs = dict(p_h=1e9, r_eq=0.01, u_r=5.0, sr=0.2, temperature=353.15)
    kwargs[field] = value
    with pytest.raises(InputError, match=field):
        ContactCase(**kwargs)
