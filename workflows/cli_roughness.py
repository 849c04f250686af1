"""``gearloss roughness show``: a roughness profile (a shipped name, a two-column text trace or a profilometer file)
with its Rq, height moments, correlation length, PSD slope and Hurst exponent, and a PNG of profile and PSD
(docs/how-to/measured-roughness.md).
"""

from __future__ import annotations

import math

from .cli_output import emit

PROFILE_PLOT_UM = 500.0
"""Length [µm] of the profile stretch the PNG shows."""


def register(subparsers) -> None:
    parser = subparsers.add_parser("roughness", help="inspect a roughness profile (name or measured file)",
                                   description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="roughness_command", metavar="COMMAND")
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)
    show = sub.add_parser("show", help="Rq, correlation length, PSD slope (Hurst exponent), PNG of profile + PSD",
                          description="Read a roughness profile — a shipped name (baseline_synthetic, "
                                      "flank_ground), a two-column text trace x z (.txt, .csv; µm unless "
                                      "--unit) or a profilometer file read by SurfaceTopography (the "
                                      "'roughness' extra) — detrend it and print Rq, Ra, skewness, kurtosis, the "
                                      "1/e correlation length and the power-law slope of its PSD with the Hurst "
                                      "exponent H = (−slope − 1)/2 over a wavelength band; write a PNG of the "
                                      "profile and its PSD.")
    show.add_argument("profile", help="shipped name or file")
    show.add_argument("--unit", choices=("m", "mm", "um", "nm"), default=None,
                      help="length unit of a file that states none (text traces: default um)")
    show.add_argument("--line", type=int, default=None, help="line along x of a 2-D map (default: the middle)")
    show.add_argument("--band-um", type=float, nargs=2, default=None, metavar=("SHORTEST", "LONGEST"),
                      help="wavelength band [µm] of the PSD fit (default: from the profile's resolution length, "
                           "at least 4 samples, to π times its correlation length)")
    show.add_argument("--png", default=None, metavar="FILE",
                      help="the figure (default: <name>_roughness.png in the current directory)")
    show.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    show.set_defaults(handler=_show)


def profile_summary(profile, band_m: tuple[float, float] | None = None) -> dict:
    """Statistics of a profile (SI): Rq, Ra, skewness, kurtosis, correlation length, the PSD fit over ``band_m``
    (shortest, longest wavelength [m]; default: :func:`default_band`) and the registry name and sha256 if any."""
    import numpy as np

    from ehl_dataset.model.roughness import psd_slope

    z = profile.z - profile.z.mean()
    rq = float(np.sqrt(np.mean(z**2)))
    band = band_m if band_m is not None else default_band(profile)
    fit = psd_slope(profile, *band)
    return {"source": profile.source, "name": profile.name or None, "sha256": profile.sha256 or None,
            "n_points": int(z.size), "spacing_m": profile.spacing, "length_m": profile.length, "rq_m": rq,
            "ra_m": float(np.mean(np.abs(z))), "skewness": float(np.mean(z**3) / rq**3),
            "kurtosis": float(np.mean(z**4) / rq**4), "correlation_length_m": float(profile.correlation_length),
            "resolution_length_m": profile.resolution_length, "psd_band_m": [float(band[0]), float(band[1])],
            **{f"psd_{k}" if not k.startswith("hurst") else k: v for k, v in fit.items()},
            "self_affine_in_band": bool(0.0 < fit["hurst"] < 1.0)}


def default_band(profile) -> tuple[float, float]:
    """PSD fit band [m]: from the profile's resolution length (a band-limited profile's cut-off; else 4 samples)
    to π times its correlation length (below the roll-off of a self-affine profile)."""
    shortest = max(4.0 * profile.spacing, profile.grid_length_m or 0.0)
    longest = math.pi * profile.correlation_length
    if longest <= 2.0 * shortest:
        longest = min(profile.length / 4.0, 8.0 * shortest)
    return shortest, longest


