"""Can one constant calibrate the homogenised model's 1-D transverse closure against the deterministic reference?

The transverse closure's pressure conductance 1/⟨max(g, h_f)⁻³⟩ is dominated by the contact spots of the dry-contact
table, floored at h_f (docs/explanation/mixed-regime.md). With h_f = h_b = 5 nm the model entrains a film of several σ and
μ falls below the smooth value; raising the floor h_f (``HomogenisedOptions.flow_floor_sigma``, in units of σ)
weakens the blocking. This script scans h_f/σ on the deterministic cases whose finest two spacings agree within
the grid targets (validation/results/deterministic_convergence_<case>.json, model det-2026.11-6: the finest run's μ
and asperity share) and writes validation/results/homogenised_calibration.json:

    python validation/homogenised_calibration.py [--floors 0.05 0.1 0.2 0.3 0.5]
    python validation/homogenised_calibration.py --amplitude-reduction     # the second experiment below

``--amplitude-reduction``: the roughness inside the conjunction is flattened by the micro-scale fluid pressure
(Venner, Couhier, Lubrecht & Greenwood 1997: A_d/A_i = F(∇), ∇ = (λ/a)·M^¾/L^½; F = 1/(1 + 0.15∇ + 0.015∇²), the
pure-rolling line-contact fit). The script scales the roughness amplitude of the dry-contact table by the
power-weighted reduction r of the shipped profile's spectrum (elastic similarity: p_a(d) → r·p_a(d/r), gap moments
⟨g^k⟩ → r^k M_k(d/r, h_b/r)), either everywhere (``all``) or only in the asperity pressure and traction, the flow
factors keeping the undeformed roughness (``contact``), and writes homogenised_amplitude_reduction.json.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.homogenised import HomogenisedOptions, solve_homogenised
from ehl_dataset.solvers.levels import get_level

RESULTS = Path(__file__).resolve().parent / "results"
CASES = ("A", "B", "C", "D")
DEFAULT_FLOORS = (None, 0.05, 0.1, 0.15, 0.2, 0.3, 0.5, 1.0)


def reference(name: str) -> dict:
    """μ and asperity share of the finest run of the case's convergence study."""
    data = json.loads((RESULTS / f"deterministic_convergence_{name}.json").read_text())
    finest = max(data["runs"], key=int)
    run = data["runs"][finest]
    return {"inputs": data["inputs"], "model_version": data["model_version"], "points_per_beta": int(finest),
            "mu": run["mu"], "asperity_load_share": run["asperity_load_share"]}


class ScaledRoughnessTable:
    """A dry-contact table of the same roughness with its heights scaled by ``r`` (elastic similarity)."""

    def __init__(self, table, r: float):
        self.table, self.r, self.meta = table, float(r), table.meta

    @property
    def sigma(self):
        return self.table.sigma * self.r

    def asperity_pressure(self, d):
        return self.r * np.asarray(self.table.asperity_pressure(np.asarray(d) / self.r))

    def d_asperity_pressure(self, d):
        return np.asarray(self.table.d_asperity_pressure(np.asarray(d) / self.r))

    def contact_fraction(self, d):
        return self.table.contact_fraction(np.asarray(d) / self.r)

    def mean_gap(self, d, h_b=0.0):
        return self.r * np.asarray(self.table.mean_gap(np.asarray(d) / self.r, h_b / self.r))

    def d_mean_gap(self, d, h_b=0.0):
        return np.asarray(self.table.d_mean_gap(np.asarray(d) / self.r, h_b / self.r))

    def gap_moment(self, d, k, h_b, part="all"):
        return self.r**k * np.asarray(self.table.gap_moment(np.asarray(d) / self.r, k, h_b / self.r, part))

    def d_gap_moment(self, d, k, h_b, part="all"):
        return self.r**(k - 1) * np.asarray(self.table.d_gap_moment(np.asarray(d) / self.r, k, h_b / self.r, part))

    def open_gap_expectation(self, d, func, h_b=0.0):
        return self.table.open_gap_expectation(np.asarray(d) / self.r, lambda g: func(self.r * g), h_b / self.r)


def amplitude_reduction(case: ContactCase, lubricant) -> float:
    """Power-weighted amplitude reduction r of the shipped profile in the conjunction of ``case`` (module doc)."""
    from ehl_dataset.solvers.planner import dimensionless_numbers

    profile = baseline_profile()
    power = np.abs(np.fft.rfft(profile.z - profile.z.mean()))[1:] ** 2
    wavelength = 1.0 / np.fft.rfftfreq(profile.z.size, profile.spacing)[1:]
    numbers = dimensionless_numbers(case, lubricant)
    nabla = wavelength / case.half_width * numbers["moes_m"] ** 0.75 / numbers["moes_l"] ** 0.5
    factor = 1.0 / (1.0 + 0.15 * nabla + 0.015 * nabla**2)
    return float(np.sqrt(np.sum(power * factor**2) / np.sum(power)))


