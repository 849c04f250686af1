"""Elastic materials of the contacting bodies."""

from __future__ import annotations

from dataclasses import dataclass

from ..validation import check_range


@dataclass(frozen=True)
class Material:
    """Isotropic elastic solid.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E [Pa].
    poisson_ratio : float
        Poisson's ratio ν [-].
    """

    youngs_modulus: float = 206e9
    poisson_ratio: float = 0.3

    def __post_init__(self):
        check_range("youngs_modulus", self.youngs_modulus, 0.0, 2e12, low_inclusive=False, unit="Pa")
        check_range("poisson_ratio", self.poisson_ratio, 0.0, 0.5, high_inclusive=False)


STEEL = Material(206e9, 0.3)
"""Gear steel, E = 206 GPa, ν = 0.3 (ISO 6336 value)."""


def reduced_modulus(material1: Material, material2: Material) -> float:
    """Plane-strain reduced modulus E' = 2 / ((1 − ν1²)/E1 + (1 − ν2²)/E2) (paper, after Eq. 4).

    Parameters
    ----------
    material1 : Material
        Material of surface 1 [-].
    material2 : Material
        Material of surface 2 [-].

    Returns
    -------
    float
        E' [Pa].
    """
    compliance = (1 - material1.poisson_ratio**2) / material1.youngs_modulus
    compliance += (1 - material2.poisson_ratio**2) / material2.youngs_modulus
    return 2.0 / compliance
