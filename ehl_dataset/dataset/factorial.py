"""Factorial plans of contact conditions: load a TOML plan, validate it, expand it to points, hash it.

A factorial is data (``data/factorials/*.toml``, docs/reference/dataset-format.md), written in engineering units with the unit in each key::

    name = "paper2009"
    lubricant = "atf"            # default lubricant (NAME or FILE), overridable at run time
    level = "standard"           # default accuracy level of the solver
    effects = "auto"             # "auto" (the planner decides) or "full"
    model = "auto"               # default contact model, one of ehl_dataset.solver.MODELS (optional)

    [axes]
    p_h_gpa = [0.5, 1.0]         # maximum Hertz pressure [GPa]
    r_eq_mm = [5, 10]            # equivalent radius [mm]
    u_r_m_s = [1, 2]             # rolling (entrainment) velocity [m/s]
    sr = [0, 0.5]                # slide-to-roll ratio [-]
    temp_c = [25, 100]           # oil inlet temperature [°C]
    roughness_um = [[0.1, 0.1], [0.2, 0.5]]   # (Rq1, Rq2) pairs [µm]

The full tensor product is expanded in C order: the first axis (``p_h_gpa``) varies slowest, the roughness pair
fastest. Point ``i`` is therefore the same contact condition on every machine and in every run, which is what lets a
store be resumed. :meth:`Factorial.points_hash` is a SHA-256 of the expanded SI point table, so two plan files that
describe the same points (in the same order) are interchangeable, and any change of a level is detected.
"""

from __future__ import annotations

import hashlib
import json
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..data_files import resolve_named_file
from ..model.contact import CONTACT_LIMITS
from ..names import EFFECT_PLANS
from ..validation import InputError

CELSIUS_ZERO_K = 273.15

POINT_FIELDS: tuple[str, ...] = ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2")
"""Input columns of a point, SI units (see :data:`POINT_UNITS`)."""

POINT_UNITS: dict[str, str] = {
    "p_h": "Pa", "r_eq": "m", "u_r": "m/s", "sr": "1", "temperature": "K", "rq1": "m", "rq2": "m",
}

POINT_DTYPE = np.dtype([(name, "<f8") for name in POINT_FIELDS])

# axis key -> the input of a contact it sets, whose accepted range (ehl_dataset.model.contact.CONTACT_LIMITS) it has
_SCALAR_AXES: dict[str, str] = {"p_h_gpa": "p_h", "r_eq_mm": "r_eq", "u_r_m_s": "u_r", "sr": "sr", "temp_c": "temperature"}
_ROUGHNESS_AXIS = "roughness_um"
AXIS_KEYS: tuple[str, ...] = (*_SCALAR_AXES, _ROUGHNESS_AXIS)
_TOP_KEYS = {"name", "description", "source", "lubricant", "level", "effects", "model", "axes"}
EFFECTS_MODES = EFFECT_PLANS
"""Effect plans a dataset can be computed with (:data:`ehl_dataset.names.EFFECT_PLANS`): ``auto`` (the planner's),
``isothermal`` (the planner's without the thermal correction of the traction: the isothermal data the paper's Eq. 9
was fitted to), ``full`` (every effect)."""


