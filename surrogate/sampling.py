"""Space-filling and random samples of contact conditions inside a factorial's ranges (off-grid validation, the
training design of the learned surrogate, the start of adaptive sampling).

The box of a factorial is the range of each of its axes: p_h, r_eq, u_r, |SR| and T from their levels, Rq1 and Rq2
from the first and second members of its roughness pairs. A sample point is a point of the unit cube mapped into
that box, axis by axis:

* linearly for p_h [Pa], T [K], Rq1 and Rq2 [m] (the factorial's levels are evenly spaced there);
* logarithmically for r_eq [m], u_r [m/s] and SR [-] (levels spread over decades: 1–20 m/s, 0.05–1);

so that a uniform sample of the cube is uniform in those coordinates. A factorial with an SR level 0 uses the
smallest positive level as the lower end (ln SR enters Eq. 9; SR = 0 is the pitch point, where μ W u_s = 0).
Points are returned as the structured array of the dataset store (:data:`ehl_dataset.dataset.factorial.POINT_DTYPE`,
SI units), ready for :class:`ehl_dataset.dataset.store.DatasetStore`.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass

import numpy as np

from ehl_dataset.dataset.factorial import CELSIUS_ZERO_K, POINT_DTYPE, POINT_FIELDS, Factorial
from ehl_dataset.validation import InputError

LOG_AXES = frozenset({"r_eq", "u_r", "sr"})
"""Inputs sampled uniformly in their logarithm."""

SAMPLE_KINDS = ("random", "sobol", "lhs")
"""``random``: independent uniform draws; ``sobol``: scrambled Sobol' sequence; ``lhs``: Latin hypercube."""


@dataclass(frozen=True)
class SampleBox:
    """The box of contact conditions a sample fills, per input of :data:`POINT_FIELDS` (SI).

    Parameters
    ----------
    low : dict of str to float
        Lower end per input [SI].
    high : dict of str to float
        Upper end per input [SI].
    """

    low: dict[str, float]
    high: dict[str, float]

    @classmethod
    def of_factorial(cls, factorial: Factorial) -> "SampleBox":
        """The ranges of ``factorial``'s axes (module docstring) in SI units.

        Parameters
        ----------
        factorial : Factorial
            The factorial [-].

        Returns
        -------
        SampleBox
            The box.
        """
        sr = [abs(v) for v in factorial.sr if v != 0.0]
        if not sr:
            raise InputError("factorial.sr", list(factorial.sr), "at least one non-zero slide-to-roll level")
        rough = np.asarray(factorial.roughness_um, dtype=float) * 1e-6
        low = {"p_h": min(factorial.p_h_gpa) * 1e9, "r_eq": min(factorial.r_eq_mm) * 1e-3,
               "u_r": min(factorial.u_r_m_s), "sr": min(sr), "temperature": min(factorial.temp_c) + CELSIUS_ZERO_K,
               "rq1": float(rough[:, 0].min()), "rq2": float(rough[:, 1].min())}
        high = {"p_h": max(factorial.p_h_gpa) * 1e9, "r_eq": max(factorial.r_eq_mm) * 1e-3,
                "u_r": max(factorial.u_r_m_s), "sr": max(sr), "temperature": max(factorial.temp_c) + CELSIUS_ZERO_K,
                "rq1": float(rough[:, 0].max()), "rq2": float(rough[:, 1].max())}
        if low["rq1"] <= 0.0 or low["rq2"] <= 0.0:
            raise InputError("factorial.roughness_um", list(factorial.roughness_um),
                             "positive roughness in every pair (a sample of rough contacts)")
        return cls(low, high)

    def to_dict(self) -> dict[str, list[float]]:
        """The box as ``{input: [low, high]}`` (SI).

        Returns
        -------
        dict of str to list
            Per input, its range.
        """
        return {name: [float(self.low[name]), float(self.high[name])] for name in POINT_FIELDS}

    def from_unit(self, unit: np.ndarray) -> np.ndarray:
        """Map points of the unit cube, shape (n, 7) in the order of :data:`POINT_FIELDS`, into the box.

        Parameters
        ----------
        unit : numpy.ndarray
            Coordinates in the unit cube, between 0 and 1 [-].

        Returns
        -------
        numpy.ndarray
            Structured array of dtype :data:`POINT_DTYPE` (SI units).
        """
        unit = np.asarray(unit, dtype=float)
        if unit.ndim != 2 or unit.shape[1] != len(POINT_FIELDS):
            raise InputError("unit sample", unit.shape, f"an (n, {len(POINT_FIELDS)}) array")
        out = np.empty(unit.shape[0], dtype=POINT_DTYPE)
        for j, name in enumerate(POINT_FIELDS):
            lo, hi = self.low[name], self.high[name]
            if name in LOG_AXES:
                out[name] = np.exp(np.log(lo) + unit[:, j] * (np.log(hi) - np.log(lo)))
            else:
                out[name] = lo + unit[:, j] * (hi - lo)
        return out

    def to_unit(self, points: np.ndarray) -> np.ndarray:
        """Inverse of :meth:`from_unit`: (n, 7) coordinates in the unit cube of structured SI points.

        Parameters
        ----------
        points : ndarray
            Structured array of dtype :data:`POINT_DTYPE` [SI].

        Returns
        -------
        ndarray
            Shape (n, 7), between 0 and 1 [-].
        """
        cols = []
        for name in POINT_FIELDS:
            lo, hi = self.low[name], self.high[name]
            values = np.abs(points[name]) if name == "sr" else points[name]
            if hi == lo:
                cols.append(np.zeros(len(points)))
            elif name in LOG_AXES:
                cols.append((np.log(values) - np.log(lo)) / (np.log(hi) - np.log(lo)))
            else:
                cols.append((values - lo) / (hi - lo))
        return np.column_stack(cols)


