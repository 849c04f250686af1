"""Smooth steady EHL films against the classic line-contact formulas.

Like is compared with like (docs/explanation/ehl-model.md, "Validation"): Moes and Dowson–Toyoda are fits to incompressible Newtonian Barus
solutions → incompressible Barus fluid; Dowson–Higginson's minimum film comes from compressible Barus solutions →
Barus with Dowson–Higginson density; Pan–Hamrock fitted compressible Roelands solutions → Roelands fluid with DH
density. Seven points span p_h 0.3–2.5 GPa, r_eq 5–80 mm, u_r 1–20 m/s (Moes M = 11…730, L = 4.6…20).

Tolerances. The discretisation error at the standard level is below 1 % (grid study in test_solver_numerics.py:
second-order convergence, finest differences 0.1–0.3 %), so the deviations below are those of the formulas, which
are curve fits: on these very points Moes and Dowson–Toyoda differ from each other by up to 12 %, Dowson–Higginson
and Pan–Hamrock by up to 11 %. Bounds: Moes ±5 %; Dowson–Toyoda within its disagreement with Moes + 5 %;
Dowson–Higginson ±8 %; Pan–Hamrock ±9 %. Measured (standard level): h_c/Moes 0.996–1.046, h_c/DT 0.883–1.081,
h_min/DH 0.959–1.072, h_min/PH 0.918–1.042 (largest deviations at the highest L ≈ 20, the edge of the fits).
"""

import pytest

from ehl_dataset.model import film_formulas as ff
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import solve_contact

POINTS = [(0.3, 80, 1), (0.5, 40, 2), (1.0, 20, 5), (1.5, 10, 10), (2.0, 5, 20), (2.5, 80, 1), (2.5, 40, 5)]
NEWTONIAN_SMOOTH = dict(roughness=False, transient=False, shear_thinning=False, mode="forced")


def _solve(lubricant_name, point, compressible=True):
    lub = load_lubricant(lubricant_name)
    case = ContactCase.from_engineering(*point, 0.0, 40.0)
    result = solve_contact(case, lub, "standard", Effects(compressibility=compressible, **NEWTONIAN_SMOOTH))
    state = lub.state(case.temperature)
    args = (state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq, case.load_per_length)
    assert result.converged, result.message
    assert abs(result.residuals["load"]) < 1e-4
    return result, args


@pytest.mark.parametrize("point", POINTS)
def test_central_film_incompressible_vs_moes_and_dowson_toyoda(point):
    """Moes (1992; Venner & Lubrecht 2000) ±5 %; Dowson & Toyoda (1979) within |Moes/DT − 1| + 5 %."""
    result, args = _solve("validation_barus_incompressible", point, compressible=False)
    moes = float(ff.moes_central_film(*args))
    dt = float(ff.dowson_toyoda_central_film(*args))
    assert result.h_central == pytest.approx(moes, rel=0.05)
    assert result.h_central == pytest.approx(dt, rel=abs(moes / dt - 1.0) + 0.05)


@pytest.mark.parametrize("point", POINTS)
def test_minimum_film_compressible_vs_dowson_higginson(point):
    """Dowson & Higginson (1977) H_min = 2.65 U^0.7 G^0.54 W^−0.13, compressible Barus fluid, ±8 %."""
    result, args = _solve("validation_barus", point)
    assert result.h_min == pytest.approx(float(ff.dowson_higginson_min_film(*args)), rel=0.08)


@pytest.mark.parametrize("point", POINTS)
def test_minimum_film_roelands_vs_pan_hamrock(point):
    """Pan & Hamrock (1989) H_min = 1.714 W^−0.128 U^0.694 G^0.568, compressible Roelands fluid, ±9 %."""
    result, args = _solve("validation_roelands_huang", point)
    assert result.h_min == pytest.approx(float(ff.pan_hamrock_min_film(*args)), rel=0.09)


def test_compressibility_thins_the_central_film():
    """Measured with an independent dense-Newton solver (docs/explanation/ehl-model.md): with DH density h_c lies 10–20 % below the incompressible film at
    M = 7–260 while h_min changes little. Checked at M = 26 and M = 231."""
    for point in [(1.0, 20, 5), (2.5, 40, 5)]:
        inc, _ = _solve("validation_barus_incompressible", point, compressible=False)
        com, _ = _solve("validation_barus", point)
        assert 0.80 <= com.h_central / inc.h_central <= 0.90
        assert 0.95 <= com.h_min / inc.h_min <= 1.0