def write_figure(profile, summary: dict, path) -> None:
    """PNG: a stretch of the profile (top) and its periodogram, log-binned, with the fitted power law (bottom)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from ehl_dataset.model.roughness import periodogram

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7))
    n_show = min(profile.z.size, int(PROFILE_PLOT_UM * 1e-6 / profile.spacing))
    x_um = np.arange(n_show) * profile.spacing * 1e6
    ax1.plot(x_um, profile.z[:n_show] * 1e6, lw=0.7)
    ax1.set_xlabel("x [µm]")
    ax1.set_ylabel("z [µm]")
    ax1.set_title(f"{summary['name'] or summary['source']}: Rq {summary['rq_m'] * 1e6:.3g} µm, "
                  f"β {summary['correlation_length_m'] * 1e6:.3g} µm, Rsk {summary['skewness']:.2f}, "
                  f"Rku {summary['kurtosis']:.2f}", fontsize=9)
    k, c = periodogram(profile)
    keep = c > 0
    k, c = k[keep], c[keep]
    edges = np.geomspace(k[0], k[-1] * 1.0001, 80)
    which = np.digitize(k, edges)
    kb = np.array([np.exp(np.mean(np.log(k[which == i]))) for i in np.unique(which)])
    cb = np.array([np.mean(c[which == i]) for i in np.unique(which)])
    wavelength = 2 * np.pi / kb * 1e6
    ax2.loglog(wavelength, cb, ".", ms=4, label="periodogram (log-binned means)")
    lo, hi = summary["psd_band_m"]
    inside = (wavelength >= lo * 1e6) & (wavelength <= hi * 1e6)
    if inside.any():
        slope = summary["psd_slope"]
        ref_k = kb[inside]
        scale = np.exp(np.mean(np.log(cb[inside]) - slope * np.log(ref_k)))
        ax2.loglog(wavelength[inside], scale * ref_k**slope, "-", lw=1.5,
                   label=f"fit: slope {slope:.2f} ± {summary['psd_slope_standard_error']:.2f}, "
                         f"H = {summary['hurst']:.2f} ± {summary['hurst_standard_error']:.2f}")
    ax2.axvspan(lo * 1e6, hi * 1e6, color="0.9", zorder=0, label="fit band")
    ax2.invert_xaxis()
    ax2.set_xlabel("wavelength 2π/k [µm]")
    ax2.set_ylabel("1-D PSD C(k) [m³]")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _show(args) -> int:
    from pathlib import Path

    from ehl_dataset.model.roughness import resolve_profile
    from ehl_dataset.validation import check_range

    from . import exit_codes

    profile = resolve_profile(args.profile, unit=args.unit, line=args.line)
    band = None
    if args.band_um is not None:
        lo = check_range("band_um shortest", args.band_um[0], 0.0, 1e5, low_inclusive=False, unit="µm")
        hi = check_range("band_um longest", args.band_um[1], lo, 1e5, low_inclusive=False, unit="µm")
        band = (lo * 1e-6, hi * 1e-6)
    summary = profile_summary(profile, band)
    stem = profile.name or Path(args.profile).stem
    png = Path(args.png) if args.png else Path(f"{stem}_roughness.png")
    write_figure(profile, summary, png)
    summary["png"] = str(png)
    emit(summary, args.json, _human)
    return exit_codes.OK


def _human(s: dict) -> str:
    name = f"{s['name']} (sha256 {s['sha256'][:12]}…)" if s["name"] else s["source"]
    lo, hi = (v * 1e6 for v in s["psd_band_m"])
    return "\n".join([
        f"roughness {name}",
        f"  {s['n_points']} points, spacing {s['spacing_m'] * 1e6:.4g} µm, length {s['length_m'] * 1e3:.4g} mm",
        f"  Rq {s['rq_m'] * 1e6:.4g} µm, Ra {s['ra_m'] * 1e6:.4g} µm, skewness {s['skewness']:.3f}, "
        f"kurtosis {s['kurtosis']:.3f}",
        f"  correlation length (1/e) {s['correlation_length_m'] * 1e6:.4g} µm; grid resolution length "
        f"{s['resolution_length_m'] * 1e6:.4g} µm",
        f"  PSD slope {s['psd_slope']:.3f} ± {s['psd_slope_standard_error']:.3f} over {lo:.3g}–{hi:.3g} µm "
        f"({s['psd_n_ordinates']} ordinates): Hurst exponent H = {s['hurst']:.3f} ± {s['hurst_standard_error']:.3f}"
        + ("" if s["self_affine_in_band"] else " (outside 0 < H < 1: not self-affine in this band)"),
        f"  figure {s['png']}"])
