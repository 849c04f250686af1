"""Every object the API reference renders has a numpydoc docstring with units.

The rendered public API is read from the ``::: module`` blocks of docs/reference/api/*.md and their explicit
``members`` lists (what mkdocstrings shows). Each function, method and class there is loaded with griffe (the
library mkdocstrings renders with) and must have

* a one-line summary;
* a ``Parameters`` section naming every parameter of its signature (a class: of its constructor; ``self``, ``cls``
  and private ``_names`` excepted; ``*args``/``**kwargs`` documented under that name) and no parameter the
  signature lacks;
* a unit in square brackets at the end of every parameter description, from the unit vocabulary below (``[-]`` for
  dimensionless and non-physical parameters: names, flags, paths, counts, options objects; ``[SI]`` for a record
  of physical quantities each in its SI unit, such as a contact case);
* a ``Returns`` (or ``Yields``) section when the function returns a value;
* no ``] [`` outside code (Markdown reads it as a reference link, which fails ``mkdocs build --strict``).

Modules whose docstrings are not converted yet are listed in ``PENDING``: their failing objects are reported as
xfail (with the problems found) instead of silently skipped, and a module leaves the list once all its objects
pass (a test fails on a listed module that has nothing left to do).
"""

from __future__ import annotations

import ast
import re
import textwrap
from pathlib import Path

import griffe
import pytest
import yaml

REPO = Path(__file__).resolve().parents[1]
API_DOCS = REPO / "docs" / "reference" / "api"
PACKAGES = ("ehl_dataset", "surrogate", "efficiency", "workflows")

# Modules rendered in the API reference whose docstrings are still to be converted to numpydoc with units.
PENDING: set[str] = set()

# Unit vocabulary: SI symbols (the numerics' units) and the engineering units of input files and reports.
_SYMBOLS = {
    "m", "s", "kg", "K", "Pa", "N", "W", "J", "rad", "Hz", "mol", "A", "V", "1",
    "mm", "µm", "μm", "nm", "deg", "°", "°C", "GPa", "MPa", "kPa", "kW", "rpm", "cSt", "h", "min", "%",
}
_EXPONENT = r"(?:\^-?\d+(?:\.\d+)?|[²³⁴]|⁻¹|⁻²|⁻³)?"
_TOKEN = re.compile(r"^√?(?:" + "|".join(sorted(map(re.escape, _SYMBOLS), key=len, reverse=True)) + ")" + _EXPONENT
                    + "$")
_TRAILING_UNIT = re.compile(r"\[([^\[\]]+)\]\.?\s*$")


def is_unit(text: str) -> bool:
    """True when ``text`` (the inside of the brackets) is ``-``, ``SI`` (a record of quantities, each in its SI
    unit) or a product/quotient of known unit symbols."""
    text = text.strip()
    if text in ("-", "SI"):
        return True
    tokens = [t for t in re.split(r"[\s/·*()]+", text) if t]
    return bool(tokens) and all(_TOKEN.match(t) for t in tokens)


def rendered_blocks(api_dir: Path = API_DOCS) -> list[tuple[str, list[str]]]:
    """``(module, members)`` of every ``::: module`` block of the API pages (members must be listed explicitly)."""
    blocks = []
    for page in sorted(api_dir.glob("*.md")):
        lines = page.read_text(encoding="utf-8").splitlines()
        for i, line in enumerate(lines):
            match = re.match(r"^::: ([\w.]+)\s*$", line)
            if not match:
                continue
            body = []
            for nxt in lines[i + 1:]:
                if nxt.strip() and not nxt.startswith(" "):
                    break
                body.append(nxt)
            options = (yaml.safe_load(textwrap.dedent("\n".join(body))) or {}).get("options", {})
            members = options.get("members")
            assert isinstance(members, list), f"{page.name}: '::: {match.group(1)}' needs an explicit members list"
            blocks.append((match.group(1), [str(m) for m in members]))
    return blocks


