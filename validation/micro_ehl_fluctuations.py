"""Why the film law is low on narrow contacts with an unsaturated traction: the micro-EHL pressure fluctuations of
the deterministic model and what they do to the Eyring shear stress (docs/explanation/mixed-regime.md).

    python validation/micro_ehl_fluctuations.py A:16 G:8 I:8 C:16

Each argument is CASE:POINTS_PER_BETA of the validation set (validation/deterministic_validation.py, short-run
options). Over the averaging window of the run and the zone |x| < 0.8a it integrates the fluid's Couette stress
θ τ0 asinh(η(p_f) u_s/(τ0 h)) (paper Eq. 7) four ways: with the time-local p_f and h (what the model computes), with
the time-mean pressure and film, with the mean pressure and the local film, and with the local pressure and the mean
film, each divided by the load W'. Also: the standard deviation of the local pressure over its time mean (median over
the zone, in p_h) and the Eyring number X_h of the planner. Writes validation/results/micro_ehl_fluctuations.json.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from deterministic_validation import CASES, LUBRICANT, options_for, run_case_specs  # noqa: E402

import ehl_dataset.solvers.deterministic as deterministic  # noqa: E402
from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.model.effects import Effects  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.model.micro_pressure import gamma_pressure_quantiles  # noqa: E402
from ehl_dataset.model.roughness import baseline_profile  # noqa: E402
from ehl_dataset.model.traction import eyring_shear_stress  # noqa: E402
from ehl_dataset.solvers.planner import dimensionless_numbers  # noqa: E402

OUT = Path(__file__).resolve().parent / "results" / "micro_ehl_fluctuations.json"
ZONE = 0.8


def analyse(name: str, n: int) -> dict:
    lubricant = load_lubricant(LUBRICANT)
    case = ContactCase.from_engineering(*CASES[name])
    state = lubricant.state(case.temperature)
    states = []
    # the validation set's roughness (its spacings are in baseline β), not the package's default profile
    result = deterministic.solve_deterministic(case, state, Effects.full(), options_for(n, False),
                                               roughness=baseline_profile(),
                                               observer=lambda t, p, h, fill: states.append((p, h, fill)))
    window = states[result.extra["average_from_step"]:]
    x = result.x / case.half_width
    zone = np.abs(x) < ZONE
    p = np.array([s[0] for s in window])[:, zone]
    h = np.array([s[1] for s in window])[:, zone]
    theta = np.array([s[2] for s in window])[:, zone]
    width = case.half_width * (x[1] - x[0])

    def mu(pressure, film):
        tau = theta * eyring_shear_stress(state.viscosity(pressure), case.u_s, film, state.tau0)
        return float(np.mean(np.sum(tau, axis=1)) * width / case.load_per_length)

    p_mean, h_mean = p.mean(axis=0), h.mean(axis=0)
    levels = gamma_pressure_quantiles(p_mean, p.std(axis=0))
    eta_levels = state.viscosity(levels.ravel()).reshape(levels.shape)
    tau_gamma = theta.mean(axis=0) * np.mean(eyring_shear_stress(eta_levels, case.u_s, h_mean[:, None], state.tau0),
                                             axis=1)
    return {"run": f"{name} beta/{n}", "model_version": deterministic.MODEL_VERSION, "mu": result.mu,
            "converged": result.converged, "eyring_number": dimensionless_numbers(case, lubricant)["eyring_number"],
            "lambda_bar": result.lambda_bar, "zone_a": ZONE,
            "couette_mu_local": mu(p, h),
            "couette_mu_mean_pressure_mean_film": mu(np.broadcast_to(p_mean, p.shape), np.broadcast_to(h_mean, h.shape)),
            "couette_mu_mean_pressure_local_film": mu(np.broadcast_to(p_mean, p.shape), h),
            "couette_mu_local_pressure_mean_film": mu(p, np.broadcast_to(h_mean, h.shape)),
            "couette_mu_gamma_pressure_mean_film": float(np.sum(tau_gamma)) * width / case.load_per_length,
            "pressure_std_over_p_h": float(np.median(p.std(axis=0))) / case.p_h,
            "film_std_over_mean": float(np.median(h.std(axis=0) / h_mean)),
            "steps": len(window)}


def main(argv=None) -> int:
    return run_case_specs("micro_ehl_fluctuations.py", argv if argv is not None else sys.argv[1:], analyse, OUT)


if __name__ == "__main__":
    raise SystemExit(main())
