"""Feasibility of a helical gear pair design (limits of Li & Kahraman 2009, §3).

Definitions (all evaluated per gear where they differ; see docs/explanation/gear-model.md):

``backlash``        normal backlash along the line of action j_bn = j_wt cos α_wt cos β_b ≥ ``min_backlash``
                    (0.04 mm in the paper). ``backlash_kind="circumferential"`` checks j_wt on the operating
                    pitch circle instead.
``pointed_tooth``   normal tip thickness s_an ≤ 0 (the involutes of the two flanks cross below the tip circle).
``tip_thickness``   normal tip thickness s_an ≥ ``min_tip_thickness`` · m_n (0.2 m_n).
``root_clearance``  c = a − r_a − r_f(mate) ≥ ``min_root_clearance`` · m_n (0.2 m_n); a negative clearance means the
                    tip of one gear would hit the root of the other.
``undercut``        the generating rack's straight flank (down to its form depth h_FfP) reaches below the base
                    circle: h_FfP − x m_n > r sin² α_t (ISO 21771 undercut limit).
``interference``    the mating tip contacts the flank below the form circle (in the fillet, or below the base
                    circle): roll distance of the start of active profile < roll distance of the form point.
``contact_ratio``   total contact ratio ε_γ = ε_α + ε_β ≥ ``min_contact_ratio`` (1.0): there is always a tooth pair
                    in contact. ε_α alone is not required: the paper's Design A has ε_α = 0.96, ε_γ = 3.13.

Everything works element-wise on vectorised :class:`~efficiency.geometry.GearPair` objects (see
:func:`feasibility_masks`), which is how :func:`paper_design_space` screens the paper's 30,464 designs at once.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ehl_dataset.validation import InputError, check_range

from .geometry import GearPair

CRITERIA = ("backlash", "pointed_tooth", "tip_thickness", "root_clearance", "undercut", "interference",
            "contact_ratio")


@dataclass(frozen=True)
class FeasibilityLimits:
    """Limits of the feasibility check (paper §3: backlash 0.04 mm, tip thickness and root clearance 0.2 m_n).

    Parameters
    ----------
    min_backlash : float
        Smallest backlash [m].
    min_tip_thickness : float
        Smallest normal tip thickness in units of the normal module [-].
    min_root_clearance : float
        Smallest root clearance in units of the normal module [-].
    min_contact_ratio : float
        Smallest total contact ratio ε_γ [-].
    backlash_kind : str
        ``normal`` (j_bn) or ``circumferential`` (j_wt) [-].
    """

    min_backlash: float = 0.04e-3
    min_tip_thickness: float = 0.2
    min_root_clearance: float = 0.2
    min_contact_ratio: float = 1.0
    backlash_kind: str = "normal"

    @classmethod
    def physical(cls) -> "FeasibilityLimits":
        """Limits of a pair that can be made and run at all, for any pair outside the paper's study.

        Backlash ≥ 0 (within 1 µm, the effect of rounding published profile shifts to 4 decimals: no
        jamming), tip thickness ≥ 0 (not pointed), root clearance ≥ 0 (no tip–root interference), ε_γ ≥ 1.
        The paper's 0.04 mm backlash and 0.2 m_n tip thickness and root clearance (Li & Kahraman 2009 §3)
        are design-study choices and apply only inside that study.

        Returns
        -------
        FeasibilityLimits
            Those limits.
        """
        return cls(min_backlash=-1e-6, min_tip_thickness=0.0, min_root_clearance=0.0, min_contact_ratio=1.0)

    def __post_init__(self):
        check_range("min_backlash", self.min_backlash, -1e-3, 1e-2, unit="m")
        check_range("min_tip_thickness", self.min_tip_thickness, 0.0, 2.0)
        check_range("min_root_clearance", self.min_root_clearance, -1.0, 2.0)
        check_range("min_contact_ratio", self.min_contact_ratio, 0.0, 10.0)
        if self.backlash_kind not in ("normal", "circumferential"):
            raise InputError("backlash_kind", self.backlash_kind, "'normal' or 'circumferential'")


@dataclass(frozen=True)
class Violation:
    """One violated limit.

    Parameters
    ----------
    name : str
        The criterion, one of :data:`CRITERIA` [-].
    gear : int or None
        1, 2, or None for the pair [-].
    value : float
        The design's value, in ``unit`` [-].
    limit : float
        The limit, in ``unit`` [-].
    unit : str
        Unit of value and limit (SI; ``-`` for ratios) [-].
    relation : str
        The relation the value must satisfy, e.g. ``>=`` [-].
    quantity : str
        What the value is, in words [-].
    """

    name: str
    gear: int | None
    value: float
    limit: float
    unit: str
    relation: str = ">="
    quantity: str = ""

    def __str__(self) -> str:
        who = f" (gear {self.gear})" if self.gear else ""
        what = f" [{self.quantity}]" if self.quantity else ""
        if self.unit == "m":
            return (f"{self.name}{who}: {self.value * 1e3:.4g} mm, required {self.relation} "
                    f"{self.limit * 1e3:.4g} mm{what}")
        return f"{self.name}{who}: {self.value:.4g}, required {self.relation} {self.limit:.4g}{what}"

    def as_dict(self) -> dict:
        """The violation as a JSON-serialisable dict (``value_m``/``limit_m`` for lengths).

        Returns
        -------
        dict
            name, gear, quantity, value, limit and relation.
        """
        suffix = "_m" if self.unit == "m" else ""
        return {"name": self.name, "gear": self.gear, "quantity": self.quantity, f"value{suffix}": float(self.value),
                f"limit{suffix}": float(self.limit), "relation": self.relation}


@dataclass(frozen=True)
class FeasibilityReport:
    """Result of :func:`check_design`: the violated limits (empty when feasible).

    Parameters
    ----------
    violations : tuple of Violation
        The violated limits [-].
    limits : FeasibilityLimits
        The limits checked [-].
    """

    violations: tuple[Violation, ...] = field(default_factory=tuple)
    limits: FeasibilityLimits = field(default_factory=FeasibilityLimits)

    @property
    def feasible(self) -> bool:
        return not self.violations

    @property
    def violated(self) -> tuple[str, ...]:
        return tuple(dict.fromkeys(v.name for v in self.violations))

    def __str__(self) -> str:
        if self.feasible:
            return "feasible"
        return "infeasible: " + "; ".join(str(v) for v in self.violations)


def _backlash(pair: GearPair, limits: FeasibilityLimits):
    return pair.normal_backlash if limits.backlash_kind == "normal" else pair.circumferential_backlash


def feasibility_masks(pair: GearPair, limits: FeasibilityLimits = FeasibilityLimits()) -> dict[str, np.ndarray]:
    """Boolean arrays, True where each criterion is satisfied (both gears), plus ``feasible`` (all of them).

    Works for scalar and vectorised pairs. A pointed tooth fails both ``pointed_tooth`` and ``tip_thickness`` here
    (:func:`check_design` reports it once, as ``pointed_tooth``).

    Parameters
    ----------
    pair : GearPair
        A scalar or vectorised pair [-].
    limits : FeasibilityLimits
        The limits [-].

    Returns
    -------
    dict of str to ndarray
        One boolean array per criterion of :data:`CRITERIA` and ``feasible``.
    """
    m = np.asarray(pair.normal_module, dtype=float)
    tips = pair.tip_normal_thicknesses
    sap, form = pair.sap_roll_distances, pair.form_roll_distances
    with np.errstate(invalid="ignore"):
        masks = {
            "backlash": _backlash(pair, limits) >= limits.min_backlash,
            "pointed_tooth": (tips[0] > 0) & (tips[1] > 0),
            "tip_thickness": (tips[0] >= limits.min_tip_thickness * m) & (tips[1] >= limits.min_tip_thickness * m),
            "root_clearance": ((pair.root_clearances[0] >= limits.min_root_clearance * m)
                               & (pair.root_clearances[1] >= limits.min_root_clearance * m)),
            "undercut": ~(pair.undercut[0] | pair.undercut[1]),
            "interference": (sap[0] >= np.maximum(form[0], 0.0)) & (sap[1] >= np.maximum(form[1], 0.0)),
            "contact_ratio": pair.total_contact_ratio >= limits.min_contact_ratio,
        }
    feasible = np.ones(np.broadcast(*masks.values()).shape, dtype=bool)
    for mask in masks.values():
        feasible &= mask
    masks = {k: np.asarray(v, dtype=bool) for k, v in masks.items()}
    masks["feasible"] = feasible
    return masks


def check_design(pair: GearPair, limits: FeasibilityLimits = FeasibilityLimits()) -> FeasibilityReport:
    """Check one (scalar) design against every limit; each violated limit is reported with its value and limit.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    limits : FeasibilityLimits
        The limits [-].

    Returns
    -------
    FeasibilityReport
        The violated limits (empty when feasible).
    """
    if np.ndim(pair.normal_module) or np.ndim(pair.z1):
        raise InputError("pair", "vectorised GearPair", "a single design (use feasibility_masks for arrays)")
    m = float(pair.normal_module)
    out: list[Violation] = []
    j = float(_backlash(pair, limits))
    if not j >= limits.min_backlash:
        out.append(Violation("backlash", None, j, limits.min_backlash, "m",
                             quantity=f"{limits.backlash_kind} backlash"))
    for i, s in enumerate(pair.tip_normal_thicknesses, start=1):
        s = float(s)
        if not s > 0:
            out.append(Violation("pointed_tooth", i, s, 0.0, "m", ">", "normal tip thickness"))
        elif s < limits.min_tip_thickness * m:
            out.append(Violation("tip_thickness", i, s, limits.min_tip_thickness * m, "m",
                                quantity="normal tip thickness"))
    for i, c in enumerate(pair.root_clearances, start=1):
        if float(c) < limits.min_root_clearance * m:
            out.append(Violation("root_clearance", i, float(c), limits.min_root_clearance * m, "m",
                                quantity="tip-to-root clearance"))
    # undercut and interference are reported as roll distances along the line of action from the gear's own
    # base-circle tangent point (the radius follows as sqrt(r_b² + g²)).
    for i, g_form in enumerate(pair.form_roll_distances, start=1):
        if float(g_form) < 0:
            out.append(Violation("undercut", i, float(g_form), 0.0, "m",
                                 quantity="roll distance of the generated form point from the base circle"))
    for i, (g_sap, g_form) in enumerate(zip(pair.sap_roll_distances, pair.form_roll_distances), start=1):
        if float(g_sap) < max(float(g_form), 0.0):
            out.append(Violation("interference", i, float(g_sap), max(float(g_form), 0.0), "m",
                                 quantity="roll distance of the start of active profile; limit: form point"))
    eps = float(pair.total_contact_ratio)
    if not eps >= limits.min_contact_ratio:
        out.append(Violation("contact_ratio", None, eps, limits.min_contact_ratio, "-",
                                 quantity="total contact ratio"))
    return FeasibilityReport(tuple(out), limits)


# ---------------------------------------------------------------------- the paper's design space
def iso_min_backlash(center_distance, normal_module):
    """Recommended minimum normal backlash j_bn,min = 2/3 (0.06 + 0.0005 a + 0.03 m_n) mm, with a and m_n in mm.

    ISO/TR 10064-2:1996, industrial drives, ferrous gears in a ferrous housing.

    Parameters
    ----------
    center_distance : float or array_like
        Centre distance a [m].
    normal_module : float or array_like
        Normal module m_n [m].

    Returns
    -------
    float or ndarray
        j_bn,min [m].
    """
    a_mm = np.asarray(center_distance) * 1e3
    m_mm = np.asarray(normal_module) * 1e3
    return (2.0 / 3.0) * (0.06 + 0.0005 * a_mm + 0.03 * m_mm) * 1e-3


def thickness_allowance(policy: str, value: float, center_distance, normal_module, normal_pressure_angle):
    """Normal tooth-thickness allowance A_sn per gear of identical gears by a backlash policy.

    ``iso10064``: both gears thinned equally to give the ISO/TR 10064-2 recommended minimum backlash,
    A_sn = j_bn,min / (2 cos α_n) (``value`` ignored); ``constant``: A_sn = ``value``; ``module``:
    A_sn = ``value`` · m_n; ``backlash``: A_sn = ``value`` / (2 cos α_n), i.e. a fixed normal backlash ``value`` at
    the standard centre distance.

    Parameters
    ----------
    policy : str
        ``iso10064``, ``constant``, ``module`` or ``backlash`` [-].
    value : float
        The policy's value: a length [m] for ``constant`` and ``backlash``, a fraction of m_n for ``module`` [-].
    center_distance : float or array_like
        Centre distance a [m].
    normal_module : float or array_like
        Normal module m_n [m].
    normal_pressure_angle : float or array_like
        Normal pressure angle α_n [rad].

    Returns
    -------
    float or ndarray
        A_sn [m].
    """
    cos_an = np.cos(normal_pressure_angle)
    if policy == "iso10064":
        return iso_min_backlash(center_distance, normal_module) / (2.0 * cos_an)
    if policy == "constant":
        return np.broadcast_to(float(value), np.broadcast(normal_module, normal_pressure_angle).shape) * 1.0
    if policy == "module":
        return float(value) * np.asarray(normal_module)
    if policy == "backlash":
        return float(value) / (2.0 * cos_an)
    raise InputError("backlash_policy", policy, "'iso10064', 'constant', 'module' or 'backlash'")


@dataclass(frozen=True)
class DesignSpace:
    """A full-factorial design space of the paper's parametrisation (angles in degrees as in the paper).

    Parameters
    ----------
    pressure_angles_deg : tuple of float
        Normal pressure angles Φ [deg].
    helix_angles_deg : tuple of float
        Helix angles Ψ [deg].
    teeth : tuple of int
        Numbers of teeth N [-].
    working_depths : tuple of float
        Working depths Λ_wd in units of m_n [-].
    center_distance : float
        Centre distance a [m].
    face_width : float
        Face width b [m].
    root_fillet_coefficient : float
        Generating rack tip radius in units of m_n [-].
    backlash_policy : str
        Policy of :func:`thickness_allowance` [-].
    backlash_policy_value : float
        The policy's value (SI; a length for ``constant`` and ``backlash``) [-].
    """

    pressure_angles_deg: tuple[float, ...]
    helix_angles_deg: tuple[float, ...]
    teeth: tuple[int, ...]
    working_depths: tuple[float, ...]
    center_distance: float = 0.0915
    face_width: float = 0.025
    root_fillet_coefficient: float = 0.25
    backlash_policy: str = "iso10064"
    backlash_policy_value: float = 0.0

    @property
    def size(self) -> int:
        return (len(self.pressure_angles_deg) * len(self.helix_angles_deg) * len(self.teeth)
                * len(self.working_depths))

    def grid(self):
        """The design parameters on the full-factorial grid.

        Returns
        -------
        list of ndarray
            (Φ [rad], Ψ [rad], N [-], Λ_wd [-]), each of shape (nΦ, nΨ, nN, nΛ).
        """
        return np.meshgrid(np.radians(self.pressure_angles_deg), np.radians(self.helix_angles_deg),
                           np.asarray(self.teeth), np.asarray(self.working_depths, dtype=float), indexing="ij")

    def pairs(self) -> GearPair:
        """The whole space as one vectorised :class:`GearPair`.

        Returns
        -------
        GearPair
            Fields of shape (nΦ, nΨ, nN, nΛ).
        """
        phi, psi, n, wd = self.grid()
        module = self.center_distance * np.cos(psi) / n
        allowance = thickness_allowance(self.backlash_policy, self.backlash_policy_value, self.center_distance,
                                        module, phi)
        if np.any(allowance < 0) or np.any(allowance > 0.01):
            raise InputError("backlash_policy_value", self.backlash_policy_value, "an allowance in [0, 10 mm]")
        return GearPair.from_paper(n, phi, psi, wd, center_distance=self.center_distance,
                                   face_width=self.face_width, root_fillet_coefficient=self.root_fillet_coefficient,
                                   thickness_allowance=allowance)


def paper_design_space(**overrides) -> DesignSpace:
    """The paper's 7 × 16 × 34 × 8 = 30,464 designs (Li & Kahraman 2009 §3).

    Φ 15–30° step 2.5, Ψ 15–30° step 1, N 20–53, Λ_wd = 1.85 + 0.218 k, k = 0..7 (1.85 … 3.376).

    Parameters
    ----------
    **overrides
        Fields of :class:`DesignSpace` that replace the paper's [-].

    Returns
    -------
    DesignSpace
        The space.
    """
    space = dict(pressure_angles_deg=tuple(15.0 + 2.5 * i for i in range(7)),
                 helix_angles_deg=tuple(float(v) for v in range(15, 31)), teeth=tuple(range(20, 54)),
                 working_depths=tuple(round(1.85 + 0.218 * k, 3) for k in range(8)))
    space.update(overrides)
    return DesignSpace(**space)


def count_feasible(space: DesignSpace, limits: FeasibilityLimits = FeasibilityLimits()) -> dict[str, int]:
    """Number of designs of ``space`` that satisfy each criterion.

    Parameters
    ----------
    space : DesignSpace
        The design space [-].
    limits : FeasibilityLimits
        The limits [-].

    Returns
    -------
    dict of str to int
        Count per criterion, ``feasible`` (all criteria) and ``total``.
    """
    masks = feasibility_masks(space.pairs(), limits)
    counts = {name: int(np.count_nonzero(mask)) for name, mask in masks.items()}
    counts["total"] = space.size
    return counts

