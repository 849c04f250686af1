"""The line-contact case: operating conditions of one EHL contact and its Hertzian derived quantities (SI)."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from ..validation import InputError, check_range
from .materials import STEEL, Material, reduced_modulus


@dataclass(frozen=True)
class Limit:
    """The accepted range of one input of a contact, in SI units, and how it reads in engineering units.

    Parameters
    ----------
    low, high : float
        Ends of the accepted range [SI unit of the input].
    low_inclusive, high_inclusive : bool
        Whether each end is accepted [-].
    unit : str
        SI unit of the input, as shown in an error [-].
    engineering : str
        Name of the input in engineering units (the command line's and the factorial files') [-].
    to_si, si_offset : float
        SI value = engineering value × ``to_si`` + ``si_offset`` [-].
    engineering_unit : str
        Engineering unit, as shown in an error [-].
    """

    low: float
    high: float
    low_inclusive: bool = True
    high_inclusive: bool = True
    unit: str = ""
    engineering: str = ""
    to_si: float = 1.0
    si_offset: float = 0.0
    engineering_unit: str = ""

    def to_si_value(self, value: float) -> float:
        """The SI value of an engineering ``value``."""
        return value * self.to_si + self.si_offset if self.si_offset else value * self.to_si

    def check(self, name: str, value: float) -> float:
        """``value`` [SI] as float, or :class:`InputError` naming ``name``, the value and the range."""
        return check_range(name, value, self.low, self.high, low_inclusive=self.low_inclusive,
                           high_inclusive=self.high_inclusive, unit=self.unit)

    def check_engineering(self, name: str, value: float) -> float:
        """An engineering ``value`` (e.g. in GPa) checked against the range, returned unchanged as float; outside,
        :class:`InputError` naming ``name``, the value and the range in engineering units."""
        try:
            self.check(name, self.to_si_value(float(value)))
        except (TypeError, ValueError) as err:
            accepted = "a finite number" if getattr(err, "accepted", "a finite number") == "a finite number" \
                else self.engineering_range()
            raise InputError(name, value, accepted) from None
        return float(value)

    def engineering_range(self) -> str:
        """The accepted range in engineering units, e.g. ``(0, 10] GPa``."""
        low, high = (round((v - self.si_offset) / self.to_si, 10) for v in (self.low, self.high))
        text = f"{'[' if self.low_inclusive else '('}{low:g}, {high:g}{']' if self.high_inclusive else ')'}"
        return f"{text} {self.engineering_unit}".rstrip()


CONTACT_LIMITS: dict[str, Limit] = {
    "p_h": Limit(0.0, 10e9, False, True, "Pa", "p_h_gpa", 1e9, 0.0, "GPa"),
    "r_eq": Limit(0.0, 10.0, False, True, "m", "r_eq_mm", 1e-3, 0.0, "mm"),
    "u_r": Limit(0.0, 200.0, False, True, "m/s", "u_r", 1.0, 0.0, "m/s"),
    "sr": Limit(-2.0, 2.0, True, True, "", "sr"),
    "temperature": Limit(0.0, 1000.0, False, True, "K", "temp_c", 1.0, 273.15, "C"),
    "rq1": Limit(0.0, 1e-4, True, True, "m", "rq1_um", 1e-6, 0.0, "um"),
    "rq2": Limit(0.0, 1e-4, True, True, "m", "rq2_um", 1e-6, 0.0, "um"),
}
"""The one table of the accepted ranges of a contact's inputs (SI; the engineering names and units the command line
and the factorial files use). :class:`ContactCase` checks every input against it once, when it is built; the
temperature is checked once more against the lubricant's data where the lubricant is resolved."""


@dataclass(frozen=True)
class ContactCase:
    """One line-contact operating condition (paper Sect. 2.1), all SI.

    Every input is checked once, when the case is built, against :data:`CONTACT_LIMITS`; the temperature is checked
    against the lubricant where it is used.

    Parameters
    ----------
    p_h : float
        Maximum Hertz pressure, > 0 [Pa].
    r_eq : float
        Equivalent radius of curvature r1 r2/(r1 + r2), > 0 [m].
    u_r : float
        Rolling (entrainment) velocity (u1 + u2)/2, > 0 [m/s].
    sr : float
        Slide-to-roll ratio (u1 − u2)/u_r, between −2 and 2 [-].
    temperature : float
        Oil inlet temperature [K].
    rq1 : float
        RMS roughness of surface 1, ≥ 0 (0: smooth) [m].
    rq2 : float
        RMS roughness of surface 2, ≥ 0 [m].
    material1 : Material
        Elastic material of surface 1 (default steel, E = 206 GPa, ν = 0.3) [-].
    material2 : Material
        Elastic material of surface 2 [-].
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
        for name, limit in CONTACT_LIMITS.items():
            limit.check(name, getattr(self, name))

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
        """Plain dictionary of the inputs (materials as nested dicts).

        Returns
        -------
        dict
            Field name to value, SI.
        """
        return asdict(self)

    @classmethod
    def from_engineering(cls, p_h_gpa: float, r_eq_mm: float, u_r: float, sr: float, temp_c: float,
                         rq1_um: float = 0.0, rq2_um: float = 0.0, **kwargs) -> "ContactCase":
        """A case from engineering units, as used at the command line and in factorial files.

        Parameters
        ----------
        p_h_gpa : float
            Maximum Hertz pressure [GPa].
        r_eq_mm : float
            Equivalent radius of curvature [mm].
        u_r : float
            Rolling (entrainment) velocity [m/s].
        sr : float
            Slide-to-roll ratio [-].
        temp_c : float
            Oil inlet temperature [°C].
        rq1_um : float
            RMS roughness of surface 1 [µm].
        rq2_um : float
            RMS roughness of surface 2 [µm].
        **kwargs
            ``material1``, ``material2`` (:class:`~ehl_dataset.model.materials.Material`) [-].

        Returns
        -------
        ContactCase
            The case in SI units. Each value is checked once, against :data:`CONTACT_LIMITS`; a value outside raises
            :class:`~ehl_dataset.validation.InputError` naming the engineering parameter, its value and the range in
            engineering units.
        """
        typed = {"p_h": p_h_gpa, "r_eq": r_eq_mm, "u_r": u_r, "sr": sr, "temperature": temp_c, "rq1": rq1_um,
                 "rq2": rq2_um}
        si = {}
        for name, value in typed.items():
            limit = CONTACT_LIMITS[name]
            try:
                si[name] = limit.to_si_value(float(value))
            except (TypeError, ValueError):
                raise InputError(limit.engineering, value, "a finite number") from None
        try:
            return cls(**si, **kwargs)
        except InputError as err:
            limit = CONTACT_LIMITS.get(err.parameter)
            if limit is None:
                raise
            value = typed[err.parameter]
            accepted = "a finite number" if err.accepted == "a finite number" else limit.engineering_range()
            raise InputError(limit.engineering, value, accepted) from None
