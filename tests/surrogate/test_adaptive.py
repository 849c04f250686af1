"""Adaptive sampling and the off-grid sample, with a cheap stand-in solver (the workflow, not the EHL physics)."""

import math
import warnings

import numpy as np
import pytest

from ehl_dataset.dataset.factorial import load_factorial
from ehl_dataset.dataset.store import DatasetStore, read_metadata, read_table
from ehl_dataset.model.film_formulas import dowson_higginson_min_film
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solvers.result import ContactResult
from surrogate.sampling import SampleBox, sample_points
from workflows.adaptive import run_adaptive
from workflows.sample_runs import offgrid_points, run_sample


def film_solve(case, lubricant, level="fast", effects="auto"):
    """μ = μ_d/(1 + λ̄) + 0.01 asinh(SR) with the Dowson–Higginson λ̄: smooth, cheap, the solver's signature."""
    state = lubricant.state(case.temperature)
    h = float(dowson_higginson_min_film(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                        case.load_per_length))
    lam = h / case.s_c
    mu = state.mu_d / (1.0 + lam) + 0.01 * math.asinh(case.sr)
    return ContactResult(mu=mu, h_min=h, h_central=4.0 / 3.0 * h, p_max=case.p_h, converged=True, iterations=1,
                         wall_time=1e-3, level=level, effects={"mode": effects, "reasons": {}}, lambda_bar=lam,
                         asperity_load_share=0.0)


ROUTE = {"level": "fast", "effects": "isothermal", "model": "auto", "workers": 0, "progress": "none",
         "solver": film_solve}


def test_sample_fills_the_factorial_box():
    quick = load_factorial("quick")
    box = SampleBox.of_factorial(quick)
    points = sample_points(quick, 2000, kind="random", seed=1)
    for name in ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2"):
        assert box.low[name] <= points[name].min() and points[name].max() <= box.high[name]
    unit = box.to_unit(points)
    np.testing.assert_allclose(box.to_unit(box.from_unit(unit)), unit, atol=1e-12)
    # log axes: half of the speeds below the geometric mean of 1 and 20 m/s (uniform in ln u_r)
    assert abs(np.mean(points["u_r"] < math.sqrt(20.0)) - 0.5) < 0.05


def test_offgrid_sample_is_resumable(tmp_path):
    quick = load_factorial("quick")
    points, desc = offgrid_points(quick, 30, seed=5)
    first = run_sample(tmp_path / "off.h5", points, desc, lubricant=load_lubricant("atf"), **ROUTE)
    again = run_sample(tmp_path / "off.h5", points, desc, lubricant=load_lubricant("atf"), **ROUTE)
    assert first.computed == 30 and again.computed == 0 and again.ok == 30
    assert read_metadata(tmp_path / "off.h5")["factorial"]["kind"] == "sample:random"


def test_adaptive_design_spends_the_budget_in_batches_and_resumes_with_the_same_points(tmp_path):
    quick = load_factorial("quick")
    atf = load_lubricant("atf")
    points, desc = offgrid_points(quick, 40, seed=5)
    run_sample(tmp_path / "offgrid.h5", points, desc, lubricant=atf, **ROUTE)
    offgrid = read_table(tmp_path / "offgrid.h5")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = run_adaptive(tmp_path / "run", quick, atf, budget=56, initial=32, batch=12, offgrid_table=offgrid,
                              **{k: v for k, v in ROUTE.items()})
    assert result.solves == 56 and result.stopped == "budget spent"
    assert [r["solves"] for r in result.rounds] == [32, 44, 56]
    assert all("offgrid_median_rel_err_mu" in r for r in result.rounds)
    batches = sorted((tmp_path / "run" / "adaptive").glob("batch_*.h5"))
    assert len(batches) == 3
    with DatasetStore.open(batches[1]) as store:
        chosen = store.points()
    # the chosen points lie in the factorial's box
    box = SampleBox.of_factorial(quick)
    assert np.all((chosen["p_h"] >= box.low["p_h"]) & (chosen["p_h"] <= box.high["p_h"]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        again = run_adaptive(tmp_path / "run", quick, atf, budget=56, initial=32, batch=12, offgrid_table=offgrid,
                             **ROUTE)
    assert again.solves == 56 and [r["solves"] for r in again.rounds] == [32, 44, 56]
    assert all(read_metadata(b)["counts"]["pending"] == 0 for b in batches)
    with DatasetStore.open(batches[1]) as store:
        assert np.array_equal(store.points(), chosen)


def test_adaptive_design_stops_at_the_target(tmp_path):
    quick = load_factorial("quick")
    atf = load_lubricant("atf")
    points, desc = offgrid_points(quick, 40, seed=5)
    run_sample(tmp_path / "offgrid.h5", points, desc, lubricant=atf, **ROUTE)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = run_adaptive(tmp_path / "run", quick, atf, budget=200, initial=32, batch=12,
                              offgrid_table=read_table(tmp_path / "offgrid.h5"), target_median=1.0, target_p90=1.0,
                              **ROUTE)
    assert result.solves == 32 and result.stopped == "off-grid target met"


@pytest.mark.parametrize("budget, initial", [(10, 32), (0, 20)])
def test_adaptive_rejects_a_budget_below_the_start(tmp_path, budget, initial):
    from ehl_dataset.validation import InputError

    with pytest.raises(InputError, match="budget"):
        run_adaptive(tmp_path, load_factorial("quick"), load_lubricant("atf"), budget=budget, initial=initial,
                     **ROUTE)


def test_initial_and_batch_options_reach_the_adaptive_design(monkeypatch, tmp_path):
    """`lubricant fit --adaptive --initial N --batch M`: the sizes reach run_adaptive (in the paper factorial's box a
    Sobol' start of 1,024 met the whole grid's off-grid error on its own, docs/validation/surrogate-off-grid.md);
    without --adaptive they are refused by name, and the defaults stay those of workflows.adaptive."""
    import argparse

    from ehl_dataset.validation import InputError
    from workflows import adaptive, surrogate_stage
    from workflows.cli_fit_lines import add_form_options, form_arguments

    parser = argparse.ArgumentParser()
    add_form_options(parser, adaptive=True)
    chosen = form_arguments(parser.parse_args(["--adaptive", "--budget", "4200", "--initial", "1024", "--batch",
                                               "640"]), 42000)
    assert (chosen["adaptive_budget"], chosen["adaptive_initial"], chosen["adaptive_batch"]) == (4200, 1024, 640)
    assert "adaptive_initial" not in form_arguments(parser.parse_args(["--adaptive"]), 42000)
    with pytest.raises(InputError, match="initial"):
        form_arguments(parser.parse_args(["--initial", "1024"]), 42000)
    with pytest.raises(InputError, match="initial"):
        form_arguments(parser.parse_args(["--adaptive", "--initial", "8"]), 42000)

    seen = []

    def fake_run_adaptive(out_dir, factorial, lubricant, **kwargs):
        seen.append((kwargs["initial"], kwargs["batch"]))
        return adaptive.AdaptiveResult(table=None)

    monkeypatch.setattr(adaptive, "run_adaptive", fake_run_adaptive)
    route = {"level": "fast", "effects": "isothermal", "model": "auto"}
    quick, atf = load_factorial("quick"), load_lubricant("atf")
    surrogate_stage.adaptive_stage(tmp_path, quick, atf, budget=200, initial=64, batch=16, **route)
    surrogate_stage.adaptive_stage(tmp_path, quick, atf, budget=200, **route)
    assert seen == [(64, 16), (adaptive.INITIAL_POINTS, adaptive.BATCH_POINTS)]
