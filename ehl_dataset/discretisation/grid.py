"""Computational grids of the EHL solver (dimensionless, X = x/a)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

GRID_CACHE_SIZE = 256
"""Clustered grids kept per process (:func:`clustered_grid`; a steady solve asks for two or three, each built from a
quadrature on some 16,000 points, ~0.35 ms)."""


def clustered_grid(x_start: float, x_end: float, dx_fine: float, dx_coarse: float,
                   bands: tuple[tuple[float, float], ...], transition: float) -> np.ndarray:
    """Nodes on [x_start, x_end] with spacing ``dx_fine`` inside ``bands`` growing linearly to ``dx_coarse``.

    The local spacing is s(X) = dx_fine + (dx_coarse − dx_fine)·min(1, d(X)/transition) with d the distance to the
    nearest band. Nodes are equidistributed in the stretched coordinate ξ(X) = ∫ dX/s, so neighbouring spacings
    differ smoothly (ratio → 1 as the grid is refined), which keeps the finite-volume scheme second order.
    The grids of the last :data:`GRID_CACHE_SIZE` argument sets are kept; each call returns a fresh copy.
    """
    if not (x_end > x_start and dx_coarse >= dx_fine > 0.0):
        raise ValueError("need x_end > x_start and dx_coarse >= dx_fine > 0")
    bands = tuple((float(lo), float(hi)) for lo, hi in bands)
    return _clustered_grid(float(x_start), float(x_end), float(dx_fine), float(dx_coarse), bands,
                           float(transition)).copy()


@lru_cache(maxsize=GRID_CACHE_SIZE)
def _clustered_grid(x_start: float, x_end: float, dx_fine: float, dx_coarse: float,
                    bands: tuple[tuple[float, float], ...], transition: float) -> np.ndarray:
    fine_grid = np.linspace(x_start, x_end, int(np.ceil((x_end - x_start) / (0.1 * dx_fine))) + 1)
    dist = np.full_like(fine_grid, np.inf)
    for lo, hi in bands:
        d = np.where(fine_grid < lo, lo - fine_grid, np.where(fine_grid > hi, fine_grid - hi, 0.0))
        dist = np.minimum(dist, d)
    spacing = dx_fine + (dx_coarse - dx_fine) * np.minimum(1.0, dist / max(transition, 1e-12))
    inv = 1.0 / spacing
    xi = np.concatenate([[0.0], np.cumsum(0.5 * (inv[1:] + inv[:-1]) * np.diff(fine_grid))])
    n_cells = max(int(np.ceil(xi[-1])), 8)
    targets = np.linspace(0.0, xi[-1], n_cells + 1)
    nodes = np.interp(targets, xi, fine_grid)
    nodes[0], nodes[-1] = x_start, x_end
    nodes.flags.writeable = False
    return nodes


def uniform_grid(x_start: float, x_end: float, dx: float) -> np.ndarray:
    """Uniform nodes on [x_start, x_end] with spacing at most ``dx``."""
    n_cells = max(int(np.ceil((x_end - x_start) / dx)), 8)
    return np.linspace(x_start, x_end, n_cells + 1)


def banded_grid(x_start: float, x_end: float, bands: tuple[tuple[float, float, float], ...], dx_coarse: float,
                transition: float) -> np.ndarray:
    """Nodes on [x_start, x_end] with spacing ``dx`` inside each band (lo, hi, dx), growing linearly over
    ``transition`` to ``dx_coarse`` away from the bands (the smallest spacing wins where bands overlap).

    Used by the transient mixed solver: the contact band at the roughness resolution, the inlet band also at the
    inlet length scale of heavy loads. Nodes are equidistributed in ξ = ∫ dX/s as in :func:`clustered_grid`.
    """
    dx_min = min(b[2] for b in bands)
    if not (x_end > x_start and dx_min > 0.0 and dx_coarse >= dx_min):
        raise ValueError("need x_end > x_start and dx_coarse >= band spacings > 0")
    fine_grid = np.linspace(x_start, x_end, int(np.ceil((x_end - x_start) / (0.1 * dx_min))) + 1)
    spacing = np.full_like(fine_grid, dx_coarse)
    for lo, hi, dx in bands:
        d = np.where(fine_grid < lo, lo - fine_grid, np.where(fine_grid > hi, fine_grid - hi, 0.0))
        spacing = np.minimum(spacing, dx + (dx_coarse - dx) * np.minimum(1.0, d / max(transition, 1e-12)))
    inv = 1.0 / spacing
    xi = np.concatenate([[0.0], np.cumsum(0.5 * (inv[1:] + inv[:-1]) * np.diff(fine_grid))])
    n_cells = max(int(np.ceil(xi[-1])), 8)
    nodes = np.interp(np.linspace(0.0, xi[-1], n_cells + 1), xi, fine_grid)
    nodes[0], nodes[-1] = x_start, x_end
    return nodes
