"""Krylov linear solves: right-preconditioned GMRES and the banded preconditioners of the deterministic mixed solver
and of the steady smooth Newton iteration (:class:`SteadyBandedPreconditioner`, the same idea on the steady
system of :mod:`ehl_dataset.discretisation.steady_band`: a banded LU of the Newton matrix in deflection variables).

The Newton matrix J = A + D·(K, 1) of :mod:`ehl_dataset.discretisation.mixed_system` is dense (K, the deflection,
couples every node), but its product with a vector costs O(N log N) with the FFT of the deflection kernel, and a
banded matrix approximates it well: in the deflection variable ΔV = K ΔP every row is local except the relation
ΔP = K⁻¹ΔV, and K⁻¹ decays like 1/m² (:func:`~ehl_dataset.discretisation.deflection.inverse_kernel_band`). GMRES
with that banded LU as right preconditioner (Saad, *Iterative Methods for Sparse Linear Systems*, 2nd ed. 2003,
§9.3.2) converges in ~10–20 iterations; the LU (LAPACK ``dgbtrf``, O(N·w²)) is reused while it stays good.

GMRES is written out here (30 lines) instead of calling ``scipy.sparse.linalg.gmres`` because the Newton loop needs
the true relative residual of the preconditioned solve and the iteration count of every call, and the
per-call overhead of the library routine was a third of the solve time on grids of a few hundred nodes.
"""

from __future__ import annotations

import math
from collections import OrderedDict

import numba
import numpy as np
from scipy.linalg import lapack, solve_triangular

from ..discretisation.deflection import inverse_kernel_band
from ..discretisation.mixed_system import preconditioner_band
from ..discretisation.steady_band import (apply_inverse_band, band_lu_solve, band_matvec, deflection_band,
                                          inverse_band, newton_band)

STEADY_INVERSE_WIDTH = 6
"""Half width w of the banded inverse kernel B ≈ K⁻¹ of :class:`SteadyBandedPreconditioner` [nodes]."""
STEADY_BAND = 16
"""Half width of the band of S B that :class:`SteadyBandedPreconditioner` factorises [nodes] (more than w + 2: the
film part E K B reaches beyond the band of B). With the inexact Newton iteration's forcing term
(:func:`~ehl_dataset.solvers.newton.forcing_term`), on 100 random paper-factorial contacts at ``standard`` (each solved
once untimed, then every way in a rotating order; median CPU of a steady smooth solve, GMRES iterations a contact):
w = 16 with half width 32: 18.9 ms, 27; 8, 20: 17.1 ms, 34; 8, 16: 16.5 ms, 39; 6, 16: 17.1 ms, 39; 6, 12: 15.8 ms,
46 (a cheaper band LU against more GMRES iterations; differences of ~1 ms are within the run-to-run spread); μ, h_min,
h_c, p_max within 2.4e-8. Solved to 1e-10 instead, the narrow bands need more GMRES iterations than they save
(:data:`WIDE_BAND`)."""
WIDE_INVERSE_WIDTH = 16
"""Half width w of B for problems that solve every Newton system to
:data:`~ehl_dataset.solvers.newton.KRYLOV_TOLERANCE` (the homogenised model's averaged-Reynolds problem) [nodes]."""
WIDE_BAND = 32
"""Half width of the factorised band of S B for those problems [nodes]: to the tight tolerance the narrow band of
:data:`STEADY_BAND` needs more GMRES iterations than it saves (steady smooth solves to 1e-10 on 60 random paper-factorial
contacts: median 56 ms with w = 16 and a band of half width 16, 32 ms with these, measured first and so at a
disadvantage)."""
STEADY_SYMBOL_POINTS = 1024
"""Angles at which the discrete symbol is sampled for the unit-spacing coefficients of B
(:func:`~ehl_dataset.discretisation.deflection.inverse_kernel_band`): once per process, ~10 ms (the default 2¹⁴ took
~0.1 s of a cold start); the coefficients differ from the default's by 2e-5 relative, which only changes how well the
preconditioner approximates, not what GMRES converges to."""
STEADY_GRID_CACHE_SIZE = 32
"""Grids whose preconditioner data (:class:`SteadyGridBand`) are kept per process, as the influence matrices."""
_STEADY_GRIDS: OrderedDict = OrderedDict()
_UNIT_COEFFICIENTS: dict = {}


