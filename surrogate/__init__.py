"""Stage 2 of gearloss: dimensionless features, the paper's two-branch ln μ regression, coefficient files.

Main entry points (imported lazily so that ``import surrogate.published`` stays light):

* :class:`surrogate.evaluate.FrictionSurrogate` — ``FrictionSurrogate.load("atf").mu(p_h, r_eq, u_r, sr, T, rq1, rq2)``
* :func:`surrogate.fit.fit_surrogate` and :func:`surrogate.coefficients.write_coefficients` /
  :func:`surrogate.coefficients.load_coefficients`
* :mod:`surrogate.published` — Xu et al. 2007, Benedict & Kelley 1961, ISO/TR 14179-2

See docs/explanation/surrogate.md.
"""

from ehl_dataset.lazy import lazy_exports

_LAZY = {
    "FrictionSurrogate": "surrogate.evaluate",
    "SurrogateExtrapolationWarning": "surrogate.evaluate",
    "fit_surrogate": "surrogate.fit",
    "write_coefficients": "surrogate.coefficients",
    "load_coefficients": "surrogate.coefficients",
}

__all__ = sorted(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY, globals())
