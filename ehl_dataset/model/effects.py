"""The set of physical effects an EHL solve simulates (the "scene" plan), recorded with every result.

:func:`ehl_dataset.solvers.planner.plan_effects` decides it from a case's dimensionless numbers; ``Effects.full()`` forces
everything. The solver honours each flag:

* ``roughness`` — moving surface roughness R1(x − u1 t), R2(x − u2 t) and asperity contact (unified Reynolds,
  Hu & Zhu 2000). Off: smooth surfaces.
* ``transient`` — the squeeze term ∂(ρh)/∂t and time stepping. Off: steady solution.
* ``shear_thinning`` — the Eyring factor cosh(τ_m/τ0) in the Poiseuille flow coefficient (paper Eq. 1b). Off:
  Newtonian flow (traction always uses the Eyring stress).
* ``compressibility`` — Dowson–Higginson density (paper Eq. 6). Off: ρ = ρ0.
* ``thermal`` — thermal correction of the Couette traction: shear heating of the film and flash temperature of the
  surfaces (:mod:`ehl_dataset.model.thermal`), applied to the film of the isothermal solve by the steady smooth
  solver. Off: isothermal traction at the inlet temperature. The rough (transient, deterministic) solvers have no
  thermal model: :func:`ehl_dataset.solver.solve_contact` records ``thermal`` off for them, with the reason.

``thermal`` comes after ``reasons`` and defaults to False, so plans built positionally and results recorded before
the flag existed read as isothermal. ``Effects.full()`` includes it: "full" is every effect the solvers model.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any


@dataclass(frozen=True)
class Effects:
    """Which effects a solve includes, why, and whether the plan was automatic (``mode="auto"``) or forced.

    Parameters
    ----------
    roughness : bool
        Simulate the surface roughness (a mixed-regime model) [-].
    transient : bool
        Simulate the roughness moving through the contact (time-dependent) [-].
    shear_thinning : bool
        Non-Newtonian (Eyring) lubricant [-].
    compressibility : bool
        Compressible lubricant (Dowson–Higginson density) [-].
    mode : str
        How the plan was made: ``auto`` (the planner) or the name of a forced plan (``full``, ...) [-].
    reasons : dict
        Why each effect is on or off: the planner's numbers and decisions [-].
    thermal : bool
        The thermal (shear heating) correction of the traction [-].
    """

    roughness: bool = True
    transient: bool = True
    shear_thinning: bool = True
    compressibility: bool = True
    mode: str = "full"
    reasons: dict[str, Any] = field(default_factory=dict, compare=False)
    thermal: bool = False

    @classmethod
    def full(cls) -> "Effects":
        """Every effect on (``--effects full``), the thermal correction included.

        Returns
        -------
        Effects
            The plan.
        """
        return cls(True, True, True, True, "full", {"forced": "effects=full"}, thermal=True)

    @classmethod
    def smooth_steady(cls, **reasons: Any) -> "Effects":
        """Steady smooth-surface solve (still non-Newtonian and compressible).

        Parameters
        ----------
        **reasons
            Entries recorded as the plan's reasons [-].

        Returns
        -------
        Effects
            The plan.
        """
        return cls(False, False, True, True, "auto", dict(reasons))

    def to_dict(self) -> dict[str, Any]:
        """JSON-serialisable form stored with results.

        Returns
        -------
        dict
            The flags, ``mode`` and ``reasons``.
        """
        return asdict(self)