class BandedPreconditioner:
    """LU of the banded approximation M (:func:`~ehl_dataset.discretisation.mixed_system.preconditioner_band`) of
    the Jacobian, bordered by the film constant H0 and the load row Σ w_j (ΔP_f + ΔP_c)_j.

    ``jac``, ``dfilm`` the band arrays of the Jacobian; ``binv`` the banded inverse kernel; ``weights`` the
    finite-volume widths w_j. :meth:`apply` returns an approximate Newton correction in the solver's variables
    (P_f, θ, P_c interleaved, H0 last).
    """

    def __init__(self, jac, dfilm, binv, weights, periodic: bool = False):
        width = (binv.size - 1) // 2
        self.n = weights.size
        self.kl = 3 * width + 5
        self.periodic = periodic
        band, col_h0 = preconditioner_band(jac, dfilm, binv, self.kl)
        lu, piv, info = lapack.dgbtrf(band, self.kl, self.kl)
        if info < 0:
            raise ValueError(f"dgbtrf: illegal argument {-info}")
        self.singular = info > 0
        self.lu, self.piv, self.binv = lu, piv, binv
        self.border = self._solve(col_h0)
        if periodic:
            # a periodic deflection has no mean mode: ΔP_f + ΔP_c = BΔV + c with c the mean pressure change, which
            # the load row fixes (Σ_j w_j (BΔV)_j = 0: B sums to zero), and ΔH0 keeps the mean of ΔV at zero
            self.total_weight = float(np.sum(weights))
            self.mean_shift = self._solve(np.sum(jac[:, :, 2], axis=1))
            self.denominator = float(np.sum(self.border[0::3])) / self.n
            self.wrap = wrap_index(self.n, width)
            return
        # load row in z': Σ_j w_j (BΔV)_j = Σ_l (Bᵀw)_l ΔV_l (ΔP_f cancels)
        self.load_row = np.zeros(3 * self.n)
        self.load_row[0::3] = banded_product(weights, binv[::-1])
        self.denominator = -float(self.load_row @ self.border)

    def _solve(self, rhs):
        x, _ = lapack.dgbtrs(self.lu, self.kl, self.kl, rhs, self.piv)
        return x

    def apply(self, r: np.ndarray) -> np.ndarray:
        """Approximate J⁻¹ r (length 3N + 1)."""
        y = self._solve(r[:-1])
        shift = 0.0
        if self.periodic:
            shift = r[-1] / self.total_weight
            y = y - self.mean_shift * shift
            dh0 = float(np.sum(y[0::3])) / self.n / self.denominator
            smoothed = wrapped_convolution(y[0::3] - self.border[0::3] * dh0, self.binv, self.wrap)
        else:
            dh0 = (r[-1] - self.load_row @ y) / self.denominator
        y = y - self.border * dh0
        out = np.empty(3 * self.n + 1)
        dpf = y[1::3]
        out[0:-1:3] = dpf
        out[1:-1:3] = y[2::3]
        if self.periodic:
            out[2:-1:3] = smoothed + shift - dpf
        else:
            out[2:-1:3] = banded_product(y[0::3], self.binv) - dpf
        out[-1] = dh0
        return out


def banded_product(values: np.ndarray, stencil: np.ndarray) -> np.ndarray:
    """Product of a banded Toeplitz matrix with a vector on a bounded grid: out_j = Σ_k s[j − k + w] v_k over the
    nodes k of the grid (entries beyond its ends are zero), for an odd-length stencil s of half width w.

    This is ``np.convolve(values, stencil, mode="same")`` when the grid has at least 2w + 1 nodes; on a shorter grid
    (a band wider than the grid) ``mode="same"`` returns 2w + 1 values centred on the stencil, whereas the product
    keeps the N nodes of the grid: the middle N of the full convolution.

    Parameters
    ----------
    values : numpy.ndarray
        Vector v on the N nodes [-].
    stencil : numpy.ndarray
        Diagonals s of the band, 2w + 1 entries, the main diagonal in the middle [-].

    Returns
    -------
    numpy.ndarray
        The N values of the product [-].
    """
    half = (stencil.size - 1) // 2
    if values.size >= stencil.size:
        return np.convolve(values, stencil, mode="same")
    return np.convolve(values, stencil, mode="full")[half: half + values.size]


