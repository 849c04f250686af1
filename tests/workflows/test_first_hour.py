"""The first hour of a new user: one test (or more) per finding, in process.

The real-subprocess acceptance (main job / smoke / main job again, Ctrl-C → 130) is in test_first_hour_subprocess.py.
"""

import json
import os
import signal
import sys
import time

import pytest

from ehl_dataset.dataset.store import read_metadata
from ehl_dataset.solver import SOLVER_VERSION
from workflows.cli import main

DESIGN_D = ["--teeth", "32", "--pressure-angle-deg", "30", "--helix-angle-deg", "19", "--working-depth", "2.068"]
STUDY_MODS = ["--profile-crown-um", "15", "--lead-crown-um", "12"]
CONTACT = ["--r-eq-mm", "20", "--u-r", "5", "--sr", "0.3", "--temp-c", "90", "--rq1-um", "0.2", "--rq2-um", "0.2"]


def _err_line(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    return err


# ---------------------------------------------------------------------- 1. runs that don't collide
def test_1_each_kind_of_run_has_its_own_directory_and_a_foreign_one_is_refused_naming_the_pipeline_options(
        tmp_path, capsys):
    """The main job and the smoke run default to different directories; a directory holding another factorial's
    run is refused before any work, with the pipeline's own options (--out-dir, --overwrite) in the message."""
    from ehl_dataset.dataset.runner import run_factorial
    from workflows.pipeline import check_inputs

    quick, smoke = check_inputs("quick"), check_inputs("smoke")
    assert str(quick.out_dir) == "gearloss_quick_fast_isothermal" and str(smoke.out_dir) == "gearloss_smoke_fast_smooth"
    assert check_inputs("quick", model="smooth").out_dir != quick.out_dir
    plan = tmp_path / "tiny.toml"
    plan.write_text('name = "tiny"\nlevel = "fast"\n[axes]\np_h_gpa = [0.5]\nr_eq_mm = [20]\nu_r_m_s = [5]\n'
                    'sr = [0.1]\ntemp_c = [75]\nroughness_um = [[0.05, 0.05]]\n')
    run_factorial(tmp_path / "run" / "dataset.h5", plan, workers=0, progress="none")
    started = time.perf_counter()
    assert main(["pipeline", "smoke", "--out-dir", str(tmp_path / "run")]) == 2
    err = _err_line(capsys)
    assert "invalid --factorial='smoke'" in err and "another --out-dir, or --overwrite" in err
    assert time.perf_counter() - started < 30
    assert read_metadata(tmp_path / "run" / "dataset.h5")["factorial"]["name"] == "tiny"  # untouched


def test_1_3_the_start_line_says_where_the_output_goes_how_to_resume_and_overwrite_starts_afresh(tmp_path, capsys):
    """Finding 3: where the output goes and the resume command, then 'resuming' on the second run (nothing
    recomputed); finding 1: --overwrite starts afresh. Finding 7: the human output opens with the smoke label."""
    out = tmp_path / "smoke"
    assert main(["pipeline", "smoke", "--out-dir", str(out), "--progress", "none"]) == 0
    captured = capsys.readouterr()
    assert f"output: {out}/dataset.h5 and {out}/atf_smoke.json" in captured.err
    assert f"resume with: gearloss pipeline smoke --out-dir {out} --progress none" in captured.err
    assert "new run of 96 points" in captured.err and captured.out.startswith("SMOKE RUN")
    assert main(["pipeline", "smoke", "--out-dir", str(out), "--progress", "none", "--json"]) == 0
    captured = capsys.readouterr()
    assert "resuming: 96 of 96 points done" in captured.err
    assert json.loads(captured.out)["stages"]["dataset"]["computed"] == 0
    assert main(["pipeline", "smoke", "--out-dir", str(out), "--overwrite", "--progress", "none", "--json"]) == 0
    captured = capsys.readouterr()
    assert "new run of 96 points" in captured.err and "--overwrite" not in captured.err.split("resume with:")[1]
    assert json.loads(captured.out)["stages"]["dataset"]["computed"] == 96


# ---------------------------------------------------------------------- 3. resuming, in --help
def test_3_pipeline_help_explains_resuming(capsys):
    for argv in (["pipeline", "--help"], ["pipeline", "quick", "--help"]):
        assert main(argv) == 0
        text = capsys.readouterr().out
        assert "resuming:" in text and "the same command again continues it" in text


# ---------------------------------------------------------------------- 4. load distribution outside its validity
def test_4_a_load_far_outside_the_linear_elastic_model_is_flagged_exit_1_or_refused_with_strict(capsys):
    """At 1e6 N·m design D 'converges' to σ_c ≈ 83 GPa: flagged not valid by all three checks, exit 1; --strict
    refuses it (exit 2) naming --torque-nm as typed."""
    from efficiency.validity import DEFAULT_LIMITS

    assert main(["gear", "evaluate", *DESIGN_D, "--torque-nm", "1e6", "--outputs", "te,stresses", "--json"]) == 1
    p = json.loads(capsys.readouterr().out)
    assert p["converged"] is True and p["valid"] is False
    failed = {c["check"] for c in p["validity"] if not c["valid"]}
    assert failed == {"contact_pressure", "root_stress", "deflection"}
    limit = next(c["limit"] for c in p["validity"] if c["check"] == "contact_pressure")
    assert limit == pytest.approx(0.6 * 700 * 9.80665e6) == DEFAULT_LIMITS.contact_pressure_limit_pa
    assert main(["gear", "evaluate", *DESIGN_D, "--torque-nm", "1e6", "--strict"]) == 2
    err = _err_line(capsys)
    assert err.startswith("gearloss: error: invalid --torque-nm=1e6: accepted a value inside the model's validity")
    # the study point is inside every limit
    assert main(["gear", "evaluate", *DESIGN_D, *STUDY_MODS, "--json"]) == 0
    p = json.loads(capsys.readouterr().out)
    assert p["valid"] is True and all(c["valid"] for c in p["validity"])


# ---------------------------------------------------------------------- 5. one clipping policy
def test_5_surrogate_predict_and_gear_evaluate_clip_the_same_way(capsys):
    """At p_h 0.1 GPa (the fit starts at 0.5 GPa) predict returns the μ of the clipped inputs — the value the gear
    evaluation's friction model (friction_from_spec) gives at the same contact — with the same note, flagged not
    valid (exit 1); --no-clip gives the extrapolated regression, also flagged."""
    import numpy as np

    from efficiency.friction import friction_from_spec

    assert main(["surrogate", "predict", "atf_quick", "--p-h-gpa", "0.1", *CONTACT, "--json"]) == 1
    p = json.loads(capsys.readouterr().out)
    gear_model = friction_from_spec("atf_quick")
    with pytest.warns(UserWarning, match="clipped to its fitted ranges"):
        expected = float(np.ravel(gear_model(0.1e9, 0.02, 5.0, 0.3, 363.15, 0.2e-6, 0.2e-6))[0])
    assert p["mu"] == pytest.approx(expected, rel=1e-12)
    assert p["clipped_inputs"]["p_h"] == 1 and p["valid"] is False
    assert p["note"] == "surrogate inputs clipped to the fitted ranges: p_h 1 of 1 point"
    assert main(["gear", "evaluate", *DESIGN_D, *STUDY_MODS, "--friction", "atf_quick"]) == 0
    assert "surrogate inputs clipped to the fitted ranges: p_h" in capsys.readouterr().out
    assert main(["surrogate", "predict", "atf_quick", "--p-h-gpa", "0.1", *CONTACT, "--no-clip", "--json"]) == 1
    raw = json.loads(capsys.readouterr().out)
    assert raw["mu"] != pytest.approx(expected) and raw["extrapolated_inputs"]["p_h"] == 1
    assert main(["surrogate", "predict", "atf_quick", "--p-h-gpa", "1.2", *CONTACT]) == 0


# ---------------------------------------------------------------------- 6. the accuracy levels are visible
def test_6_help_shows_the_level_defaults_and_the_fast_standard_difference(capsys):
    assert main(["contact", "solve", "--help"]) == 0
    assert "(default: standard)" in " ".join(capsys.readouterr().out.split())
    assert main(["pipeline", "quick", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    # the measured fast/standard difference (docs/validation/accuracy_random_levels.md) and the narrow-contact caveat
    # (docs/explanation/mixed-regime.md) are in the help
    assert "fast for quick and smoke" in text and "agree within 0.1 % in median" in text
    assert "within a median 5.3 % of the deterministic model" in text and "23-78 % low" in text


# ---------------------------------------------------------------------- 7. the smoke pipeline, all stages, seconds
def test_7_the_smoke_pipeline_runs_all_three_stages_in_seconds_and_says_it_is_a_smoke_run(tmp_path, capsys):
    started = time.perf_counter()
    assert main(["pipeline", "quick", "--factorial", "smoke", "--out-dir", str(tmp_path), "--progress", "none",
                 "--json"]) == 0
    wall = time.perf_counter() - started
    p = json.loads(capsys.readouterr().out)
    assert p["label"].startswith("SMOKE RUN") and p["stages"]["dataset"]["model"] == "smooth"
    assert p["stages"]["dataset"]["ok"] == 96 and p["stages"]["fit"]["n_used"] == 96
    assert set(p["stages"]) == {"dataset", "fit", "design"} and p["valid"] and 0.99 < p["efficiency"] < 1.0
    assert wall < 120  # about 10 s on an idle 2-core machine


# ---------------------------------------------------------------------- 8. inputs checked before stage 1
@pytest.mark.parametrize("design, fragment", [("Z", "invalid --design=Z: accepted a published design of study "
                                                    "paper2009 (A, B, C, D) or a design TOML file"),
                                              ("no_such_design.toml", "no_such_design.toml")])
def test_8_a_bad_design_is_refused_before_stage_1(tmp_path, capsys, design, fragment):
    started = time.perf_counter()
    assert main(["pipeline", "quick", "--out-dir", str(tmp_path / "run"), "--design", design]) == 2
    assert fragment in _err_line(capsys)
    assert not (tmp_path / "run").exists() and time.perf_counter() - started < 30


# ---------------------------------------------------------------------- 9. accuracy writes outside docs/
def test_9_accuracy_writes_outside_docs_by_default():
    from workflows.cli import build_parser

    args = build_parser().parse_args(["accuracy"])
    assert args.out_dir == "gearloss_accuracy"
    assert build_parser().parse_args(["accuracy", "--out", "docs"]).out_dir == "docs"


# ---------------------------------------------------------------------- 10. errors name the option as typed
@pytest.mark.parametrize("argv, message", [
    (["contact", "solve", "--p-h-gpa", "1.2", *CONTACT[:6], "--temp-c", "400"],
     "gearloss: error: invalid --temp-c=400: accepted [0, 150] °C for lubricant atf"),
    (["gear", "geometry", *DESIGN_D[:4], "--helix-angle-deg", "89", *DESIGN_D[6:]],
     "gearloss: error: invalid --helix-angle-deg=89: accepted [0, 45) °"),
    (["contact", "solve", "--p-h-gpa", "abc", "--r-eq-mm", "20", "--u-r", "5"],
     "gearloss contact solve: error: invalid --p-h-gpa='abc': accepted a number [GPa]"),
    (["gear", "evaluate", *DESIGN_D, "--profile-crown-um", "-5"],
     "gearloss: error: invalid --profile-crown-um=-5: accepted [0, 1000] µm"),
    (["contact", "solve", "--p-h-gpa", "1", "--r-eq-mm", "20", "--u-r", "5", "--level", "fastest"],
     "gearloss contact solve: error: invalid --level='fastest': accepted one of fast, standard, reference"),
    (["gear", "evaluate", *DESIGN_D, "--contact-model", "hertz"],
     "gearloss gear evaluate: error: invalid --contact-model='hertz': accepted one of weber, linear"),
])
def test_10_errors_name_the_option_as_typed_in_its_units_in_one_line(capsys, argv, message):
    assert main(argv) == 2
    assert _err_line(capsys) == message
    assert main(argv + ["--json"]) == 2
    captured = capsys.readouterr()
    error = json.loads(captured.out)["error"]
    assert error["exit_code"] == 2 and error["kind"] == "bad_input" and error["message"] in message
    assert len(captured.err.strip().splitlines()) == 1


def test_10_a_stage_error_is_a_json_object_too(tmp_path, capsys):
    plan = tmp_path / "tiny.toml"
    plan.write_text('name = "tiny"\nlevel = "fast"\n[axes]\np_h_gpa = [0.5]\nr_eq_mm = [20]\nu_r_m_s = [5]\n'
                    'sr = [0.1]\ntemp_c = [75]\nroughness_um = [[0.05, 0.05]]\n')
    assert main(["pipeline", "quick", "--factorial", str(plan), "--out-dir", str(tmp_path / "r"), "--progress",
                 "none", "--json"]) == 3
    error = json.loads(capsys.readouterr().out)["error"]
    assert error["exit_code"] == 3 and error["kind"] == "stage_failed" and "fit stage" in error["message"]


# ---------------------------------------------------------------------- 11. --version and the top-level help
def test_11_version_and_a_clean_top_level_help(capsys):
    from workflows.exit_codes import TABLE

    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip().startswith("gearloss 0.1.0 (EHL solver " + SOLVER_VERSION)
    assert main(["--help"]) == 0
    text = capsys.readouterr().out
    assert "``" not in text and "report" in text
    for code, _, meaning in TABLE:
        assert f"{code:>3}  {meaning[:30]}" in text


def test_11_the_exit_code_table_of_the_docs_is_the_codes(capsys):
    from pathlib import Path

    from workflows.exit_codes import table_markdown

    assert table_markdown() in (Path(__file__).resolve().parents[2] / "docs" / "reference" / "cli.md").read_text()


# ---------------------------------------------------------------------- 12. the figures, from commands
def test_12_mesh_cycle_loss_along_the_line_of_action_adds_up_to_the_mean_power_loss(tmp_path, capsys):
    """Conservation: the cycle-mean loss per unit length integrated along the path of contact is the mean P of
    Eq. 11, for each friction model; the PNG records its command."""
    from PIL import Image

    out = tmp_path / "cycle.png"
    assert main(["report", "mesh-cycle", "--out", str(out), "--json"]) == 0
    p = json.loads(capsys.readouterr().out)
    widths = [b - a for a, b in zip(p["roll_bin_edges_m"][:-1], p["roll_bin_edges_m"][1:])]
    assert set(p["models"]) == {"atf", "xu2007"}
    for model in p["models"].values():
        total = sum(q * w for q, w in zip(model["loss_per_length_w_per_m"], widths))
        assert total == pytest.approx(model["power_loss_w"], rel=1e-9)
        assert sum(model["power_loss_instant_w"]) / len(model["power_loss_instant_w"]) == pytest.approx(
            model["power_loss_w"], rel=1e-12)
    info = Image.open(out).info
    assert info["Description"] == f"gearloss report mesh-cycle --out {out} --json"
    assert SOLVER_VERSION in info["Software"] and "atf fitted on paper2009 data" in info["Comment"]


def test_12_efficiency_map_is_eta_of_gear_evaluate_and_hatches_cells_outside_validity(tmp_path, capsys):
    out = tmp_path / "map.png"
    assert main(["report", "efficiency-map", "--torques-nm", "50,250", "--speeds-rpm", "4000", "--out", str(out),
                 "--json"]) == 0
    p = json.loads(capsys.readouterr().out)
    assert out.is_file()
    assert main(["gear", "evaluate", *DESIGN_D, *STUDY_MODS, "--friction", "atf", "--positions", "24",
                 "--json"]) == 0
    direct = json.loads(capsys.readouterr().out)
    assert p["efficiency"][1][0] == pytest.approx(direct["efficiency"], rel=1e-12)
    assert p["valid"] == [[False], [True]]  # 50 N·m: > 10 % of the loss at inputs below the fitted 0.5 GPa
    assert any("clipped" in r for r in p["not_valid_reasons"])


def test_12_report_sweep_prints_the_papers_sole_influence_lines_and_table1(tmp_path, capsys):
    """The JSON of `report sweep` carries the numbers drawn (Li & Kahraman 2009 Fig. 3a, 4a-c lines and Table 1):
    P falls with N, Φ and Ψ and rises with Λ_wd for each friction model, as in the paper's figures, and the Table 1
    design D is the same mesh cycle as `report mesh-cycle` (same P, to round-off)."""
    assert main(["report", "sweep", "--limit", "12", "--out-dir", str(tmp_path), "--json"]) == 0
    p = json.loads(capsys.readouterr().out)
    assert p["designs_evaluated"] == 12 and all(path.endswith(".png") for path in p["figures"])
    assert set(p["lines"]) == {"atf", "xu2007"}
    trends = {"teeth": -1, "normal_pressure_angle_deg": -1, "helix_angle_deg": -1, "working_depth": 1}
    for model, lines in p["lines"].items():
        assert set(lines) == set(trends), model
        for column, sign in trends.items():
            x, power = lines[column][column], lines[column]["power_loss_w"]
            assert len(x) >= 5 and x == sorted(x), (model, column)
            assert all(sign * (b - a) > 0 for a, b in zip(power[:-1], power[1:])), (model, column, power)
    assert main(["report", "mesh-cycle", "--out", str(tmp_path / "cycle.png"), "--json"]) == 0
    cycle = json.loads(capsys.readouterr().out)
    for model in ("atf", "xu2007"):
        assert p["table1"][model]["D"]["power_loss_w"] == pytest.approx(cycle["models"][model]["power_loss_w"],
                                                                         rel=1e-9)


def test_12_every_docs_figure_says_under_it_the_command_and_the_solver_version_and_report_pngs_match():
    """Each image in README/docs has a caption naming the command that made it and the EHL solver version; the
    figures of gearloss report carry the same command in their PNG metadata (they are the command's output)."""
    import re
    from pathlib import Path

    from PIL import Image

    from workflows.doc_examples import CAPTION, REPO, figure_captions

    captions = figure_captions()
    assert len(captions) >= 14
    for page, image, caption in captions:
        assert CAPTION.search(caption), f"{page}: {image} has no '*Made by `command`' caption: {caption!r}"
        assert re.search(r"EHL solver (ehl-[0-9.]+-\d+|none|unversioned)", caption), f"{page}: {image}: no solver version"
        command = CAPTION.search(caption).group(1)
        if command.startswith("gearloss report"):
            png = (REPO / Path(page).parent / image).resolve()
            info = Image.open(png).info
            assert info.get("Description") == command, (page, image)
            assert info["Software"].split("EHL solver ")[1] in caption
    studies = [c for p, i, c in captions if "sweep" in i or "modifications" in i]
    assert studies and all("--friction atf" in c or "gearloss report" in c for c in studies)


@pytest.mark.parametrize("wrapper, message", [
    (SystemError, "<CPUDispatcher> returned a result with an exception set"),  # numba, SIGTERM during a contact solve
    (ImportError, "initialization failed"),  # scipy's HiGHS extension, Ctrl-C during its import
])
@pytest.mark.parametrize("interrupt, code, words", [("_CtrlC", 130, "interrupted by SIGINT"),
                                                    ("_Terminated", 143, "terminated by SIGTERM")])
def test_a_signal_that_arrives_inside_compiled_code_still_gives_its_exit_code(monkeypatch, capsys, interrupt, code,
                                                                              words, wrapper, message):
    """A signal handler's exception raised while compiled code runs comes back as the cause of another error: a
    SystemError from numba-compiled code, an ImportError from an extension module whose initialisation it stopped.
    It still exits 130/143 with the one-line message; the same error without an interrupt behind it is not
    swallowed."""
    import workflows.cli as cli
    import workflows.cli_gear_studies as studies

    def interrupted_sweep(args):
        try:
            raise getattr(cli, interrupt)()
        except BaseException as err:
            raise wrapper(message) from err

    monkeypatch.setattr(studies, "run_sweep", interrupted_sweep)
    assert cli.main(["gear", "sweep", "--friction", "xu2007"]) == code
    assert capsys.readouterr().err.strip() == f"gearloss: {words}: gearloss gear sweep --friction xu2007 stopped"

    def broken_sweep(args):
        raise wrapper("a genuine error")

    monkeypatch.setattr(studies, "run_sweep", broken_sweep)
    with pytest.raises(wrapper, match="genuine"):
        cli.main(["gear", "sweep", "--friction", "xu2007"])


@pytest.mark.parametrize("sig, code, words", [(signal.SIGINT, 130, "interrupted by SIGINT"),
                                              (signal.SIGTERM, 143, "terminated by SIGTERM")])
def test_a_signal_whose_exception_is_lost_is_sent_again_until_the_command_stops(monkeypatch, capsys, sig, code, words):
    """A handler's exception raised inside a ``__del__`` (or a ctypes callback: numba's object-cache hook) is
    printed as "Exception ignored" and lost. The command must still stop with its exit code and one line, within a
    re-send interval, not run to its end."""
    import threading

    import workflows.cli as cli
    import workflows.cli_gear_studies as studies

    class SignalledOnDelete:
        def __del__(self):
            os.kill(os.getpid(), sig)
            for _ in range(10_000):  # bytecodes for the handler to run on, inside __del__
                pass

    finished = []

    def sweep_that_loses_the_signal(args):
        SignalledOnDelete()
        time.sleep(5 * cli.RESEND_INTERVAL_S)
        finished.append(True)
        return 0

    monkeypatch.setattr(studies, "run_sweep", sweep_that_loses_the_signal)
    hook, term_handler = sys.unraisablehook, signal.getsignal(signal.SIGTERM)
    started = time.monotonic()
    assert cli.main(["gear", "sweep", "--friction", "xu2007"]) == code
    assert time.monotonic() - started < 3 * cli.RESEND_INTERVAL_S and not finished
    assert capsys.readouterr().err.strip() == f"gearloss: {words}: gearloss gear sweep --friction xu2007 stopped"
    assert not [t for t in threading.enumerate() if t.name.startswith("gearloss-resend")]
    assert sys.unraisablehook is hook and signal.getsignal(signal.SIGTERM) is term_handler
