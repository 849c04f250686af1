"""Bad-input errors named as the user typed them: the option, its value as typed and the accepted range in the
option's units.

The models check their inputs in SI units under their own parameter names (``temperature=673.15 ... K``,
``helix_angle=1.5533 ... rad``). :func:`translate` maps such an :class:`~ehl_dataset.validation.InputError` back to
the command-line option it came from: ``invalid --temp-c=400: accepted [0, 150] °C for lubricant atf``. An error
that already names an option (``torque-nm``, ``time_limit_s``, ``--cases``) is given the option's ``--`` form.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from ehl_dataset.validation import InputError


@dataclass(frozen=True)
class SiOption:
    """An option (by its argparse ``dest``; the first one present in the command wins) that feeds the SI
    parameter: option value = SI value × ``scale`` + ``offset``; ``si_unit`` and ``unit`` name the two units."""

    dests: tuple[str, ...]
    scale: float = 1.0
    offset: float = 0.0
    si_unit: str = ""
    unit: str = ""


SI_PARAMETERS: dict[str, SiOption] = {
    "temperature": SiOption(("temp_c", "oil_temp_c"), 1.0, -273.15, "K", "°C"),
    "oil_temperature": SiOption(("oil_temp_c", "temp_c"), 1.0, -273.15, "K", "°C"),
    "p_h": SiOption(("p_h_gpa",), 1e-9, 0.0, "Pa", "GPa"),
    "r_eq": SiOption(("r_eq_mm",), 1e3, 0.0, "m", "mm"),
    "u_r": SiOption(("u_r",), 1.0, 0.0, "m/s", "m/s"),
    "sr": SiOption(("sr",)),
    "rq1": SiOption(("rq1_um", "rq_um"), 1e6, 0.0, "m", "µm"),
    "rq2": SiOption(("rq2_um", "rq_um"), 1e6, 0.0, "m", "µm"),
    "helix_angle": SiOption(("helix_angle_deg",), 180.0 / math.pi, 0.0, "rad", "°"),
    "normal_pressure_angle": SiOption(("pressure_angle_deg",), 180.0 / math.pi, 0.0, "rad", "°"),
    "pressure_angle": SiOption(("pressure_angle_deg",), 180.0 / math.pi, 0.0, "rad", "°"),
    "face_width": SiOption(("face_width_mm",), 1e3, 0.0, "m", "mm"),
    "normal_module": SiOption(("module_mm",), 1e3, 0.0, "m", "mm"),
    "center_distance": SiOption(("center_distance_mm",), 1e3, 0.0, "m", "mm"),
    "thickness_allowance1": SiOption(("thickness_allowance_mm",), 1e3, 0.0, "m", "mm"),
    "thickness_allowance2": SiOption(("thickness_allowance_mm",), 1e3, 0.0, "m", "mm"),
    "z1": SiOption(("teeth1", "teeth")),
    "z2": SiOption(("teeth2", "teeth")),
    "teeth": SiOption(("teeth",)),
    "working_depth": SiOption(("working_depth",)),
    "x1": SiOption(("shift1",)),
    "x2": SiOption(("shift2",)),
    "addendum_coefficient": SiOption(("addendum_coefficient",)),
    "dedendum_coefficient": SiOption(("dedendum_coefficient",)),
    "root_fillet_coefficient": SiOption(("root_fillet_coefficient",)),
    "torque": SiOption(("torque_nm",), 1.0, 0.0, "N·m", "N·m"),
    "input_torque": SiOption(("torque_nm",), 1.0, 0.0, "N·m", "N·m"),
    "speed": SiOption(("speed_rpm",), 30.0 / math.pi, 0.0, "rad/s", "rpm"),
    "input_speed": SiOption(("speed_rpm",), 30.0 / math.pi, 0.0, "rad/s", "rpm"),
    "positions": SiOption(("positions",)),
    "slices": SiOption(("slices",)),
    "contact_model": SiOption(("contact_model",)),
    "coupling_length_factor": SiOption(("coupling_length_factor",)),
    "k_folds": SiOption(("k_folds",)),
    "profile_crown": SiOption(("profile_crown_um",), 1e6, 0.0, "m", "µm"),
    "lead_crown": SiOption(("lead_crown_um",), 1e6, 0.0, "m", "µm"),
    "lead_slope": SiOption(("lead_slope_um",), 1e6, 0.0, "m", "µm"),
    "tip_relief": SiOption(("tip_relief_um",), 1e6, 0.0, "m", "µm"),
    "tip_relief_length": SiOption(("tip_relief_length_mm",), 1e3, 0.0, "m", "mm"),
    "coefficient": SiOption(("friction",)),
    "time_limit_s": SiOption(("time_limit_s",)),
    "dx_m": SiOption(("dx_um",), 1e6, 0.0, "m", "µm"),
}
"""Internal parameter names of the models → the command-line options they come from."""

_INTERVAL = re.compile(r"([\[(])\s*([-+0-9.eE]+|-?inf)\s*,\s*([-+0-9.eE]+|-?inf)\s*([\])])(\s*)([^\s,;()]*)")


def _fmt(value: float) -> str:
    return f"{value:.6g}"


def convert_accepted(accepted: str, option: SiOption) -> str:
    """The accepted text with every interval ``[a, b] SI_UNIT`` (or an interval without a unit when the
    parameter has one) converted to the option's units."""
    if option.scale == 1.0 and option.offset == 0.0 and option.si_unit == option.unit:
        return accepted

    def convert(match: re.Match) -> str:
        left, low, high, right, space, unit = match.groups()
        if unit and unit != option.si_unit:
            return match.group(0)
        lo, hi = (float(v) * option.scale + option.offset for v in (low, high))
        if option.scale < 0:
            lo, hi = hi, lo
        return f"{left}{_fmt(lo)}, {_fmt(hi)}{right} {option.unit}".rstrip()

    return _INTERVAL.sub(convert, accepted)


