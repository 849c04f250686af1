"""Surface roughness profiles for the rough EHL models (paper Sect. 2.1, Eq. 3; docs/reference/data.md).

The paper scales one measured shaved-gear profile (Rq = 0.5 µm) by a constant to get every roughness level. No
measured profile is available to this project, so :func:`generate_profile` makes a synthetic stand-in: a stationary
Gaussian-height random process with a Gaussian autocorrelation

    C(τ) = Rq² exp(−τ²/β²)        (β: correlation length, C(β) = Rq²/e),

synthesised spectrally (complex Gaussian Fourier coefficients with variance ∝ the power spectral density
S(k) ∝ exp(−k²β²/4), zero mean, inverse FFT), then scaled to Rq exactly. The result is periodic with the profile
length, so reading it modulo its length is continuous. An exponential autocorrelation C = Rq² exp(−|τ|/β) is also
available (``acf="exponential"``); the baseline uses the Gaussian one because its spectrum is negligible beyond
k ≈ 2π/β, so point sampling on a solver grid of spacing ≤ β/2 neither aliases nor misses roughness, and μ has a
grid-converged limit (an exponential ACF has roughness at every scale).

The shipped baseline ``data/roughness/baseline_synthetic.txt`` (two columns x [µm], z [µm]) is regenerated
bit-for-bit by :func:`baseline_text` (constants ``BASELINE_*`` below).

:func:`load_profile` reads a user's measured profile (two-column text), detrends it (least-squares line),
resamples it to uniform spacing and optionally scales it to a target Rq.

:func:`plan_surfaces` / :func:`surface_pair` give the two moving surfaces R1(x − u1 t), R2(x − u2 t) on the
solver's grid, read from two non-overlapping segments of the profile, each scaled to the case's Rq1, Rq2.
All functions are pure and work in SI units (m, s).
"""

from __future__ import annotations

import functools
import hashlib
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..data_files import data_path
from ..validation import InputError, check_range

BASELINE_FILE = "baseline_synthetic.txt"
"""File name of the shipped baseline profile in ``data/roughness/``."""
BASELINE_SEED = 20090317
"""Seed of the baseline profile (legacy ``numpy.random.RandomState``, whose stream NumPy keeps frozen, NEP 19)."""
BASELINE_POINTS = 2**17
"""Number of samples of the baseline profile."""
BASELINE_SPACING_M = 1.0e-6
"""Sampling interval of the baseline profile [m] (β/15: linear interpolation error ≈ 0.2 % of Rq, see docs)."""
BASELINE_CORRELATION_LENGTH_M = 15.0e-6
"""Correlation length β of the baseline [m] (C(β) = Rq²/e), middle of the 10–20 µm of shaved/ground flanks."""
BASELINE_RQ_M = 0.5e-6
"""RMS roughness of the baseline [m] (the paper's measured shaved profile)."""

SEGMENT_GAP_CORRELATION_LENGTHS = 10.0
"""Gap between the two surfaces' segments, in correlation lengths (Gaussian ACF at 10β: e^-100)."""

_UNIT_SCALE = {"m": 1.0, "mm": 1e-3, "um": 1e-6}


@dataclass(frozen=True, eq=False)
class RoughnessProfile:
    """A uniformly sampled, zero-mean, periodic-by-convention roughness profile.

    Position s maps to sample s/spacing; reading wraps modulo :attr:`length`.

    Parameters
    ----------
    z : ndarray
        Heights, positive = material above the mean line [m].
    spacing : float
        Sampling interval [m].
    source : str
        A short provenance text [-].
    grid_length_m : float, optional
        The length scale a solver grid resolves; None: the correlation length (:attr:`resolution_length`) [m].
    name : str
        Registry name of a shipped profile (:func:`named_profile`; empty otherwise) [-].
    sha256 : str
        File hash of a shipped profile (empty otherwise) [-].
    """

    z: np.ndarray
    spacing: float
    source: str = ""
    grid_length_m: float | None = None
    name: str = ""
    sha256: str = ""

    def __post_init__(self):
        # heights are read-only, so that what is derived from them once (correlation length, content hash) stays
        # true; a caller's writeable array is copied rather than frozen under them
        z = np.asarray(self.z, dtype=float)
        if z.flags.writeable:
            z = z.copy()
            z.flags.writeable = False
        object.__setattr__(self, "z", z)

    @property
    def resolution_length(self) -> float:
        """Length scale [m] a solver grid must resolve: ``grid_length_m`` (the short-wavelength cut-off of a
        band-limited profile, e.g. :data:`FLANK_CUTOFF_WAVELENGTH_M`), else the correlation length (a Gaussian-ACF
        profile has no roughness below ≈ β, see the module docstring)."""
        return float(self.grid_length_m) if self.grid_length_m is not None else float(self.correlation_length)

    @property
    def length(self) -> float:
        """Profile length [m] (number of samples × spacing; the wrap period)."""
        return self.z.size * self.spacing

    @property
    def rq(self) -> float:
        """RMS roughness [m] about the mean line."""
        return float(np.sqrt(np.mean((self.z - self.z.mean()) ** 2)))

    @functools.cached_property
    def content_hash(self) -> str:
        """SHA-256 (hex) of the heights as little-endian float64 bytes and the spacing's repr: what the dry-contact
        tables and caches key a profile by."""
        digest = hashlib.sha256(np.ascontiguousarray(self.z, dtype="<f8").tobytes())
        digest.update(repr(float(self.spacing)).encode())
        return digest.hexdigest()

    @functools.cached_property
    def correlation_length(self) -> float:
        """Lag [m] at which the (circular) autocorrelation first falls to 1/e."""
        return autocorrelation_length(self.z, self.spacing)

    def scaled(self, rq: float) -> "RoughnessProfile":
        """The same profile multiplied by a constant so that its Rq equals ``rq`` (paper Sect. 2.1).

        Parameters
        ----------
        rq : float
            Target RMS roughness [m].

        Returns
        -------
        RoughnessProfile
            The scaled profile.
        """
        check_range("rq", rq, 0.0, 1e-4, unit="m")
        current = self.rq
        if current == 0.0:
            raise InputError("roughness profile", self.source or "<profile>", "a profile with non-zero Rq")
        return RoughnessProfile(self.z * (rq / current), self.spacing, self.source, self.grid_length_m, self.name,
                                self.sha256)

    def sample(self, s) -> np.ndarray:
        """Heights at positions ``s`` (any shape) by periodic linear interpolation.

        Parameters
        ----------
        s : array_like
            Positions [m].

        Returns
        -------
        ndarray
            Heights, shaped like ``s`` [m].
        """
        pos = np.asarray(s, dtype=float) / self.spacing
        base = np.floor(pos)
        frac = pos - base
        n = self.z.size
        i0 = np.mod(base, n).astype(np.intp)
        i1 = np.where(i0 + 1 == n, 0, i0 + 1)
        return self.z[i0] * (1.0 - frac) + self.z[i1] * frac


