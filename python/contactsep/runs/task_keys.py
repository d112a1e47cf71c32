"""The names of a journal's simulations (:class:`contactsep.runs.journal.
RunJournal`): a task as plain JSON data, the same for equal inputs, and
the digest of a function applied to it."""

from __future__ import annotations

import dataclasses
import hashlib
import json

import numpy as np


def canonical(value):
    """``value`` as plain JSON data, the same for equal inputs: a
    dataclass (a Design) as its class name and fields, a dict by sorted
    keys, a NumPy scalar or array as Python numbers (floats keep every
    digit: ``json`` writes their shortest exact repr)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {"__class__": type(value).__name__,
                **{field.name: canonical(getattr(value, field.name))
                   for field in dataclasses.fields(value)}}
    if isinstance(value, dict):
        return {str(key): canonical(item)
                for key, item in sorted(value.items(),
                                        key=lambda pair: str(pair[0]))}
    if isinstance(value, (list, tuple)):
        return [canonical(item) for item in value]
    if isinstance(value, np.ndarray):
        return {"__array__": str(value.dtype),
                "values": canonical(value.tolist())}
    if isinstance(value, np.generic):
        return value.item()
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    # an unforeseen type: its repr (at worst a miss, a rerun of the task)
    return {"__repr__": type(value).__qualname__, "text": repr(value)}


def task_key(function, task) -> str:
    """The digest that names one simulation: ``function`` (by module and
    name) applied to ``task``; a task with a ``key_tuple()`` (a
    :class:`~contactsep.studies.preload.runs.PreloadRun`) by that tuple,
    so that its key is the one its plain tuple had (a journal kept
    before the tasks were named is still answered from)."""
    if callable(getattr(task, "key_tuple", None)):
        task = task.key_tuple()
    text = json.dumps([f"{function.__module__}.{function.__qualname__}",
                       canonical(task)], sort_keys=True,
                      separators=(",", ":"), allow_nan=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()
