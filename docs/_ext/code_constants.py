"""Numbers on the pages, drawn from the package's own constants at build
time.

The inline role ``constant`` (not ``const``: that is the Python
domain's cross-reference) puts the value of one of the package's named
constants into the text, so that a page that says how the code behaves
(a chunk's seconds, a limit, a window) cannot disagree with it::

    {constant}`contactsep.runs.chunks.CHUNKS_PER_WORKER`
    {constant}`contactsep.model.design_domain.SIZE_RANGE[1]:g`
    {constant}`contactsep.runs.backend.DASK_WINDOW_PER_WORKER:words`

The role's text is ``MODULE.NAME[INDEX]...[:FORMAT]``:

``MODULE.NAME``
    a module of the package and a constant of it: a name in capitals
    (``MAX_MODES``), or a class's (``Class.LIMIT``).
``[INDEX]``
    an item of a tuple, list or dict constant (an integer or a quoted
    key), as often as needed.
``FORMAT``
    a Python format spec (``.2g``, ``,d``); ``words``: a whole number
    from zero to twenty as an English word (``four``); ``sci``: the
    shortest form, a power of ten as the pages write one (``1e9``,
    ``3e8``, ``1e5``, ``1e-5``; 1024 stays ``1024``).  Without one the
    value is shown as Python's ``str`` gives it.

:func:`resolve` is the whole lookup, without Sphinx, so the tests run it
on every use in the pages; every way it can fail raises
:class:`ConstantError` with one printable line.
"""

from __future__ import annotations

import ast
import importlib
import numbers
import re

from data_values import one_line

#: The words of the ``words`` format.
WORDS = ("zero one two three four five six seven eight nine ten eleven "
         "twelve thirteen fourteen fifteen sixteen seventeen eighteen "
         "nineteen twenty").split()
#: The package whose constants a page may quote.
PACKAGE = "contactsep"
_SPEC = re.compile(r"^(?P<path>[A-Za-z_][\w.]*)(?P<index>(\[[^\]]+\])*)"
                   r"(:(?P<fmt>[^:]*))?$")
_INDEX = re.compile(r"\[([^\]]+)\]")


class ConstantError(ValueError):
    """A ``constant`` that cannot be shown; its message is one line."""


def _lookup(path: str):
    """The object ``path`` names: the longest importable module prefix,
    then attributes; the first after the module starts with a capital
    (a constant, or a class whose constant follows), and the value is
    not a function."""
    parts = path.split(".")
    if parts[0] != PACKAGE:
        raise ConstantError(f"{path}: not a name of the {PACKAGE} package")
    for cut in range(len(parts) - 1, 0, -1):
        name = ".".join(parts[:cut])
        try:
            value = importlib.import_module(name)
        except ImportError:
            continue
        rest = parts[cut:]
        if not rest[0][:1].isupper():
            raise ConstantError(f"{path}: {rest[0]} is not a constant of "
                                f"{name} (a name in capitals, or a "
                                f"class's)")
        for attribute in rest:
            try:
                value = getattr(value, attribute)
            except AttributeError:
                raise ConstantError(f"{path}: {name} has no "
                                    f"{attribute}") from None
            name = f"{name}.{attribute}"
        if callable(value) and not isinstance(value, type):
            raise ConstantError(f"{path}: a function, not a constant")
        return value
    raise ConstantError(f"{path}: no module of it can be imported")


def _item(value, index: str, where: str):
    try:
        key = ast.literal_eval(index.strip())
    except (ValueError, SyntaxError):
        raise ConstantError(f"{where}: [{index}] is not an integer or a "
                            f"quoted key") from None
    try:
        return value[key]
    except (KeyError, IndexError, TypeError):
        raise ConstantError(f"{where}: has no item [{index}]") from None


def _shortest(number: float) -> str:
    """``number`` written the shorter way: as a plain number, or as a
    mantissa and a power of ten with neither a plus nor leading zeros
    (100000 is 1e5, 1024 stays 1024)."""
    mantissa, _, exponent = f"{number:.15e}".partition("e")
    mantissa = mantissa.rstrip("0").rstrip(".")
    power = f"{mantissa}e{int(exponent)}"
    plain = f"{number:.15g}"
    if "e" in plain or len(power) < len(plain):
        return power
    return plain


def _format(value, fmt: str | None, where: str) -> str:
    if fmt is None or fmt == "":
        return str(value)
    if fmt == "sci":
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise ConstantError(f"{where}: {value!r} is not a number")
        return _shortest(float(value))
    if fmt == "words":
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) \
                or not 0 <= value < len(WORDS):
            raise ConstantError(f"{where}: {value!r} has no word (whole "
                                f"numbers 0 to {len(WORDS) - 1})")
        return WORDS[int(value)]
    try:
        return format(value, fmt)
    except (ValueError, TypeError) as error:
        raise ConstantError(f"{where}: format {fmt!r} does not take "
                            f"{value!r} ({one_line(error)})") from None


def resolve(spec: str) -> str:
    """The text the role shows for ``spec`` (module docstring)."""
    text = one_line(spec).replace(" ", "")
    match = _SPEC.match(text)
    if match is None:
        raise ConstantError(f"{one_line(spec)!r}: expected "
                            f"MODULE.NAME[INDEX][:FORMAT]")
    where = match.group("path") + (match.group("index") or "")
    value = _lookup(match.group("path"))
    for index in _INDEX.findall(match.group("index") or ""):
        value = _item(value, index, where)
    if isinstance(value, type):
        raise ConstantError(f"{where}: a class, not a value (name its "
                            f"constant)")
    if isinstance(value, (dict, list, tuple, set)):
        raise ConstantError(f"{where}: a {type(value).__name__}, not one "
                            f"value (give an [INDEX])")
    return _format(value, match.group("fmt"), where)


def constant_role(name, rawtext, text, lineno, inliner, options=None,
               content=None):
    """The ``constant`` role: the value as text, or an error at
    ``lineno``."""
    from docutils import nodes

    try:
        value = resolve(text)
    except ConstantError as error:
        message = inliner.reporter.error(f"constant: {error}", line=lineno)
        problem = inliner.problematic(rawtext, rawtext, message)
        return [problem], [message]
    return [nodes.Text(value)], []


def setup(app):
    """Register the ``constant`` role."""
    app.add_role("constant", constant_role)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
