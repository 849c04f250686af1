"""Friction models inside the gear loss: EHL at every point, EHL on a grid, published formulas, the pitch point.

Smooth surfaces (Rq = 0) keep the EHL solves steady and fast (tens of ms at the ``fast`` level).
"""

import math
import warnings

import numpy as np
import pytest

from efficiency.design_io import load_study
from efficiency.friction import (SR_FLOOR, ConstantFriction, EhlFriction, EhlGridFriction, PathOfContact,
                                 PublishedFriction, barycentric_matrix, friction_from_spec, lobatto_nodes)
from efficiency.friction_accuracy import compare_friction_models, pitch_point_behaviour, pitch_region_share
from efficiency.geometry import GearPair
from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
from efficiency.modifications import Modifications
from efficiency.power_loss import contact_conditions, mesh_power_loss
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.validation import InputError
from workflows.cli import main

OIL_K = 363.15


@pytest.fixture(scope="module")
def atf():
    return load_lubricant("atf")


@pytest.fixture(scope="module")
def design_d_mesh():
    """The paper's design D at its study point (250 N·m, 4000 rpm, M_P 15 µm, M_L 12 µm), a coarse mesh."""
    pair = load_study("paper2009").design("D")
    return evaluate_mesh(pair, 250.0, 4000 * math.pi / 30,
                         Modifications(profile_crown=15e-6, lead_crown=12e-6),
                         MeshOptions(positions=6, slices=8, outputs=frozenset()))


@pytest.fixture(scope="module")
def fzg_c_mesh():
    """FZG type C spur gears (DIN ISO 14635-1), no modifications: a uniform load across the face."""
    pair = GearPair(16, 24, 4.5e-3, math.radians(20), 0.0, 14e-3, 0.1817, 0.1715, center_distance=0.0915)
    return evaluate_mesh(pair, 302.0, 2170 * math.pi / 30, options=MeshOptions(positions=6, slices=6,
                                                                                 outputs=frozenset()))


# ---------------------------------------------------------------------- interpolation
def test_barycentric_lobatto_interpolation_is_exact_for_polynomials_and_converges_geometrically():
    """Interpolation on n Chebyshev–Lobatto nodes reproduces polynomials of degree n − 1 exactly, and for an
    analytic function the error falls geometrically with n (Berrut & Trefethen 2004, §6)."""
    x = np.linspace(-0.3, 2.0, 101)
    nodes = lobatto_nodes(-0.3, 2.0, 6)
    poly = lambda t: 1.0 - 2.0 * t + 0.5 * t**3 - 0.1 * t**5
    np.testing.assert_allclose(barycentric_matrix(nodes, x) @ poly(nodes), poly(x), rtol=0, atol=1e-12)
    np.testing.assert_array_equal(barycentric_matrix(nodes, nodes), np.eye(6))
    errors = [np.abs(barycentric_matrix(lobatto_nodes(-0.3, 2.0, n), x) @ np.exp(lobatto_nodes(-0.3, 2.0, n))
                     - np.exp(x)).max() for n in (4, 6, 8)]
    assert errors[1] < 0.02 * errors[0] and errors[2] < 0.02 * errors[1]


