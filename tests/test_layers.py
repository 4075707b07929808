"""Imports inside ``pas`` point down the layers, and nothing closes a circle.

Every ``import``/``from ... import`` of a ``pas`` module is an edge, whether it
sits at module level or inside a function: a function-level import only
postpones a dependency to call time (``study.replay`` importing ``api`` inside
``open_study`` was one), so it counts like any other.  ``from pkg import name``
is an edge to ``pkg.name`` when that is a module and to ``pkg`` (its
``__init__``) otherwise.  The implicit import of a module's parent packages is
not an edge: Python runs a package's ``__init__`` before its submodules by
design.

A *unit* is a sub-package (``pas.stats``) or a loose module at the top
(``pas.api``); ``pas`` itself (``__init__``, the face) is the unit
``"__init__"``.  :data:`LAYERS` lists the units bottom to top: a unit may
import its own layer and the layers below, never one above.
"""

import ast
import functools
from pathlib import Path

import pas

ROOT = Path(pas.__file__).parent

#: Layers bottom to top, one line each: (layer, its units).
LAYERS = (
    ("helpers", {"_version", "_support"}),
    ("stats", {"stats"}),
    ("models", {"models"}),
    ("strategies", {"strategies"}),
    ("study", {"study"}),
    ("longterm", {"longterm"}),
    ("waves", {"waves"}),
    ("runners", {"api", "design_waves", "cfd"}),
    ("records", {"records"}),
    ("plotting", {"plotting"}),
    ("validation", {"validation"}),
    ("face", {"__init__"}),
    ("cli", {"cli", "__main__"}),
)
LAYER_OF = {unit: level for level, (_, units) in enumerate(LAYERS) for unit in units}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@functools.cache
def import_graph() -> dict[str, set[str]]:
    """``{module: {pas modules it imports}}`` over every module of the package (read once)."""
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


def unit_of(module: str) -> str:
    """The unit of a module name: ``pas.stats.weibull`` -> ``stats``, ``pas`` -> ``__init__``."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def unit_graph(graph) -> dict[str, set[str]]:
    """The module graph collapsed to units, without a unit's edges to itself."""
    units = {}
    for module, targets in graph.items():
        here = unit_of(module)
        units.setdefault(here, set()).update(unit_of(t) for t in targets)
    return {unit: targets - {unit} for unit, targets in units.items()}


def upward_imports(graph, layer_of=LAYER_OF) -> list[str]:
    """``"importer -> imported"`` for every edge from a lower layer to a higher one.

    Units without a layer are left to :func:`test_every_unit_has_a_layer`.
    """
    never = len(LAYERS)
    return sorted(f"{module} -> {target}" for module, targets in graph.items()
                  for target in targets
                  if layer_of.get(unit_of(target), -1) > layer_of.get(unit_of(module), never))


def find_cycle(graph) -> list[str] | None:
    """One cycle of ``graph`` as a list of nodes (first = last), or None."""
    state, stack = {}, []

    def visit(node):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
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


def test_checks_flag_a_planted_upward_import_and_circle():
    planted = {"pas.stats.records": {"pas.plotting.records"}, "pas.plotting.records": set()}
    assert upward_imports(planted) == ["pas.stats.records -> pas.plotting.records"]
    assert upward_imports({"pas.plotting.records": {"pas.stats.weibull"}}) == []
    circle = {"pas.api": {"pas.design_waves"}, "pas.design_waves": {"pas.api.x"}}
    assert find_cycle(unit_graph(circle)) == ["api", "design_waves", "api"]


def test_graph_sees_function_level_and_relative_imports():
    graph = import_graph()
    assert "pas.stats.exceedance" in graph["pas.strategies.screening"]      # module level, relative
    assert "pas.plotting.figures" in graph["pas.cli.plot"]       # inside a function


def test_every_unit_has_a_layer():
    unlisted = set(unit_graph(import_graph())) - set(LAYER_OF)
    assert not unlisted, f"add to LAYERS in {Path(__file__).name}: {sorted(unlisted)}"


def test_imports_point_down_the_layers():
    upward = upward_imports(import_graph())
    assert not upward, "imports pointing up a layer:\n" + "\n".join(upward)


def test_no_circle_between_units():
    cycle = find_cycle(unit_graph(import_graph()))
    assert cycle is None, "units importing each other in a circle: " + " -> ".join(cycle)


def test_no_import_cycle_between_modules():
    cycle = find_cycle(import_graph())
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_at_most_five_modules_sit_loose_at_the_package_top():
    loose = sorted(p.name for p in ROOT.glob("*.py"))
    assert len(loose) <= 5, f"loose modules at the top of pas: {loose}; move helpers into a layer"
