"""The paper's §3 studies (efficiency.studies): trends of Li & Kahraman 2009, Fig. 3, 4 and 6, on small subsets of
the design space with a constant friction coefficient (μ = 0.05, a typical mixed-EHL value; with μ fixed the trends
come from the gear kinematics and load sharing alone, which is what the figures' "sole influence" lines isolate)."""

import math

import numpy as np
import pandas as pd
import pytest

from ehl_dataset.validation import InputError
from efficiency.design_io import load_study
from efficiency.feasibility import count_feasible, feasibility_masks
from efficiency.friction import ConstantFriction, friction_from_spec
from efficiency.mesh_cycle import MeshOptions
from efficiency.studies import (PAPER_SEARCH_LIMITS, StudyPoint, design_pair, design_sweep, evaluate_design,
                                feasible_designs, find_design_like_d, modification_study,
                                rank_by_limits, trend_line)

MU = ConstantFriction(0.05)


@pytest.fixture(scope="module")
def study():
    return load_study("paper2009")


@pytest.fixture(scope="module")
def point(study):
    return StudyPoint.from_operating_point(study.operating_point)


def _sweep(study, point, where, **kw):
    return design_sweep(study.space, MU, point, study.limits, MeshOptions(), where=where, **kw)


# ---------------------------------------------------------------------- the feasible set and its subsets
def test_feasible_designs_match_the_feasibility_screen(study):
    """The sweep visits exactly the designs that pass the feasibility screen (count_feasible), and `where`
    selects the same designs as masking the screen's grid."""
    table = feasible_designs(study.space, study.limits)
    assert len(table) == count_feasible(study.space, study.limits)["feasible"]
    line = feasible_designs(study.space, study.limits,
                            where={"normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20.0, "working_depth": 2.286})
    phi, psi, teeth, depth = study.space.grid()
    mask = feasibility_masks(study.space.pairs(), study.limits)["feasible"]
    on_line = mask & np.isclose(np.degrees(phi), 22.5) & np.isclose(np.degrees(psi), 20.0) & np.isclose(depth, 2.286)
    assert sorted(line["teeth"]) == sorted(teeth[on_line].astype(int))
    assert list(feasible_designs(study.space, study.limits, stride=7, limit=5)["teeth"]) == \
        list(table["teeth"].iloc[::7].iloc[:5])


def test_design_pair_reproduces_table1_design_d(study):
    """A sweep row rebuilds the study's GearPair: Design D (Table 1: m = 2.7036 mm, d_o = 96.42 mm)."""
    table = feasible_designs(study.space, study.limits, where={"teeth": 32, "normal_pressure_angle_deg": 30.0,
                                                               "helix_angle_deg": 19.0, "working_depth": 2.068})
    assert len(table) == 1
    row = table.iloc[0]
    assert row["normal_module_m"] == pytest.approx(2.7036e-3, abs=5e-8)
    assert row["tip_diameter_m"] == pytest.approx(96.42e-3, abs=5e-6)
    pair = design_pair(row, study.space)
    reference = study.design("D")
    assert float(pair.tip_diameters_m[0]) == pytest.approx(float(reference.tip_diameters_m[0]), rel=1e-12)
    assert float(pair.thickness_allowance1) == pytest.approx(float(reference.thickness_allowance1), rel=1e-12)


# ---------------------------------------------------------------------- exact relations
def test_power_loss_is_linear_in_a_constant_mu_and_efficiency_is_consistent(study, point):
    """Eq. 11: P = Σ μ W |u_s| is linear in a constant μ; η = 1 − P/(T ω) (energy balance)."""
    pair = study.design("D")
    a = evaluate_design(pair, ConstantFriction(0.05), point)
    b = evaluate_design(pair, ConstantFriction(0.10), point)
    assert b["power_loss_w"] == pytest.approx(2.0 * a["power_loss_w"], rel=1e-12)
    assert a["efficiency"] == pytest.approx(1.0 - a["power_loss_w"] / (point.input_torque * point.input_speed),
                                            rel=1e-14)
    assert a["mu_mean"] == pytest.approx(0.05, rel=1e-12)
    assert a["converged"] and a["error"] == ""


# ---------------------------------------------------------------------- paper Fig. 3 and 4
def _niemann_hv(pair) -> float:
    """Niemann's tooth loss factor H_V = π (u+1)/(z1 u cos β_b) (1 − ε_α + ε_1² + ε_2²) for u = 1 (Ohlendorf 1958;
    ISO/TR 14179-2), ε_1, ε_2 the addendum contact ratios of the two gears."""
    p_bt = float(pair.transverse_base_pitch)
    pitch = float(pair.pitch_point)
    eps1 = (float(pair.contact_end) - pitch) / p_bt
    eps2 = (pitch - float(pair.contact_start)) / p_bt
    return (math.pi * 2.0 / (int(pair.z1) * math.cos(float(pair.base_helix_angle)))
            * (1.0 - float(pair.contact_ratio) + eps1**2 + eps2**2))


FIG3_LINE = {"normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20.0, "working_depth": 2.286}


def test_fig3a_power_loss_falls_with_teeth(study, point):
    """Fig. 3a/3b (Φ = 22.5°, Ψ = 20°, Λ_wd = 2.286, the study's crowns): P falls as N rises (as m falls): "P ≈
    0.6 kW for N = 20 teeth, which is reduced to half when the number of teeth is increased to 50"."""
    line = trend_line(_sweep(study, point, FIG3_LINE, stride=3), "teeth", {})
    assert len(line) >= 10
    p = line["power_loss_w"].to_numpy()
    assert np.all(np.diff(p) < 0.0)
    assert np.all(np.diff(line["normal_module_m"]) < 0.0)
    assert 0.3 < p[-1] / p[0] < 0.6  # N 20 → 53 (measured 0.37 with μ = 0.05, validation/study_trends.py)


def test_fig3a_unmodified_teeth_follow_niemann_hv(study, point):
    """Without modifications and with μ constant, the loss is μ·H_V·P_in up to a load-distribution factor that
    does not depend on N along the Fig. 3a line: P(N)/P(20) = H_V(N)/H_V(20) within 3 % (measured 2.3 %)."""
    bare = StudyPoint(point.input_torque, point.input_speed, point.oil_temperature, point.rq1, point.rq2)
    line = trend_line(design_sweep(study.space, MU, bare, study.limits, MeshOptions(), where=FIG3_LINE, stride=3),
                      "teeth", {})
    hv = np.array([_niemann_hv(design_pair(row, study.space)) for _, row in line.iterrows()])
    p = line["power_loss_w"].to_numpy()
    np.testing.assert_allclose((p / p[0]) / (hv / hv[0]), 1.0, atol=0.03)


def test_fig4a_power_loss_falls_with_pressure_angle(study, point):
    """Fig. 4a (N = 30, Ψ = 20°, Λ_wd = 2.286): "an increase in Φ helps reduce P" (0.8 → 0.4 kW for 15 → 25°)."""
    line = trend_line(_sweep(study, point, {"teeth": 30, "helix_angle_deg": 20.0, "working_depth": 2.286}),
                      "normal_pressure_angle_deg", {})
    assert list(line["normal_pressure_angle_deg"]) == [15.0, 17.5, 20.0, 22.5, 25.0, 27.5, 30.0]
    assert np.all(np.diff(line["power_loss_w"]) < 0.0)


def test_fig4b_power_loss_falls_mildly_with_helix_angle(study, point):
    """Fig. 4b (N = 30, Φ = 22.5°, Λ_wd = 2.286): increasing Ψ from 15° to 30° "reduces P by only about 20 %"."""
    line = trend_line(_sweep(study, point, {"teeth": 30, "normal_pressure_angle_deg": 22.5, "working_depth": 2.286}),
                      "helix_angle_deg", {})
    assert line["helix_angle_deg"].iloc[0] == 15.0 and line["helix_angle_deg"].iloc[-1] == 30.0
    p = line["power_loss_w"].to_numpy()
    assert np.all(np.diff(p) < 0.0)
    assert 0.10 < 1.0 - p[-1] / p[0] < 0.30


def test_fig4c_power_loss_rises_with_working_depth(study, point):
    """Fig. 4c (N = 30, Φ = 22.5°, Ψ = 20°): "a sizable increase in P with Λ_wd" (longer teeth slide more)."""
    line = trend_line(_sweep(study, point, {"teeth": 30, "normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20.0}),
                      "working_depth", {})
    assert len(line) >= 5
    assert np.all(np.diff(line["power_loss_w"]) > 0.0)
    assert np.all(np.diff(line["tip_diameter_m"]) > 0.0)  # Fig. 3c: P grows with d_o along this line


# ---------------------------------------------------------------------- paper Fig. 6
@pytest.fixture(scope="module")
def modifications(study, point):
    return modification_study(study.design("D"), MU, [0.0, 15e-6, 30e-6], [0.0, 12e-6, 30e-6], [50.0, 250.0, 500.0],
                               point)


def test_fig6a_profile_crown_reduces_power_loss_at_every_torque(modifications):
    """Fig. 6a: "regardless of T_in, increases in M_P help reduce P" (Design D, M_L = 12 µm)."""
    for torque in (50.0, 250.0, 500.0):
        rows = modifications[(modifications["torque_nm"] == torque)
                             & np.isclose(modifications["lead_crown_m"], 12e-6)].sort_values("profile_crown_m")
        assert len(rows) == 3 and rows["converged"].all()
        assert np.all(np.diff(rows["power_loss_w"]) < 0.0), torque


def test_fig6b_transmission_error_grows_with_profile_crown(modifications):
    """Fig. 6b: increases in M_P come "with severe consequences on TE". At 50 N·m the deflections are small and the
    crowns dominate: TE grows with M_P for every M_L. At 250 N·m the crown first compensates the tooth deflection
    (the TE minimum of a Harris map) and TE grows with M_P beyond it (15 → 30 µm)."""
    for lead in (0.0, 12e-6, 30e-6):
        rows = modifications[(modifications["torque_nm"] == 50.0)
                             & np.isclose(modifications["lead_crown_m"], lead)].sort_values("profile_crown_m")
        assert np.all(np.diff(rows["te_pp_m"]) > 0.0), lead
    for lead in (0.0, 12e-6, 30e-6):
        rows = modifications[(modifications["torque_nm"] == 250.0)
                             & np.isclose(modifications["lead_crown_m"], lead)].sort_values("profile_crown_m")
        assert rows["te_pp_m"].iloc[2] > rows["te_pp_m"].iloc[1], lead


def test_power_loss_scales_about_linearly_with_torque(modifications):
    """Constant μ: P = μ Σ W |u_s| with ΣW ∝ T_in, so P(500)/P(250) ≈ 2 up to the load-dependent contact pattern
    (crowned teeth carry load over more of the flank as the torque rises: within 25 %)."""
    sel = modifications[np.isclose(modifications["profile_crown_m"], 15e-6)
                        & np.isclose(modifications["lead_crown_m"], 12e-6)].set_index("torque_nm")
    assert sel.loc[500.0, "power_loss_w"] / sel.loc[250.0, "power_loss_w"] == pytest.approx(2.0, rel=0.25)


# ---------------------------------------------------------------------- the design-D search
def _table(**columns):
    base = {"power_loss_w": [250.0, 280.0, 200.0, 100.0, 150.0], "sigma_b_pa": [230e6, 200e6, 240e6, 100e6, 100e6],
            "sigma_c_pa": [1.1e9, 1.0e9, 1.1e9, 1.0e9, 1.0e9], "te_pp_m": [0.2e-6, 0.1e-6, 0.2e-6, 0.1e-6, 0.1e-6],
            "converged": [True, True, True, False, True], "error": ["", "", "", "", "SolverError: x"]}
    base.update(columns)
    return pd.DataFrame(base)


def test_find_design_like_d_applies_every_limit_strictly():
    """Rows 0 and 1 meet P < 0.3 kW, σ_b < 235 MPa, σ_c < 1.175 GPa, TE < 0.25 µm (§3); row 2 fails σ_b; rows 3
    and 4 would pass but did not converge / raised, so they are never selected. Sorted by P."""
    found = find_design_like_d(_table(), PAPER_SEARCH_LIMITS)
    assert list(found["power_loss_w"]) == [250.0, 280.0]
    assert (found["worst_ratio"] < 1.0).all()
    assert found["worst_ratio"].iloc[0] == pytest.approx(max(250 / 300, 230 / 235, 1.1 / 1.175, 0.2 / 0.25))
    ranked = rank_by_limits(_table(), PAPER_SEARCH_LIMITS)
    assert len(ranked) == 3 and ranked["worst_ratio"].is_monotonic_increasing
    assert ranked["ratio_sigma_b_pa"].iloc[-1] == pytest.approx(240 / 235)
    with pytest.raises(InputError, match="limits"):
        rank_by_limits(_table(), {"max_noise_db": 1.0})


def test_sweep_records_failing_designs_and_never_selects_them(study, point):
    """A friction model returning NaN is refused by the power-loss stage: the sweep records the error per design
    instead of stopping, and the search ignores those rows."""
    def broken(p_h, *rest):
        return np.full(np.shape(p_h), np.nan)

    table = design_sweep(study.space, broken, point, study.limits, MeshOptions(positions=6, slices=8), limit=3)
    assert len(table) == 3
    assert table["error"].str.contains("friction model output").all()
    assert not table["converged"].any() and table["power_loss_w"].isna().all()
    assert len(find_design_like_d(table, PAPER_SEARCH_LIMITS)) == 0


def test_unphysical_mu_is_refused(study, point):
    """μ > 1 (e.g. a regression far outside its data) is not a friction coefficient: the design is recorded as an
    error, never as a loss."""
    table = design_sweep(study.space, ConstantFriction(1.0), point, study.limits, MeshOptions(positions=6, slices=8),
                         limit=1)
    assert table["error"].iloc[0] == "" and table["converged"].iloc[0]

    def huge(p_h, *rest):
        return np.full(np.shape(p_h), 1.0e3)

    table = design_sweep(study.space, huge, point, study.limits, MeshOptions(positions=6, slices=8), limit=1)
    assert "not physical" in table["error"].iloc[0] and np.isnan(table["power_loss_w"].iloc[0])


def test_sweep_records_warnings_per_design(study, point):
    """Warnings of a design's evaluation (e.g. a surrogate extrapolating) go into its row, not to the terminal."""
    import warnings

    def warning_mu(p_h, *rest):
        warnings.warn("outside the fitted range", UserWarning)
        return np.full(np.shape(p_h), 0.05)

    with warnings.catch_warnings(record=True) as escaped:
        warnings.simplefilter("always")
        table = design_sweep(study.space, warning_mu, point, study.limits, MeshOptions(positions=6, slices=8),
                             limit=2)
    assert not escaped
    assert (table["warning"] == "UserWarning: outside the fitted range").all()
    assert table["converged"].all()


def test_bad_input_is_named(study, point):
    with pytest.raises(InputError, match="stride"):
        feasible_designs(study.space, study.limits, stride=0)
    with pytest.raises(InputError, match="where"):
        feasible_designs(study.space, study.limits, where={"module": 2.0})
    with pytest.raises(InputError, match="friction"):
        friction_from_spec("constant:abc")
    with pytest.raises(InputError, match="mu"):
        friction_from_spec("constant:2")
    with pytest.raises(InputError, match="profile_crown"):
        modification_study(study.design("D"), MU, [-1e-6], [0.0], [250.0], point)
    with pytest.raises(InputError, match="input_torque"):
        StudyPoint(-1.0, 400.0, 363.15, 4e-7, 4e-7)


# ---------------------------------------------------------------------- CLI
def test_cli_sweep_json_and_csv(tmp_path, capsys):
    """`gearloss gear sweep` on the Fig. 4a line: one JSON object, the CSV holds every evaluated design, and the
    numbers equal the library's."""
    import json

    from workflows.cli import main

    out = tmp_path / "sweep.csv"
    code = main(["gear", "sweep", "--friction", "constant:0.05", "--fix", "teeth=30", "--fix", "helix_angle_deg=20",
                 "--fix", "working_depth=2.286", "--out", str(out), "--json"])
    payload = json.loads(capsys.readouterr().out)
    assert code == 0
    table = pd.read_csv(out)
    assert payload["designs_evaluated"] == len(table) == 7
    assert payload["friction_model"] == "constant mu=0.05"
    assert payload["power_loss_w_range"] == pytest.approx([table["power_loss_w"].min(), table["power_loss_w"].max()])
    assert payload["matches"] == len(find_design_like_d(table, PAPER_SEARCH_LIMITS))
    assert len(payload["nearest"]) == 5


def test_cli_modifications_and_bad_input(capsys):
    import json

    from workflows.cli import main

    code = main(["gear", "modifications", "--design", "D", "--friction", "constant:0.05", "--torques-nm", "50",
                 "--profile-crowns-um", "0,30", "--lead-crowns-um", "0", "--json"])
    payload = json.loads(capsys.readouterr().out)
    assert code == 0 and payload["design"] == "D" and payload["cases"] == 2
    te = [r["te_pp_m"] for r in payload["rows"]]
    assert te[1] > te[0]  # Fig. 6b at light load
    assert main(["gear", "modifications", "--torques-nm", "50,-1"]) == 2
    assert "torques-nm" in capsys.readouterr().err
    assert main(["gear", "sweep", "--fix", "module=2"]) == 2
    assert "fix" in capsys.readouterr().err
    assert main(["gear", "sweep", "--friction", "constant:1.5", "--limit", "1"]) == 2
    assert main(["gear", "sweep", "--limit", "0"]) == 2
