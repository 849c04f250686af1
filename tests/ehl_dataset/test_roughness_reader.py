"""Measured profiles: the profilometer reader (SurfaceTopography, optional), the name/file resolver, and
``gearloss roughness show`` on the known synthetic profile."""

import json
import math

import numpy as np
import pytest

from ehl_dataset.model import roughness as rg
from ehl_dataset.validation import InputError
from workflows.cli import main


def _write_xz(path, x_m, z_m):
    np.savetxt(path, np.column_stack([x_m, z_m]), fmt="%.9e")


def test_surfacetopography_reader_gives_the_written_line(tmp_path):
    """A line written as x-z text with a non-.txt name goes through SurfaceTopography: same spacing and the heights
    of the written line less its least-squares line (the tilt 1e-3 and the sine's own linear part), to the 1e-9
    relative precision of the text."""
    pytest.importorskip("SurfaceTopography")
    n, dx = 400, 0.5e-6
    x = np.arange(n) * dx
    z = 1e-7 * np.sin(2 * np.pi * 8 * np.arange(n) / n) + 1e-3 * x
    path = tmp_path / "line.xyz"
    _write_xz(path, x, z)
    profile = rg.read_topography_profile(path, unit="m")
    assert profile.spacing == pytest.approx(dx, rel=1e-9)
    assert profile.z.size == n
    expected = rg.detrend(x, z)
    np.testing.assert_allclose(profile.z, expected - expected.mean(), rtol=0, atol=1e-15)
    assert 0.9 * 1e-7 / math.sqrt(2) < profile.rq < 1e-7 / math.sqrt(2)


def test_reader_unit_scaling(tmp_path):
    """A line stated in µm reads in metres (SurfaceTopography's unit conversion): spacing 0.5 µm, Rq of the cosine
    0.2 µm/√2 (an integer number of periods: orthogonal to the removed line to 1e-3)."""
    pytest.importorskip("SurfaceTopography")
    n = 200
    x_um = np.arange(n) * 0.5
    z_um = 0.2 * np.cos(2 * np.pi * 5 * np.arange(n) / n)
    path = tmp_path / "line_um.xyz"
    _write_xz(path, x_um, z_um)
    profile = rg.read_topography_profile(path, unit="um")
    assert profile.spacing == pytest.approx(0.5e-6, rel=1e-9)
    assert profile.rq == pytest.approx(0.2e-6 / math.sqrt(2), rel=1e-3)


def test_reader_without_unit_is_one_clear_error(tmp_path):
    pytest.importorskip("SurfaceTopography")
    path = tmp_path / "line.xyz"
    _write_xz(path, np.arange(64) * 1e-6, np.sin(np.arange(64)) * 1e-7)
    with pytest.raises(InputError, match="unit"):
        rg.read_topography_profile(path)


def test_resolver_names_text_files_and_missing(tmp_path):
    """A registry name gives the shipped profile; a .txt two-column trace goes to the text reader (µm default);
    anything else that does not exist is one error naming the accepted inputs."""
    assert rg.resolve_profile("flank_ground").name == "flank_ground"
    path = tmp_path / "trace.txt"
    _write_xz(path, np.arange(64) * 1.0, 0.3 * np.sin(np.arange(64) / 3.0))
    assert rg.resolve_profile(str(path)).spacing == pytest.approx(1e-6)
    with pytest.raises(InputError, match="flank_ground"):
        rg.resolve_profile(str(tmp_path / "nothing.sur"))


def test_show_prints_the_flank_profiles_design_numbers(tmp_path, capsys):
    """``gearloss roughness show flank_ground --json``: Rq 0.5 µm, the registry hash, Hurst exponent within 3 of
    its standard errors of the design 0.85 over the default band (λ_s to π·β), a PNG written."""
    png = tmp_path / "flank.png"
    assert main(["roughness", "show", "flank_ground", "--png", str(png), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["rq_m"] == pytest.approx(0.5e-6, rel=1e-6)
    assert out["sha256"] == rg.PROFILES["flank_ground"].sha256
    assert out["psd_band_m"][0] == pytest.approx(rg.FLANK_CUTOFF_WAVELENGTH_M)
    assert abs(out["hurst"] - rg.FLANK_HURST) < 3 * out["hurst_standard_error"]
    assert out["self_affine_in_band"]
    assert out["correlation_length_m"] == pytest.approx(rg.named_profile("flank_ground").correlation_length)
    assert png.stat().st_size > 10_000


def test_show_flags_the_gaussian_acf_profile_as_not_self_affine(tmp_path, capsys):
    """The baseline's Gaussian spectrum is not a power law: the fitted H is far outside 0–1 and the output says so."""
    assert main(["roughness", "show", "baseline_synthetic", "--png", str(tmp_path / "b.png")]) == 0
    assert "not self-affine in this band" in capsys.readouterr().out


def test_show_bad_band_is_an_input_error(tmp_path, capsys):
    code = main(["roughness", "show", "flank_ground", "--band-um", "50", "3", "--png", str(tmp_path / "x.png")])
    assert code == 2
