"""Elastic deflection of a line contact (plane strain), paper Eq. 4.

    V(x) = −4/(πE') ∫ ln|x − x'| p(x') dx'

The pressure is taken piecewise linear between the nodes (hat functions), and the log kernel is integrated EXACTLY
over every element, using the antiderivatives

    ∫ ln|t| dt = t ln|t| − t,        ∫ t ln|t| dt = t²/2 ln|t| − t²/4.

Two forms of the same discretisation:

* :func:`influence_matrix` — dense matrix for any (non-uniform) grid, K[i, j] = ∂V_i/∂p_j. Used by the steady
  Newton solver, whose Jacobian needs K anyway.
* :func:`uniform_kernel` + :func:`deflection_fft` — on a uniform grid K is Toeplitz, K[i, j] = k[i − j], and the
  product K p is a linear convolution computed by zero-padded FFT in O(N log N) (the DC-FFT method of Liu, Wang &
  Liu, Wear 243 (2000) 101–111). Used for the long uniform grids of rough transient runs.

The kernels are written for the generic operator  (Kp)_i = −(1/π) ∫ ln|x_i − x'| p(x') dx'  in whatever length unit
``x`` has; multiply by ``4/E'`` for the SI deflection. Because ln|x − x'| changes by a constant when the length unit
changes, V is defined up to a constant times ∫p dx, which the film constant h0 absorbs.
"""

from __future__ import annotations

from collections import OrderedDict

import numba
import numpy as np

INFLUENCE_CACHE_SIZE = 32
"""Number of grids whose :func:`influence_matrix` is kept (per process): K depends only on the grid, and the solves
of one contact (continuation grid, level grid, the mixed models on the same grid) and of a factorial's contacts on
the level's grid ask for the same few."""
_INFLUENCE_CACHE: OrderedDict = OrderedDict()


def _f1(t):
    """Antiderivative of ln|t|: t ln|t| − t (0 at t = 0)."""
    at = np.abs(t)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(at > 0.0, t * np.log(np.where(at > 0.0, at, 1.0)) - t, 0.0)
    return out


def _f2(t):
    """Antiderivative of t ln|t|: t²/2 ln|t| − t²/4 (0 at t = 0)."""
    at = np.abs(t)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(at > 0.0, 0.5 * t * t * np.log(np.where(at > 0.0, at, 1.0)) - 0.25 * t * t, 0.0)
    return out


def _hat_weights(x_eval, x_nodes):
    """Exact ∫ ln|x_eval − x'| φ_j(x') dx' for the hat functions φ_j of the nodes ``x_nodes`` (shape (M, N))."""
    x_eval = np.asarray(x_eval, dtype=float)[:, None]
    x_nodes = np.asarray(x_nodes, dtype=float)
    left, right = x_nodes[:-1], x_nodes[1:]
    length = right - left
    ta = left[None, :] - x_eval  # element start relative to the evaluation point
    tb = right[None, :] - x_eval
    int_ln = _f1(tb) - _f1(ta)
    int_tln = _f2(tb) - _f2(ta)
    # On element e = [x_e, x_{e+1}] (t measured from the evaluation point):
    #   φ_e = (t_b − t)/L,  φ_{e+1} = (t − t_a)/L
    to_left = (tb * int_ln - int_tln) / length
    to_right = (int_tln - ta * int_ln) / length
    weights = np.zeros((x_eval.shape[0], x_nodes.size))
    weights[:, :-1] += to_left
    weights[:, 1:] += to_right
    return weights


@numba.njit(cache=True)
def _hat_weights_self(x):
    """:func:`_hat_weights` of the nodes ``x`` at the nodes themselves, (N, N), with one logarithm per node pair: the
    antiderivatives at an element's end serve both elements that share the node."""
    n = x.size
    weights = np.zeros((n, n))
    f1 = np.empty(n)
    f2 = np.empty(n)
    for i in range(n):
        for j in range(n):
            t = x[j] - x[i]
            if t == 0.0:
                f1[j] = 0.0
                f2[j] = 0.0
            else:
                ln = np.log(abs(t))
                f1[j] = t * ln - t
                f2[j] = 0.5 * t * t * ln - 0.25 * t * t
        for e in range(n - 1):
            ta = x[e] - x[i]
            tb = x[e + 1] - x[i]
            int_ln = f1[e + 1] - f1[e]
            int_tln = f2[e + 1] - f2[e]
            length = x[e + 1] - x[e]
            weights[i, e] += (tb * int_ln - int_tln) / length
            weights[i, e + 1] += (int_tln - ta * int_ln) / length
    return weights


def influence_matrix(x, scale: float = 1.0) -> np.ndarray:
    """Dense influence matrix K with (K p)_i = −(scale/π) ∫ ln|x_i − x'| p(x') dx' for piecewise-linear p.

    Parameters
    ----------
    x : array_like
        Strictly increasing nodes [any length unit; a for the solvers].
    scale : float
        Factor of the operator [same unit as K p per unit of p]; ``4/E'`` with x in metres gives the deflection
        V [m] of paper Eq. 4 for p in Pa.

    Returns
    -------
    numpy.ndarray
        K, shape (N, N), read-only: the matrix of a grid is computed once per process and shared
        (:data:`INFLUENCE_CACHE_SIZE` grids are kept).
    """
    x = np.ascontiguousarray(x, dtype=float)
    if x.ndim != 1 or x.size < 2 or np.any(np.diff(x) <= 0.0):
        raise ValueError("x must be a strictly increasing 1-D array with at least two nodes")
    key = (x.tobytes(), float(scale))
    kmat = _INFLUENCE_CACHE.get(key)
    if kmat is not None:
        _INFLUENCE_CACHE.move_to_end(key)
        return kmat
    kmat = -(scale / np.pi) * _hat_weights_self(x)
    kmat.flags.writeable = False
    _INFLUENCE_CACHE[key] = kmat
    if len(_INFLUENCE_CACHE) > INFLUENCE_CACHE_SIZE:
        _INFLUENCE_CACHE.popitem(last=False)
    return kmat


