"""The line-contact case: operating conditions of one EHL contact and its Hertzian derived quantities (SI)."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from ..validation import check_range
from .materials import STEEL, Material, reduced_modulus


@dataclass(frozen=True)
class ContactCase:
    """One line-contact operating condition (paper Sect. 2.1; docs/ehl_solver.md), all SI.

    Attributes
    ----------
    p_h : maximum Hertz pressure [Pa], > 0
    r_eq : equivalent radius of curvature r1 r2/(r1 + r2) [m], > 0
    u_r : rolling (entrainment) velocity (u1 + u2)/2 [m/s], > 0
    sr : slide-to-roll ratio (u1 − u2)/u_r [-], in [−2, 2]
    temperature : oil inlet temperature [K] (checked against the lubricant where it is used)
    rq1, rq2 : RMS roughness of surfaces 1 and 2 [m], ≥ 0
    material1, material2 : elastic materials (default steel, E = 206 GPa, ν = 0.3)
    """

    p_h: float
    r_eq: float
    u_r: float
    sr: float
    temperature: float
    rq1: float = 0.0
    rq2: float = 0.0
    material1: Material = STEEL
    material2: Material = STEEL

    def __post_init__(self):
        check_range("p_h", self.p_h, 0.0, 10e9, low_inclusive=False, unit="Pa")
        check_range("r_eq", self.r_eq, 0.0, 10.0, low_inclusive=False, unit="m")
        check_range("u_r", self.u_r, 0.0, 200.0, low_inclusive=False, unit="m/s")
        check_range("sr", self.sr, -2.0, 2.0)
        check_range("temperature", self.temperature, 0.0, 1000.0, low_inclusive=False, unit="K")
        check_range("rq1", self.rq1, 0.0, 1e-4, unit="m")
        check_range("rq2", self.rq2, 0.0, 1e-4, unit="m")

    @property
    def e_reduced(self) -> float:
        """Reduced modulus E' [Pa]."""
        return reduced_modulus(self.material1, self.material2)

    @property
    def load_per_length(self) -> float:
        """Load per unit length W' = 2π r_eq p_h²/E' [N/m] (Hertz line contact)."""
        return 2.0 * math.pi * self.r_eq * self.p_h**2 / self.e_reduced

    @property
    def half_width(self) -> float:
        """Hertz half width a = 4 r_eq p_h/E' [m]."""
        return 4.0 * self.r_eq * self.p_h / self.e_reduced

    @property
    def u1(self) -> float:
        """Surface velocity of body 1, u_r (1 + SR/2) [m/s]."""
        return self.u_r * (1.0 + 0.5 * self.sr)

    @property
    def u2(self) -> float:
        """Surface velocity of body 2, u_r (1 − SR/2) [m/s]."""
        return self.u_r * (1.0 - 0.5 * self.sr)

    @property
    def u_s(self) -> float:
        """Sliding velocity u1 − u2 = SR·u_r [m/s]."""
        return self.u_r * self.sr

    @property
    def s_c(self) -> float:
        """Composite RMS roughness S_c = √(Rq1² + Rq2²) [m]."""
        return math.hypot(self.rq1, self.rq2)

    @property
    def s_eq(self) -> float:
        """Equivalent roughness S_eq = Rq1 Rq2/(Rq1 + Rq2) [m] (0 if both surfaces are smooth)."""
        total = self.rq1 + self.rq2
        return self.rq1 * self.rq2 / total if total > 0 else 0.0

    def to_dict(self) -> dict:
        """Plain dictionary of the inputs (materials as nested dicts)."""
        return asdict(self)

    @classmethod
    def from_engineering(cls, p_h_gpa: float, r_eq_mm: float, u_r: float, sr: float, temp_c: float,
                         rq1_um: float = 0.0, rq2_um: float = 0.0, **kwargs) -> "ContactCase":
        """Build from engineering units (GPa, mm, m/s, -, °C, µm), as used at the CLI and in factorial files."""
        check_range("p_h_gpa", p_h_gpa, 0.0, 10.0, low_inclusive=False, unit="GPa")
        check_range("r_eq_mm", r_eq_mm, 0.0, 1e4, low_inclusive=False, unit="mm")
        check_range("temp_c", temp_c, -273.15, 726.0, low_inclusive=False, unit="C")
        check_range("rq1_um", rq1_um, 0.0, 100.0, unit="um")
        check_range("rq2_um", rq2_um, 0.0, 100.0, unit="um")
        return cls(p_h_gpa * 1e9, r_eq_mm * 1e-3, u_r, sr, temp_c + 273.15, rq1_um * 1e-6, rq2_um * 1e-6, **kwargs)
