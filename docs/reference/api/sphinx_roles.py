"""Griffe extension of the API reference: Sphinx cross-reference roles in docstrings render as inline code.

The docstrings name other objects the Sphinx way (``:func:`solve_contact```, ``:class:`~a.b.C```), which
mkdocstrings would print verbatim; this extension turns each into inline code (``solve_contact``, ``C``: a leading
``~`` keeps the last component, as Sphinx shows it). Loaded by the mkdocstrings handler options in mkdocs.yml.
"""

from __future__ import annotations

import re

import griffe

ROLE = re.compile(r":(?:py:)?(?:func|class|meth|mod|data|attr|exc|obj|const):`(~?)([^`]+)`")


def plain_roles(text: str) -> str:
    """``text`` with every Sphinx cross-reference role replaced by inline code of its target."""
    return ROLE.sub(lambda m: f"`{m.group(2).rsplit('.', 1)[-1] if m.group(1) else m.group(2)}`", text)


class SphinxRolesAsCode(griffe.Extension):
    """Rewrite the roles of every docstring once the object tree is built."""

    def on_object(self, *, obj: griffe.Object, **kwargs) -> None:
        if obj.docstring is not None:
            obj.docstring.value = plain_roles(obj.docstring.value)
