"""Imports inside ``pas`` point down the layers: the import graph has no cycle.

The rule checked here: every ``import``/``from ... import`` of a ``pas`` module
is an edge, whether it sits at module level or inside a function.  A
function-level import only postpones a cycle to call time (``study.replay``
importing ``api`` inside ``open_study`` was one), so it counts as a dependency
like any other.  ``from pkg import name`` is an edge to ``pkg.name`` when that
is a module and to ``pkg`` (its ``__init__``) otherwise.  The implicit import
of a module's parent packages is not an edge: Python runs a package's
``__init__`` before its submodules by design.
"""

import ast
from pathlib import Path

import pas

ROOT = Path(pas.__file__).parent


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def import_graph() -> dict[str, set[str]]:
    """``{module: {pas modules it imports}}`` over every module of the package."""
    files = {_module_name(f): f for f in ROOT.rglob("*.py")}
    graph = {}
    for name, path in files.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        edges = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                edges.update(a.name for a in node.names)
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[:len(package.split(".")) - node.level + 1]
                    module = ".".join(base + ([node.module] if node.module else []))
                else:
                    module = node.module
                for a in node.names:
                    edges.add(f"{module}.{a.name}" if f"{module}.{a.name}" in files else module)
        graph[name] = {e for e in edges if e in files and e != name}
    return graph


def find_cycle(graph) -> list[str] | None:
    """One cycle of ``graph`` as a list of nodes (first = last), or None."""
    state, stack = {}, []

    def visit(node):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state and (found := visit(nxt)):
                return found
        stack.pop()
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state and (found := visit(node)):
            return found
    return None


def test_cycle_finder_finds_a_cycle_and_accepts_a_tree():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b", "c"}, "b": {"c"}, "c": set()}) is None


def test_graph_sees_function_level_and_relative_imports():
    graph = import_graph()
    assert "pas.stats.exceedance" in graph["pas.screening"]      # module level, relative
    assert "pas.plotting.figures" in graph["pas.cli.plot"]       # inside a function


def test_no_import_cycle_in_pas():
    cycle = find_cycle(import_graph())
    assert cycle is None, "import cycle: " + " -> ".join(cycle)