def uniform_kernel(n: int, dx: float, scale: float = 1.0) -> np.ndarray:
    """Kernel k[m], m = −(n−1)..(n−1) (array index m + n − 1), with K[i, j] = k[i − j] on a uniform grid."""
    if n < 2 or not dx > 0.0:
        raise ValueError("need n >= 2 nodes and dx > 0")
    offsets = np.arange(-(n - 1), n, dtype=float) * dx
    # weight of node j = 0 (a full hat on [−dx, dx]) seen from x_i = m·dx
    x_nodes = np.array([-dx, 0.0, dx])
    w = _hat_weights(offsets, x_nodes)[:, 1]
    return -(scale / np.pi) * w


def deflection_fft(p: np.ndarray, kernel: np.ndarray) -> np.ndarray:
    """Linear convolution V_i = Σ_j k[i − j] p_j by zero-padded FFT (DC-FFT), O(N log N).

    ``kernel`` from :func:`uniform_kernel` with the same n. End nodes are treated as full hats; callers keep
    p = 0 there (the Reynolds boundary condition), so the result equals the dense :func:`influence_matrix` product.
    """
    p = np.asarray(p, dtype=float)
    n = p.size
    if kernel.size != 2 * n - 1:
        raise ValueError(f"kernel has {kernel.size} entries, expected {2 * n - 1} for {n} nodes")
    size = 1 << int(np.ceil(np.log2(3 * n - 2)))
    spectrum = np.fft.rfft(kernel, size) * np.fft.rfft(p, size)
    full = np.fft.irfft(spectrum, size)
    return full[n - 1: 2 * n - 1]


def uniform_symbol(n_fft: int, dx: float, images: int = 200) -> np.ndarray:
    """Discrete Fourier symbol s(θ_k), θ_k = 2π k/n_fft, of the uniform-grid operator (K p)_i = Σ_j k[i − j] p_j of
    :func:`uniform_kernel` (unit scale) on the infinite line, for the n_fft angles of ``np.fft.fftfreq``.

    The operator −(1/π)∫ln|x − x'| p(x') dx' has the continuous symbol 1/|ξ|; with hat-function pressures sampled at
    the nodes its discrete symbol is the aliased sum s(θ) = dx Σ_j sinc²(θ/2 + πj)/|θ + 2πj| (sinc t = sin t/t),
    summed over |j| ≤ ``images`` (the terms fall off as 1/j³). s(0) = ∞ (the log kernel); the entry is set to inf.
    """
    theta = 2.0 * np.pi * np.fft.fftfreq(n_fft)
    total = np.zeros(n_fft)
    half = 0.5 * theta
    for j in range(-images, images + 1):
        t = theta + 2.0 * np.pi * j
        with np.errstate(divide="ignore", invalid="ignore"):
            total += np.where(t != 0.0, np.sin(half) ** 2 / (0.5 * t) ** 2 / np.abs(t), 0.0)
    total *= dx
    total[0] = np.inf
    return total


def periodic_kernel_spectrum(n: int, dx: float, images: int = 200) -> np.ndarray:
    """Real-FFT multiplier (length n//2 + 1) of the deflection of a pressure periodic over n nodes of spacing
    ``dx``: V = irfft(rfft(P)·K̂, n) is (K p)_i of :func:`uniform_kernel` summed over all periodic images, which is
    :func:`uniform_symbol` at the n angles 2πk/n. The mean mode (k = 0, the log kernel's infinite constant) is set to
    0: a periodic window's mean deflection belongs to its film constant. A pressure cos(2πx/L) gives the
    deflection cos(2πx/L)·L/(2π) up to O((2πΔ/L)²) (the symbol of the continuous operator is 1/|ξ|)."""
    if n < 2 or not dx > 0.0:
        raise ValueError("need n >= 2 nodes and dx > 0")
    symbol = uniform_symbol(n, dx, images)[: n // 2 + 1]
    symbol[0] = 0.0
    return symbol


def inverse_kernel_band(width: int, dx: float, n_fft: int = 1 << 14) -> np.ndarray:
    """Coefficients b[m], m = −width … width (array index m + width), of the banded approximation B ≈ K⁻¹ of the
    uniform-grid deflection operator of :func:`uniform_kernel` (unit scale), spacing ``dx``.

    The exact inverse of the infinite Toeplitz operator has the symbol 1/s(θ) (:func:`uniform_symbol`), whose
    coefficients decay like −1/(π m² dx) (the hypersingular kernel of the Hilbert-transform derivative). They are
    truncated at ``width`` and their sum set to zero (a constant deflection needs no pressure: the film constant
    takes it). B is local, so the preconditioner of the mixed solver that uses it stays banded; it is exact at the
    grid scale and wrong only for wavelengths above ~ width·dx, which the Krylov iteration corrects.
    """
    if width < 1 or not dx > 0.0:
        raise ValueError("need width >= 1 and dx > 0")
    inverse = 1.0 / uniform_symbol(n_fft, dx)
    coefficients = np.fft.ifft(inverse).real
    band = np.concatenate([coefficients[-width:], coefficients[: width + 1]])
    band[width] -= band.sum()
    return band
