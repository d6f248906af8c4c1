"""The package layout: the data flow reads top to bottom, and no module hides a cycle.

Checks the structural rules of the house style (shared STYLE.md): no import
cycle between modules of bild_mdo, counting imports inside functions; no
module over 450 lines; the runtime package never imports sympy (the quartic
generator lives in tools/); a layer never imports a layer above it.
"""
import ast
import pathlib

import pytest

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "bild_mdo"
MAX_LINES = 450

# The data flow, bottom to top; a module may import its own layer and the layers below it.
LAYERS = ("constants", "utils", "validation", "airfoil", "atmosphere", "bem", "bild", "mil", "multipoint", "optimization",
          "verification", "io", "results", "plots", "cli")


def _module_name(path):
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _modules():
    return {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def _imports(path, name, known):
    """bild_mdo modules imported anywhere in ``path`` (functions included), resolved to known module names."""
    tree = ast.parse(path.read_text())
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(tree):
        targets = []
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.split(".")
                parent = parent[:len(parent) - node.level + 1]
                base = ".".join(parent + ([base] if base else []))
            targets = [f"{base}.{alias.name}" for alias in node.names] + [base]
        for target in targets:
            while target and target not in known:
                target = target.rpartition(".")[0]
            if target and target != name:
                found.add(target)
    return found


def _graph():
    modules = _modules()
    return {name: _imports(path, name, modules) for name, path in modules.items()}


def _is_reexport_package(name, modules):
    """An ``__init__`` whose body is only imports, ``__all__`` and a docstring: re-exports, not a dependency."""
    path = modules[name]
    if path.name != "__init__.py":
        return False
    body = ast.parse(path.read_text()).body
    allowed = (ast.Import, ast.ImportFrom, ast.Expr, ast.Assign, ast.AugAssign)
    return all(isinstance(node, allowed) for node in body)


def test_no_import_cycles():
    modules = _modules()
    graph = _graph()
    # A re-exporting package __init__ is not a node of the dependency graph: importing ``bild_mdo.bem``
    # means importing the modules it names.
    skip = {name for name in graph if _is_reexport_package(name, modules)}
    edges = {name: {t for t in targets if t not in skip} for name, targets in graph.items() if name not in skip}
    state, cycles = {}, []

    def visit(node, stack):
        state[node] = "open"
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == "open":
                cycles.append(stack[stack.index(nxt):] + [nxt])
            elif nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = "done"

    for node in sorted(edges):
        if node not in state:
            visit(node, [node])
    assert not cycles, "import cycles: " + "; ".join(" -> ".join(c) for c in cycles)


def _layer(name):
    parts = name.split(".")
    return parts[1] if len(parts) > 1 else None


def test_no_layer_imports_a_layer_above_it():
    modules = _modules()
    graph = _graph()
    upward = []
    for name, targets in graph.items():
        if _layer(name) not in LAYERS or _is_reexport_package(name, modules):
            continue
        for target in targets:
            if _layer(target) in LAYERS and LAYERS.index(_layer(target)) > LAYERS.index(_layer(name)):
                upward.append(f"{name} -> {target}")
    assert not upward, "imports from a higher layer: " + ", ".join(sorted(upward))


@pytest.mark.parametrize("path", sorted(PACKAGE.rglob("*.py")), ids=lambda p: str(p.relative_to(PACKAGE)))
def test_module_fits_in_one_reading(path):
    assert len(path.read_text().splitlines()) <= MAX_LINES


def test_runtime_package_does_not_import_sympy():
    for path in PACKAGE.rglob("*.py"):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                assert all(not a.name.startswith("sympy") for a in node.names), path
            elif isinstance(node, ast.ImportFrom):
                assert not (node.module or "").startswith("sympy"), path
