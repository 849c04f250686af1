"""The import structure of the package: no cycles, and every import goes down the stages and layers.

Stages: ``ehl_dataset`` < ``surrogate`` < ``efficiency`` < ``workflows`` (a stage imports only from itself and the
stages before it). Within ``ehl_dataset``: ``validation``, ``data_files``, ``lazy`` and ``names`` (shared by every stage) <
``model`` and ``discretisation`` < ``solvers`` and the entry ``solver`` < ``dataset`` < the package's own
``__init__`` (the lazy public API). docs/explanation/architecture.md explains the layout.

The graph is read from the source with :mod:`ast`: every ``import`` and ``from ... import`` anywhere in a module
(function-local ones included), relative imports resolved, ``from package import submodule`` counted as an import
of the submodule. Importing ``a.b.c`` counts as importing ``a.b.c`` only (not its parent packages' ``__init__``).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
PACKAGES = ("ehl_dataset", "surrogate", "efficiency", "workflows")
STAGE = {name: rank for rank, name in enumerate(PACKAGES)}
EHL_LAYERS = {
    "ehl_dataset.validation": 0, "ehl_dataset.data_files": 0, "ehl_dataset.lazy": 0, "ehl_dataset.names": 0,
    "ehl_dataset.model": 1, "ehl_dataset.discretisation": 1,
    "ehl_dataset.solvers": 2, "ehl_dataset.solver": 2,
    "ehl_dataset.dataset": 3,
    "ehl_dataset": 4,
}
"""Layer of each part of ``ehl_dataset`` (a module belongs to the longest prefix listed)."""


# ---------------------------------------------------------------------------------------------------------------
# Reading the graph
# ---------------------------------------------------------------------------------------------------------------
def module_name(path: Path, root: Path = REPO) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def discover(root: Path = REPO, packages=PACKAGES) -> dict[str, Path]:
    """{module name: file} of every module of ``packages`` under ``root``."""
    modules = {}
    for package in packages:
        for path in sorted((root / package).rglob("*.py")):
            modules[module_name(path, root)] = path
    return modules


def imported_modules(name: str, source: str, is_package: bool, known: set[str]) -> set[str]:
    """The modules of ``known`` that module ``name`` imports anywhere in ``source``."""
    found: set[str] = set()

    def add(target: str) -> None:
        # the longest known prefix: "ehl_dataset.model.contact.ContactCase" -> "ehl_dataset.model.contact"
        parts = target.split(".")
        for k in range(len(parts), 0, -1):
            candidate = ".".join(parts[:k])
            if candidate in known:
                found.add(candidate)
                return

    package = name if is_package else name.rpartition(".")[0]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            for alias in node.names:
                add(alias.name)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base_parts = package.split(".")
                base_parts = base_parts[: len(base_parts) - (node.level - 1)]
                base = ".".join(base_parts + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            for alias in node.names:
                add(f"{base}.{alias.name}" if f"{base}.{alias.name}" in known else base)
    found.discard(name)
    return found


def import_graph(root: Path = REPO, packages=PACKAGES) -> dict[str, set[str]]:
    modules = discover(root, packages)
    known = set(modules)
    return {name: imported_modules(name, path.read_text(encoding="utf-8"), path.name == "__init__.py", known)
            for name, path in modules.items()}


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:  # recursion depth is bounded by the module count (~100)
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def rank(module: str) -> tuple[int, int]:
    """(stage, layer within ehl_dataset) of a module."""
    stage = STAGE[module.split(".")[0]]
    layer = 0
    if stage == 0:
        prefix = max((p for p in EHL_LAYERS if module == p or module.startswith(p + ".")), key=len)
        layer = EHL_LAYERS[prefix]
    return stage, layer


def upward_imports(graph: dict[str, set[str]]) -> list[str]:
    """Imports from a lower stage into a higher one, or within ``ehl_dataset`` from a lower layer into a higher one
    (:func:`rank` compares the stage first, then the layer)."""
    return [f"{source} -> {target}" for source, targets in sorted(graph.items()) for target in sorted(targets)
            if rank(target) > rank(source)]


# ---------------------------------------------------------------------------------------------------------------
# The checks
# ---------------------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def graph():
    return import_graph()


def test_every_layer_is_mapped_and_the_graph_is_read(graph):
    assert len(graph) > 60
    for name in graph:
        rank(name)  # every module belongs to a stage (and ehl_dataset modules to a layer)
    # a function-local import is seen (cli_contact imports the solver inside its handler)
    assert "ehl_dataset.solver" in graph["workflows.cli_contact"]
    # relative imports are resolved, across sub-packages too
    assert "ehl_dataset.solvers.steady" in graph["ehl_dataset.solvers.deterministic"]
    assert "ehl_dataset.model.contact" in graph["ehl_dataset.solvers.deterministic"]
    assert "ehl_dataset.validation" in graph["ehl_dataset.dataset.runner"]


def test_no_import_cycles(graph):
    assert cycles(graph) == []


def test_imports_go_down_the_stages_and_layers(graph):
    assert upward_imports(graph) == []


def test_the_checks_find_what_they_look_for(tmp_path):
    """A planted cycle (one side a function-local relative import) and a planted upward import are reported."""
    pkg = tmp_path / "ehl_dataset"
    (pkg / "solvers").mkdir(parents=True)
    (pkg / "model").mkdir()
    for init in (pkg, pkg / "solvers", pkg / "model"):
        (init / "__init__.py").write_text("")
    (pkg / "solver.py").write_text("from .solvers.transient import run\n")
    (pkg / "solvers" / "transient.py").write_text("def run():\n    from ..solver import x\n")
    (pkg / "model" / "contact.py").write_text("import ehl_dataset.solvers.transient\n")
    planted = import_graph(tmp_path, ("ehl_dataset",))
    assert cycles(planted) == [["ehl_dataset.solver", "ehl_dataset.solvers.transient"]]
    assert upward_imports(planted) == ["ehl_dataset.model.contact -> ehl_dataset.solvers.transient"]


def _guarded_own_imports(path: Path) -> list[str]:
    """Imports of the package's own modules inside a ``try`` that catches ImportError (a broken import would pass
    silently)."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if not isinstance(node, ast.Try):
            continue
        caught = set()
        for handler in node.handlers:
            types = handler.type.elts if isinstance(handler.type, ast.Tuple) else [handler.type]
            caught |= {t.id for t in types if isinstance(t, ast.Name)}
        if not caught & {"ImportError", "ModuleNotFoundError"}:
            continue
        for inner in (n for stmt in node.body for n in ast.walk(stmt)):
            names = ([a.name for a in inner.names] if isinstance(inner, ast.Import)
                     else [inner.module or ""] if isinstance(inner, ast.ImportFrom) else [])
            if isinstance(inner, ast.ImportFrom) and inner.level:
                names = ["(relative)"]
            if any(n == "(relative)" or n.split(".")[0] in PACKAGES for n in names):
                found.append(f"{path.relative_to(REPO)}:{inner.lineno}")
    return found


def test_no_import_error_guards_around_own_modules():
    files = [p for package in (*PACKAGES, "tests", "benchmarks", "validation") for p in (REPO / package).rglob("*.py")]
    assert [hit for path in files for hit in _guarded_own_imports(path)] == []


def test_tests_do_not_skip_on_missing_own_modules():
    bad = []
    for path in (REPO / "tests").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if (isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "importorskip" and node.args
                    and isinstance(node.args[0], ast.Constant)
                    and str(node.args[0].value).split(".")[0] in PACKAGES):
                bad.append(f"{path.relative_to(REPO)}:{node.lineno}")
    assert bad == []