def _returns_value(func: griffe.Function) -> bool:
    """Whether the function's own body (not nested functions) has a ``return <value>`` or ``yield``."""
    source = textwrap.dedent(func.source)
    tree = ast.parse(source).body[0]
    stack = list(tree.body)
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef, ast.Lambda)):
            continue
        if isinstance(node, ast.Return) and node.value is not None and not (
                isinstance(node.value, ast.Constant) and node.value.value is None):
            return True
        if isinstance(node, (ast.Yield, ast.YieldFrom)):
            return True
        stack.extend(ast.iter_child_nodes(node))
    return False


def _signature_parameters(obj: griffe.Object) -> list[griffe.Parameter]:
    return [p for p in obj.parameters if p.name not in ("self", "cls") and not p.name.startswith("_")]


def problems(obj: griffe.Object) -> list[str]:
    """What is missing from the docstring of a function, method or class (empty list: conforming)."""
    if obj.docstring is None or not obj.docstring.value.strip():
        return ["no docstring"]
    found = []
    if re.search(r"\]\s?\[", re.sub(r"(`+).*?\1", "", obj.docstring.value)):
        found.append("'] [' reads as a Markdown reference link (mkdocs --strict fails): reword")
    summary = obj.docstring.value.strip().splitlines()[0]
    if not summary.strip():
        found.append("no one-line summary")
    sections = obj.docstring.parse("numpy", warnings=False)
    documented = {}
    for section in sections:
        if section.kind is griffe.DocstringSectionKind.parameters:
            for param in section.value:
                documented[param.name.lstrip("*")] = param.description or ""
    expected = [p.name for p in _signature_parameters(obj)]
    missing = [name for name in expected if name not in documented]
    extra = [name for name in documented if name not in expected]
    if missing:
        found.append(f"parameters not documented: {', '.join(missing)}")
    if extra:
        found.append(f"documented parameters not in the signature: {', '.join(extra)}")
    for name in expected:
        if name not in documented:
            continue
        match = _TRAILING_UNIT.search(documented[name])
        if match is None:
            found.append(f"parameter {name}: no [unit] at the end of its description")
        elif not is_unit(match.group(1)):
            found.append(f"parameter {name}: [{match.group(1)}] is not a unit")
    if obj.is_function and "property" not in obj.labels and _returns_value(obj):
        kinds = {s.kind for s in sections}
        if not kinds & {griffe.DocstringSectionKind.returns, griffe.DocstringSectionKind.yields}:
            found.append("no Returns section")
    return found


def rendered_objects(blocks, loaded: dict[str, griffe.Object]) -> list[tuple[str, str, griffe.Object]]:
    """``(module, path, object)`` of every function, class and public method the API pages render."""
    out = []
    for module, members in blocks:
        package = module.split(".")[0]
        mod = loaded[package] if module == package else loaded[package][module[len(package) + 1:]]
        for name in members:
            assert name in mod.members, f"{module}.{name} is listed in the API reference but does not exist"
            obj = mod.members[name]
            if obj.is_alias:
                obj = obj.final_target
            if obj.is_attribute:
                continue
            out.append((module, obj.path, obj))
            if obj.is_class:
                for mname, member in obj.members.items():
                    if mname.startswith("_") or member.is_alias or not member.is_function:
                        continue
                    if "property" in member.labels:
                        continue
                    out.append((module, member.path, member))
    return out


def _load(package: str) -> griffe.Object:
    return griffe.load(package, search_paths=[str(REPO)], docstring_parser="numpy", resolve_aliases=False)


_LOADED = {package: _load(package) for package in PACKAGES}
_BLOCKS = rendered_blocks()
_OBJECTS = rendered_objects(_BLOCKS, _LOADED)


def _param(module, path, obj):
    marks = []
    if module in PENDING:
        found = problems(obj)
        if found:
            marks.append(pytest.mark.xfail(reason=f"module still to convert ({'; '.join(found)})", strict=True))
    return pytest.param(obj, id=path, marks=marks)


def test_the_api_reference_renders_the_public_modules():
    modules = {module for module, _ in _BLOCKS}
    for required in ("ehl_dataset.solver", "surrogate.evaluate", "efficiency.mesh_cycle", "workflows.pipeline"):
        assert required in modules
    assert len(_OBJECTS) > 100


