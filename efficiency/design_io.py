"""Gear design files (TOML) and the paper's study definition, read into frozen dataclasses (SI inside).

A design file has one ``[design]`` table, either the paper's parametrisation::

    [design]
    kind = "paper"                  # identical gears, 1:1, standard centre distance (Li & Kahraman 2009 §3)
    teeth = 32
    normal_pressure_angle_deg = 30.0
    helix_angle_deg = 19.0
    working_depth = 2.068
    center_distance_mm = 91.5       # optional (default 91.5)
    face_width_mm = 25.0            # optional (default 25)
    root_fillet_coefficient = 0.25  # optional
    thickness_allowance_mm = 0.06   # optional, per gear (normal); or backlash_policy = "iso10064"

or a general pair::

    [design]
    kind = "general"
    teeth = [16, 24]
    normal_module_mm = 4.5
    normal_pressure_angle_deg = 20.0
    helix_angle_deg = 0.0
    face_width_mm = 14.0
    profile_shift = [0.1817, 0.1715]           # optional
    center_distance_mm = 91.5                  # optional: zero-backlash centre distance when absent
    addendum_coefficient = 1.0                 # optional basic rack (ISO 53 A: 1.0, 1.25, 0.38)
    dedendum_coefficient = 1.25
    root_fillet_coefficient = 0.38
    thickness_allowance_mm = [0.05, 0.05]      # optional
    tip_reduction = true                       # optional
    tip_diameter_mm = [82.4567, 118.3649]      # optional, overrides the basic-rack tip diameters

Other tables in the file (e.g. ``[modifications]``, ``[operating_point]``) belong to other parts of the model and
are ignored here. Unknown keys inside ``[design]`` are an error.
"""

from __future__ import annotations

import math
import os
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from ehl_dataset.data_files import resolve_named_file
from ehl_dataset.validation import InputError

from .feasibility import DesignSpace, FeasibilityLimits, thickness_allowance
from .geometry import PAPER_CENTER_DISTANCE, PAPER_FACE_WIDTH, GearPair

_PAPER_KEYS = {"kind", "name", "teeth", "normal_pressure_angle_deg", "helix_angle_deg", "working_depth",
               "center_distance_mm", "face_width_mm", "root_fillet_coefficient", "thickness_allowance_mm",
               "backlash_policy", "backlash_policy_value"}
_GENERAL_KEYS = {"kind", "name", "teeth", "normal_module_mm", "normal_pressure_angle_deg", "helix_angle_deg",
                 "face_width_mm", "profile_shift", "center_distance_mm", "addendum_coefficient",
                 "dedendum_coefficient", "root_fillet_coefficient", "thickness_allowance_mm", "tip_reduction",
                 "tip_diameter_mm", "root_diameter_mm", "normal_thickness_mm"}


def read_toml(path: str | os.PathLike) -> dict:
    """Parse a TOML file; a syntax error becomes an :class:`InputError` naming the file."""
    path = Path(path)
    try:
        with path.open("rb") as handle:
            return tomllib.load(handle)
    except tomllib.TOMLDecodeError as err:
        raise InputError("toml file", str(path), "valid TOML", str(err)) from None


def _number(table: Mapping, key: str, where: str, default: Any = None) -> float:
    if key not in table:
        if default is None:
            raise InputError(f"{where}.{key}", None, "a number (missing)")
        return default
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{where}.{key}", value, "a number")
    return float(value)