def _flag(dest: str) -> str:
    return "--" + dest.replace("_", "-")


def _typed(value):
    """A value as the user typed it (a list of one element → the element)."""
    if isinstance(value, list) and len(value) == 1:
        return value[0]
    return value


def option_dests(args) -> set[str]:
    """The argparse destinations of a parsed command (its options)."""
    return {k for k in vars(args) if not k.startswith("_") and k not in ("handler", "argv", "command_line")}


def translate(err: InputError, args) -> InputError:
    """``err`` named by the command-line option it came from (see the module docstring); unchanged when no
    option of this command feeds the parameter."""
    parameter = str(err.parameter)
    dests = option_dests(args)
    bare = parameter.lstrip("-")
    if bare.startswith("solver.") and bare[len("solver."):] in ("level", "effects", "model", "function"):
        bare = {"function": "solver"}.get(bare[len("solver."):], bare[len("solver."):])
    dest = bare.replace("-", "_")
    if parameter.startswith("--") or (dest in dests and dest not in SI_PARAMETERS):
        if dest in dests:
            value = typed_text(getattr(args, "argv", []), _flag(dest))
            return _renamed(err, _flag(dest), err.value if value is None else value, err.accepted)
        return err
    option = SI_PARAMETERS.get(dest)
    if option is not None:
        for candidate in option.dests:
            typed = getattr(args, candidate, None)
            if candidate in dests and typed is not None:
                flag = _flag(candidate)
                value = typed_text(getattr(args, "argv", []), flag)
                if value is None:
                    value = _typed(typed)
                    if isinstance(typed, list) and len(typed) > 1 and isinstance(err.value, (int, float)):
                        value = _si_to_option(err.value, option)
                return _renamed(err, flag, value, convert_accepted(str(err.accepted), option))
    if dest in dests:
        return _renamed(err, _flag(dest), err.value, err.accepted)
    return err


class Typed(str):
    """An option's value exactly as typed (its repr is the text itself: ``--temp-c=400``, not ``'400'``)."""

    def __repr__(self) -> str:
        return str(self)

    def as_json(self):
        try:
            return int(self)
        except ValueError:
            try:
                return float(self)
            except ValueError:
                return str(self)


def typed_text(argv: list[str], flag: str) -> Typed | None:
    """The text typed after ``flag`` (``--flag VALUE`` or ``--flag=VALUE``; the last occurrence wins, as in
    argparse); None when the option takes several values or was not typed."""
    found = None
    for i, token in enumerate(argv):
        if token == flag and i + 1 < len(argv):
            if i + 2 < len(argv) and not argv[i + 2].startswith("-") and _numeric(argv[i + 2]):
                return None  # several values (nargs="+")
            found = argv[i + 1]
        elif token.startswith(flag + "="):
            found = token[len(flag) + 1:]
    return None if found is None else Typed(found)


def _numeric(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _si_to_option(value, option: SiOption):
    try:
        return float(f"{float(value) * option.scale + option.offset:.10g}")
    except (TypeError, ValueError):
        return value


def _renamed(err: InputError, option: str, value, accepted: str) -> InputError:
    detail = ""
    text = str(err)
    head = f"invalid {err.parameter}={err.value!r}: accepted {err.accepted}"
    if text.startswith(head) and len(text) > len(head):
        detail = text[len(head):].strip()
        if detail.startswith("(") and detail.endswith(")"):
            detail = detail[1:-1]
    new = InputError(option, value, accepted, detail)
    new.internal_parameter = err.parameter
    return new
