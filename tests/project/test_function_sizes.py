"""One step a function: no function of the package has a body over
MAX_BODY_LINES lines unless its docstring says why ("Long because ...").
A long function is read as named steps: a short front door over helpers
or a small state class."""

from __future__ import annotations

import ast
from pathlib import Path

from conftest import ROOT

PACKAGE = ROOT / "python" / "contactsep"
#: The most lines a function's body may have (its docstring left out).
MAX_BODY_LINES = 80
#: The words a docstring gives its reason with.
REASON = "Long because"


def body_lines(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Lines of ``node``'s body from its first statement after the
    docstring to its last line (0 for a docstring alone)."""
    body = node.body
    first = body[0]
    if (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
            and isinstance(first.value.value, str)):
        if len(body) == 1:
            return 0
        first = body[1]
    return node.end_lineno - first.lineno + 1


def long_functions(package: Path, most: int = MAX_BODY_LINES) -> dict:
    """{"module:function": body lines} of every function in ``package``
    over ``most`` lines whose docstring gives no reason."""
    found = {}
    for path in sorted(package.rglob("*.py")):
        name = path.relative_to(package).as_posix()
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        for node in ast.walk(tree):
            if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            lines = body_lines(node)
            if lines > most and REASON not in (ast.get_docstring(node) or ""):
                found[f"{name}:{node.name}"] = lines
    return found


def test_no_function_is_long_without_a_reason():
    assert long_functions(PACKAGE) == {}


def test_the_checker_sees_a_long_function_and_its_reason(tmp_path):
    """The rule can fail: a planted function of MAX_BODY_LINES + 1 body
    lines is found; the same with a reason, or of MAX_BODY_LINES lines,
    or with a long docstring, is not."""
    def function(name, lines, doc="One line."):
        body = "".join(f"    x{k} = {k}\n" for k in range(lines))
        return f'def {name}():\n    """{doc}"""\n{body}\n\n'

    (tmp_path / "chatter").mkdir()
    (tmp_path / "chatter" / "long.py").write_text(
        function("too_long", MAX_BODY_LINES + 1)
        + function("at_limit", MAX_BODY_LINES)
        + function("explained", MAX_BODY_LINES + 5,
                   doc="Long because one table is set up in order.")
        + function("long_doc", 3, doc="words\n" * 200))
    (tmp_path / "top.py").write_text(
        "class A:\n" + "".join(
            "    " + line + "\n" for line in
            function("method", MAX_BODY_LINES + 2).splitlines()))
    assert long_functions(tmp_path) == {
        "chatter/long.py:too_long": MAX_BODY_LINES + 1,
        "top.py:method": MAX_BODY_LINES + 2}