def unit_sample(n: int, kind: str = "random", seed: int = 0, *, skip: int = 0) -> np.ndarray:
    """``n`` points of the 7-dimensional unit cube.

    Parameters
    ----------
    n : int
        Number of points [-].
    kind : str
        ``random`` (independent uniform), ``sobol`` (scrambled Sobol', Owen scrambling; ``scipy.stats.qmc.Sobol``)
        or ``lhs`` (Latin hypercube, ``scipy.stats.qmc.LatinHypercube``) [-].
    seed : int
        Seed of the generator [-].
    skip : int
        Sobol' only: points of the sequence to skip first (a continuation of an earlier sample) [-].

    Returns
    -------
    numpy.ndarray
        (n, 7) coordinates in [0, 1) [-].
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError("n", n, "an integer >= 1")
    dim = len(POINT_FIELDS)
    if kind == "random":
        return np.random.default_rng(seed).random((int(n), dim))
    from scipy.stats import qmc

    if kind == "sobol":
        engine = qmc.Sobol(dim, scramble=True, seed=seed)
        if skip:
            engine.fast_forward(int(skip))
        return engine.random(int(n))
    if kind == "lhs":
        return qmc.LatinHypercube(dim, seed=seed).random(int(n))
    raise InputError("kind", kind, f"one of {list(SAMPLE_KINDS)}")


def sample_points(factorial: Factorial, n: int, *, kind: str = "random", seed: int = 0) -> np.ndarray:
    """``n`` contact conditions inside ``factorial``'s ranges (:class:`SampleBox`), as store points (SI).

    Parameters
    ----------
    factorial : Factorial
        The factorial whose axis ranges bound the sample [-].
    n : int
        Number of points [-].
    kind : str
        One of :data:`SAMPLE_KINDS` [-].
    seed : int
        Seed [-].

    Returns
    -------
    numpy.ndarray
        Structured array of dtype :data:`POINT_DTYPE` [SI].
    """
    return SampleBox.of_factorial(factorial).from_unit(unit_sample(n, kind, seed))


def points_sha256(points: np.ndarray) -> str:
    """SHA-256 of a structured point array's bytes (the ``points_sha256`` a store records).

    Parameters
    ----------
    points : ndarray
        Structured array of dtype :data:`POINT_DTYPE` [SI].

    Returns
    -------
    str
        Hex digest.
    """
    return hashlib.sha256(np.ascontiguousarray(points).tobytes()).hexdigest()


def sample_description(factorial: Factorial, points: np.ndarray, *, name: str, kind: str, seed: int,
                       purpose: str) -> dict:
    """The ``factorial`` entry a store of a sample records (a store records the plan its points came from).

    Parameters
    ----------
    factorial : Factorial
        The factorial whose ranges the sample fills [-].
    points : numpy.ndarray
        The sample (dtype :data:`POINT_DTYPE`) [SI].
    name : str
        Name of the sample (``<factorial>-offgrid``, ...) [-].
    kind : str
        Sampling kind [-].
    seed : int
        Seed [-].
    purpose : str
        What the sample is for (free text) [-].

    Returns
    -------
    dict
        JSON-ready description with ``points_sha256``.
    """
    return {"name": name, "kind": f"sample:{kind}", "seed": int(seed), "purpose": purpose,
            "within_factorial": factorial.name, "box": SampleBox.of_factorial(factorial).to_dict(),
            "log_axes": sorted(LOG_AXES), "n_points": int(points.size), "points_sha256": points_sha256(points),
            "lubricant": factorial.lubricant, "level": factorial.level, "effects": factorial.effects,
            "model": factorial.model}
