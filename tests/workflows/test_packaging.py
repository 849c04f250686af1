"""The package works installed from a wheel: shipped data is found through the locator, not the checkout."""

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_wheel_ships_data_and_locator_finds_it(tmp_path):
    dist = tmp_path / "dist"
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w",
                    str(dist), str(REPO)], check=True)
    wheel = next(dist.glob("gearloss-*.whl"))
    names = zipfile.ZipFile(wheel).namelist()
    assert "ehl_dataset/shipped_data/lubricants/atf.toml" in names
    assert not any(name.startswith("data/") for name in names), "no top-level data package in the wheel"
    target = tmp_path / "site"
    zipfile.ZipFile(wheel).extractall(target)
    code = ("from ehl_dataset.data_files import data_root; from ehl_dataset.model.lubricant import load_lubricant; "
            "print(data_root()); load_lubricant('atf')")
    env = {k: v for k, v in os.environ.items() if k not in ("GEARLOSS_DATA", "PYTHONPATH")}
    env["PYTHONPATH"] = str(target)
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True, cwd=tmp_path,
                         env=env)
    assert Path(out.stdout.strip()) == target / "ehl_dataset" / "shipped_data"