# ---------------------------------------------------------------------------------------------------------------
# Synthesis and statistics
# ---------------------------------------------------------------------------------------------------------------
def gaussian_acf_psd(k, correlation_length: float):
    """One-sided spectral shape of C(τ) = exp(−τ²/β²): S(k) ∝ exp(−k²β²/4) (unnormalised), k [rad/m]."""
    return np.exp(-0.25 * (np.asarray(k) * correlation_length) ** 2)


def exponential_acf_psd(k, correlation_length: float):
    """One-sided spectral shape of C(τ) = exp(−|τ|/β): S(k) ∝ 1/(1 + k²β²) (unnormalised), k [rad/m]."""
    return 1.0 / (1.0 + (np.asarray(k) * correlation_length) ** 2)


def generate_profile(n_points: int, spacing_m: float, correlation_length_m: float, rq_m: float, seed: int,
                     acf: str = "gaussian") -> RoughnessProfile:
    """Synthesise a periodic Gaussian random profile with the given autocorrelation, scaled to Rq exactly.

    Fourier coefficients c_k = √S(k)·(g1 + i g2)/√2 with g1, g2 independent standard normals from
    ``numpy.random.RandomState(seed)`` (legacy stream, frozen by NumPy), c_0 = 0, c_{N/2} real; z = irfft(c);
    then z ← z·rq/rms(z). Deterministic for given arguments.

    Parameters
    ----------
    n_points : int
        Number of samples, even and ≥ 16 [-].
    spacing_m : float
        Sampling interval [m].
    correlation_length_m : float
        Correlation length β of the autocorrelation [m].
    rq_m : float
        RMS roughness [m].
    seed : int
        Seed of the random stream [-].
    acf : str
        Autocorrelation: ``gaussian`` exp(−τ²/β²) or ``exponential`` exp(−|τ|/β) [-].

    Returns
    -------
    RoughnessProfile
        The profile.
    """
    if not isinstance(n_points, (int, np.integer)) or n_points < 16 or n_points % 2:
        raise InputError("n_points", n_points, "an even integer >= 16")
    check_range("spacing_m", spacing_m, 0.0, 1e-2, low_inclusive=False, unit="m")
    check_range("correlation_length_m", correlation_length_m, 0.0, 1e-2, low_inclusive=False, unit="m")
    check_range("rq_m", rq_m, 0.0, 1e-4, low_inclusive=False, unit="m")
    psd = {"gaussian": gaussian_acf_psd, "exponential": exponential_acf_psd}.get(acf)
    if psd is None:
        raise InputError("acf", acf, "'gaussian' or 'exponential'")
    if correlation_length_m * 20 > n_points * spacing_m:
        raise InputError("correlation_length_m", correlation_length_m,
                         f"<= profile length/20 = {n_points * spacing_m / 20:g} m")
    k = 2.0 * math.pi * np.fft.rfftfreq(n_points, d=spacing_m)
    amplitude = np.sqrt(psd(k, correlation_length_m))
    rng = np.random.RandomState(seed)
    noise = rng.standard_normal((2, k.size))
    coefficients = amplitude * (noise[0] + 1j * noise[1]) / math.sqrt(2.0)
    coefficients[0] = 0.0
    coefficients[-1] = amplitude[-1] * noise[0, -1]  # Nyquist term of an even-length real signal is real
    z = np.fft.irfft(coefficients, n_points)
    z *= rq_m / np.sqrt(np.mean(z**2))
    return RoughnessProfile(z, float(spacing_m), f"synthetic {acf} ACF, beta={correlation_length_m:g} m, seed={seed}")


def circular_autocorrelation(z: np.ndarray) -> np.ndarray:
    """Normalised circular autocorrelation ρ(j) of a sampled profile (ρ(0) = 1), by FFT (Wiener–Khinchin)."""
    zz = np.asarray(z, dtype=float) - np.mean(z)
    spectrum = np.abs(np.fft.rfft(zz)) ** 2
    acf = np.fft.irfft(spectrum, zz.size)
    return acf / acf[0]


