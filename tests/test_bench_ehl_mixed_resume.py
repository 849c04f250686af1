"""benchmarks/bench_ehl_mixed.py records the roughness of every row and --resume refuses a file solved on another:
rows of earlier versions (before the flank-like default, ehl-2026.11-17) count as baseline_synthetic."""

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import bench_ehl_mixed  # noqa: E402


def test_rows_name_their_roughness_and_old_rows_are_the_baseline():
    assert bench_ehl_mixed.row_roughness({"roughness": "flank_ground", "solver_version": "ehl-2026.11-9"}) == \
        "flank_ground"
    assert bench_ehl_mixed.row_roughness({"solver_version": "ehl-2026.11-16"}) == "baseline_synthetic"
    assert bench_ehl_mixed.row_roughness({}) == "baseline_synthetic"  # before versions were recorded per row
    assert bench_ehl_mixed.row_roughness({"solver_version": "ehl-2026.11-17"}) == "not recorded"


def test_resume_refuses_rows_of_another_roughness(tmp_path, capsys):
    out = tmp_path / "rows.json"
    out.write_text(json.dumps({"rows": [{"case": [1.0, 5.0, 5.0, 0.3, 90.0, 0.3, 0.3], "solver_version":
                                         "ehl-2026.11-14"}]}))
    code = bench_ehl_mixed.main(["--sample", "corners", "--indices", "0", "--resume", "--out", str(out)])
    assert code == 2
    assert "baseline_synthetic" in capsys.readouterr().err