class SteadyGridBand:
    """What :class:`SteadyBandedPreconditioner` needs of a grid and its deflection matrix, computed once per grid:
    B ≈ K_II⁻¹ (:func:`~ehl_dataset.discretisation.steady_band.inverse_band`), the band of K_I B
    (:func:`~ehl_dataset.discretisation.steady_band.deflection_band`) and the load row in the deflection variables
    Bᵀℓ.

    Parameters
    ----------
    kmat : numpy.ndarray
        Dense deflection matrix K of the grid, (N, N) [-].
    weights : numpy.ndarray
        Control-volume widths w_i of the N nodes [a].
    load_row : numpy.ndarray
        Derivative of the relative load error with respect to the interior pressures, M = N − 2 entries [-].
    width : int or None
        Half width w of B [nodes]; None takes :data:`STEADY_INVERSE_WIDTH`.
    band : int or None
        Half width of the band of S B the preconditioner factorises [nodes]; None takes :data:`STEADY_BAND`.
    """

    def __init__(self, kmat: np.ndarray, weights: np.ndarray, load_row: np.ndarray, width: int | None = None,
                 band: int | None = None):
        width = STEADY_INVERSE_WIDTH if width is None else int(width)
        self.band = STEADY_BAND if band is None else int(band)
        coefficients = _UNIT_COEFFICIENTS.get(width)
        if coefficients is None:
            coefficients = _UNIT_COEFFICIENTS.setdefault(width, inverse_kernel_band(width, 1.0, STEADY_SYMBOL_POINTS))
        self.kmat = kmat
        self.binv = inverse_band(np.ascontiguousarray(weights, dtype=float), coefficients)
        self.kb = deflection_band(np.ascontiguousarray(kmat), self.binv, self.band + 2)
        self.load = _transpose_band_product(self.binv, np.asarray(load_row, dtype=float))

    @classmethod
    def of(cls, kmat: np.ndarray, weights: np.ndarray, load_row: np.ndarray, width: int | None = None,
           band: int | None = None) -> "SteadyGridBand":
        """The kept data of the deflection matrix ``kmat`` (the same object) and the widths, computed on the first
        request.

        Parameters
        ----------
        kmat : numpy.ndarray
            Dense deflection matrix K, (N, N) [-].
        weights : numpy.ndarray
            Control-volume widths of the N nodes [a].
        load_row : numpy.ndarray
            Load-row derivative over the M interior pressures [-].
        width, band : int or None
            Half widths of B and of the factorised band (:class:`SteadyGridBand`) [nodes].

        Returns
        -------
        SteadyGridBand
            The data, shared by every problem on the same matrix.
        """
        width = STEADY_INVERSE_WIDTH if width is None else int(width)
        band = STEADY_BAND if band is None else int(band)
        key = (id(kmat), width, band)
        entry = _STEADY_GRIDS.get(key)
        if entry is not None and entry.kmat is kmat:  # the entry holds kmat, so its id cannot be reused meanwhile
            _STEADY_GRIDS.move_to_end(key)
            return entry
        entry = cls(kmat, weights, load_row, width, band)
        if not kmat.flags.writeable:  # only the shared read-only matrices of influence_matrix are kept
            _STEADY_GRIDS[key] = entry
            while len(_STEADY_GRIDS) > STEADY_GRID_CACHE_SIZE:
                _STEADY_GRIDS.popitem(last=False)
        return entry


