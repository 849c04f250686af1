"""Reading a friction dataset for fitting: the HDF5 store of stage 1, or a CSV table with the same columns.

This is the only IO of the surrogate stage besides coefficient files. HDF5 files carry their lubricant and solver
configuration (:func:`ehl_dataset.dataset.store.read_metadata`); a CSV table needs the lubricant from the caller. The
contacts of stage 1 use the default materials (steel on steel, E = 206 GPa, ν = 0.3) unless the solver
configuration records ``e_reduced_pa``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from ehl_dataset.model.lubricant import Lubricant, load_lubricant, lubricant_from_dict
from ehl_dataset.model.materials import STEEL, reduced_modulus
from ehl_dataset.validation import InputError

from .coefficients import file_sha256

HDF5_SUFFIXES = (".h5", ".hdf5")


@dataclass
class Dataset:
    """A table of contact results (SI columns of the store), its lubricant, E' and provenance.

    Parameters
    ----------
    table : pandas.DataFrame
        One row per contact, columns of the HDF5 store in SI units [-].
    lubricant : Lubricant
        The lubricant of the dataset [-].
    e_reduced : float
        Reduced modulus E' of the contacts [Pa].
    source : dict
        Provenance: file path, its hash, solver version and level [-].
    roughness : dict or None
        The roughness profile the dataset's rough points used, ``{"name", "sha256"}`` as the HDF5 file records it
        (:mod:`ehl_dataset.model.roughness_identity`); None where not recorded (older files, CSV tables) [-].
    """

    table: pd.DataFrame
    lubricant: Lubricant
    e_reduced: float
    source: dict[str, Any]
    roughness: dict[str, str] | None = None


def load_dataset(path: str | Path, lubricant: str | Path | Lubricant | None = None) -> Dataset:
    """Load every row of an HDF5 dataset or a CSV table (all statuses: the fit counts what it excludes).

    Parameters
    ----------
    path : str or Path
        HDF5 dataset file written by the stage-1 runner, or a CSV table with the same columns [-].
    lubricant : str or Path or Lubricant, optional
        The dataset's lubricant (shipped name, TOML path or object); default the one recorded in the file [-].

    Returns
    -------
    Dataset
        The table (SI columns), its lubricant, E' and provenance.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("dataset", str(path), "an existing HDF5 (.h5) dataset file or a CSV table")
    source: dict[str, Any] = {"path": path.name, "sha256": file_sha256(path)}  # the name: no machine path
    roughness = None
    if path.suffix.lower() in HDF5_SUFFIXES:
        from ehl_dataset.dataset.store import read_metadata, read_table

        meta = read_metadata(path)
        table = read_table(path, status=None)
        lub = lubricant_from_dict(meta["lubricant"], origin=f"{path} [lubricant]")
        if lubricant is not None:
            raise InputError("lubricant", str(lubricant), "no --lubricant for an HDF5 dataset (it records its own)")
        solver = meta.get("solver") or {}
        e_reduced = float(solver.get("e_reduced_pa", reduced_modulus(STEEL, STEEL)))
        source.update(format="hdf5", n_points=int(meta["n_points"]), counts=meta.get("counts"),
                      accuracy_level=solver.get("level"), effects=solver.get("effects"),
                      solver_version=solver.get("version"),
                      factorial=(meta.get("factorial") or {}).get("name"), created=meta.get("created"),
                      git_revision=meta.get("git_revision"), dataset_package_version=meta.get("package_version"))
        roughness = meta.get("roughness")
    elif path.suffix.lower() == ".csv":
        try:
            table = pd.read_csv(path)
        except (pd.errors.ParserError, UnicodeDecodeError) as err:
            raise InputError("dataset", str(path), "a readable CSV table", str(err)) from None
        lub = lubricant if isinstance(lubricant, Lubricant) else load_lubricant(lubricant or "atf")
        e_reduced = reduced_modulus(STEEL, STEEL)
        levels = sorted(set(table["level"].astype(str))) if "level" in table.columns else []
        source.update(format="csv", n_points=int(len(table)), accuracy_level=",".join(levels) or None)
    else:
        raise InputError("dataset", str(path), f"a file ending in {HDF5_SUFFIXES} or .csv")
    return Dataset(table, lub, e_reduced, source, roughness)
