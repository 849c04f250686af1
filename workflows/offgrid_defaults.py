"""Defaults of a fit's off-grid validation sample (no imports, so the command line's parser stays light)."""

OFFGRID_POINTS = 200
"""Default size of the off-grid validation sample of a fit."""
OFFGRID_SEED = 2009
"""Default seed of the off-grid sample (independent uniform draws in the factorial's box)."""
