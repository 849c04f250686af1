"""The roughness profile a run's rough points take: chosen once by the coordinator, resolved once by each worker.

A run names its profile (:func:`choose_roughness`): a registered name of
:data:`ehl_dataset.model.roughness.PROFILES` or a user's profile file. What travels with every task is a small
picklable :class:`RoughnessChoice` — the name, the sha256 of the profile file and, for a user's file, its path and
length unit — never the heights. Each worker process resolves it once (:func:`resolve_choice`: reads the file,
checks its sha256 against the one chosen by the coordinator, keeps the profile), so a worker that reads another
file under that name or path refuses to solve instead of solving on it. The default profile resolves to None: the
solver then takes its own default, exactly as a run that names no profile.

A dataset file records ``choice.record`` (``{"name", "sha256"}``,
:func:`ehl_dataset.model.roughness_identity.roughness_identity`); a resume without a choice takes the profile the
file records (:func:`choice_from_record`), which for a user's file must be given again (the record carries no
path).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..validation import InputError

UNITS = ("um", "mm", "m")
"""Length units of the two columns of a user's profile file (as ``gearloss contact solve --roughness-unit``)."""

_RESOLVED: dict[tuple[str, str, str, str], object] = {}


@dataclass(frozen=True)
class RoughnessChoice:
    """The roughness profile of a run as tasks carry it (picklable, a few hundred bytes).

    Parameters
    ----------
    name : str
        Registry name (:data:`ehl_dataset.model.roughness.PROFILES`), or the file name of a user's file [-].
    sha256 : str
        Hex sha256 of the profile file's bytes [-].
    path : str
        Absolute path of a user's profile file; empty for a registered profile [-].
    unit : str
        Length unit of both columns of a user's two-column file (one of :data:`UNITS`; for a profilometer file the
        unit used when the file states none); empty for a registered profile [-].
    """

    name: str
    sha256: str
    path: str = ""
    unit: str = ""

    @property
    def registered(self) -> bool:
        """True for a shipped profile named by its registry name."""
        return not self.path

    @property
    def record(self) -> dict[str, str]:
        """``{"name", "sha256"}``, what a dataset and its coefficient file record."""
        return {"name": self.name, "sha256": self.sha256}

    @property
    def is_default(self) -> bool:
        """True for the registered default profile (the solver's own default: nothing is passed to it)."""
        from ..model.roughness import DEFAULT_PROFILE, PROFILES

        return self.registered and self.name == DEFAULT_PROFILE and self.sha256 == PROFILES[DEFAULT_PROFILE].sha256

    @property
    def option(self) -> str:
        """The command-line option that chooses this profile (``--roughness NAME`` or ``--roughness-file NAME``)."""
        return f"--roughness {self.name}" if self.registered else f"--roughness-file {self.name}"


def choose_roughness(name: str | None = None, path: str | Path | None = None,
                     unit: str = "um") -> RoughnessChoice | None:
    """The choice of ``--roughness NAME`` or ``--roughness-file FILE [--roughness-unit U]``, checked here (the file
    read and hashed, a registered file hash-checked) before anything is computed.

    Parameters
    ----------
    name : str, optional
        A registered profile name (:data:`ehl_dataset.model.roughness.PROFILES`) [-].
    path : str or Path, optional
        A user's profile file: two columns x, z (``.txt``, ``.csv``) or a profilometer format read by
        SurfaceTopography (the ``roughness`` extra) [-].
    unit : str
        Length unit of a two-column file's columns (one of :data:`UNITS`) [-].

    Returns
    -------
    RoughnessChoice or None
        The choice; None when neither ``name`` nor ``path`` is given (the default profile, recorded as before).

    Raises
    ------
    InputError
        For both given, an unknown name (listing the registered ones), an unknown unit, or a file that cannot be
        read as a profile.
    """
    from ..model.roughness import PROFILES

    if name is not None and path is not None:
        raise InputError("roughness", name, "either a registered name (--roughness) or a profile file "
                         "(--roughness-file), not both")
    if name is not None:
        if name not in PROFILES:
            raise InputError("roughness", name, f"a registered profile name, one of {sorted(PROFILES)} (a measured "
                             "profile: --roughness-file FILE)")
        choice = RoughnessChoice(name, PROFILES[name].sha256)
    elif path is not None:
        if unit not in UNITS:
            raise InputError("roughness_unit", unit, f"one of {list(UNITS)}")
        path = Path(path).resolve()
        if not path.is_file():
            raise InputError("roughness_file", str(path), "an existing profile file")
        from ..model.roughness import file_sha256

        choice = RoughnessChoice(path.name, file_sha256(path), str(path), unit)
    else:
        return None
    resolve_choice(choice)  # a file that cannot be read is refused now, not at every point
    return choice