@pytest.mark.parametrize("obj", [_param(*row) for row in _OBJECTS])
def test_docstring_documents_every_parameter_with_a_unit(obj):
    found = problems(obj)
    assert not found, f"{obj.path}: " + "; ".join(found)


def test_every_pending_module_is_rendered_and_still_has_work_left():
    rendered = {m for m, _ in _BLOCKS}
    for module in sorted(PENDING):
        assert module in rendered, f"{module} is pending but not rendered"
        assert any(problems(obj) for m, _, obj in _OBJECTS if m == module), f"{module} conforms: remove it from PENDING"


def test_the_index_lists_every_facade_name():
    """The facade tables of api/index.md name exactly what ``ehl_dataset`` and ``surrogate`` re-export."""
    import ehl_dataset
    import surrogate

    text = (API_DOCS / "index.md").read_text(encoding="utf-8")
    listed = set(re.findall(r"`(\w+)`", text))
    for package in (ehl_dataset, surrogate):
        missing = sorted(set(package.__all__) - listed)
        assert not missing, f"{package.__name__} re-exports names api/index.md does not list: {missing}"


# --- the checker itself fails on bad docstrings --------------------------------------------------------------------

_PLANTED = '''
def good(p_h, r_eq, *, name="x"):
    """Hertz-like thing.

    Parameters
    ----------
    p_h : float
        Hertz pressure [Pa].
    r_eq : float
        Reduced radius of curvature [m]
    name : str
        Label of the case [-].

    Returns
    -------
    float
        Load per length [N/m].
    """
    return p_h * r_eq


def no_unit(p_h):
    """Thing.

    Parameters
    ----------
    p_h : float
        Hertz pressure in Pa.
    """


def not_a_unit(width):
    """Thing.

    Parameters
    ----------
    width : float
        Width, in [0, 1].
    """


def undocumented(p_h, temperature):
    """Thing.

    Parameters
    ----------
    p_h : float
        Hertz pressure [Pa].
    speed : float
        Not a parameter [m/s].
    """


def link_like(x):
    """Thing in [0, 1] [-].

    Parameters
    ----------
    x : float
        Value [-].
    """


def no_returns(x):
    """Thing.

    Parameters
    ----------
    x : float
        Value [-].
    """
    return 2 * x


class Plain:
    """Constructor parameters undocumented."""

    def __init__(self, load):
        self.load = load
'''


def test_the_checker_fails_on_planted_bad_docstrings(tmp_path):
    (tmp_path / "planted_api.py").write_text(_PLANTED, encoding="utf-8")
    module = griffe.load("planted_api", search_paths=[str(tmp_path)], docstring_parser="numpy")
    assert problems(module["good"]) == []
    assert problems(module["no_unit"]) == ["parameter p_h: no [unit] at the end of its description"]
    assert problems(module["not_a_unit"]) == ["parameter width: [0, 1] is not a unit"]
    assert problems(module["undocumented"]) == ["parameters not documented: temperature",
                                                "documented parameters not in the signature: speed"]
    assert problems(module["no_returns"]) == ["no Returns section"]
    assert problems(module["link_like"]) == ["'] [' reads as a Markdown reference link (mkdocs --strict fails): reword"]
    assert problems(module["Plain"]) == ["parameters not documented: load"]


def test_the_unit_vocabulary():
    for unit in ("-", "Pa", "m/s", "Pa s", "Pa·s", "1/Pa", "m²/s", "W/(m K)", "J/(kg K)", "N/m^2", "√Pa", "kg/m³",
                 "N·m", "rad/s", "K", "mm", "°C"):
        assert is_unit(unit), unit
    for text in ("0, 1", "Pa, m", "bar", "inches", "", "x", "n"):
        assert not is_unit(text), text


def test_the_api_pages_list_members_explicitly(tmp_path):
    (tmp_path / "page.md").write_text("# x\n\n::: surrogate.evaluate\n    options:\n      show_source: false\n")
    with pytest.raises(AssertionError, match="explicit members list"):
        rendered_blocks(tmp_path)
