"""Tooth modifications and errors → unloaded normal separations at the contact points, SI units.

All amounts are material removed from (or, for errors, added to) the flank, measured normal to the flank, per gear
(ISO 21771 §9 and ISO 1328-1 notation). The separation of a contact point is the sum over both gears. Constant
offsets are irrelevant for the load distribution (they shift the rigid-body approach) but appear in the loaded
transmission error, which includes the unloaded (kinematic) transmission error of the modifications.

Shapes (per gear unless noted):
- profile crown M_P: parabolic over the gear's active profile, M_P at both ends (SAP and tip), 0 in the middle,
  in terms of the roll distance. Gear 1's active profile is s ∈ [contact_start, contact_end] measured from T1, gear
  2's is T1T2 − s over the same interval, so the pair's crown separation is 2 M_P ((s − s_mid)/(g_α/2))² for equal
  crowns;
- lead crown M_L: parabolic across the face, M_L at both faces, 0 at mid-face;
- lead slope f_Hβ (misalignment or helix slope deviation of the pair): linear across the face, f_Hβ (z/b − ½);
  positive values open the z = b end (the load moves to z = 0);
- tip relief C_a over a roll length L_a from the tip, linear (ISO 21771 "linear tip relief"); root relief
  C_f over L_f from the start of active profile, linear;
- spacing (pitch) errors: one normal offset per contact line (tooth pair) in the analysed window; positive = that
  pair is farther apart (it picks up load later).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ehl_dataset.validation import InputError, check_range

_MAX_MODIFICATION = 1e-3  # [m] 1 mm: beyond any flank modification


@dataclass(frozen=True)
class Modifications:
    """Flank modifications and errors of the pair (per gear; the module docstring gives their shapes).

    Parameters
    ----------
    profile_crown : float
        Profile crown M_P of each gear (the paper's design study: 15 µm) [m].
    lead_crown : float
        Lead crown M_L of each gear (the paper's design study: 12 µm) [m].
    lead_slope : float
        Lead slope f_Hβ of the pair across the face width (misalignment); may be negative [m].
    tip_relief : tuple of float
        Tip relief amounts (C_a1, C_a2) [m].
    tip_relief_length : tuple of float
        Tip relief roll lengths (L_a1, L_a2) [m].
    root_relief : tuple of float
        Root relief amounts (C_f1, C_f2) [m].
    root_relief_length : tuple of float
        Root relief roll lengths (L_f1, L_f2) [m].
    spacing_errors : tuple of float
        Normal offsets per contact line k = 0, 1, … of the analysed window [m].
    """

    profile_crown: float = 0.0
    lead_crown: float = 0.0
    lead_slope: float = 0.0
    tip_relief: tuple[float, float] = (0.0, 0.0)
    tip_relief_length: tuple[float, float] = (0.0, 0.0)
    root_relief: tuple[float, float] = (0.0, 0.0)
    root_relief_length: tuple[float, float] = (0.0, 0.0)
    spacing_errors: tuple[float, ...] = field(default=())

    def __post_init__(self):
        check_range("profile_crown", self.profile_crown, 0.0, _MAX_MODIFICATION, unit="m")
        check_range("lead_crown", self.lead_crown, 0.0, _MAX_MODIFICATION, unit="m")
        check_range("lead_slope", self.lead_slope, -_MAX_MODIFICATION, _MAX_MODIFICATION, unit="m")
        for name in ("tip_relief", "tip_relief_length", "root_relief", "root_relief_length"):
            values = getattr(self, name)
            if len(values) != 2:
                raise InputError(name, values, "a pair (gear 1, gear 2)")
            for i, v in enumerate(values, start=1):
                check_range(f"{name}{i}", v, 0.0, _MAX_MODIFICATION if "length" not in name else 1.0, unit="m")
        for k, v in enumerate(self.spacing_errors):
            check_range(f"spacing_errors[{k}]", v, -_MAX_MODIFICATION, _MAX_MODIFICATION, unit="m")

    @classmethod
    def paper(cls) -> "Modifications":
        """The paper's design-study modifications: M_P = 15 µm, M_L = 12 µm (Li & Kahraman 2009 §3).

        Returns
        -------
        Modifications
            Those modifications.
        """
        return cls(profile_crown=15e-6, lead_crown=12e-6)


def normal_separation(mods: Modifications, roll, z, line_index, contact_start: float, contact_end: float,
                      face_width: float):
    """Unloaded normal separation ε at contact points (broadcasting arrays).

    Gear 1's tip is at s = contact_end and its SAP at contact_start; gear 2's tip at contact_start and its SAP at
    contact_end.

    Parameters
    ----------
    mods : Modifications
        The modifications [-].
    roll : array_like
        Roll distance s from T1 [m].
    z : array_like
        Position across the face [m].
    line_index : array_like
        Contact line k of each point [-].
    contact_start : float
        Roll distance of the start of active contact [m].
    contact_end : float
        Roll distance of the end of active contact [m].
    face_width : float
        Face width b [m].

    Returns
    -------
    ndarray
        ε [m].
    """
    roll = np.asarray(roll, dtype=float)
    z = np.asarray(z, dtype=float)
    half_path = 0.5 * (contact_end - contact_start)
    mid = 0.5 * (contact_end + contact_start)
    half_face = 0.5 * face_width
    sep = 2.0 * mods.profile_crown * ((roll - mid) / half_path) ** 2
    sep = sep + 2.0 * mods.lead_crown * ((z - half_face) / half_face) ** 2
    sep = sep + mods.lead_slope * (z / face_width - 0.5)
    ca1, ca2 = mods.tip_relief
    la1, la2 = mods.tip_relief_length
    cf1, cf2 = mods.root_relief
    lf1, lf2 = mods.root_relief_length
    sep = sep + _linear_relief(ca1, la1, roll - (contact_end - la1))       # tip of gear 1 at contact_end
    sep = sep + _linear_relief(ca2, la2, (contact_start + la2) - roll)     # tip of gear 2 at contact_start
    sep = sep + _linear_relief(cf1, lf1, (contact_start + lf1) - roll)     # SAP of gear 1 at contact_start
    sep = sep + _linear_relief(cf2, lf2, roll - (contact_end - lf2))       # SAP of gear 2 at contact_end
    if mods.spacing_errors:
        errors = np.asarray(mods.spacing_errors, dtype=float)
        k = np.asarray(line_index)
        sep = sep + np.where(k < errors.size, errors[np.minimum(k, errors.size - 1)], 0.0)
    return sep


def _linear_relief(amount: float, length: float, depth_into_zone):
    """Linear relief: 0 at the start of the zone, ``amount`` at its end (``length`` into the zone)."""
    if amount == 0.0 or length == 0.0:
        return 0.0
    return amount * np.clip(depth_into_zone / length, 0.0, None)


_MAPPING_KEYS = {
    "profile_crown_um": ("profile_crown", 1e-6, False),
    "lead_crown_um": ("lead_crown", 1e-6, False),
    "lead_slope_um": ("lead_slope", 1e-6, False),
    "tip_relief_um": ("tip_relief", 1e-6, True),
    "tip_relief_length_mm": ("tip_relief_length", 1e-3, True),
    "root_relief_um": ("root_relief", 1e-6, True),
    "root_relief_length_mm": ("root_relief_length", 1e-3, True),
    "spacing_errors_um": ("spacing_errors", 1e-6, None),
}


def modifications_from_mapping(mapping: dict) -> Modifications:
    """Build :class:`Modifications` from a ``[modifications]`` TOML table in engineering units.

    Keys: profile_crown_um, lead_crown_um, lead_slope_um (numbers); tip_relief_um, tip_relief_length_mm,
    root_relief_um, root_relief_length_mm (a number for both gears or a pair gear 1, gear 2); spacing_errors_um (a
    list, one per contact line). Unknown keys are an error.

    Parameters
    ----------
    mapping : dict
        The parsed table (µm and mm as the key names say) [-].

    Returns
    -------
    Modifications
        The modifications in SI.
    """
    kwargs = {}
    for key, value in mapping.items():
        if key not in _MAPPING_KEYS:
            raise InputError(f"modifications.{key}", value, f"one of {sorted(_MAPPING_KEYS)}")
        field_name, factor, paired = _MAPPING_KEYS[key]
        try:
            if paired is None:
                kwargs[field_name] = tuple(float(v) * factor for v in value)
            elif paired:
                values = value if isinstance(value, (list, tuple)) else (value, value)
                kwargs[field_name] = tuple(float(v) * factor for v in values)
            else:
                kwargs[field_name] = float(value) * factor
        except (TypeError, ValueError):
            raise InputError(f"modifications.{key}", value, "numbers (a pair where per gear)") from None
    return Modifications(**kwargs)
