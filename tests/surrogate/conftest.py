"""Shared fixtures: one synthetic Eq. 9 table and its fit, reused by the surrogate tests (fitting takes ~1 s)."""

import warnings

import pytest

from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.materials import STEEL, reduced_modulus
from surrogate.fit import fit_surrogate
from surrogate.synthetic import SMALL_LEVELS, eq9_table, factorial_inputs, reference_coefficients

NOISE_SD = 0.05


@pytest.fixture(scope="session")
def atf():
    return load_lubricant("atf")


@pytest.fixture(scope="session")
def e_reduced():
    return reduced_modulus(STEEL, STEEL)


@pytest.fixture(scope="session")
def true_params(atf, e_reduced):
    return reference_coefficients(atf, e_reduced)


@pytest.fixture(scope="session")
def eq9_data(atf, e_reduced, true_params):
    return eq9_table(factorial_inputs(SMALL_LEVELS), true_params, atf, e_reduced, noise_sd=NOISE_SD, seed=1)


@pytest.fixture(scope="session")
def eq9_fit(eq9_data, atf, e_reduced):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fit_surrogate(eq9_data, atf, e_reduced, allow_unstable=True, blend_half_width=0.1)


@pytest.fixture(scope="session")
def coefficient_file(eq9_fit, tmp_path_factory):
    from surrogate.coefficients import write_coefficients

    return write_coefficients(eq9_fit, tmp_path_factory.mktemp("coef") / "eq9.json", source={"path": "synthetic"})
