"""``contactsep``'s namespace is its documented names and its own
subpackages: no module it imported for itself (importlib was one)."""

from __future__ import annotations

import types

import contactsep


def test_the_namespace_holds_only_its_names_and_subpackages():
    stray = []
    for name in dir(contactsep):
        if name.startswith("_") or name in contactsep.__all__:
            continue
        value = getattr(contactsep, name)
        if isinstance(value, types.ModuleType) and \
                value.__name__ == f"contactsep.{name}":
            continue
        stray.append(name)
    assert not stray, f"not contactsep's own names: {stray}"