@dataclass(frozen=True)
class Factorial:
    """A full factorial plan in engineering units, as written in its TOML file.

    Parameters
    ----------
    name : str
        Name of the factorial [-].
    p_h_gpa : tuple of float
        Hertz pressure levels [GPa].
    r_eq_mm : tuple of float
        Equivalent radius levels [mm].
    u_r_m_s : tuple of float
        Rolling velocity levels [m/s].
    sr : tuple of float
        Slide-to-roll ratio levels [-].
    temp_c : tuple of float
        Inlet temperature levels [°C].
    roughness_um : tuple of tuple of float
        (Rq1, Rq2) roughness pairs [µm].
    lubricant : str
        Default lubricant of the solves (shipped name or TOML file) [-].
    level : str
        Default accuracy level [-].
    effects : str
        Default effect plan [-].
    model : str
        Default contact model [-].
    description : str
        Free text [-].
    source : str
        Where the plan comes from (free text) [-].
    origin : str
        Where the definition was read from, for messages [-].
    """

    name: str
    p_h_gpa: tuple[float, ...]
    r_eq_mm: tuple[float, ...]
    u_r_m_s: tuple[float, ...]
    sr: tuple[float, ...]
    temp_c: tuple[float, ...]
    roughness_um: tuple[tuple[float, float], ...]
    lubricant: str = "atf"
    level: str = "standard"
    effects: str = "auto"
    model: str = "auto"
    description: str = ""
    source: str = ""
    origin: str = field(default="<dict>", compare=False)

    @property
    def shape(self) -> tuple[int, ...]:
        """Number of levels per axis, in expansion order."""
        return tuple(len(getattr(self, key)) for key in AXIS_KEYS)

    @property
    def size(self) -> int:
        """Number of points (product of :attr:`shape`)."""
        return math.prod(self.shape)

    def points(self) -> np.ndarray:
        """Every point of the plan in SI, in C order over :data:`AXIS_KEYS`.

        Returns
        -------
        ndarray
            Structured array of dtype :data:`POINT_DTYPE` (p_h [Pa], r_eq [m], u_r [m/s], sr [-], temperature [K], rq1,
            rq2 [m]).
        """
        grids = np.meshgrid(
            np.asarray(self.p_h_gpa) * 1e9,
            np.asarray(self.r_eq_mm) * 1e-3,
            np.asarray(self.u_r_m_s, dtype=float),
            np.asarray(self.sr, dtype=float),
            np.asarray(self.temp_c) + CELSIUS_ZERO_K,
            np.arange(len(self.roughness_um)),
            indexing="ij",
        )
        rough = np.asarray(self.roughness_um, dtype=float) * 1e-6
        out = np.empty(self.size, dtype=POINT_DTYPE)
        for name, grid in zip(POINT_FIELDS[:5], grids[:5]):
            out[name] = grid.ravel()
        pair = grids[5].ravel()
        out["rq1"] = rough[pair, 0]
        out["rq2"] = rough[pair, 1]
        return out

    def points_hash(self) -> str:
        """SHA-256 of the expanded SI point table (little-endian float64 bytes, row order included).

        Returns
        -------
        str
            Hex digest.
        """
        return hashlib.sha256(np.ascontiguousarray(self.points()).tobytes()).hexdigest()

    def to_dict(self) -> dict[str, Any]:
        """JSON-serialisable definition (the TOML structure, with the point count and hash).

        Returns
        -------
        dict
            The definition.
        """
        return {
            "name": self.name,
            "description": self.description,
            "source": self.source,
            "lubricant": self.lubricant,
            "level": self.level,
            "effects": self.effects,
            "model": self.model,
            "axes": {
                "p_h_gpa": list(self.p_h_gpa),
                "r_eq_mm": list(self.r_eq_mm),
                "u_r_m_s": list(self.u_r_m_s),
                "sr": list(self.sr),
                "temp_c": list(self.temp_c),
                "roughness_um": [list(pair) for pair in self.roughness_um],
            },
            "n_points": self.size,
            "points_sha256": self.points_hash(),
        }


def _number_list(axes: dict, key: str, where: str) -> tuple[float, ...]:
    limit = CONTACT_LIMITS[_SCALAR_AXES[key]]
    values = axes.get(key)
    name = f"{where}.{key}"
    if not isinstance(values, list) or not values:
        raise InputError(name, values if values is not None else "<missing>", "a non-empty list of numbers")
    out = []
    for i, value in enumerate(values):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InputError(f"{name}[{i}]", value, "a number")
        out.append(limit.check_engineering(f"{name}[{i}]", value))
    if len(set(out)) != len(out):
        raise InputError(name, values, "distinct levels (a repeated level would duplicate points)")
    return tuple(out)


