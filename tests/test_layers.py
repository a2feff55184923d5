"""The Python package in layers without cycles: base (formats, closures, statistics) -> input (what a
scene asks) -> build (stones and flume from a scene) -> results (output files, analysis, plots,
reports) -> run (the run loop, ensembles, calibration, studies) -> the command line and the package's
face. A module imports only from its own layer or those below, every import counted (those inside
functions too), and no module imports itself back through others. The results sit below the run
because the run loop writes, analyses and plots as it goes. Each module also imports alone."""
from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[1] / "python" / "vofdem"
LAYERS = [
    {"schema", "outline", "reference", "fidelity", "closure", "porosity", "flow", "polygon_output", "output_3d",
     "fragility", "cluster"},
    {"scene", "flood", "grading", "stone_models"},
    {"builder", "outline_packing"},
    {"analysis", "io", "plots", "checkpoint", "reports"},
    {"run", "calibration", "calibration_3d", "ensemble", "study"},
    {"cli", "__main__", "__init__"},
]
LAYER = {m: k for k, layer in enumerate(LAYERS) for m in layer}
MODULES = sorted(p.stem for p in PKG.glob("*.py"))


def imports(module: str) -> set[str]:
    """The package's modules `module` imports (`from . import x`, `from .x import y`, `vofdem.x`)."""
    out = set()
    for node in ast.walk(ast.parse((PKG / f"{module}.py").read_text())):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            out |= {node.module.split(".")[0]} if node.module else {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("vofdem."):
            out.add(node.module.split(".")[1])
    return (out & set(MODULES)) - {module}


def cycle(graph: dict[str, set[str]]):
    """A cycle of the graph as a list of modules, or None."""
    state: dict[str, int] = {}

    def visit(m, path):
        state[m] = 1
        for n in sorted(graph[m]):
            if state.get(n) == 1:
                return path[path.index(n):] + [n]
            if n not in state and (found := visit(n, path + [n])):
                return found
        state[m] = 2
        return None

    for m in sorted(graph):
        if m not in state and (found := visit(m, [m])):
            return found
    return None


def test_every_module_has_a_layer():
    assert [m for m in MODULES if m not in LAYER and m != "_core"] == []


def test_no_module_imports_from_a_layer_above_it():
    bad = [f"{m} (layer {LAYER[m]}) imports {n} (layer {LAYER[n]})" for m in MODULES if m in LAYER
           for n in sorted(imports(m)) if n in LAYER and LAYER[n] > LAYER[m]]
    assert bad == []


def test_no_import_cycle():
    graph = {m: imports(m) for m in MODULES}
    assert cycle(graph) is None, " -> ".join(cycle(graph))


def test_the_checks_find_a_cycle_and_a_layer_breach():
    assert cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert cycle({"a": {"b"}, "b": set()}) is None
    assert LAYER["grading"] < LAYER["builder"] and LAYER["io"] < LAYER["run"]


@pytest.mark.parametrize("module", [m for m in MODULES if not m.startswith("__")])
def test_each_module_imports_alone(module):
    subprocess.run([sys.executable, "-c", f"import vofdem.{module}"], check=True, timeout=120)
