"""The flank-like reference's queue (validation/flank_reference/run_sweeps.py) leaves out the finest spacing of a point
only when the two spacings before it agree and carry no asperity load."""

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "validation" / "flank_reference"))
import run_sweeps  # noqa: E402

POINT = run_sweeps.POINTS[0]


def write(folder, n, windows, share=0.0):
    mu = sum(windows) / len(windows)
    seg = {"mu": mu, "asperity_load_share": share, "mu_windows": [[0.25 * k, m, 10] for k, m in enumerate(windows)]}
    (folder / f"{run_sweeps.run_name(POINT, n)}.json").write_text(json.dumps(seg))


@pytest.fixture()
def results(tmp_path, monkeypatch):
    monkeypatch.setattr(run_sweeps, "RESULTS", tmp_path)
    return tmp_path


def test_a_converged_point_skips_its_finest_spacing(results):
    windows = [0.0139, 0.0141, 0.0137, 0.0140, 0.0138, 0.0142, 0.0139, 0.0140]
    write(results, 4, windows)
    write(results, 8, [w + 0.00002 for w in windows])  # a paired step of 0.14 % of μ
    assert "grid-converged" in run_sweeps.converged_before(POINT, 16)
    assert run_sweeps.converged_before(POINT, 8) == ""  # only one spacing before it


def test_a_step_or_asperity_load_keeps_it(results):
    windows = [0.0139, 0.0141, 0.0137, 0.0140, 0.0138, 0.0142, 0.0139, 0.0140]
    write(results, 4, windows)
    write(results, 8, [w + 0.0005 for w in windows])  # 3.6 % of μ
    assert run_sweeps.converged_before(POINT, 16) == ""
    write(results, 8, windows, share=0.05)
    assert run_sweeps.converged_before(POINT, 16) == ""


def test_richardson_limit_of_first_order_steps():
    """Steps halving with the spacing (first order): μ∞ = μ_fine + s2/(s1/s2 − 1) = 0.020 + 0.008 + 0.004 + 0.004."""
    text = run_sweeps.richardson(0.020, (0.008, 0.0005), (0.004, 0.0005))
    assert "observed order 1.00" in text and "Richardson limit 0.03600" in text
    assert "no Richardson limit" in run_sweeps.richardson(0.020, (0.008, 0.0005), (0.009, 0.0005))  # not shrinking
    assert "no Richardson limit" in run_sweeps.richardson(0.020, (0.008, 0.0005), (0.0008, 0.0005))  # unresolved
