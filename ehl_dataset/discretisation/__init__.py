"""Discretisation of the line-contact equations: grids, the finite-volume Reynolds residual and its Jacobian
(numba), and the elastic deflection matrix. Arrays in, arrays out, dimensionless."""