def _pair_of(table: Mapping, key: str, where: str, default: Any = None) -> tuple[float, float]:
    if key not in table:
        if default is None:
            raise InputError(f"{where}.{key}", None, "two numbers (missing)")
        return default
    value = table[key]
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return (float(value), float(value))
    if (not isinstance(value, list) or len(value) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
        raise InputError(f"{where}.{key}", value, "a number or a list of two numbers")
    return (float(value[0]), float(value[1]))


def _teeth(value, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or float(value) != int(value):
        raise InputError(where, value, "a whole number of teeth")
    return int(value)


def paper_design(teeth: int, normal_pressure_angle_deg: float, helix_angle_deg: float, working_depth: float,
                 center_distance_mm: float = PAPER_CENTER_DISTANCE * 1e3, face_width_mm: float = PAPER_FACE_WIDTH * 1e3,
                 root_fillet_coefficient: float = 0.25, thickness_allowance_mm: float | None = None,
                 backlash_policy: str = "iso10064", backlash_policy_value: float = 0.0) -> GearPair:
    """The paper's design (Li & Kahraman 2009 §3) from engineering units.

    Without ``thickness_allowance_mm`` the teeth are thinned by ``backlash_policy``
    (:func:`efficiency.feasibility.thickness_allowance`).

    Parameters
    ----------
    teeth : int
        Number of teeth N of each gear [-].
    normal_pressure_angle_deg : float
        Normal pressure angle Φ [deg].
    helix_angle_deg : float
        Helix angle Ψ [deg].
    working_depth : float
        Working depth Λ_wd in units of m_n [-].
    center_distance_mm : float
        Centre distance [mm].
    face_width_mm : float
        Face width [mm].
    root_fillet_coefficient : float
        Generating rack tip radius in units of m_n [-].
    thickness_allowance_mm : float, optional
        Normal thickness allowance of each gear; None: from ``backlash_policy`` [mm].
    backlash_policy : str
        Policy of :func:`efficiency.feasibility.thickness_allowance`: ``iso10064``, ``constant``, ``module`` or
        ``backlash`` [-].
    backlash_policy_value : float
        The policy's value (thickness allowance or backlash for ``constant`` and ``backlash``) [mm].

    Returns
    -------
    GearPair
        The design in SI.
    """
    a = center_distance_mm * 1e-3
    phi = math.radians(normal_pressure_angle_deg)
    psi = math.radians(helix_angle_deg)
    if thickness_allowance_mm is None:
        module = a * math.cos(psi) / teeth
        value = backlash_policy_value * (1e-3 if backlash_policy in ("constant", "backlash") else 1.0)
        allowance = float(thickness_allowance(backlash_policy, value, a, module, phi))
    else:
        allowance = thickness_allowance_mm * 1e-3
    return GearPair.from_paper(teeth, phi, psi, working_depth, center_distance=a, face_width=face_width_mm * 1e-3,
                               root_fillet_coefficient=root_fillet_coefficient, thickness_allowance=allowance)


def design_from_mapping(table: Mapping[str, Any], where: str = "design") -> GearPair:
    """Build a :class:`GearPair` from a ``[design]`` table (engineering units, see the module docstring).

    Parameters
    ----------
    table : Mapping
        The parsed table, lengths in mm and angles in degrees as the module docstring lists [-].
    where : str
        Name of the table in error messages [-].

    Returns
    -------
    GearPair
        The design in SI.

    Raises
    ------
    InputError
        Naming the first bad or unknown key.
    """
    if not isinstance(table, Mapping):
        raise InputError(where, table, "a TOML table")
    kind = table.get("kind", "paper" if "working_depth" in table else "general")
    if kind == "paper":
        unknown = set(table) - _PAPER_KEYS
        if unknown:
            raise InputError(f"{where}.{sorted(unknown)[0]}", table[sorted(unknown)[0]],
                             f"one of the keys {sorted(_PAPER_KEYS)}")
        allowance = table.get("thickness_allowance_mm")
        return paper_design(
            _teeth(table.get("teeth"), f"{where}.teeth"),
            _number(table, "normal_pressure_angle_deg", where), _number(table, "helix_angle_deg", where),
            _number(table, "working_depth", where),
            center_distance_mm=_number(table, "center_distance_mm", where, PAPER_CENTER_DISTANCE * 1e3),
            face_width_mm=_number(table, "face_width_mm", where, PAPER_FACE_WIDTH * 1e3),
            root_fillet_coefficient=_number(table, "root_fillet_coefficient", where, 0.25),
            thickness_allowance_mm=None if allowance is None else _number(table, "thickness_allowance_mm", where),
            backlash_policy=str(table.get("backlash_policy", "iso10064")),
            backlash_policy_value=_number(table, "backlash_policy_value", where, 0.0))
    if kind != "general":
        raise InputError(f"{where}.kind", kind, "'paper' or 'general'")
    unknown = set(table) - _GENERAL_KEYS
    if unknown:
        raise InputError(f"{where}.{sorted(unknown)[0]}", table[sorted(unknown)[0]],
                         f"one of the keys {sorted(_GENERAL_KEYS)}")
    teeth = table.get("teeth")
    if not isinstance(teeth, list) or len(teeth) != 2:
        raise InputError(f"{where}.teeth", teeth, "a list of two whole numbers [z1, z2]")
    x1, x2 = _pair_of(table, "profile_shift", where, (0.0, 0.0))
    a1, a2 = _pair_of(table, "thickness_allowance_mm", where, (0.0, 0.0))
    tips = _pair_of(table, "tip_diameter_mm", where, (None, None))
    roots = _pair_of(table, "root_diameter_mm", where, (None, None))
    thick = _pair_of(table, "normal_thickness_mm", where, (None, None))
    if thick[0] is not None and "thickness_allowance_mm" in table:
        raise InputError(f"{where}.normal_thickness_mm", thick, "either normal_thickness_mm or "
                         "thickness_allowance_mm, not both")
    tip_reduction = table.get("tip_reduction", True)
    if not isinstance(tip_reduction, bool):
        raise InputError(f"{where}.tip_reduction", tip_reduction, "true or false")
    a = table.get("center_distance_mm")
    return GearPair(
        z1=_teeth(teeth[0], f"{where}.teeth[0]"), z2=_teeth(teeth[1], f"{where}.teeth[1]"),
        normal_module=_number(table, "normal_module_mm", where) * 1e-3,
        normal_pressure_angle=math.radians(_number(table, "normal_pressure_angle_deg", where)),
        helix_angle=math.radians(_number(table, "helix_angle_deg", where, 0.0)),
        face_width=_number(table, "face_width_mm", where) * 1e-3, x1=x1, x2=x2,
        addendum_coefficient=_number(table, "addendum_coefficient", where, 1.0),
        dedendum_coefficient=_number(table, "dedendum_coefficient", where, 1.25),
        root_fillet_coefficient=_number(table, "root_fillet_coefficient", where, 0.38),
        center_distance=None if a is None else _number(table, "center_distance_mm", where) * 1e-3,
        thickness_allowance1=a1 * 1e-3, thickness_allowance2=a2 * 1e-3, tip_reduction=tip_reduction,
        tip_diameters=None if tips[0] is None else (tips[0] * 1e-3, tips[1] * 1e-3),
        root_diameters_given=None if roots[0] is None else (roots[0] * 1e-3, roots[1] * 1e-3),
        normal_thicknesses_given=None if thick[0] is None else (thick[0] * 1e-3, thick[1] * 1e-3))


def load_design(path: str | os.PathLike) -> GearPair:
    """Read the ``[design]`` table of a design TOML file (engineering units, module docstring).

    Parameters
    ----------
    path : str or PathLike
        The TOML file [-].

    Returns
    -------
    GearPair
        The design.
    """
    data = read_toml(path)
    if "design" not in data:
        raise InputError("design file", str(path), "a TOML file with a [design] table")
    return design_from_mapping(data["design"])


def design_to_toml(pair: GearPair, name: str = "") -> str:
    """A ``kind = "general"`` design table that reproduces ``pair`` exactly (SI → mm/deg, full precision).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    name : str
        Name written into the table [-].

    Returns
    -------
    str
        The TOML text.
    """
    def num(v) -> str:
        return repr(float(v))

    lines = ["[design]", 'kind = "general"']
    if name:
        lines.append(f"name = {name!r}".replace("'", '"'))
    lines += [
        f"teeth = [{int(pair.z1)}, {int(pair.z2)}]",
        f"normal_module_mm = {num(pair.normal_module * 1e3)}",
        f"normal_pressure_angle_deg = {num(math.degrees(pair.normal_pressure_angle))}",
        f"helix_angle_deg = {num(math.degrees(pair.helix_angle))}",
        f"face_width_mm = {num(pair.face_width * 1e3)}",
        f"profile_shift = [{num(pair.x1)}, {num(pair.x2)}]",
        f"center_distance_mm = {num(pair.center_distance * 1e3)}",
        f"addendum_coefficient = {num(pair.addendum_coefficient)}",
        f"dedendum_coefficient = {num(pair.dedendum_coefficient)}",
        f"root_fillet_coefficient = {num(pair.root_fillet_coefficient)}",
        f"thickness_allowance_mm = [{num(pair.thickness_allowance1 * 1e3)}, {num(pair.thickness_allowance2 * 1e3)}]",
        f"tip_reduction = {'true' if pair.tip_reduction else 'false'}",
    ]
    if pair.tip_diameters is not None:
        lines.append(f"tip_diameter_mm = [{num(pair.tip_diameters[0] * 1e3)}, {num(pair.tip_diameters[1] * 1e3)}]")
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------- the paper's study
def _values(spec, where: str) -> tuple[float, ...]:
    """A list of numbers, or an inclusive range ``{start, stop, step}``."""
    if isinstance(spec, list) and spec and all(isinstance(v, (int, float)) for v in spec):
        return tuple(float(v) for v in spec)
    if isinstance(spec, Mapping) and {"start", "stop", "step"} <= set(spec):
        start, stop, step = (float(spec[k]) for k in ("start", "stop", "step"))
        if step <= 0 or stop < start:
            raise InputError(where, dict(spec), "start <= stop and step > 0")
        count = int(math.floor((stop - start) / step + 1e-9)) + 1
        return tuple(round(start + i * step, 12) for i in range(count))
    raise InputError(where, spec, "a list of numbers or {start, stop, step}")


@dataclass(frozen=True)
class OperatingPoint:
    """The study's operating point in SI.

    Parameters
    ----------
    input_torque : float
        Input (gear 1) torque [N·m].
    input_speed : float
        Input angular speed [rad/s].
    lubricant : str
        Lubricant name [-].
    oil_temperature : float
        Oil inlet temperature [K].
    rq1 : float
        RMS roughness of gear 1's flanks [m].
    rq2 : float
        RMS roughness of gear 2's flanks [m].
    profile_crown : float
        Profile crown M_P of each gear [m].
    lead_crown : float
        Lead crown M_L of each gear [m].
    """

    input_torque: float
    input_speed: float
    lubricant: str
    oil_temperature: float
    rq1: float
    rq2: float
    profile_crown: float
    lead_crown: float


@dataclass(frozen=True)
class PublishedDesign:
    """A Table 1 design: parameters and the published d_o, root diameter and module (SI).

    Parameters
    ----------
    name : str
        Design name (A–D) [-].
    teeth : int
        Number of teeth N of each gear [-].
    normal_pressure_angle_deg : float
        Normal pressure angle Φ [deg].
    helix_angle_deg : float
        Helix angle Ψ [deg].
    working_depth : float
        Working depth Λ_wd in units of m_n [-].
    tip_diameter : float
        Published outside diameter d_o [m].
    root_diameter : float
        Published root diameter [m].
    normal_module : float
        Published normal module [m].
    """

    name: str
    teeth: int
    normal_pressure_angle_deg: float
    helix_angle_deg: float
    working_depth: float
    tip_diameter: float
    root_diameter: float
    normal_module: float


@dataclass(frozen=True)
class PaperStudy:
    """The paper's design study (``data/studies/paper2009.toml``).

    Parameters
    ----------
    name : str
        Study name [-].
    source : str
        The publication the study reproduces [-].
    space : DesignSpace
        The design space swept [-].
    operating_point : OperatingPoint
        The study's operating point [-].
    limits : FeasibilityLimits
        Feasibility limits of the screen [-].
    search_limits : Mapping of str to float
        Limits of the design-D search (P, TE, σ_c, σ_b; SI, units in the keys) [-].
    modification_study : Mapping
        Crowns and torques of the modification study [-].
    designs : Mapping of str to PublishedDesign
        The published designs of Table 1 by name (A–D) [-].
    paper_feasible_count : int, optional
        Number of feasible designs the paper reports [-].
    """

    name: str
    source: str
    space: DesignSpace
    operating_point: OperatingPoint
    limits: FeasibilityLimits
    search_limits: Mapping[str, float]
    modification_study: Mapping[str, Any]
    designs: Mapping[str, PublishedDesign] = field(default_factory=dict)
    paper_feasible_count: int | None = None

    def design(self, name: str) -> GearPair:
        """The published design ``name`` (A–D) as a :class:`GearPair` with the study's assumptions.

        Parameters
        ----------
        name : str
            Design name, a key of ``designs`` [-].

        Returns
        -------
        GearPair
            The design.
        """
        if name not in self.designs:
            raise InputError("design", name, f"one of {sorted(self.designs)}")
        d = self.designs[name]
        s = self.space
        value = s.backlash_policy_value
        return paper_design(d.teeth, d.normal_pressure_angle_deg, d.helix_angle_deg, d.working_depth,
                            center_distance_mm=s.center_distance * 1e3, face_width_mm=s.face_width * 1e3,
                            root_fillet_coefficient=s.root_fillet_coefficient, backlash_policy=s.backlash_policy,
                            backlash_policy_value=value * (1e3 if s.backlash_policy in ("constant", "backlash")
                                                           else 1.0))


def load_study(name_or_path: str | os.PathLike = "paper2009") -> PaperStudy:
    """Read a study definition (a shipped name such as ``paper2009`` or a TOML path).

    Parameters
    ----------
    name_or_path : str or PathLike
        Shipped study name (``data/studies/NAME.toml``) or path of a study TOML file [-].

    Returns
    -------
    PaperStudy
        The study.
    """
    path = resolve_named_file("studies", name_or_path, ".toml")
    data = read_toml(path)
    try:
        par, sweep, op, fe = data["parametrisation"], data["sweep"], data["operating_point"], data["feasibility"]
    except KeyError as err:
        raise InputError("study table", err.args[0], "[parametrisation], [sweep], [operating_point], [feasibility]")
    policy = str(par.get("backlash_policy", "iso10064"))
    value = _number(par, "backlash_policy_value", "parametrisation", 0.0)
    if policy in ("constant", "backlash"):
        value *= 1e-3
    space = DesignSpace(
        pressure_angles_deg=_values(sweep["normal_pressure_angle_deg"], "sweep.normal_pressure_angle_deg"),
        helix_angles_deg=_values(sweep["helix_angle_deg"], "sweep.helix_angle_deg"),
        teeth=tuple(int(v) for v in _values(sweep["teeth"], "sweep.teeth")),
        working_depths=_values(sweep["working_depth"], "sweep.working_depth"),
        center_distance=_number(par, "center_distance_mm", "parametrisation") * 1e-3,
        face_width=_number(par, "face_width_mm", "parametrisation") * 1e-3,
        root_fillet_coefficient=_number(par, "root_fillet_coefficient", "parametrisation", 0.25),
        backlash_policy=policy, backlash_policy_value=value)
    operating = OperatingPoint(
        input_torque=_number(op, "input_torque_nm", "operating_point"),
        input_speed=_number(op, "input_speed_rpm", "operating_point") * math.pi / 30.0,
        lubricant=str(op.get("lubricant", "atf")),
        oil_temperature=_number(op, "oil_temperature_c", "operating_point") + 273.15,
        rq1=_number(op, "rq1_um", "operating_point") * 1e-6, rq2=_number(op, "rq2_um", "operating_point") * 1e-6,
        profile_crown=_number(op, "profile_crown_um", "operating_point") * 1e-6,
        lead_crown=_number(op, "lead_crown_um", "operating_point") * 1e-6)
    limits = FeasibilityLimits(
        min_backlash=_number(fe, "min_backlash_mm", "feasibility") * 1e-3,
        min_tip_thickness=_number(fe, "min_tip_thickness_module", "feasibility"),
        min_root_clearance=_number(fe, "min_root_clearance_module", "feasibility"),
        min_contact_ratio=_number(fe, "min_contact_ratio", "feasibility", 1.0),
        backlash_kind=str(fe.get("backlash_kind", "normal")))
    search = data.get("design_d_search", {})
    search_si = {}
    for key, scale, si in (("max_power_loss_kw", 1e3, "max_power_loss_w"),
                           ("max_root_stress_mpa", 1e6, "max_root_stress_pa"),
                           ("max_contact_stress_gpa", 1e9, "max_contact_stress_pa"),
                           ("max_transmission_error_um", 1e-6, "max_transmission_error_m")):
        if key in search:
            search_si[si] = _number(search, key, "design_d_search") * scale
    designs = {}
    for name, d in data.get("designs", {}).items():
        where = f"designs.{name}"
        designs[name] = PublishedDesign(
            name, _teeth(d.get("teeth"), f"{where}.teeth"), _number(d, "normal_pressure_angle_deg", where),
            _number(d, "helix_angle_deg", where), _number(d, "working_depth", where),
            _number(d, "tip_diameter_mm", where) * 1e-3, _number(d, "root_diameter_mm", where) * 1e-3,
            _number(d, "normal_module_mm", where) * 1e-3)
    mod = dict(data.get("modification_study", {}))
    for key in ("profile_crown_um", "lead_crown_um", "input_torque_nm"):
        if key in mod:
            mod[key] = _values(mod[key], f"modification_study.{key}")
    study = data.get("study", {})
    count = sweep.get("paper_feasible_count")
    return PaperStudy(str(study.get("name", Path(path).stem)), str(study.get("source", "")), space, operating,
                      limits, search_si, mod, designs, None if count is None else int(count))