def _transpose_band_product(binv: np.ndarray, row: np.ndarray) -> np.ndarray:
    """Bᵀ row for B in the diagonal storage of :func:`~ehl_dataset.discretisation.steady_band.inverse_band`."""
    m, size = binv.shape
    width = (size - 1) // 2
    out = np.zeros(m)
    for k in range(-width, width + 1):
        lo, hi = max(0, -k), min(m, m - k)
        out[lo + k: hi + k] += binv[lo:hi, k + width] * row[lo:hi]
    return out


class SteadyBandedPreconditioner:
    """Approximate inverse of the steady Newton matrix S from the LU of the band of S B
    (:func:`~ehl_dataset.discretisation.steady_band.newton_band`), bordered by the film constant and the load row.

    :meth:`apply` solves M y = r (the band of S B), eliminates ΔH0 with the exact load row in the deflection
    variables, and returns ΔP = B y: S·apply(r) = r up to what the band leaves out of S B, which a right-preconditioned
    GMRES (:func:`gmres`) corrects in a few iterations.

    Parameters
    ----------
    lb, eb : numpy.ndarray
        Local parts of the Newton matrix (:func:`~ehl_dataset.discretisation.steady_band.newton_bands`), (M, 4) [-].
    grid : SteadyGridBand
        Data of the grid [-].
    """

    def __init__(self, lb: np.ndarray, eb: np.ndarray, grid: SteadyGridBand):
        self.kl = grid.band
        self.grid = grid
        self.m = lb.shape[0]
        band, col_h0 = newton_band(lb, eb, grid.binv, grid.kb, self.kl)
        self.lu, self.piv, info = lapack.dgbtrf(band, self.kl, self.kl, overwrite_ab=True)
        if info < 0:
            raise ValueError(f"dgbtrf: illegal argument {-info}")
        self.singular = info > 0
        if self.singular:
            return
        self.border = self._solve(col_h0)
        self.denominator = float(grid.load @ self.border)
        self.singular = not (math.isfinite(self.denominator) and self.denominator != 0.0)

    def _solve(self, rhs):
        x, _ = lapack.dgbtrs(self.lu, self.kl, self.kl, rhs, self.piv)
        return x

    def apply(self, r: np.ndarray) -> np.ndarray:
        """Approximate S⁻¹ r (length M + 1: ΔP, ΔH0).

        Parameters
        ----------
        r : numpy.ndarray
            Right-hand side, M + 1 entries [-].

        Returns
        -------
        numpy.ndarray
            The approximate correction (ΔP, ΔH0) [-].
        """
        y = self._solve(r[:-1])
        dh0 = (float(self.grid.load @ y) - r[-1]) / self.denominator
        out = np.empty(self.m + 1)
        out[:-1] = apply_inverse_band(self.grid.binv, y - self.border * dh0)
        out[-1] = dh0
        return out

    def solve(self, lb: np.ndarray, eb: np.ndarray, load_row: np.ndarray, rhs: np.ndarray, tol: float,
              max_iterations: int, give_up_after: int) -> tuple[np.ndarray, int, float]:
        """Solve S δ = ``rhs`` by :func:`gmres` right-preconditioned with :meth:`apply`, compiled in one numba
        function (:func:`steady_gmres`): S v from its bands and one product with K.

        Parameters
        ----------
        lb, eb : numpy.ndarray
            The bands this preconditioner was built from, (M, 4) [-].
        load_row : numpy.ndarray
            The load row, M + 1 entries [-].
        rhs : numpy.ndarray
            Right-hand side, M + 1 entries [-].
        tol : float
            Relative residual to reach [-].
        max_iterations : int
            GMRES iterations allowed [-].
        give_up_after : int
            Iterations after which GMRES stops when its mean convergence rate would not reach ``tol`` [-].

        Returns
        -------
        tuple
            (δ, iterations, relative residual) as :func:`gmres`.
        """
        return steady_gmres(lb, eb, self.grid.kmat, load_row, self.lu, self.piv, self.kl, self.border,
                            self.grid.load, self.denominator, self.grid.binv, rhs, tol, max_iterations, give_up_after)


