"""``gearloss lubricant show|fit``: a user's lubricant checked, tabulated and turned into a coefficient file."""

import json
import math
from pathlib import Path

import pytest

from ehl_dataset.dataset.store import read_metadata, read_table
from workflows.cli import main

ATF = Path(__file__).resolve().parents[2] / "data" / "lubricants" / "atf.toml"


def _json(capsys):
    return json.loads(capsys.readouterr().out)


@pytest.fixture()
def my_oil(tmp_path):
    """The shipped ATF file renamed and made more viscous (ISO VG 46-like: 46 mm²/s at 40 °C, 7.5 at 100 °C)."""
    text = ATF.read_text().replace('name = "atf"', 'name = "my_oil"')
    text = text.replace("nu1_mm2_s = 30.0", "nu1_mm2_s = 46.0").replace("nu2_mm2_s = 6.0", "nu2_mm2_s = 7.5")
    path = tmp_path / "my_oil.toml"
    path.write_text(text)
    return path


def test_show_reproduces_the_definition_at_its_data_points(my_oil, capsys):
    """The Walther (ASTM D341) fit passes through its two data points; α1 is the file's value at 40 °C; ρ0 the
    linear expansion from 15 °C; η0 = ν ρ0; η(p) grows with p (paper Eq. 5)."""
    assert main(["lubricant", "show", str(my_oil), "--temp-c", "40", "100", "--json"]) == 0
    out = _json(capsys)
    assert out["name"] == "my_oil"
    at40, at100 = out["rows"]
    assert at40["nu_m2_s"] == pytest.approx(46e-6, rel=1e-9)
    assert at100["nu_m2_s"] == pytest.approx(7.5e-6, rel=1e-9)
    assert at40["alpha1_per_pa"] == pytest.approx(1.5e-8, rel=1e-12)
    assert at40["rho0_kg_m3"] == pytest.approx(845.0 * (1.0 - 6.4e-4 * 25.0), rel=1e-12)
    assert at40["eta0_pa_s"] == pytest.approx(at40["nu_m2_s"] * at40["rho0_kg_m3"], rel=1e-12)
    eta = at40["eta_pa_s"]
    assert eta[0] == pytest.approx(at40["eta0_pa_s"], rel=1e-12)
    assert all(b > a for a, b in zip(eta, eta[1:]))
    # below the transition pressure p_a = 0.4 GPa the law is Barus with α1 (the file's two-slope form)
    assert main(["lubricant", "show", str(my_oil), "--temp-c", "40", "--p-gpa", "0.3", "--json"]) == 0
    assert _json(capsys)["rows"][0]["eta_pa_s"][0] == pytest.approx(at40["eta0_pa_s"] * math.exp(1.5e-8 * 0.3e9),
                                                                    rel=1e-9)


def test_show_refuses_a_temperature_outside_the_data_and_a_broken_file(my_oil, tmp_path, capsys):
    assert main(["lubricant", "show", str(my_oil), "--temp-c", "160", "--json"]) == 2
    err = _json(capsys)["error"]
    assert err["parameter"] == "--temp-c" and "[0, 150] °C" in err["accepted"]
    broken = tmp_path / "broken.toml"
    broken.write_text(my_oil.read_text().replace("nu1_mm2_s = 46.0\n", ""))
    assert main(["lubricant", "show", str(broken), "--json"]) == 2
    assert "nu1_mm2_s" in _json(capsys)["error"]["parameter"]


def test_fit_refuses_a_factorial_outside_the_lubricants_temperature_range_before_computing(my_oil, tmp_path,
                                                                                            capsys):
    """A factorial at 160 °C with a lubricant whose data end at 150 °C: one error naming the level and the range,
    and no directory, no dataset written."""
    factorial = tmp_path / "hot.toml"
    factorial.write_text('name = "hot"\nlubricant = "atf"\nlevel = "fast"\n[axes]\np_h_gpa = [0.5]\nr_eq_mm = [20.0]\n'
                         'u_r_m_s = [5.0]\nsr = [0.1]\ntemp_c = [90.0, 160.0]\nroughness_um = [[0.05, 0.05]]\n')
    out = tmp_path / "run"
    assert main(["lubricant", "fit", str(my_oil), "--factorial", str(factorial), "--out-dir", str(out),
                 "--json"]) == 2
    err = _json(capsys)["error"]
    assert "temp" in err["parameter"] and float(err["value"]) == 160.0 and "my_oil" in err["accepted"]
    assert "factorial 'hot'" in err["message"]
    assert not out.exists()
    # the same check guards `gearloss dataset run`
    store = tmp_path / "hot.h5"
    assert main(["dataset", "run", "--factorial", str(factorial), "--lubricant", str(my_oil), "--out", str(store),
                 "--workers", "0", "--json"]) == 2
    assert "my_oil" in _json(capsys)["error"]["accepted"] and not store.exists()