def choice_from_record(record: dict | None, name: str | None = None, path: str | Path | None = None,
                       unit: str = "um", where: str = "the file") -> RoughnessChoice | None:
    """The profile a resume uses: the one chosen (``name`` or ``path``), else the one ``record`` names.

    Parameters
    ----------
    record : dict or None
        The roughness a dataset file records (``{"name", "sha256"}``; None for files that record none) [-].
    name : str, optional
        A registered profile name given for the resume [-].
    path : str or Path, optional
        A user's profile file given for the resume [-].
    unit : str
        Length unit of that file's columns [-].
    where : str
        The dataset file, for the error message [-].

    Returns
    -------
    RoughnessChoice or None
        The choice (whether it matches the record is checked by the store); None for a file that records no
        profile, or records the default one, when none is given.

    Raises
    ------
    InputError
        When the record names a user's profile file (it must be given again with ``--roughness-file``), or a
        registered name whose shipped file has changed since.
    """
    from ..model.roughness import PROFILES
    from ..model.roughness_identity import describe_roughness

    if name is not None or path is not None:
        return choose_roughness(name, path, unit)
    if record is None:
        return None
    entry = PROFILES.get(record["name"])
    if entry is None:
        raise InputError("roughness_file", None, f"the profile file recorded in {where} "
                         f"({describe_roughness(record)})", "its path is not recorded: give it with "
                         f"--roughness-file {record['name']}")
    if entry.sha256 != record["sha256"]:
        raise InputError("roughness", record["name"], f"the profile recorded in {where} "
                         f"({describe_roughness(record)})", f"the registered {record['name']} now has sha256 "
                         f"{entry.sha256[:12]}...; give the recorded file with --roughness-file FILE")
    choice = RoughnessChoice(record["name"], record["sha256"])
    return None if choice.is_default else choice


def recorded_option(record: dict) -> str:
    """The command-line option that chooses the profile of ``record``: ``--roughness NAME`` for a registered
    profile (the name and the registered sha256 match), else ``--roughness-file NAME``.

    Parameters
    ----------
    record : dict
        ``{"name", "sha256"}`` as a dataset records it [-].

    Returns
    -------
    str
        The option with its value [-].
    """
    from ..model.roughness import PROFILES

    entry = PROFILES.get(record["name"])
    registered = entry is not None and entry.sha256 == record["sha256"]
    return f"--roughness {record['name']}" if registered else f"--roughness-file {record['name']}"


def resolve_choice(choice: RoughnessChoice | None):
    """The profile a solve takes for ``choice``: read once per process, its sha256 checked against the choice's.

    Parameters
    ----------
    choice : RoughnessChoice or None
        The run's choice [-].

    Returns
    -------
    RoughnessProfile or None
        The profile; None for no choice or the default profile (the solver's default is used).

    Raises
    ------
    InputError
        When the file found here is not the one chosen (another sha256), or cannot be read as a profile.
    """
    if choice is None or choice.is_default:
        return None
    key = (choice.name, choice.sha256, choice.path, choice.unit)
    profile = _RESOLVED.get(key)
    if profile is not None:
        return profile
    from ..model import roughness

    if choice.registered:
        profile = roughness.named_profile(choice.name)  # checks the shipped file against its registry entry
        if profile.sha256 != choice.sha256:
            raise InputError("roughness", choice.name, f"the profile of sha256 {choice.sha256[:12]}... the run "
                             "was started with", f"the registered file has sha256 {profile.sha256[:12]}...")
    else:
        path = Path(choice.path)
        if not path.is_file():
            raise InputError("roughness_file", choice.path, f"the profile file {choice.name} (sha256 "
                             f"{choice.sha256[:12]}...) readable at this path where the point is solved")
        digest = roughness.file_sha256(path)
        if digest != choice.sha256:
            raise InputError("roughness_file", choice.path, f"the profile file of sha256 {choice.sha256[:12]}... "
                             "the run was started with", f"found sha256 {digest[:12]}...: the file changed")
        if path.suffix.lower() in roughness.TEXT_SUFFIXES:
            profile = roughness.load_profile(path, unit=choice.unit or "um")
        else:
            profile = roughness.read_topography_profile(path, unit=choice.unit or None)
    if len(_RESOLVED) >= 4:
        _RESOLVED.clear()
    _RESOLVED[key] = profile
    return profile