@numba.njit(cache=True)
def _steady_matvec(lb, eb, kmat, load_row, v):
    m = lb.shape[0]
    p = np.zeros(m + 2)
    p[1:-1] = v[:m]
    out = np.empty(m + 1)
    out[:m] = band_matvec(lb, eb, v, np.dot(kmat, p))
    out[m] = np.dot(load_row, v)
    return out


@numba.njit(cache=True)
def _steady_precondition(lu, piv, kl, border, load, denominator, binv, r):
    m = border.size
    y = band_lu_solve(lu, piv, kl, r[:m])
    dh0 = (np.dot(load, y) - r[m]) / denominator
    out = np.empty(m + 1)
    out[:m] = apply_inverse_band(binv, y - border * dh0)
    out[m] = dh0
    return out


@numba.njit(cache=True)
def steady_gmres(lb, eb, kmat, load_row, lu, piv, kl, border, load, denominator, binv, b, tol, max_iterations,
                 give_up_after):
    """:func:`gmres` (the same algorithm and stopping rules) for the steady Newton matrix held in bands
    (:class:`SteadyBandedPreconditioner`), compiled: S v from :func:`~ehl_dataset.discretisation.steady_band.band_matvec`
    and one product with K, the preconditioner from the banded LU factors (``dgbtrf``). Returns (x, iterations,
    relative residual)."""
    size = b.size
    beta = math.sqrt(np.dot(b, b))
    if beta == 0.0:
        return np.zeros(size), 0, 0.0
    basis = np.zeros((max_iterations + 1, size))
    directions = np.zeros((max_iterations, size))
    hess = np.zeros((max_iterations + 1, max_iterations))
    g = np.zeros(max_iterations + 1)
    cs = np.zeros(max_iterations)
    sn = np.zeros(max_iterations)
    basis[0] = b / beta
    g[0] = beta
    done = 0
    relative = 1.0
    for k in range(max_iterations):
        directions[k] = _steady_precondition(lu, piv, kl, border, load, denominator, binv, basis[k])
        w = _steady_matvec(lb, eb, kmat, load_row, directions[k])
        for _ in range(2):  # classical Gram–Schmidt twice
            for j in range(k + 1):
                c = np.dot(basis[j], w)
                hess[j, k] += c
                w -= c * basis[j]
        hess[k + 1, k] = math.sqrt(np.dot(w, w))
        if hess[k + 1, k] > 0.0:
            basis[k + 1] = w / hess[k + 1, k]
        for j in range(k):
            top = cs[j] * hess[j, k] + sn[j] * hess[j + 1, k]
            hess[j + 1, k] = -sn[j] * hess[j, k] + cs[j] * hess[j + 1, k]
            hess[j, k] = top
        norm = math.hypot(hess[k, k], hess[k + 1, k])
        if norm > 0.0:
            cs[k] = hess[k, k] / norm
            sn[k] = hess[k + 1, k] / norm
        else:
            cs[k] = 1.0
            sn[k] = 0.0
        hess[k, k] = norm
        hess[k + 1, k] = 0.0
        g[k + 1] = -sn[k] * g[k]
        g[k] = cs[k] * g[k]
        done = k + 1
        relative = abs(g[k + 1]) / beta
        if relative <= tol or hess[k, k] == 0.0:
            break
        if done >= give_up_after and relative > 0.0 and math.log(relative) * max_iterations / done > math.log(tol):
            break
    biggest = 0.0
    smallest = math.inf
    for j in range(done):
        biggest = max(biggest, abs(hess[j, j]))
        smallest = min(smallest, abs(hess[j, j]))
    if done and smallest <= 1e-300 * max(biggest, 1e-300):  # breakdown: least squares
        upper = np.zeros((done, done))
        for i in range(done):
            for j in range(i, done):
                upper[i, j] = hess[i, j]
        coefficients = np.linalg.lstsq(upper, g[:done])[0]
    else:
        coefficients = np.zeros(done)
        for i in range(done - 1, -1, -1):
            total = g[i]
            for j in range(i + 1, done):
                total -= hess[i, j] * coefficients[j]
            coefficients[i] = total / hess[i, i]
    x = np.zeros(size)
    for j in range(done):
        x += coefficients[j] * directions[j]
    return x, done, relative


