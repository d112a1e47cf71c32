"""The digest of the code that computes a result.

A resumable sweep's chunks and a preload search's runs, kept in their
journal (:mod:`contactsep.runs.journal`), are finished
results for a later run to take.  The package version in their manifest
tells one release from another, but not an edited development install
from the code that made the results: a rerun would mix the two without
noticing.  So the manifest also holds :func:`code_digest`, a SHA-256 of
the modules that compute the results (their source, and the compiled
extension modules' files), and a resume is refused when it differs.

Only the layers a result depends on are read: the simulation layers
(restored, model, beams, chatter and the package's top-level modules)
for a journal, whose runs are keyed by their whole task; those and the
studies for a sweep, whose chunks are columns a study computed.  The
command line and the output helpers are left out: editing a message
does not throw away hours of finished runs.  The digest is the code of
the process that resumes (a Dask cluster's workers run their own
install; that is the cluster's to keep equal).
"""

from __future__ import annotations

import functools
import hashlib
import importlib
import importlib.util
import pkgutil

#: The layers that compute a simulation's result.
SIMULATION = ("restored", "model", "beams", "chatter")
#: Those and the studies: what a sweep's columns depend on.
STUDIES = (*SIMULATION, "runs", "studies")
#: Top-level modules of the package that every layer uses.
_SHARED = ("constants", "errors", "units")


def module_files(package: str, layers, shared=()) -> list:
    """(module name, file) of every module of ``package``'s subpackages
    ``layers`` (recursively) and of its top-level modules ``shared``,
    sorted by name: sources and compiled extension modules alike, found
    by the import system (so an editable install's build directory
    too)."""
    found = {}

    def add(name: str) -> None:
        spec = importlib.util.find_spec(name)
        if spec is None or not spec.origin or spec.origin in (
                "built-in", "frozen"):
            return
        found[name] = spec.origin

    for name in shared:
        add(f"{package}.{name}")
    for layer in layers:
        name = f"{package}.{layer}"
        add(name)
        module = importlib.import_module(name)
        for info in pkgutil.walk_packages(module.__path__, f"{name}."):
            add(info.name)
    return sorted(found.items())


def digest_files(files) -> str:
    """SHA-256 (hex) of ``files`` ((name, path) pairs): each name, its
    file's length and its bytes, in the order given."""
    digest = hashlib.sha256()
    for name, path in files:
        with open(path, "rb") as handle:
            data = handle.read()
        digest.update(f"{name}\0{len(data)}\0".encode("utf-8"))
        digest.update(data)
    return digest.hexdigest()


@functools.lru_cache(maxsize=None)
def code_digest(layers=SIMULATION) -> str:
    """SHA-256 (hex) of the contactsep modules in ``layers``
    (:data:`SIMULATION` or :data:`STUDIES`) and the shared top-level
    modules, as this process imports them; read once a process.

    Examples
    --------
    >>> from contactsep.runs.code_digest import code_digest
    >>> len(code_digest())
    64
    """
    return digest_files(module_files("contactsep", layers, _SHARED))
