"""The package is a picture of its layers (issue 20): what every layer
shares at the root, one subpackage a layer, imports only downwards and no
import cycles.  Imports are read from the sources (every ``import``, at
module level or inside a function), so a lazy import counts too."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from conftest import ROOT

PACKAGE = ROOT / "python" / "contactsep"
#: Modules every layer shares, at the package root.
SHARED = {"beams", "constants", "errors", "output", "units"}
#: Rank of each layer: a module imports only its own layer, the shared
#: modules and layers of lower rank.
RANK = {"shared": 0, "restored": 1, "model": 1, "chatter": 2, "runs": 3,
        "studies": 4, "cli": 5}
#: The one door from the model into the restoration (issue 20).
MODEL_TO_RESTORED = {("contactsep.restored.dataset", "computed_data_set")}


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imports(name: str) -> set[tuple[str, str | None]]:
    """(module, imported name or None) for every import of contactsep
    code in module ``name``, ``from pkg import sub`` resolved to the
    submodule ``pkg.sub`` where it is one."""
    path = MODULES[name]
    tree = ast.parse(path.read_text(), str(path))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found |= {(a.name, None) for a in node.names
                      if a.name.split(".")[0] == "contactsep"}
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package.split(".")[:len(package.split("."))
                                                  - node.level + 1]
                                + ([node.module] if node.module else []))
            if base.split(".")[0] != "contactsep":
                continue
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                # a submodule, or a compiled one (_model, _chatter, ...)
                if sub in MODULES or alias.name.startswith("_core") or \
                        alias.name in ("_model", "_chatter"):
                    found.add((sub, None))
                else:
                    found.add((base, alias.name))
    return found


def layer(name: str) -> str | None:
    parts = name.split(".")
    if len(parts) == 1:
        return None                  # the package's own __init__
    if parts[1] in SHARED:
        return "shared"              # beams is a package of its own
    return parts[1] if parts[1] in RANK else None


def test_the_root_holds_at_most_six_modules():
    root = {p.stem for p in PACKAGE.glob("*.py")} - {"__init__", "__main__"}
    packages = {p.name for p in PACKAGE.iterdir()
                if (p / "__init__.py").is_file()}
    # the beam physics is a shared package (one module per concern)
    assert root | (packages & SHARED) == SHARED and len(root) <= 6
    assert packages - SHARED == {"restored", "model", "chatter", "runs",
                                 "studies", "cli"}


@pytest.mark.parametrize("name", sorted(MODULES), ids=str)
def test_imports_run_downwards(name):
    own = layer(name)
    if own is None:
        return                       # contactsep/__init__, __main__
    bad = []
    for target, item in imports(name):
        other = layer(target)
        if other is None or other == own:
            continue
        if own == "shared" or RANK[other] > RANK[own]:
            bad.append(target)
        elif RANK[other] == RANK[own] and (
                own != "model" or (target, item) not in MODEL_TO_RESTORED):
            bad.append(f"{target}.{item}")
    assert not bad


def test_no_import_cycles():
    graph = {name: {t for t, _ in imports(name) if t in MODULES}
             for name in MODULES}
    # a module importing its own package's __init__ (for its re-exported
    # names) is an edge too; only the standard library is left out
    state, cycles = {}, []

    def visit(node, path):
        state[node] = "open"
        for nxt in graph[node]:
            if state.get(nxt) == "open":
                cycles.append(path[path.index(nxt):] + [nxt])
            elif nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = "done"

    for name in graph:
        if name not in state:
            visit(name, [name])
    assert not cycles


def test_the_checker_sees_a_cycle_and_an_upward_import(tmp_path,
                                                       monkeypatch):
    """The rules above can fail: an upward import and a cycle, planted."""
    fake = {"contactsep.model.a": tmp_path / "a.py",
            "contactsep.model.b": tmp_path / "b.py"}
    fake["contactsep.model.a"].write_text(
        "from contactsep.chatter import simulate\n"
        "from contactsep.model import b\n")
    fake["contactsep.model.b"].write_text("import contactsep.model.a\n")
    monkeypatch.setitem(MODULES, "contactsep.model.a", fake[
        "contactsep.model.a"])
    monkeypatch.setitem(MODULES, "contactsep.model.b", fake[
        "contactsep.model.b"])
    monkeypatch.setitem(MODULES, "contactsep.chatter.simulate",
                        MODULES["contactsep.chatter.simulate"])
    with pytest.raises(AssertionError):
        test_imports_run_downwards("contactsep.model.a")
    with pytest.raises(AssertionError):
        test_no_import_cycles()


#: What the run machinery may import besides its own package: the
#: shared root modules and the outputs, nothing of a simulation or study.
RUNS_MAY_IMPORT = {"shared", "runs"}


@pytest.mark.parametrize(
    "name", sorted(n for n in MODULES if layer(n) == "runs"), ids=str)
def test_runs_import_only_shared_modules(name):
    bad = [target for target, _ in imports(name)
           if layer(target) is not None
           and layer(target) not in RUNS_MAY_IMPORT]
    assert not bad


def test_run_machinery_left_studies():
    studies = {p.stem for p in (PACKAGE / "studies").glob("*.py")}
    moved = {"pool", "dask_run", "dask_map", "chunks", "stops",
             "code_digest"}
    assert not studies & moved
    assert moved <= {p.stem for p in (PACKAGE / "runs").glob("*.py")}


def test_the_designs_vocabulary_has_one_home():
    """The Design's fields are named, read and written in the model
    (model/fields.py, the design file's reader beside its format), not
    in the studies; the model's vocabulary imports no layer above it."""
    studies = {p.stem for p in (PACKAGE / "studies").rglob("*.py")}
    assert not studies & {"fields", "design_file"}
    model = {p.stem for p in (PACKAGE / "model").glob("*.py")}
    assert {"fields", "design_file", "design_file_read"} <= model
    for name in ("contactsep.model.fields", "contactsep.model.design_file",
                 "contactsep.model.design_file_read"):
        assert {layer(t) for t, _ in imports(name)} <= {"shared", "model"}


def test_studies_has_its_three_subpackages():
    subpackages = {p.name for p in (PACKAGE / "studies").iterdir()
                   if (p / "__init__.py").is_file()}
    assert subpackages == {"thesis", "preload", "sweep"}