def wrap_index(n: int, half: int) -> np.ndarray:
    """Indices of a length-``n`` periodic array padded by ``half`` wrapped entries on each side."""
    return np.arange(-half, n + half) % n


def wrapped_convolution(values: np.ndarray, weights: np.ndarray, index: np.ndarray | None = None) -> np.ndarray:
    """Periodic convolution of ``values`` with the odd-length stencil ``weights`` centred on its middle entry (what
    ``scipy.ndimage.convolve1d(values, weights, mode="wrap")`` returns, at a fraction of its per-call cost on short
    arrays); ``index`` is :func:`wrap_index` of the sizes, computed once by a caller that convolves many times."""
    if index is None:
        index = wrap_index(values.size, (weights.size - 1) // 2)
    return np.convolve(values[index], weights, mode="valid")


def gmres(matvec, precondition, b: np.ndarray, tol: float, max_iterations: int = 60, give_up_after: int | None = None):
    """Solve A x = b by GMRES with right preconditioning (x = M⁻¹y; Saad 2003, Alg. 9.5), modified Gram–Schmidt and
    Givens rotations, no restart. Stops when ‖b − A x‖ ≤ ``tol``·‖b‖ (the Arnoldi estimate, exact in exact
    arithmetic for right preconditioning). With ``give_up_after`` = k it also stops after k or more iterations when
    the residual's mean reduction so far, continued geometrically, would not reach ``tol`` within ``max_iterations``
    (a caller with a fallback, e.g. a fresh factorisation, wastes no more work). Returns (x, iterations, relative
    residual)."""
    beta = math.sqrt(float(b @ b))
    if beta == 0.0:
        return np.zeros_like(b), 0, 0.0
    basis = np.empty((max_iterations + 1, b.size))
    directions = np.empty((max_iterations, b.size))
    hess = np.zeros((max_iterations + 1, max_iterations))
    g = np.zeros(max_iterations + 1)
    cs = np.zeros(max_iterations)
    sn = np.zeros(max_iterations)
    basis[0] = b / beta
    g[0] = beta
    done, relative = 0, 1.0
    for k in range(max_iterations):
        directions[k] = precondition(basis[k])
        w = matvec(directions[k])
        for _ in range(2):  # classical Gram–Schmidt twice ("twice is enough", Giraud et al. 2005)
            coefficients = basis[: k + 1] @ w
            w -= coefficients @ basis[: k + 1]
            hess[: k + 1, k] += coefficients
        hess[k + 1, k] = math.sqrt(float(w @ w))
        if hess[k + 1, k] > 0.0:
            basis[k + 1] = w / hess[k + 1, k]
        for j in range(k):
            top = cs[j] * hess[j, k] + sn[j] * hess[j + 1, k]
            hess[j + 1, k] = -sn[j] * hess[j, k] + cs[j] * hess[j + 1, k]
            hess[j, k] = top
        norm = math.hypot(hess[k, k], hess[k + 1, k])
        cs[k], sn[k] = (hess[k, k] / norm, hess[k + 1, k] / norm) if norm > 0.0 else (1.0, 0.0)
        hess[k, k] = norm
        hess[k + 1, k] = 0.0
        g[k + 1] = -sn[k] * g[k]
        g[k] = cs[k] * g[k]
        done = k + 1
        relative = abs(g[k + 1]) / beta
        if relative <= tol or hess[k, k] == 0.0:
            break
        if give_up_after is not None and done >= give_up_after and relative > 0.0 \
                and math.log(relative) * max_iterations / done > math.log(tol):
            break
    diagonal = np.abs(np.diag(hess[:done, :done]))
    if done and diagonal.min() <= 1e-300 * max(diagonal.max(), 1e-300):  # breakdown: least squares
        coefficients = np.linalg.lstsq(np.triu(hess[:done, :done]), g[:done], rcond=None)[0]
    else:
        coefficients = solve_triangular(hess[:done, :done], g[:done], check_finite=False)
    return directions[:done].T @ coefficients, done, relative