def autocorrelation_length(z: np.ndarray, spacing: float) -> float:
    """First lag where the circular autocorrelation falls to 1/e (linear interpolation between samples).

    Parameters
    ----------
    z : ndarray
        Heights of a uniformly sampled profile [m].
    spacing : float
        Sampling interval [m].

    Returns
    -------
    float
        The 1/e lag [m].
    """
    rho = circular_autocorrelation(z)[: z.size // 2]
    below = np.flatnonzero(rho <= math.exp(-1.0))
    if below.size == 0:
        return math.inf
    j = int(below[0])
    r0, r1 = rho[j - 1], rho[j]
    return (j - 1 + (r0 - math.exp(-1.0)) / (r0 - r1)) * spacing


def correlation_length_standard_error(correlation_length: float, profile_length: float) -> float:
    """Standard error [m] of the 1/e-lag estimate of β for a Gaussian ACF profile of the given length.

    Bartlett's large-sample variance of the normalised sample autocorrelation at lag τ (continuous form),
        Var ρ̂(τ) ≈ (1/L) ∫ [ρ²(u) + ρ(u+τ)ρ(u−τ) + 2ρ²(τ)ρ²(u) − 4ρ(τ)ρ(u)ρ(u+τ)] du,
    evaluated for ρ(u) = exp(−u²/β²) at τ = β in closed form, Var ρ̂(β) = (β√(π/2)/L)·(1 + 3e⁻² − 4e^{−3/2}),
    and propagated through the slope ρ'(β) = −2/(eβ): σ_β = σ_ρ̂(β)/|ρ'(β)|.
    (Integrals: ∫ρ² = β√(π/2); ∫ρ(u+β)ρ(u−β) = β√(π/2)e⁻²; ∫ρ(u)ρ(u+β) = β√(π/2)e^{−1/2}.)
    """
    beta = correlation_length
    var_rho = beta * math.sqrt(math.pi / 2.0) / profile_length * (1 + 3 * math.exp(-2.0) - 4 * math.exp(-1.5))
    return math.sqrt(var_rho) * beta * math.e / 2.0


# ---------------------------------------------------------------------------------------------------------------
# The shipped baseline
# ---------------------------------------------------------------------------------------------------------------
def generate_baseline() -> RoughnessProfile:
    """The baseline profile from the ``BASELINE_*`` constants (what ``data/roughness/`` ships)."""
    return generate_profile(BASELINE_POINTS, BASELINE_SPACING_M, BASELINE_CORRELATION_LENGTH_M, BASELINE_RQ_M,
                            BASELINE_SEED)


def profile_text(profile: RoughnessProfile, header: str = "") -> str:
    """Two-column text of a profile: x [µm] with 3 decimals, z [µm] with 6 decimals (1 pm); '#' header lines."""
    lines = [f"# {line}" if line else "#" for line in header.splitlines()]
    x_um = np.arange(profile.z.size) * (profile.spacing * 1e6)
    z_um = profile.z * 1e6
    lines += [f"{x:.3f} {z:.6f}" for x, z in zip(x_um.tolist(), z_um.tolist())]
    return "\n".join(lines) + "\n"


BASELINE_HEADER = f"""gearloss synthetic baseline roughness profile (stand-in for a measured shaved-gear trace)
columns: x [um]  z [um]   (z positive = material above the mean line)
Gaussian random process, Gaussian autocorrelation C(tau) = Rq^2 exp(-tau^2/beta^2)
beta = {BASELINE_CORRELATION_LENGTH_M * 1e6:g} um, Rq = {BASELINE_RQ_M * 1e6:g} um, spacing = {BASELINE_SPACING_M * 1e6:g} um, \
N = {BASELINE_POINTS}, periodic, seed = {BASELINE_SEED}
regenerate: python -c "from ehl_dataset.model.roughness import write_baseline; write_baseline()"
"""


def baseline_text() -> str:
    """Exact text of the shipped baseline file."""
    return profile_text(generate_baseline(), BASELINE_HEADER)


def write_baseline(path: str | Path | None = None) -> Path:
    """Write the baseline profile file (default: the shipped location) and return its path."""
    target = Path(path) if path is not None else data_path("roughness", BASELINE_FILE)
    target.write_text(baseline_text(), encoding="ascii")
    return target


def baseline_profile() -> RoughnessProfile:
    """The shipped baseline profile, ``named_profile("baseline_synthetic")`` (Gaussian ACF, β 15 µm): the profile
    of the baseline validation cases.

    Read once per process, its sha256 checked. Not detrended: it is periodic and zero-mean.

    Returns
    -------
    RoughnessProfile
        The profile.
    """
    return named_profile(BASELINE_NAME)


def default_profile() -> RoughnessProfile:
    """The profile every model uses when none is given, ``named_profile(DEFAULT_PROFILE)``.

    Returns
    -------
    RoughnessProfile
        The profile.
    """
    return named_profile(DEFAULT_PROFILE)


@functools.lru_cache(maxsize=2)
def long_baseline_profile(n_points: int) -> RoughnessProfile:
    """The baseline's random process over ``n_points`` samples (> :data:`BASELINE_POINTS`, a power of two): the same
    generator, seed, spacing, β and Rq as the shipped baseline, rounded to the file's 1 pm and made zero-mean as the
    shipped file is read. It is another realisation of the process, not the baseline continued (every Fourier
    coefficient changes with the length). For runs that read more roughness than the 131 mm baseline holds: the
    long runs of narrow contacts whose standard error of μ needs more independent asperities
    (validation/deterministic_validation.py, ``PROFILE_POINTS``). Generated, not shipped: 2^18 samples take 0.1 s.
    """
    if not isinstance(n_points, (int, np.integer)) or n_points <= BASELINE_POINTS or n_points & (n_points - 1):
        raise InputError("n_points", n_points, f"a power of two above the baseline's {BASELINE_POINTS}")
    z = generate_profile(int(n_points), BASELINE_SPACING_M, BASELINE_CORRELATION_LENGTH_M, BASELINE_RQ_M,
                         BASELINE_SEED).z
    z = np.round(z * 1e12) * 1e-12
    return RoughnessProfile(z - z.mean(), BASELINE_SPACING_M,
                            f"baseline process over {n_points} samples (gaussian ACF, beta="
                            f"{BASELINE_CORRELATION_LENGTH_M:g} m, seed={BASELINE_SEED})")


# ---------------------------------------------------------------------------------------------------------------
# Flank-like profile: self-affine between a roll-off and a short cut-off
# ---------------------------------------------------------------------------------------------------------------
FLANK_FILE = "flank_ground.txt"
"""File name of the flank-like profile in ``data/roughness/``."""
FLANK_SEED = 20170113
"""Seed of the flank-like profile (legacy ``numpy.random.RandomState``, NEP 19)."""
FLANK_POINTS = 2**17
"""Number of samples of the flank-like profile (32.768 mm at :data:`FLANK_SPACING_M`)."""
FLANK_SPACING_M = 0.25e-6
"""Sampling interval of the flank-like profile [m]: a tenth of the short cut-off wavelength."""
FLANK_HURST = 0.85
"""Hurst exponent H of the flank-like profile [-]: fractal dimension D_f = 3 − H = 2.15, the centre of the
D_f = 2.15 ± 0.15 that Persson (Tribol. Lett. 54 (2014) 99) finds on most engineering surfaces."""
FLANK_ROLLOFF_WAVELENGTH_M = 50.0e-6
"""Roll-off wavelength λ_r [m]: the PSD is flat at longer wavelengths (Jacobs, Junge & Pastewka 2017). A choice,
not a measured flank value: it puts the 1/e correlation length near 10 µm (docs/explanation/roughness.md)."""
FLANK_CUTOFF_WAVELENGTH_M = 2.5e-6
"""Short cut-off wavelength λ_s [m]: no roughness at shorter wavelengths. 2.5 µm is the short-wave filter λs of a
stylus profile with λc = 0.8 mm and a 2 µm tip (ISO 3274, ISO 4288): measured flank spectra end there."""
FLANK_RQ_M = 0.5e-6
"""RMS roughness of the shipped flank-like profile [m] (the baseline's; every case rescales it)."""


def self_affine_psd(k, hurst: float, rolloff_wavelength: float, cutoff_wavelength: float):
    """One-sided 1-D power spectral density shape (unnormalised) of a self-affine profile with a roll-off.

    C(k) = 1 for k < k_r, (k/k_r)^−(1+2H) for k_r ≤ k ≤ k_s, 0 for k > k_s, with k_r = 2π/λ_r, k_s = 2π/λ_s
    (Jacobs, Junge & Pastewka, Surf. Topogr. Metrol. Prop. 5 (2017) 013001, the 1-D form of their Eq. for a
    self-affine surface with roll-off).

    Parameters
    ----------
    k : array_like
        Wavenumbers [rad/m].
    hurst : float
        Hurst exponent H, 0 < H < 1 [-].
    rolloff_wavelength : float
        Roll-off wavelength λ_r [m].
    cutoff_wavelength : float
        Short cut-off wavelength λ_s < λ_r [m].

    Returns
    -------
    numpy.ndarray
        C(k) [-], 1 on the plateau.
    """
    k = np.asarray(k, dtype=float)
    k_r = 2.0 * math.pi / rolloff_wavelength
    k_s = 2.0 * math.pi / cutoff_wavelength
    ratio = np.maximum(k, k_r) / k_r
    return np.where(k > k_s * (1.0 + 1e-12), 0.0, ratio ** (-(1.0 + 2.0 * hurst)))


def johnson_su_heights(z: np.ndarray, skewness: float, kurtosis: float) -> np.ndarray:
    """Monotone (Johnson S_U translation) transform of Gaussian heights to a skewed, heavy-tailed distribution.

    y = sinh((g − γ)/δ) with g = z/std(z) standard normal (Johnson, Biometrika 36 (1949) 149); γ, δ are solved so
    that the distribution of y has the requested skewness and kurtosis (scipy.stats.johnsonsu). The transform keeps
    the order of the heights, so the profile's peaks stay where they were; it reshapes the spectrum a little (the
    spectrum of the result is measured, not assumed).

    Parameters
    ----------
    z : numpy.ndarray
        Zero-mean Gaussian heights [m].
    skewness : float
        Target skewness Rsk [-].
    kurtosis : float
        Target kurtosis Rku > 3 + 1.5·Rsk² (the S_U region) [-].

    Returns
    -------
    numpy.ndarray
        Heights [-] with the target distribution (not yet scaled; the caller scales to Rq).
    """
    from scipy import optimize, stats

    check_range("kurtosis", kurtosis, 3.0 + 1.5 * skewness**2, 50.0, low_inclusive=False)

    def mismatch(params):
        gamma, log_delta = params
        sk, ku = stats.johnsonsu.stats(gamma, math.exp(log_delta), moments="sk")
        return [float(sk) - skewness, float(ku) + 3.0 - kurtosis]

    solution = optimize.least_squares(mismatch, x0=[-skewness, math.log(2.0)], xtol=1e-14, ftol=1e-14)
    if max(abs(r) for r in solution.fun) > 1e-8:
        raise InputError("skewness/kurtosis", (skewness, kurtosis), "a pair reachable by a Johnson S_U law",
                         f"moment mismatch {solution.fun}")
    gamma, delta = solution.x[0], math.exp(solution.x[1])
    g = np.asarray(z, dtype=float) / np.std(z)
    return np.sinh((g - gamma) / delta)


def generate_self_affine_profile(n_points: int, spacing_m: float, hurst: float, rolloff_wavelength_m: float,
                                 cutoff_wavelength_m: float, rq_m: float, seed: int, *,
                                 skewness: float | None = None, kurtosis: float | None = None) -> RoughnessProfile:
    """Synthesise a periodic self-affine profile with a roll-off and a short cut-off, scaled to Rq exactly.

    Fourier synthesis as :func:`generate_profile` (c_k = √C(k)·(g1 + i g2)/√2, ``RandomState(seed)``, c_0 = 0, real
    Nyquist term) with the spectrum :func:`self_affine_psd`; Gaussian heights, or with ``skewness`` and ``kurtosis``
    the monotone Johnson S_U transform :func:`johnson_su_heights` of them. The profile's ``grid_length_m`` is the
    cut-off wavelength: a solver grid resolves λ_s, not the correlation length.

    Parameters
    ----------
    n_points : int
        Number of samples, even, ≥ 16 [-].
    spacing_m : float
        Sampling interval, ≤ λ_s/4 [m].
    hurst : float
        Hurst exponent H, 0 < H < 1 [-].
    rolloff_wavelength_m : float
        Roll-off wavelength λ_r, ≤ profile length/8 [m].
    cutoff_wavelength_m : float
        Short cut-off wavelength λ_s < λ_r [m].
    rq_m : float
        RMS roughness [m].
    seed : int
        Seed of the legacy NumPy generator [-].
    skewness, kurtosis : float, optional
        Height distribution moments Rsk, Rku (both or neither; None: Gaussian heights) [-].

    Returns
    -------
    RoughnessProfile
        Zero-mean profile with Rq = ``rq_m`` and ``grid_length_m`` = λ_s.
    """
    if not isinstance(n_points, (int, np.integer)) or n_points < 16 or n_points % 2:
        raise InputError("n_points", n_points, "an even integer >= 16")
    check_range("spacing_m", spacing_m, 0.0, 1e-3, low_inclusive=False, unit="m")
    check_range("hurst", hurst, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
    check_range("cutoff_wavelength_m", cutoff_wavelength_m, 4.0 * spacing_m, 1e-2, unit="m")
    check_range("rolloff_wavelength_m", rolloff_wavelength_m, cutoff_wavelength_m, n_points * spacing_m / 8.0,
                low_inclusive=False, unit="m")
    check_range("rq_m", rq_m, 0.0, 1e-4, low_inclusive=False, unit="m")
    if (skewness is None) != (kurtosis is None):
        raise InputError("skewness/kurtosis", (skewness, kurtosis), "both given or both None")
    k = 2.0 * math.pi * np.fft.rfftfreq(n_points, d=spacing_m)
    amplitude = np.sqrt(self_affine_psd(k, hurst, rolloff_wavelength_m, cutoff_wavelength_m))
    rng = np.random.RandomState(seed)
    noise = rng.standard_normal((2, k.size))
    coefficients = amplitude * (noise[0] + 1j * noise[1]) / math.sqrt(2.0)
    coefficients[0] = 0.0
    coefficients[-1] = amplitude[-1] * noise[0, -1]
    z = np.fft.irfft(coefficients, n_points)
    heights = "gaussian heights"
    if skewness is not None:
        z = johnson_su_heights(z, skewness, kurtosis)
        heights = f"Johnson S_U heights Rsk={skewness:g} Rku={kurtosis:g}"
    z = z - z.mean()
    z *= rq_m / np.sqrt(np.mean(z**2))
    return RoughnessProfile(z, float(spacing_m),
                            f"synthetic self-affine H={hurst:g}, lambda_r={rolloff_wavelength_m:g} m, "
                            f"lambda_s={cutoff_wavelength_m:g} m, {heights}, seed={seed}",
                            grid_length_m=float(cutoff_wavelength_m))


def generate_flank() -> RoughnessProfile:
    """The flank-like profile from the ``FLANK_*`` constants (what ``data/roughness/flank_ground.txt`` ships)."""
    return generate_self_affine_profile(FLANK_POINTS, FLANK_SPACING_M, FLANK_HURST, FLANK_ROLLOFF_WAVELENGTH_M,
                                        FLANK_CUTOFF_WAVELENGTH_M, FLANK_RQ_M, FLANK_SEED)


FLANK_HEADER = f"""gearloss synthetic flank-like roughness profile (ground gear flank stand-in; not a measurement)
columns: x [um]  z [um]   (z positive = material above the mean line)
Gaussian heights, self-affine PSD C(k) ~ k^-(1+2H) between lambda_r and lambda_s, flat above lambda_r, 0 below lambda_s
H = {FLANK_HURST:g}, lambda_r = {FLANK_ROLLOFF_WAVELENGTH_M * 1e6:g} um, lambda_s = {FLANK_CUTOFF_WAVELENGTH_M * 1e6:g} um, \
Rq = {FLANK_RQ_M * 1e6:g} um, spacing = {FLANK_SPACING_M * 1e6:g} um, N = {FLANK_POINTS}, periodic, seed = {FLANK_SEED}
regenerate: python -c "from ehl_dataset.model.roughness import write_flank; write_flank()"
"""


def flank_text() -> str:
    """Exact text of the shipped flank-like profile file."""
    return profile_text(generate_flank(), FLANK_HEADER)


def write_flank(path: str | Path | None = None) -> Path:
    """Write the flank-like profile file (default: the shipped location) and return its path."""
    target = Path(path) if path is not None else data_path("roughness", FLANK_FILE)
    target.write_text(flank_text(), encoding="ascii")
    return target


# ---------------------------------------------------------------------------------------------------------------
# Registry of named profiles
# ---------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ProfileEntry:
    """A shipped roughness profile: ``file`` in ``data/roughness/``, its ``sha256``, a ``description``, the
    length scale [m] a solver grid resolves on it (``grid_length_m``; None: its correlation length) and the
    ``source`` text results record (empty: ``shipped <name> (<file>)``)."""

    file: str
    sha256: str
    description: str
    grid_length_m: float | None = None
    source: str = ""


PROFILES = {
    "baseline_synthetic": ProfileEntry(
        BASELINE_FILE, "01f539a6266e17d2ad3cdda3e787b616d7e54a855d572c17f33573a26bb9258a",
        "Gaussian heights, Gaussian ACF, beta 15 um, Rq 0.5 um",
        source=f"shipped baseline {BASELINE_FILE}"),
    "flank_ground": ProfileEntry(
        FLANK_FILE, "4631d4a6a54bdabb8e9c9d1b7327596efaabd452dc789a0ffc6364bbe4e1bf78",
        "Gaussian heights, self-affine H 0.85 between lambda_r 50 um and lambda_s 2.5 um, Rq 0.5 um",
        FLANK_CUTOFF_WAVELENGTH_M),
}
"""Named roughness profiles: name → :class:`ProfileEntry`; :data:`DEFAULT_PROFILE` is the default of every model."""

BASELINE_NAME = "baseline_synthetic"
"""Name of the Gaussian-ACF baseline profile (the baseline validation cases)."""

DEFAULT_PROFILE = "flank_ground"
"""Name of the default roughness profile."""


def file_sha256(path: str | Path) -> str:
    """Hex sha256 of a file's bytes."""
    import hashlib

    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


@functools.lru_cache(maxsize=4)
def named_profile(name: str) -> RoughnessProfile:
    """The shipped profile registered as ``name`` (:data:`PROFILES`), checked against its sha256.

    Parameters
    ----------
    name : str
        A key of :data:`PROFILES` [-].

    Returns
    -------
    RoughnessProfile
        Zero-mean profile read from ``data/roughness/`` carrying ``name``, ``sha256`` and ``grid_length_m``.
    """
    entry = PROFILES.get(name)
    if entry is None:
        raise InputError("roughness profile name", name, f"one of {sorted(PROFILES)}")
    path = data_path("roughness", entry.file)
    digest = file_sha256(path)
    if digest != entry.sha256:
        raise InputError("roughness file", str(path), f"sha256 {entry.sha256}", f"found {digest}")
    data = _read_two_columns(path)
    x = data[:, 0] * 1e-6
    z = data[:, 1] * 1e-6
    spacing = float((x[-1] - x[0]) / (x.size - 1))
    return RoughnessProfile(z - z.mean(), spacing, entry.source or f"shipped {name} ({entry.file})",
                            entry.grid_length_m, name, digest)


def psd_slope(profile: RoughnessProfile, shortest_wavelength_m: float, longest_wavelength_m: float) -> dict:
    """Power-law slope of the periodogram of ``profile`` between two wavelengths, and the Hurst exponent from it.

    Least squares of ln I(k_j) on ln k_j over the Fourier ordinates in the band. For a Gaussian process each
    periodogram ordinate is C(k_j)·E_j with E_j independent standard exponentials, so ln I = ln C + ln E with
    Var ln E = π²/6 (a constant bias −γ that the intercept absorbs): the slope's standard error is
    √(π²/6 / Σ(ln k_j − mean)²) (the log-periodogram regression of Geweke & Porter-Hudak, J. Time Ser. Anal. 4
    (1983) 221). A 1-D self-affine profile has C ∝ k^−(1+2H), so H = (−slope − 1)/2.

    Parameters
    ----------
    profile : RoughnessProfile
        The profile (uniform, periodic by convention) [m].
    shortest_wavelength_m, longest_wavelength_m : float
        Band of the fit [m].

    Returns
    -------
    dict
        ``slope`` [-], ``slope_standard_error`` [-], ``hurst`` [-], ``hurst_standard_error`` [-], ``n_ordinates``.
    """
    check_range("shortest_wavelength_m", shortest_wavelength_m, 2.0 * profile.spacing, longest_wavelength_m,
                unit="m")
    z = profile.z - profile.z.mean()
    k = 2.0 * math.pi * np.fft.rfftfreq(z.size, d=profile.spacing)
    power = np.abs(np.fft.rfft(z)) ** 2
    band = (k >= 2.0 * math.pi / longest_wavelength_m) & (k <= 2.0 * math.pi / shortest_wavelength_m) & (power > 0)
    if band.sum() < 8:
        raise InputError("wavelength band", (shortest_wavelength_m, longest_wavelength_m),
                         "a band holding at least 8 non-zero Fourier ordinates", f"holds {int(band.sum())}")
    x = np.log(k[band])
    y = np.log(power[band])
    xc = x - x.mean()
    slope = float(np.sum(xc * (y - y.mean())) / np.sum(xc**2))
    se = math.sqrt(math.pi**2 / 6.0 / float(np.sum(xc**2)))
    return {"slope": slope, "slope_standard_error": se, "hurst": (-slope - 1.0) / 2.0,
            "hurst_standard_error": se / 2.0, "n_ordinates": int(band.sum())}


def periodogram(profile: RoughnessProfile) -> tuple[np.ndarray, np.ndarray]:
    """One-sided 1-D power spectral density estimate of a profile, C(k_j) = 2·Δx/N·|Z_j|² (Z its DFT).

    Σ_j C(k_j)·Δk/(2π) = Rq² (Parseval; the DC term excluded).

    Parameters
    ----------
    profile : RoughnessProfile
        The profile [-].

    Returns
    -------
    tuple of ndarray
        (k [rad/m], C [m³]).
    """
    z = profile.z - profile.z.mean()
    n = z.size
    k = 2.0 * math.pi * np.fft.rfftfreq(n, d=profile.spacing)
    power = np.abs(np.fft.rfft(z)) ** 2 * (2.0 * profile.spacing / n)
    if n % 2 == 0:
        power[-1] *= 0.5
    return k[1:], power[1:]


# ---------------------------------------------------------------------------------------------------------------
# User profiles
# ---------------------------------------------------------------------------------------------------------------
def _read_two_columns(path: Path) -> np.ndarray:
    """Rows (x, z) of a two-column text file; any defect raises InputError naming the file and line."""
    if not path.is_file():
        raise InputError("roughness file", str(path), "an existing two-column text file")
    try:  # fast C parser for well-formed whitespace-separated files; the line loop below explains any defect
        data = np.loadtxt(path, comments="#", ndmin=2)
    except ValueError:
        data = None
    if data is not None and data.ndim == 2 and data.shape[1] == 2 and data.shape[0] >= 16 \
            and np.all(np.isfinite(data)) and np.all(np.diff(data[:, 0]) > 0):
        return data
    rows = []
    with open(path, encoding="utf-8", errors="replace") as handle:
        for number, raw in enumerate(handle, start=1):
            line = raw.split("#", 1)[0].strip()
            if not line:
                continue
            fields = line.replace(",", " ").replace(";", " ").split()
            if len(fields) != 2:
                raise InputError("roughness file", str(path), "two numeric columns x z per line",
                                 f"line {number} has {len(fields)} fields: {line[:60]!r}")
            try:
                x, z = float(fields[0]), float(fields[1])
            except ValueError:
                raise InputError("roughness file", str(path), "two numeric columns x z per line",
                                 f"line {number} is not numeric: {line[:60]!r}") from None
            if not (math.isfinite(x) and math.isfinite(z)):
                raise InputError("roughness file", str(path), "finite numbers",
                                 f"line {number}: {line[:60]!r}")
            rows.append((x, z))
    if len(rows) < 16:
        raise InputError("roughness file", str(path), "at least 16 data lines", f"found {len(rows)}")
    data = np.array(rows)
    if np.any(np.diff(data[:, 0]) <= 0):
        bad = int(np.flatnonzero(np.diff(data[:, 0]) <= 0)[0]) + 2
        raise InputError("roughness file", str(path), "strictly increasing x",
                         f"data line {bad} does not increase x")
    return data


def detrend(x, z) -> np.ndarray:
    """z minus its least-squares straight line in x (removes a + b·x exactly).

    Parameters
    ----------
    x : array_like
        Positions [m].
    z : array_like
        Heights [m].

    Returns
    -------
    ndarray
        Detrended heights [m].
    """
    x = np.asarray(x, dtype=float)
    z = np.asarray(z, dtype=float)
    design = np.column_stack([np.ones_like(x), x - x.mean()])
    coefficients, *_ = np.linalg.lstsq(design, z, rcond=None)
    return z - design @ coefficients


def resample_uniform(x, z, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Linear interpolation of (x, z) onto a uniform grid of ``spacing`` from x[0].

    Box-averaged first when the new spacing is coarser than the data (anti-aliasing).

    Parameters
    ----------
    x : array_like
        Increasing positions [m].
    z : array_like
        Heights [m].
    spacing : float
        Spacing of the uniform grid [m].

    Returns
    -------
    tuple of ndarray
        (grid [m], heights [m]).
    """
    x = np.asarray(x, dtype=float)
    z = np.asarray(z, dtype=float)
    data_spacing = float(np.median(np.diff(x)))
    if spacing > 1.5 * data_spacing:
        width = int(round(spacing / data_spacing))
        kernel = np.ones(width) / width
        z = np.convolve(z, kernel, mode="same")
    n = int(math.floor((x[-1] - x[0]) / spacing + 1e-9)) + 1
    grid = x[0] + spacing * np.arange(n)
    return grid, np.interp(grid, x, z)


def load_profile(path: str | Path, *, unit: str = "um", spacing_m: float | None = None,
                 target_rq_m: float | None = None) -> RoughnessProfile:
    """Read a measured roughness profile: two columns x, z in ``unit``, whitespace or comma separated, ``#`` comments.

    The profile is detrended (least-squares line), resampled to a uniform spacing and scaled to ``target_rq_m`` if
    given.

    Parameters
    ----------
    path : str or Path
        The text file [-].
    unit : str
        Unit of both columns: ``um``, ``mm`` or ``m`` [-].
    spacing_m : float, optional
        Uniform spacing to resample to; None: the file's median spacing [m].
    target_rq_m : float, optional
        RMS roughness to scale to; None: as measured [m].

    Returns
    -------
    RoughnessProfile
        The profile.

    Raises
    ------
    InputError
        Naming the file and the problem (non-numeric line, wrong column count, NaN, non-increasing x, fewer than 16
        points, flat profile, spacing outside the data).
    """
    if unit not in _UNIT_SCALE:
        raise InputError("unit", unit, f"one of {sorted(_UNIT_SCALE)}")
    path = Path(path)
    data = _read_two_columns(path)
    x = data[:, 0] * _UNIT_SCALE[unit]
    raw = data[:, 1] * _UNIT_SCALE[unit]
    z = detrend(x, raw)
    if np.sqrt(np.mean(z**2)) <= 1e-9 * np.max(np.abs(raw)):
        raise InputError("roughness file", str(path), "a profile that is not flat after detrending",
                         "the heights lie on a straight line")
    return _uniform_profile(x, z, path.name, spacing_m, target_rq_m)


def _uniform_profile(x, z, label: str, spacing_m: float | None, target_rq_m: float | None) -> RoughnessProfile:
    """Detrended heights ``z`` [m] at ``x`` [m] resampled to a uniform spacing and optionally scaled."""
    span = x[-1] - x[0]
    if spacing_m is None:
        spacing_m = float(np.median(np.diff(x)))
    check_range("spacing_m", spacing_m, 0.0, span / 15.0, low_inclusive=False, unit=f"m for {label}")
    _, zu = resample_uniform(x, z, spacing_m)
    zu = zu - zu.mean()
    profile = RoughnessProfile(zu, float(spacing_m), f"measured {label} (detrended)")
    if target_rq_m is not None:
        profile = profile.scaled(target_rq_m)
    return profile


TEXT_SUFFIXES = (".txt", ".csv")
"""File name endings read by the two-column text reader (:func:`load_profile`); other files go to
:func:`read_topography_profile`."""


def read_topography_profile(path: str | Path, *, unit: str | None = None, line: int | None = None,
                            spacing_m: float | None = None, target_rq_m: float | None = None) -> RoughnessProfile:
    """Read a profilometer file with SurfaceTopography (the ``roughness`` extra): line scans, or one line of a
    topography map, in any format ``SurfaceTopography.open_topography`` knows (Digital Surf SUR, Zygo, Keyence,
    Bruker, MI, x-y text, ...); detrended, resampled and scaled as :func:`load_profile`.

    Parameters
    ----------
    path : str or Path
        The file [-].
    unit : str, optional
        Length unit of the file when it does not state one (``"m"``, ``"mm"``, ``"um"``, ``"nm"``) [-].
    line : int, optional
        Index of the line along x of a 2-D map (default: the middle one) [-].
    spacing_m : float, optional
        Uniform spacing to resample to (default: the file's median spacing) [m].
    target_rq_m : float, optional
        Rq to scale the profile to [m].

    Returns
    -------
    RoughnessProfile
        The detrended, uniformly sampled profile.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("roughness file", str(path), "an existing profilometer file")
    try:
        from SurfaceTopography import open_topography
        from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor
    except ImportError:
        raise InputError("roughness file", str(path), "a two-column text file (.txt, .csv), or install the "
                         "'roughness' extra (SurfaceTopography) to read profilometer formats") from None
    try:
        topography = open_topography(str(path)).topography()
    except Exception as error:  # the library raises many types for unreadable files
        raise InputError("roughness file", str(path), "a profilometer file SurfaceTopography can read",
                         f"{type(error).__name__}: {error}") from None
    file_unit = topography.unit
    if file_unit is None:
        if unit is None:
            raise InputError("unit", None, "the file's length unit ('m', 'mm', 'um', 'nm'): the file states none")
        file_unit = unit
    factor = get_unit_conversion_factor(file_unit.replace("um", "µm"), "m")
    if topography.dim == 1:
        if topography.is_uniform:
            x = np.asarray(topography.positions(), dtype=float)
            z = np.asarray(topography.heights(), dtype=float)
        else:
            x, z = (np.asarray(v, dtype=float) for v in topography.positions_and_heights())
    else:
        heights = np.asarray(topography.heights(), dtype=float)
        j = heights.shape[1] // 2 if line is None else int(line)
        check_range("line", j, 0, heights.shape[1] - 1)
        x = np.arange(heights.shape[0]) * (topography.physical_sizes[0] / heights.shape[0])
        z = heights[:, j]
    x, z = x * factor, z * factor
    if x.size < 16 or not np.all(np.isfinite(z)):
        raise InputError("roughness file", str(path), "at least 16 finite heights along the line")
    z = detrend(x, z)
    if np.sqrt(np.mean(z**2)) == 0.0:
        raise InputError("roughness file", str(path), "a profile that is not flat after detrending")
    return _uniform_profile(x, z, path.name, spacing_m, target_rq_m)


def resolve_profile(spec: str, *, unit: str | None = None, line: int | None = None) -> RoughnessProfile:
    """A profile from a registry name (:data:`PROFILES`), a two-column text file (:data:`TEXT_SUFFIXES`; ``unit``
    default µm) or a profilometer file (:func:`read_topography_profile`).

    Parameters
    ----------
    spec : str
        Registry name or file path [-].
    unit : str, optional
        Length unit of a file that does not state one [-].
    line : int, optional
        Line of a 2-D map [-].

    Returns
    -------
    RoughnessProfile
        The profile.
    """
    if spec in PROFILES:
        return named_profile(spec)
    path = Path(spec)
    if path.suffix.lower() in TEXT_SUFFIXES:
        return load_profile(path, unit=unit or "um")
    if not path.exists():
        raise InputError("roughness", spec, f"one of {sorted(PROFILES)} or an existing file")
    return read_topography_profile(path, unit=unit, line=line)


# ---------------------------------------------------------------------------------------------------------------
# The two moving surfaces
# ---------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class SurfacePair:
    """Roughness of both surfaces on a fixed solver grid for one transient run (see :func:`plan_surfaces`).

    R_i(x, t) = (Rq_i/Rq_profile)·P(x − u_i t − c_i) with offsets c_i that put surface 1 and surface 2 on
    non-overlapping stretches of the profile for 0 ≤ t ≤ ``t_end``. ``independent`` is False when the profile is too
    short for that (it is then read periodically and the stretches overlap; the solver should record it).
    """

    profile: RoughnessProfile
    x: np.ndarray
    u1: float
    u2: float
    scale1: float
    scale2: float
    offset1: float
    offset2: float
    t_end: float
    required_length: float

    @property
    def independent(self) -> bool:
        """True when the two surfaces read disjoint stretches of the profile (separated by the gap)."""
        return self.required_length <= self.profile.length

    def at(self, t) -> tuple[np.ndarray, np.ndarray]:
        """(R1, R2) [m] at time(s) ``t`` [s]: shape ``x.shape`` for scalar t, ``t.shape + x.shape`` for arrays."""
        tt = np.asarray(t, dtype=float)[..., None] if np.ndim(t) else float(t)
        r1 = self.profile.sample(self.x - self.u1 * tt - self.offset1) * self.scale1
        r2 = self.profile.sample(self.x - self.u2 * tt - self.offset2) * self.scale2
        return r1, r2

    def disjoint_until(self, t_s: float) -> bool:
        """True when, over 0 ≤ t ≤ ``t_s`` [s] (shorter or longer than ``t_end``: beyond it the profile is read on,
        periodically), the two surfaces read disjoint parts of the periodic profile. A run that stops before the
        end of its layout may read disjoint stretches of a profile too short for the whole layout."""
        t = float(t_s)
        (a1, b1), (a2, b2) = _stretch(self.x, self.u1, t, self.offset1), _stretch(self.x, self.u2, t, self.offset2)
        length = self.profile.length
        l1, l2 = b1 - a1, b2 - a2
        if l1 + l2 >= length:
            return False
        shift = (a2 - a1) % length
        return l1 <= shift and shift + l2 <= length

    def stretches(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """Profile-coordinate intervals [m] (unwrapped) that surfaces 1 and 2 read over the run."""
        return (_stretch(self.x, self.u1, self.t_end, self.offset1), _stretch(self.x, self.u2, self.t_end,
                                                                               self.offset2))


def _stretch(x: np.ndarray, u: float, t_end: float, offset: float) -> tuple[float, float]:
    travel = u * t_end
    return (float(x.min() - max(travel, 0.0) - offset), float(x.max() - min(travel, 0.0) - offset))


def plan_surfaces(case, x_m, t_end_s: float, profile: RoughnessProfile | None = None) -> SurfacePair:
    """Lay the two surfaces of ``case`` (a :class:`~ehl_dataset.model.contact.ContactCase`: u1, u2, rq1, rq2) out on
    the profile for a run over the solver grid ``x_m`` [m] from t = 0 to ``t_end_s`` [s].

    Surface 1 reads the stretch starting at profile coordinate 0, surface 2 the stretch that follows after a gap
    of :data:`SEGMENT_GAP_CORRELATION_LENGTHS` correlation lengths. Needed profile length:
    2(x_max − x_min) + (|u1| + |u2|) t_end + gap.
    """
    x = np.ascontiguousarray(x_m, dtype=float)
    if x.ndim != 1 or x.size < 2 or not np.all(np.isfinite(x)):
        raise InputError("x_m", f"array of shape {x.shape}", "a finite 1-D grid with at least 2 nodes")
    check_range("t_end_s", t_end_s, 0.0, 1e3, unit="s")
    profile = profile if profile is not None else default_profile()
    rq0 = profile.rq
    if rq0 == 0.0:
        raise InputError("roughness profile", profile.source, "a profile with non-zero Rq")
    gap = SEGMENT_GAP_CORRELATION_LENGTHS * min(profile.correlation_length, profile.length / 40)
    u1, u2 = float(case.u1), float(case.u2)
    lo1, hi1 = _stretch(x, u1, t_end_s, 0.0)
    offset1 = lo1  # surface 1 starts at profile coordinate 0
    lo2, hi2 = _stretch(x, u2, t_end_s, 0.0)
    offset2 = lo2 - (hi1 - lo1) - gap  # surface 2 starts after surface 1's stretch and the gap
    required = (hi1 - lo1) + gap + (hi2 - lo2)
    return SurfacePair(profile, x, u1, u2, case.rq1 / rq0, case.rq2 / rq0, offset1, offset2, float(t_end_s),
                       float(required))


def surface_pair(case, x_m, t_s, t_end_s: float, profile: RoughnessProfile | None = None):
    """(R1, R2) [m] = (R1(x − u1 t), R2(x − u2 t)) on the grid ``x_m`` at time(s) ``t_s`` of a run lasting
    ``t_end_s`` [s], from independent stretches of ``profile`` (default: :func:`default_profile`) scaled to the
    case's Rq1 and Rq2. Equivalent to ``plan_surfaces(case, x_m, t_end_s, profile).at(t_s)``; use
    :func:`plan_surfaces` once per run when calling at many time steps.
    """
    return plan_surfaces(case, x_m, t_end_s, profile).at(t_s)


def profile_record(profile: RoughnessProfile) -> dict:
    """What a rough result records of the profile both surfaces took.

    Parameters
    ----------
    profile : RoughnessProfile
        The profile [-].

    Returns
    -------
    dict
        ``roughness_profile`` (its source), ``roughness_correlation_length_m`` [m], and for a named profile
        (:func:`named_profile`) ``roughness_name`` and ``roughness_sha256``.
    """
    record = {"roughness_profile": profile.source,
              "roughness_correlation_length_m": float(profile.correlation_length)}
    if profile.name:
        record.update(roughness_name=profile.name, roughness_sha256=profile.sha256)
    return record
