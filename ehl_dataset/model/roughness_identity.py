"""Which roughness profile a result used, as a small record ``{"name": ..., "sha256": ...}``.

A shipped profile (:data:`ehl_dataset.model.roughness.PROFILES`) is named by its registry name and the sha256 of its
file; a user's profile file by its file name (no directory: records carry no machine path) and the sha256 of its
bytes. The record travels with a result: a dataset file's ``roughness`` attribute
(:mod:`ehl_dataset.dataset.store`), a coefficient file's ``roughness`` key (:mod:`surrogate.coefficients`), the
``roughness_name`` / ``roughness_sha256`` of a contact result. Files written before the record existed carry none:
:func:`describe_roughness` says "not recorded".
"""

from __future__ import annotations

from pathlib import Path

NOT_RECORDED = "not recorded"
"""What a report prints for a file that records no roughness profile."""


def roughness_identity(profile=None, path: str | Path | None = None) -> dict[str, str]:
    """The record ``{"name", "sha256"}`` of the roughness profile a solve uses.

    Parameters
    ----------
    profile : RoughnessProfile or None
        A registered profile (:func:`~ehl_dataset.model.roughness.named_profile`, which carries its name and file
        hash); None with no ``path``: the default profile every model uses when given none, recorded from its
        registry entry without reading the file (every model reads it through ``named_profile``, which refuses a
        file whose sha256 differs from the entry's) [-].
    path : str or Path, optional
        A user's profile file the profile was read from: recorded by its file name and the sha256 of its bytes [-].

    Returns
    -------
    dict
        ``name`` (registry name, or the file's name) and ``sha256`` (hex digest of the file) [-].

    Raises
    ------
    InputError
        For a profile that is neither registered nor given with its file.
    """
    from ..validation import InputError
    from .roughness import DEFAULT_PROFILE, PROFILES, file_sha256

    if path is not None:
        path = Path(path)
        return {"name": path.name, "sha256": file_sha256(path)}
    if profile is None:
        return {"name": DEFAULT_PROFILE, "sha256": PROFILES[DEFAULT_PROFILE].sha256}
    if not profile.name or not profile.sha256:
        raise InputError("roughness profile", profile.source or "<profile>",
                         "a registered profile (named_profile) or the file it was read from")
    return {"name": profile.name, "sha256": profile.sha256}


def check_roughness_record(record, where: str) -> dict[str, str] | None:
    """A recorded roughness (``{"name", "sha256"}`` or None) checked for its form.

    Parameters
    ----------
    record : dict or None
        The record as read from a file [-].
    where : str
        The key or attribute it was read from, for the error message [-].

    Returns
    -------
    dict or None
        The record (strings), or None where nothing is recorded [-].

    Raises
    ------
    InputError
        For a record that is not a table of a non-empty name and a 64-digit hex sha256.
    """
    from ..validation import InputError

    if record is None:
        return None
    name, digest = (record.get("name"), record.get("sha256")) if isinstance(record, dict) else (None, None)
    if (not isinstance(name, str) or not name or not isinstance(digest, str) or len(digest) != 64
            or any(c not in "0123456789abcdef" for c in digest)):
        raise InputError(where, record, '{"name": <profile or file name>, "sha256": <64 hex digits>}')
    return {"name": name, "sha256": digest}


def describe_roughness(record: dict | None) -> str:
    """One line naming a recorded roughness: ``name (sha256 <first 12 hex digits>...)``, or "not recorded".

    Parameters
    ----------
    record : dict or None
        ``{"name", "sha256"}`` or None [-].

    Returns
    -------
    str
        The text [-].
    """
    if not record:
        return NOT_RECORDED
    return f"{record['name']} (sha256 {record['sha256'][:12]}...)"
