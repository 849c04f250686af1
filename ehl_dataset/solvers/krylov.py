"""Linear solves of the deterministic mixed solver: right-preconditioned GMRES and the banded preconditioner.

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

import numpy as np
from scipy.linalg import lapack, solve_triangular

from ..discretisation.mixed_system import preconditioner_band


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
        self.load_row[0::3] = np.convolve(weights, binv[::-1], mode="same")
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
            out[2:-1:3] = np.convolve(y[0::3], self.binv, mode="same") - dpf
        out[-1] = dh0
        return out


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