def test_fit_runs_the_route_resumes_and_refuses_a_changed_lubricant(my_oil, tmp_path, capsys):
    """The smoke factorial (96 smooth-surface points, seconds): dataset and coefficient file in the default
    directory named after the lubricant, both recording the user's definition; the same command again computes
    nothing; the file changed afterwards is another lubricant and is refused with the dataset left as it was."""
    import os

    os.chdir(tmp_path)
    assert main(["lubricant", "fit", str(my_oil), "--factorial", "smoke", "--progress", "none", "--json"]) == 0
    out = _json(capsys)
    folder = tmp_path / "gearloss_my_oil_smoke_fast_smooth"
    coefficients = folder / "my_oil_smoke.json"
    assert Path(out["coefficients"]).resolve() == coefficients.resolve() and coefficients.is_file()
    data = out["stages"]["dataset"]
    assert data["n_points"] == data["computed"] == data["ok"] == 96
    recorded = read_metadata(folder / "dataset.h5")["lubricant"]
    assert recorded["name"] == "my_oil" and recorded["viscosity"]["nu1_mm2_s"] == 46.0
    doc = json.loads(coefficients.read_text())
    assert doc["lubricant"]["name"] == "my_oil"
    assert out["use_with"].endswith(str(Path("gearloss_my_oil_smoke_fast_smooth") / "my_oil_smoke.json"))
    rows = read_table(folder / "dataset.h5")
    assert len(rows) == 96 and rows["mu"].between(0.0, 0.2).all()

    assert main(["lubricant", "fit", str(my_oil), "--factorial", "smoke", "--progress", "none", "--json"]) == 0
    assert _json(capsys)["stages"]["dataset"]["computed"] == 0

    before = (folder / "dataset.h5").stat().st_mtime_ns
    my_oil.write_text(my_oil.read_text().replace("eyring_stress_mpa = 5.0", "eyring_stress_mpa = 6.0"))
    assert main(["lubricant", "fit", str(my_oil), "--factorial", "smoke", "--progress", "none", "--json"]) == 2
    assert "lubricant" in _json(capsys)["error"]["parameter"]
    assert (folder / "dataset.h5").stat().st_mtime_ns == before


@pytest.mark.slow
def test_fit_through_a_dask_scheduler_address_gives_the_rows_and_coefficients_of_local_processes(my_oil, tmp_path,
                                                                                                   capsys,
                                                                                                   monkeypatch):
    """A distributed fit through the command itself: `lubricant fit ... --scheduler tcp://...` sends the points
    to a Dask cluster (here a LocalCluster of 2 worker processes behind a TCP scheduler), records that executor, and
    stores the same physics rows and the same coefficients as local worker processes."""
    import os

    distributed = pytest.importorskip("distributed")
    repo = Path(__file__).resolve().parents[2]
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(repo), os.environ.get("PYTHONPATH", "")]))
    local_dir, dask_dir = tmp_path / "local", tmp_path / "dask"
    assert main(["lubricant", "fit", str(my_oil), "--factorial", "smoke", "--workers", "2", "--progress", "none",
                 "--out-dir", str(local_dir), "--json"]) == 0
    local = _json(capsys)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  host="127.0.0.1") as cluster:
        address = cluster.scheduler_address
        assert address.startswith("tcp://")
        assert main(["lubricant", "fit", str(my_oil), "--factorial", "smoke", "--scheduler", address, "--progress",
                     "none", "--out-dir", str(dask_dir), "--json"]) == 0
    remote = _json(capsys)
    executor = remote["stages"]["dataset"]["executor"]
    assert executor["executor"] == "dask" and executor["workers"] == 2, executor
    assert remote["stages"]["dataset"]["ok"] == local["stages"]["dataset"]["ok"] == 96
    columns = ["point", "p_h", "r_eq", "u_r", "sr", "temperature", "mu", "h_min", "h_central", "lambda_bar"]
    a = read_table(local_dir / "dataset.h5").sort_values("point").reset_index(drop=True)
    b = read_table(dask_dir / "dataset.h5").sort_values("point").reset_index(drop=True)
    assert a[columns].equals(b[columns])
    workers = set(b["worker"])
    assert len(workers) == 2 and not any(w.endswith(f":{os.getpid()}") for w in workers)
    coefficients = {name: json.loads(Path(out["coefficients"]).read_text())["branches"]
                    for name, out in (("local", local), ("dask", remote))}
    assert coefficients["local"] == coefficients["dask"]