def amplitude_experiment(lubricant) -> list[dict]:
    from ehl_dataset.model.flow_factors import isotropic_flow_factors, transverse_flow_factors
    from ehl_dataset.solvers import homogenised

    rows = []
    original_table, original_factors = homogenised.dry_contact_table, homogenised.HomogenisedProblem.flow_factors

    def undeformed_factors(problem, h):
        d = h * problem.film_scale
        table = problem.table.table
        if problem.closure == "transverse":
            return transverse_flow_factors(table, d, problem.flow_floor_m, problem.transport)
        return isotropic_flow_factors(table, d, problem.transport)

    try:
        for name in CASES:
            ref = reference(name)
            case = ContactCase.from_engineering(*ref["inputs"])
            state = lubricant.state(case.temperature)
            r = amplitude_reduction(case, lubricant)
            homogenised.dry_contact_table = lambda *a, **k: ScaledRoughnessTable(original_table(*a, **k), r)
            for where in ("all", "contact"):
                homogenised.HomogenisedProblem.flow_factors = original_factors if where == "all" else \
                    undeformed_factors
                for closure in ("transverse", "isotropic"):
                    # the reference's (and r's) baseline profile, not the package's default
                    res = solve_homogenised(case, state, get_level("standard"), Effects.full(),
                                            roughness=baseline_profile(), closure=closure)
                    row = {"case": name, "r": r, "scaled": where, "closure": closure, "mu": res.mu,
                           "mu_reference": ref["mu"], "mu_error": res.mu / ref["mu"] - 1.0,
                           "asperity_load_share": res.asperity_load_share,
                           "share_reference": ref["asperity_load_share"], "converged": res.converged}
                    rows.append(row)
                    print(f"{name} r {r:.2f} {where} {closure}: mu {res.mu:.4f} ({100 * row['mu_error']:+.0f} %) "
                          f"share {res.asperity_load_share:.3f} (ref {ref['asperity_load_share']:.3f})", flush=True)
    finally:
        homogenised.dry_contact_table, homogenised.HomogenisedProblem.flow_factors = original_table, original_factors
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--floors", nargs="+", type=float, default=None, help="h_f/σ values (default: a scan)")
    parser.add_argument("--amplitude-reduction", action="store_true", help="the amplitude-reduction experiment")
    args = parser.parse_args(argv)
    if args.amplitude_reduction:
        rows = amplitude_experiment(load_lubricant("atf"))
        out = RESULTS / "homogenised_amplitude_reduction.json"
        out.write_text(json.dumps({"command": "python validation/homogenised_calibration.py --amplitude-reduction",
                                   "rows": rows}, indent=1))
        print(f"wrote {out}")
        return 0
    floors = args.floors or DEFAULT_FLOORS
    lubricant = load_lubricant("atf")
    rows = []
    for name in CASES:
        ref = reference(name)
        case = ContactCase.from_engineering(*ref["inputs"])
        state = lubricant.state(case.temperature)
        for closure, floor in [("transverse", f) for f in floors] + [("isotropic", None)]:
            start = time.perf_counter()
            r = solve_homogenised(case, state, get_level("standard"), Effects.full(),
                                  roughness=baseline_profile(),  # the reference's profile, not the default
                                  options=HomogenisedOptions(closure=closure, flow_floor_sigma=floor))
            inside = np.abs(r.x) < case.half_width
            row = {"case": name, "closure": closure, "flow_floor_sigma": floor, "mu": r.mu,
                   "mu_reference": ref["mu"], "mu_error": r.mu / ref["mu"] - 1.0,
                   "asperity_load_share": r.asperity_load_share, "share_reference": ref["asperity_load_share"],
                   "mean_film_hertz_m": float(np.mean(r.film[inside])), "sigma_m": case.s_c,
                   "converged": r.converged, "wall_time_s": time.perf_counter() - start,
                   "reference_points_per_beta": ref["points_per_beta"], "reference_model": ref["model_version"]}
            rows.append(row)
            print(f"{name} {closure} h_f/sigma {floor}: mu {r.mu:.4f} ({100 * row['mu_error']:+.0f} %) share "
                  f"{r.asperity_load_share:.3f} (ref {ref['asperity_load_share']:.3f}) film "
                  f"{row['mean_film_hertz_m'] * 1e9:.0f} nm", flush=True)
    out = RESULTS / "homogenised_calibration.json"
    out.write_text(json.dumps({"command": "python validation/homogenised_calibration.py", "rows": rows}, indent=1))
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
