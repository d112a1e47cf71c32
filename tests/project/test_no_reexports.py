"""No module re-exports a name from another module's home: every name a
module (not a package's ``__init__``, the documented namespaces)
imports at its top is used in it.  A name imported only to be imported
again from here is an "old home" that a reader cannot tell from the
real one; importers take a name from the module that defines it."""

from __future__ import annotations

import ast
from pathlib import Path

from conftest import ROOT

PACKAGE = ROOT / "python" / "contactsep"


def _imported(tree: ast.Module) -> dict[str, int]:
    """{name bound: line} of the module-level imports (not
    ``__future__``'s), those in a module-level ``try`` or ``if`` too."""
    found = {}
    nodes = list(tree.body)
    while nodes:
        node = nodes.pop(0)
        if isinstance(node, (ast.Try, ast.If)):
            nodes.extend(node.body + node.orelse
                         + [s for h in getattr(node, "handlers", [])
                            for s in h.body])
        elif isinstance(node, ast.ImportFrom) and node.module != "__future__":
            for alias in node.names:
                found[alias.asname or alias.name] = node.lineno
        elif isinstance(node, ast.Import):
            for alias in node.names:
                found[alias.asname or alias.name.split(".")[0]] = node.lineno
    return found


def _used(tree: ast.Module) -> set[str]:
    used = {node.id for node in ast.walk(tree)
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)}
    for node in ast.walk(tree):        # __all__ = ["name", ...]
        if (isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "__all__"
                for t in node.targets)
                and isinstance(node.value, (ast.List, ast.Tuple))):
            used |= {e.value for e in node.value.elts
                     if isinstance(e, ast.Constant)}
    return used


def unused_imports(package: Path) -> list[str]:
    """"module:line name" of every module-level import that its module
    (a package's __init__ left out) never uses."""
    found = []
    for path in sorted(package.rglob("*.py")):
        if path.name == "__init__.py":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        used = _used(tree)
        name = path.relative_to(package).as_posix()
        found += [f"{name}:{line} {bound}"
                  for bound, line in _imported(tree).items()
                  if bound not in used]
    return found


def test_no_module_imports_a_name_it_does_not_use():
    assert unused_imports(PACKAGE) == []


def test_the_checker_sees_a_re_export(tmp_path):
    """The rule can fail: a planted module that imports a name only to
    hand it on is found; one that uses it, lists it in __all__, or is a
    package's __init__, is not."""
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "__init__.py").write_text(
        "from pkg.home import name\n")
    (tmp_path / "pkg" / "old.py").write_text(
        "from __future__ import annotations\n"
        "import math\n"
        "from pkg.home import name, other  # noqa: F401\n"
        "try:\n    import numpy as np\nexcept ImportError:\n    np = None\n"
        "def f() -> float:\n    return other(math.pi)\n")
    (tmp_path / "pkg" / "listed.py").write_text(
        "from pkg.home import name\n__all__ = ['name']\n")
    assert unused_imports(tmp_path) == ["pkg/old.py:3 name",
                                        "pkg/old.py:5 np"]
