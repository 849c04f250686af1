"""The range of a fitted friction surrogate and the one policy for inputs outside it (``surrogate predict``,
``gear evaluate --friction COEFFS``, the pipeline's design stage).

The surrogate's range is the box of its fitted data (``input_ranges`` of the coefficient file: p_h, r_eq, u_r, |SR|,
T, Rq1, Rq2). Eq. 9's power terms do not extrapolate (μ ≈ 1e14 has been met at 41 MPa), so by default every input is
clipped to that box (:class:`~surrogate.evaluate.FrictionSurrogate` with ``clip_to_fitted_ranges=True``) and the
points moved are counted per input. A result is then judged by the share of it that rests on clipped inputs:

* one contact (``surrogate predict``): clipped → the μ printed is the μ at the nearest fitted condition, not at the one
  asked for → ``valid: false`` (exit 1);
* a gear mesh: the share of the friction power loss Σ μ W |u_s| computed at points with a clipped input; above
  :data:`CLIPPED_SHARE_LIMIT` → ``valid: false``. Below it the clipped points (typically the lightly loaded ends of
  the contact lines, and the tips where |SR| exceeds the fitted SR) change the loss little and the result stands,
  with the counts reported.

``--no-clip`` evaluates the raw regression instead: every input outside the box is then an extrapolation and the
result is ``valid: false`` whatever its share (:func:`judge`).
"""

from __future__ import annotations

import numpy as np

CLIPPED_SHARE_LIMIT = 0.10
"""Largest share of a result (of the friction power loss of a mesh; of one contact: all or nothing) that may rest on
inputs clipped to the fitted ranges for the result to count as inside the surrogate's validity."""

INPUT_NAMES = ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2")


def clipped_mask(surrogate, p_h, r_eq, u_r, sr, temperature, rq1, rq2) -> np.ndarray:
    """Where at least one input lies outside the fitted ranges (where :meth:`FrictionSurrogate.clip` moves it).

    Parameters
    ----------
    surrogate : FrictionSurrogate
        The evaluator whose fitted ranges apply [-].
    p_h : array_like
        Hertz pressure [Pa].
    r_eq : array_like
        Equivalent radius of curvature [m].
    u_r : array_like
        Rolling velocity [m/s].
    sr : array_like
        Slide-to-roll ratio [-].
    temperature : array_like
        Inlet temperature [K].
    rq1 : array_like
        RMS roughness of surface 1 [m].
    rq2 : array_like
        RMS roughness of surface 2 [m].

    Returns
    -------
    ndarray of bool
        True at clipped points, shaped like the broadcast inputs.
    """
    arrays = surrogate.validate(p_h, r_eq, u_r, sr, temperature, rq1, rq2)
    clipped, _ = surrogate.clip(arrays)
    mask = np.zeros(np.shape(arrays["p_h"]), dtype=bool)
    for name in INPUT_NAMES:
        raw = np.abs(arrays[name]) if name == "sr" else arrays[name]
        mask |= clipped[name] != raw
    return mask


def clipping_note(clipped_inputs: dict[str, int], points: int, *, clipped: bool = True) -> str:
    """The sentence that reports clipped inputs, the same in every command.

    For example ``surrogate inputs clipped to the fitted ranges: p_h 76, sr 105 of 598 points``.

    Parameters
    ----------
    clipped_inputs : dict of str to int
        Points moved to the fitted range, per input [-].
    points : int
        Points evaluated [-].
    clipped : bool
        Say "clipped" (True) or "outside" (extrapolated) [-].

    Returns
    -------
    str
        The note.
    """
    moved = ", ".join(f"{k} {v}" for k, v in clipped_inputs.items() if v)
    verb = "clipped to" if clipped else "outside (extrapolated)"
    return f"surrogate inputs {verb} the fitted ranges: {moved or 'none'} of {points} point{'s' * (points != 1)}"


def judge(share: float, clipped_inputs: dict[str, int], points: int, *, clip: bool = True) -> dict:
    """The validity entry of a surrogate result.

    Parameters
    ----------
    share : float
        Share of the result (e.g. of the friction power) computed at clipped inputs [-].
    clipped_inputs : dict of str to int
        Points moved to the fitted range, per input [-].
    points : int
        Points evaluated [-].
    clip : bool
        Whether the inputs were clipped (False: Eq. 9 extrapolated, ``--no-clip``) [-].

    Returns
    -------
    dict
        ``{"check": "friction_surrogate_range", "valid", "value"`` (the share), ``"limit", "unit", "reason"}``.
    """
    note = clipping_note(clipped_inputs, points, clipped=clip)
    outside = sum(clipped_inputs.values()) > 0
    limit = CLIPPED_SHARE_LIMIT if clip else 0.0
    valid = (share <= limit) if outside else True
    if not outside:
        reason = "every input inside the fitted ranges"
    elif clip:
        reason = (f"{note}; they carry {share:.1%} of the result (limit {limit:.0%}: "
                  f"{'inside' if valid else 'outside'} the surrogate's validity)")
    else:
        reason = f"{note}; Eq. 9 extrapolated (--no-clip)"
    return {"check": "friction_surrogate_range", "valid": bool(valid), "value": float(share), "limit": limit,
            "unit": "share", "reason": reason}
