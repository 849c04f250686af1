"""Stage 1 of gearloss: lubricant and material models, the mixed-EHL line-contact solver, the factorial and its store."""
