"""Arithmetic on committed values, for the ``datum`` role.

A number a page draws from the data is not always a cell: a ratio of
two timings, a difference in per cent, a time scaled to another unit.
The role's text may then be an expression, ``=EXPR[:FORMAT]``, in which
each ``[SPEC]`` is a value the plain role would show (``SPEC`` is
``FILE:COLUMN[@KEY=VALUE,...]``, without a format)::

    {datum}`=100 * ([run.md#2:seconds@output=CSV] / [run.md#2:seconds@output=no] - 1):+.1f`

EXPR is numbers, ``[SPEC]`` values, ``+ - * / **``, parentheses and the
functions ``abs``, ``min``, ``max`` and ``round``; nothing else is
evaluated (the expression is parsed, never passed to ``eval``).  Every
failure is a data_values.DatumError with one printable line.
"""

from __future__ import annotations

import ast
import operator
import re

from data_values import DatumError, one_line

#: A value in an expression: [FILE:COLUMN@...], no brackets inside.
_VALUE = re.compile(r"\[([^\[\]]+)\]")
_BINARY = {ast.Add: operator.add, ast.Sub: operator.sub,
           ast.Mult: operator.mul, ast.Div: operator.truediv,
           ast.Pow: operator.pow}
_UNARY = {ast.USub: operator.neg, ast.UAdd: operator.pos}
_FUNCTIONS = {"abs": abs, "min": min, "max": max, "round": round}


def split(text: str) -> tuple[str, list[str], str | None]:
    """(EXPR with each value as ``v0, v1, ...``, the values' SPECs, the
    FORMAT or None) of ``=EXPR[:FORMAT]``."""
    body = one_line(text).strip().removeprefix("=")
    specs = []

    def name(found: re.Match) -> str:
        specs.append(found.group(1).strip())
        return f"v{len(specs) - 1}"

    expression = _VALUE.sub(name, body)
    expression, colon, fmt = expression.partition(":")
    if not specs:
        raise DatumError(f"datum {text!r}: an expression needs at least "
                         "one [FILE:COLUMN...] value")
    return expression.strip(), specs, fmt.strip() if colon else None


def _evaluate(node, values: dict, text: str):
    if isinstance(node, ast.Expression):
        return _evaluate(node.body, values, text)
    if isinstance(node, ast.Constant) and type(node.value) in (int, float):
        return node.value
    if isinstance(node, ast.Name) and node.id in values:
        return values[node.id]
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        left = _evaluate(node.left, values, text)
        right = _evaluate(node.right, values, text)
        try:
            return _BINARY[type(node.op)](left, right)
        except (ZeroDivisionError, OverflowError) as error:
            raise DatumError(f"datum {text!r}: {one_line(error)}") from None
    if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
        return _UNARY[type(node.op)](_evaluate(node.operand, values, text))
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and \
            node.func.id in _FUNCTIONS and not node.keywords:
        arguments = [_evaluate(a, values, text) for a in node.args]
        try:
            return _FUNCTIONS[node.func.id](*arguments)
        except (TypeError, ValueError) as error:
            raise DatumError(f"datum {text!r}: {one_line(error)}") from None
    raise DatumError(f"datum {text!r}: only numbers, [values], + - * / **, "
                     "parentheses, abs, min, max and round are allowed")


def evaluate(text: str, value) -> float:
    """The number ``=EXPR`` gives, each ``[SPEC]`` read by
    ``value(SPEC)`` (a number)."""
    expression, specs, _ = split(text)
    try:
        tree = ast.parse(expression, mode="eval")
    except SyntaxError:
        raise DatumError(f"datum {text!r}: not an expression") from None
    values = {f"v{i}": value(spec) for i, spec in enumerate(specs)}
    return _evaluate(tree, values, text)