def test_path_of_contact_reproduces_the_mesh_kinematics(design_d_mesh):
    """SR and r_eq as functions of roll distance equal the mesh's own values at every loaded point; the pitch point
    (u_s = 0) is r_b1 tan α_wt (the pair's pitch point); roll_at inverts SR on each side."""
    mesh = design_d_mesh
    cond = contact_conditions(mesh)
    loaded = cond["loaded"]
    path = PathOfContact.of(mesh.kinematics)
    s = mesh.kinematics.roll[loaded]
    np.testing.assert_allclose(path.sr(s), cond["sr"][loaded], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(path.r_eq(s), cond["r_eq"][loaded], rtol=1e-12)
    pair = load_study("paper2009").design("D")
    assert path.pitch == pytest.approx(float(pair.pitch_point), rel=1e-9)
    for side in (-1.0, 1.0):
        mask = (s - path.pitch) * side > 0
        np.testing.assert_allclose(path.roll_at(path.sr(s[mask]), side), s[mask], rtol=1e-12)


# ---------------------------------------------------------------------- EHL at every point
def test_ehl_power_is_the_sum_of_mu_w_us_and_identical_points_are_solved_once(fzg_c_mesh, atf):
    """Eq. 11a: P(φ_m) = Σ_q μ_q W_q |u_s,q| with the per-point EHL μ (an independent recomputation from the
    returned μ and the mesh); the spur pair's slices carry the same load (to round-off), so each contact line is
    solved once and its slices share that μ exactly."""
    mesh = fzg_c_mesh
    friction = EhlFriction(atf, "fast", "auto")
    result = mesh_power_loss(mesh, friction, OIL_K, 0.0, 0.0)
    loaded = mesh.loads > 0
    by_hand = np.array([sum(result.mu[m][loaded[m]] * mesh.loads[m][loaded[m]]
                            * np.abs(mesh.kinematics.u_s[m][loaded[m]])) for m in range(mesh.loads.shape[0])])
    np.testing.assert_allclose(result.power_loss_instant, by_hand, rtol=1e-12)
    assert result.power_loss == pytest.approx(by_hand.mean(), rel=1e-12)
    assert result.efficiency == pytest.approx(1 - by_hand.mean() / (302.0 * 2170 * math.pi / 30), rel=1e-12)
    lines = loaded.any(axis=2)  # (position, contact line) pairs in contact: one distinct contact each
    assert result.extra["ehl_solves"] == lines.sum() < result.extra["ehl_points"] == loaded.sum()
    assert np.all(np.ptp(np.where(loaded, result.mu, 0.0), axis=2)[lines] == 0.0)
    assert np.all((result.mu[loaded] > 0.0) & (result.mu[loaded] < atf.mu_d))


@pytest.mark.slow
def test_ehl_grid_agrees_with_per_point_ehl(atf):
    """The interpolated-EHL option against the EHL solver at every loaded point of design D (smooth, fast level):
    P within 1 % (measured 0.1–0.3 % on the full 24 × 30 mesh, docs/validation/gear.md), μ within 2 % on
    average weighted by the dissipated power, with fewer solves than loaded points."""
    pair = load_study("paper2009").design("D")
    mesh = evaluate_mesh(pair, 250.0, 4000 * math.pi / 30, Modifications(profile_crown=15e-6, lead_crown=12e-6),
                         MeshOptions(positions=12, slices=16, outputs=frozenset()))
    per_point = mesh_power_loss(mesh, EhlFriction(atf, "fast", "auto"), OIL_K, 0.0, 0.0)
    grid = mesh_power_loss(mesh, EhlGridFriction(atf, "fast", "auto", roll_nodes=4, load_nodes=5), OIL_K, 0.0, 0.0)
    assert grid.power_loss == pytest.approx(per_point.power_loss, rel=0.01)
    loaded = mesh.loads > 0
    weight = per_point.mu[loaded] * mesh.loads[loaded] * np.abs(mesh.kinematics.u_s[loaded])
    mean_rel = np.sum(np.abs(grid.mu[loaded] / per_point.mu[loaded] - 1) * weight) / weight.sum()
    assert mean_rel < 0.02
    assert grid.extra["ehl_solves"] <= 2 * 4 * 5 + 5 < per_point.extra["ehl_solves"]


def test_ehl_grid_is_exact_at_its_nodes(design_d_mesh, atf):
    """At the grid's node values the interpolant returns the solver's μ (a limit case of the interpolation): the
    bound model's node table equals direct solves."""
    mesh = design_d_mesh
    loaded = mesh.loads > 0
    bound = EhlGridFriction(atf, "fast", "auto", roll_nodes=2, load_nodes=2).for_mesh(mesh, loaded)
    cond = contact_conditions(mesh)
    n = int(loaded.sum())
    bound(cond["p_h"][loaded], cond["r_eq"][loaded], cond["u_r"][loaded], cond["sr"][loaded], np.full(n, OIL_K),
          np.zeros(n), np.zeros(n))
    path = PathOfContact.of(mesh.kinematics)
    side = bound.grid["sides"][-1]
    s_node = path.roll_at(side["sr"][-1:], 1.0)
    direct = EhlFriction(atf, "fast", "auto")(side["p_h_pa"][-1], path.r_eq(s_node), path.u_r(s_node),
                                               side["sr"][-1], OIL_K, 0.0, 0.0)
    assert side["mu"][-1, -1] == pytest.approx(float(direct[0]), rel=1e-12)
    assert side["sr"][0] >= SR_FLOOR


# ---------------------------------------------------------------------- the pitch point
@pytest.fixture(scope="module")
def illustrative_surrogate(atf, tmp_path_factory):
    """A coefficient file fitted to a synthetic Eq. 9 table (illustrative coefficients; tests/surrogate/conftest)."""
    from ehl_dataset.model.materials import STEEL, reduced_modulus
    from surrogate.coefficients import write_coefficients
    from surrogate.evaluate import FrictionSurrogate
    from surrogate.fit import fit_surrogate
    from surrogate.synthetic import SMALL_LEVELS, eq9_table, factorial_inputs, reference_coefficients

    e_red = reduced_modulus(STEEL, STEEL)
    table = eq9_table(factorial_inputs(SMALL_LEVELS), reference_coefficients(atf, e_red), atf, e_red,
                      noise_sd=0.05, seed=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit = fit_surrogate(table, atf, e_red, allow_unstable=True, blend_half_width=0.1)
        path = write_coefficients(fit, tmp_path_factory.mktemp("coef") / "eq9.json", source={"path": "synthetic"})
        return FrictionSurrogate.load(path)


@pytest.mark.parametrize("name", ["constant", "xu2007", "benedict_kelley", "iso14179", "surrogate", "ehl"])
def test_every_friction_model_is_finite_at_the_pitch_point_and_dissipates_nothing_there(name, atf,
                                                                                         illustrative_surrogate):
    """SR → 0 (pitch point): μ finite and ≥ 0 for every model (the surrogate floors SR, Benedict & Kelley is capped
    at μ_d, Xu's |SR|^1.04 → 0), and the friction power per unit load μ |u_s| = μ SR u_r vanishes with SR
    (exactly 0 at SR = 0, and ≤ 1 % of its SR = 0.05 value at SR = 1e-4)."""
    models = {"constant": ConstantFriction(0.05), "xu2007": PublishedFriction("xu2007", atf),
              "benedict_kelley": PublishedFriction("benedict_kelley", atf),
              "iso14179": PublishedFriction("iso14179", atf), "surrogate": illustrative_surrogate,
              "ehl": EhlFriction(atf, "fast", "auto")}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the illustrative surrogate extrapolates in r_eq
        out = pitch_point_behaviour(models[name], 1.0e9, 0.0124, 10.0, OIL_K, 0.4e-6 if name != "ehl" else 0.0,
                                    0.4e-6 if name != "ehl" else 0.0, sr_values=(0.0, 1e-4, 0.05))
    assert out["finite"]
    power = out["power_per_load_w_per_n"]
    assert power[0] == 0.0
    assert power[1] <= 0.01 * power[2]


def test_pitch_region_carries_a_small_share_of_the_loss(design_d_mesh, atf):
    """Design D with Xu's formula: the points with SR ≤ 0.02 dissipate a small share of P (μ W |u_s| → 0 there).
    Bound: with μ ≤ μ_max and SR ≤ 0.02 the share is at most 0.02 μ_max ΣW_near / (μ_min SR_mean ΣW) — here
    measured against 5 %."""
    result = mesh_power_loss(design_d_mesh, PublishedFriction("xu2007", atf), OIL_K, 0.4e-6, 0.4e-6)
    share = pitch_region_share(result, design_d_mesh, 0.02)
    assert 0.0 < share < 0.05
    assert pitch_region_share(result, design_d_mesh, 10.0) == pytest.approx(1.0)


# ---------------------------------------------------------------------- comparison and names
def test_compare_friction_models_errors_follow_the_linearity_of_eq_11(fzg_c_mesh):
    """P is linear in μ (Eq. 11): constant 0.1 against constant 0.05 is +100 %; a model that cannot be evaluated
    gets a row with its error and NaN numbers."""
    def broken(*args):
        raise InputError("friction model output", "nan", "finite")

    rows = compare_friction_models(fzg_c_mesh, {"ref": ConstantFriction(0.05), "double": ConstantFriction(0.1),
                                                "broken": broken}, OIL_K, 0.4e-6, 0.4e-6, reference="ref")
    by = {r.name: r for r in rows}
    assert math.isnan(by["ref"].rel_error)
    assert by["double"].rel_error == pytest.approx(1.0, rel=1e-12)
    assert by["double"].mu_mean == pytest.approx(0.1, rel=1e-12)
    assert math.isnan(by["broken"].power_loss_w) and "friction model output" in by["broken"].error
    with pytest.raises(InputError, match="reference"):
        compare_friction_models(fzg_c_mesh, {"a": ConstantFriction(0.05)}, OIL_K, 0.0, 0.0, reference="b")


def test_friction_from_name(atf):
    model = friction_from_spec("ehl:standard:full", atf)
    assert isinstance(model, EhlFriction) and (model.level, model.effects) == ("standard", "full")
    grid = friction_from_spec("ehl-grid:fast:3x4", "atf")
    assert isinstance(grid, EhlGridFriction) and (grid.roll_nodes, grid.load_nodes) == (3, 4)
    assert friction_from_spec("constant:0.07").mu == 0.07
    assert isinstance(friction_from_spec("xu2007", atf), PublishedFriction)
    for bad in ("ehl:coarse", "ehl-grid:fast:3by4", "ehl:fast:auto:9", "ehl-grid:fast:1x4", "constant:2"):
        with pytest.raises(InputError):
            friction_from_spec(bad, atf)


# ---------------------------------------------------------------------- CLI
DESIGN_D = ["gear", "evaluate", "--teeth", "32", "--pressure-angle-deg", "30", "--helix-angle-deg", "19",
            "--working-depth", "2.068", "--profile-crown-um", "15", "--lead-crown-um", "12", "--positions", "8",
            "--slices", "10", "--outputs", ""]


def _json(capsys, argv):
    import json

    code = main(argv + ["--json"])
    return code, json.loads(capsys.readouterr().out)


def test_cli_power_loss_only_when_asked(capsys):
    """Without --friction nothing about power is computed; with it the JSON carries P, η and P(φ_m) per position,
    and P equals mesh_power_loss on the same mesh (xu2007, ATF at 90 °C, Rq 0.4 µm); η = 1 − P/(T ω)."""
    code, plain = _json(capsys, DESIGN_D)
    assert code == 0 and not any(k.startswith("power_loss") or k == "efficiency" for k in plain)
    code, out = _json(capsys, DESIGN_D + ["--friction", "xu2007", "--oil-temp-c", "90", "--rq-um", "0.4"])
    assert code == 0
    assert len(out["power_loss_instant_w"]) == 8
    assert out["power_loss_w"] == pytest.approx(np.mean(out["power_loss_instant_w"]), rel=1e-12)
    input_power = 250.0 * 4000 * math.pi / 30
    assert out["efficiency"] == pytest.approx(1 - out["power_loss_w"] / input_power, rel=1e-12)
    pair = load_study("paper2009").design("D")
    mesh = evaluate_mesh(pair, 250.0, 4000 * math.pi / 30, Modifications(profile_crown=15e-6, lead_crown=12e-6),
                         MeshOptions(positions=8, slices=10, outputs=frozenset()))
    direct = mesh_power_loss(mesh, PublishedFriction("xu2007", load_lubricant("atf")), OIL_K, 0.4e-6, 0.4e-6)
    assert out["power_loss_w"] == pytest.approx(direct.power_loss, rel=1e-9)
    assert out["power_loss_instant_min_w"] <= out["power_loss_w"] <= out["power_loss_instant_max_w"]


def test_cli_power_loss_human_output_and_bad_input(capsys):
    assert main(DESIGN_D + ["--friction", "constant:0.05", "--rq-um", "0.3", "0.5"]) == 0
    text = capsys.readouterr().out
    assert "power loss P =" in text and "Rq 0.3/0.5 µm" in text and "instantaneous P(φ)" in text
    assert main(DESIGN_D + ["--friction", "constant:0.05", "--rq-um", "-1"]) == 2
    assert "rq-um" in capsys.readouterr().err
    assert main(DESIGN_D + ["--friction", "constant:0.05", "--rq-um", "0.1", "0.2", "0.3"]) == 2
    assert main(DESIGN_D + ["--friction", "ehl:turbo"]) == 2
    assert "friction" in capsys.readouterr().err


def test_cli_reports_the_surrogates_clipped_inputs(capsys):
    """A coefficient file (atf_quick) is held inside its fitted ranges by the surrogate's own clipping; the JSON
    says at how many of the loaded points each input was clipped (the lightly loaded tooth ends lie below the
    fitted 0.5 GPa), and a constant μ reports nothing of the kind."""
    code, out = _json(capsys, DESIGN_D + ["--friction", "atf_quick"])
    assert code == 0
    counts = out["friction_clipped_inputs"]
    assert set(counts) == {"p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2"}
    assert 0 < counts["p_h"] < out["friction_points"]
    assert any("clipped to its fitted ranges" in w for w in out["friction_warnings"])
    code, constant = _json(capsys, DESIGN_D + ["--friction", "constant:0.05"])
    assert code == 0 and "friction_clipped_inputs" not in constant


def test_ehl_friction_takes_the_roughness_profile_and_the_pressure_spread(atf):
    """A rough gear contact below λ̄ 1 (1.2 GPa, 10 mm, 3 m/s, SR 0.3, 90 °C, Rq 0.3 µm): the EHL friction model
    passes the flanks' profile and the spread form to the contact solve, so each gives the μ of
    ``solve_contact`` with the same choices (the asperity-closure route of the planner), and they differ from each other;
    a bad form is one InputError naming it."""
    from ehl_dataset.model.contact import ContactCase
    from ehl_dataset.model.roughness import baseline_profile, named_profile
    from ehl_dataset.solver import solve_contact
    from ehl_dataset.solvers.homogenised import HomogenisedOptions

    flank = named_profile("flank_ground")
    args = (1.2e9, 10e-3, 3.0, 0.3, OIL_K, 0.3e-6, 0.3e-6)
    case = ContactCase(*args)
    values = {}
    for name, roughness, form in (("baseline", baseline_profile(), "inlet"), ("flank", None, "inlet"),
                                  ("flank spectral", None, "spectral")):
        mu = float(EhlFriction(atf, "fast", roughness=roughness, fluctuations=form)(*args))
        direct = solve_contact(case, atf, "fast", roughness=roughness,
                               homogenised=HomogenisedOptions(fluctuations=form))
        assert direct.extra["closure"] == "asperity" and mu == direct.mu
        values[name] = mu
    assert len(set(values.values())) == 3
    grid = EhlGridFriction(atf, "fast", roughness=flank, fluctuations="spectral")
    assert "roughness=flank_ground" in grid.describe() and "fluctuations=spectral" in grid.describe()
    with pytest.raises(InputError, match="fluctuations"):
        EhlGridFriction(atf, "fast", fluctuations="other")