def _roughness_pairs(axes: dict, where: str) -> tuple[tuple[float, float], ...]:
    values = axes.get(_ROUGHNESS_AXIS)
    name = f"{where}.{_ROUGHNESS_AXIS}"
    if not isinstance(values, list) or not values:
        raise InputError(name, values if values is not None else "<missing>",
                         "a non-empty list of [rq1_um, rq2_um] pairs")
    pairs = []
    for i, pair in enumerate(values):
        if not (isinstance(pair, list) and len(pair) == 2):
            raise InputError(f"{name}[{i}]", pair, "a pair [rq1_um, rq2_um]")
        for j, value in enumerate(pair):
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise InputError(f"{name}[{i}][{j}]", value, "a number")
        pairs.append((CONTACT_LIMITS["rq1"].check_engineering(f"{name}[{i}][0]", pair[0]),
                      CONTACT_LIMITS["rq2"].check_engineering(f"{name}[{i}][1]", pair[1])))
    if len(set(pairs)) != len(pairs):
        raise InputError(name, values, "distinct pairs (a repeated pair would duplicate points)")
    return tuple(pairs)


def _string(data: dict, key: str, default: str, where: str) -> str:
    value = data.get(key, default)
    if not isinstance(value, str) or (key in ("name", "lubricant", "level", "model") and not value.strip()):
        raise InputError(f"{where}{key}", value, "a non-empty string")
    return value


def factorial_from_dict(data: dict[str, Any], origin: str = "<dict>") -> Factorial:
    """Validate a parsed factorial (TOML structure, module docstring) and build a :class:`Factorial`.

    Unknown keys are rejected (a misspelt axis would otherwise be silently ignored); every error names the field.

    Parameters
    ----------
    data : dict
        The parsed TOML structure [-].
    origin : str
        Where it was read from, for messages [-].

    Returns
    -------
    Factorial
        The factorial.

    Raises
    ------
    InputError
        Naming the first bad field.
    """
    if not isinstance(data, dict):
        raise InputError("factorial", type(data).__name__, f"a table (in {origin})")
    unknown = sorted(set(data) - _TOP_KEYS - {"n_points", "points_sha256"})
    if unknown:
        raise InputError(f"factorial key {unknown[0]!r}", data[unknown[0]], f"one of {sorted(_TOP_KEYS)} in {origin}")
    axes = data.get("axes")
    if not isinstance(axes, dict):
        raise InputError("axes", axes if axes is not None else "<missing>", f"an [axes] table in {origin}")
    unknown_axes = sorted(set(axes) - set(AXIS_KEYS))
    if unknown_axes:
        raise InputError(f"axes.{unknown_axes[0]}", axes[unknown_axes[0]], f"axes named {list(AXIS_KEYS)}")
    effects = _string(data, "effects", "auto", "")
    if effects not in EFFECTS_MODES:
        raise InputError("effects", effects, f"one of {list(EFFECTS_MODES)}")
    factorial = Factorial(
        name=_string(data, "name", "", ""),
        p_h_gpa=_number_list(axes, "p_h_gpa", "axes"),
        r_eq_mm=_number_list(axes, "r_eq_mm", "axes"),
        u_r_m_s=_number_list(axes, "u_r_m_s", "axes"),
        sr=_number_list(axes, "sr", "axes"),
        temp_c=_number_list(axes, "temp_c", "axes"),
        roughness_um=_roughness_pairs(axes, "axes"),
        lubricant=_string(data, "lubricant", "atf", ""),
        level=_string(data, "level", "standard", ""),
        effects=effects,
        model=_string(data, "model", "auto", ""),
        description=_string(data, "description", "", ""),
        source=_string(data, "source", "", ""),
        origin=origin,
    )
    recorded = data.get("points_sha256")
    if recorded is not None and recorded != factorial.points_hash():
        raise InputError("points_sha256", recorded, f"the hash of the listed axes, {factorial.points_hash()}")
    return factorial


def load_factorial(name_or_path: str | Path) -> Factorial:
    """Load a factorial by shipped name (``paper2009``, ``quick``, ``smoke``) or from a TOML file.

    Parameters
    ----------
    name_or_path : str or Path
        Shipped name or TOML path [-].

    Returns
    -------
    Factorial
        The validated factorial.
    """
    path = resolve_named_file("factorials", name_or_path, ".toml")
    try:
        with open(path, "rb") as handle:
            data = tomllib.load(handle)
    except tomllib.TOMLDecodeError as err:
        raise InputError("factorial file", str(path), "a valid TOML file", str(err)) from None
    return factorial_from_dict(data, origin=str(path))


def canonical_json(value: Any) -> str:
    """Compact, key-sorted JSON: the form in which configurations are stored and compared."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False)
