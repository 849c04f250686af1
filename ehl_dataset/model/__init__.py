"""Physical models of one line contact (SI units): the contact case and materials, the lubricant (viscosity,
density, Eyring stress), surface roughness, the effect plan, classic film formulas and traction.

Pure functions and frozen dataclasses; nothing here solves an equation system (that is :mod:`ehl_dataset.solvers`).
"""
