"""The range in which a loaded mesh cycle (and its power loss) is a result, and the checks that say so.

The load distribution (:mod:`efficiency.mesh_cycle`) is linear elastic with small deflections: teeth are elastic
beams and Hertzian half-spaces, loaded along the theoretical lines of contact. It keeps computing far outside that —
at 1e6 N·m on design D it "converges" to σ_c ≈ 83 GPa, σ_b ≈ 2 TPa and a 44 mm approach — so every result is checked
against three stated limits (:class:`ValidityLimits`; the defaults are for case-carburised gear steel, the material
of Li & Kahraman 2009's gears):

* ``contact_pressure``: max Hertz pressure σ_c ≤ 0.6 × the flank hardness. First yield below the surface of an
  elastic line contact at p_0 = 1.79 Y (von Mises; Johnson, *Contact Mechanics*, 1985, §4.2(d)), with hardness
  H ≈ 2.8–3 Y (Tabor) → p_0 ≈ 0.6 H; beyond it the contact is elastic-plastic. Case-carburised flanks of 58–62 HRC
  have HV ≈ 700, H = 6.9 GPa → σ_c ≤ 4.1 GPa.
* ``root_stress``: max root stress σ_b ≤ the static bending strength of the tooth, σ_FE · Y_NT,static =
  1000 MPa × 2.5 = 2.5 GPa (ISO 6336-3 and -5: case-carburised, quality MQ, σ_FE = 2 σ_Flim = 1000 MPa, life
  factor 2.5 for a single load): above it the tooth breaks.
* ``deflection``: max normal approach δ ≤ 5 % of the normal module: the model loads the teeth along their
  unloaded lines of contact; larger deflections bring tooth pairs into contact outside the theoretical path of
  contact (corner contact at the tips), which it does not represent.

:func:`mesh_checks` returns one entry per check (``check``, ``valid``, ``value``, ``limit``, ``unit``, ``reason``);
:func:`friction_checks` adds the surrogate's range (:mod:`surrogate.validity`) for a power loss computed with a
coefficient file. A result is valid when every entry is (:func:`summarize`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

HARDNESS_CASE_CARBURISED_PA = 700 * 9.80665e6
"""Vickers hardness HV 700 (58-62 HRC, case-carburised flanks) as a pressure [Pa] (1 kgf/mm² = 9.80665 MPa)."""


@dataclass(frozen=True)
class ValidityLimits:
    """The limits of a loaded mesh result (module docstring).

    Parameters
    ----------
    hardness_pa : float
        Flank hardness [Pa].
    contact_pressure_factor : float
        Multiple of the hardness that σ_c may reach [-].
    root_strength_pa : float
        Static bending strength of the root [Pa].
    approach_module_fraction : float
        Largest normal approach as a fraction of m_n [-].
    """

    hardness_pa: float = HARDNESS_CASE_CARBURISED_PA
    contact_pressure_factor: float = 0.6
    root_strength_pa: float = 2.5e9
    approach_module_fraction: float = 0.05

    @property
    def contact_pressure_limit_pa(self) -> float:
        return self.contact_pressure_factor * self.hardness_pa


DEFAULT_LIMITS = ValidityLimits()


def _entry(check: str, value: float, limit: float, unit: str, reason: str) -> dict:
    valid = bool(np.isfinite(value) and value <= limit)
    return {"check": check, "valid": valid, "value": float(value), "limit": float(limit), "unit": unit,
            "reason": reason}


def mesh_checks(mesh, pair, limits: ValidityLimits = DEFAULT_LIMITS) -> list[dict]:
    """The checks of a loaded mesh of ``pair``: σ_c and σ_b (only when the mesh computed stresses) and the approach.

    Parameters
    ----------
    mesh : MeshCycleResult
        The loaded mesh [-].
    pair : GearPair
        The pair [-].
    limits : ValidityLimits
        The limits [-].

    Returns
    -------
    list of dict
        One entry per check: ``check``, ``valid``, ``value``, ``limit``, ``unit``, ``reason``.
    """
    out = []
    if mesh.sigma_c_max is not None:
        out.append(_entry("contact_pressure", mesh.sigma_c_max, limits.contact_pressure_limit_pa, "Pa",
                          f"max contact pressure σ_c {mesh.sigma_c_max / 1e9:.3g} GPa against "
                          f"{limits.contact_pressure_factor:g} × flank hardness = "
                          f"{limits.contact_pressure_limit_pa / 1e9:.3g} GPa (first subsurface yield)"))
    if mesh.sigma_b_max is not None:
        out.append(_entry("root_stress", mesh.sigma_b_max, limits.root_strength_pa, "Pa",
                          f"max root stress σ_b {mesh.sigma_b_max / 1e6:.4g} MPa against the static bending "
                          f"strength {limits.root_strength_pa / 1e6:.4g} MPa"))
    if not np.all(np.isfinite(mesh.approach)):  # rigid teeth (load_sharing="rigid-uniform"): no deflection
        return out
    approach = float(np.max(np.abs(mesh.approach)))
    limit = limits.approach_module_fraction * pair.normal_module
    out.append(_entry("deflection", approach, limit, "m",
                      f"max normal approach {approach * 1e6:.4g} µm against {limits.approach_module_fraction:.0%} "
                      f"of the normal module = {limit * 1e6:.4g} µm (small deflections)"))
    return out


def friction_checks(loss, mesh, friction, temperature: float, rq1: float, rq2: float, *,
                    clip: bool = True) -> list[dict]:
    """The surrogate-range check of a power loss: the share of the friction power loss at points with an input outside
    the fitted ranges (:func:`surrogate.validity.judge`); empty unless ``friction`` is a coefficient file's surrogate.

    Parameters
    ----------
    loss : PowerLossResult
        The power loss [-].
    mesh : MeshCycleResult
        The mesh it was computed on [-].
    friction : callable
        The friction model used [-].
    temperature : float
        Oil inlet temperature [K].
    rq1 : float
        RMS roughness of gear 1's flanks [m].
    rq2 : float
        RMS roughness of gear 2's flanks [m].
    clip : bool
        Whether the surrogate clipped its inputs (False: it extrapolated) [-].

    Returns
    -------
    list of dict
        The check entries.
    """
    if not hasattr(friction, "coefficients") or not hasattr(friction, "clip"):
        return []
    from surrogate.validity import clipped_mask, judge

    from .power_loss import contact_conditions

    cond = contact_conditions(mesh)
    loaded = cond["loaded"]
    n = int(loaded.sum())
    mask = clipped_mask(friction, cond["p_h"][loaded], cond["r_eq"][loaded], cond["u_r"][loaded], cond["sr"][loaded],
                        np.full(n, temperature), np.full(n, rq1), np.full(n, rq2))
    power = (np.nan_to_num(loss.mu) * mesh.loads * np.abs(mesh.kinematics.u_s))[loaded]
    total = float(power.sum())
    share = float(power[mask].sum() / total) if total > 0 else float(mask.any())
    counts = _outside_counts(friction, cond, loaded, temperature, rq1, rq2)
    return [judge(share, counts, n, clip=clip)]


def _outside_counts(friction, cond, loaded, temperature, rq1, rq2) -> dict[str, int]:
    """Per input, the loaded points outside the fitted ranges (when the surrogate did not clip)."""
    n = int(loaded.sum())
    arrays = friction.validate(cond["p_h"][loaded], cond["r_eq"][loaded], cond["u_r"][loaded], cond["sr"][loaded],
                               np.full(n, temperature), np.full(n, rq1), np.full(n, rq2))
    _, moved = friction.clip(arrays)
    return moved


def summarize(checks: list[dict]) -> tuple[bool, list[str]]:
    """Overall validity of a list of checks.

    Parameters
    ----------
    checks : list of dict
        Check entries (:func:`mesh_checks`, :func:`friction_checks`) [-].

    Returns
    -------
    tuple
        (every check valid, the reasons of those that are not).
    """
    failed = [c["reason"] for c in checks if not c["valid"]]
    return not failed, failed
