"""Stage 2 of gearloss: dimensionless features, the paper's two-branch ln μ regression, coefficient files."""
