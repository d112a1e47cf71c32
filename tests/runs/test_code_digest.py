"""The digest of the code in a resume's manifest
(contactsep.runs.code_digest): it reads every module of the layers a
result depends on (sources and compiled extensions, found by the import
system) and nothing else, so that an edited development install refuses
to resume results made by other code, and an edited message does not."""

from __future__ import annotations

import importlib
import pathlib
import subprocess
import sys

import pytest

import contactsep
from contactsep.runs import code_digest as digests


@pytest.fixture
def package(tmp_path, monkeypatch):
    """A package ``dig_pkg`` of its own with two layers and a top-level
    module, importable for this test only."""
    root = tmp_path / "dig_pkg"
    for layer in ("physics", "physics/deep", "talk"):
        (root / layer).mkdir(parents=True)
        (root / layer / "__init__.py").write_text("")
    (root / "__init__.py").write_text("")
    (root / "shared.py").write_text("G = 1\n")
    (root / "physics" / "law.py").write_text("K = 2\n")
    (root / "physics" / "deep" / "step.py").write_text("DT = 3\n")
    (root / "talk" / "message.py").write_text("TEXT = 'hello'\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    importlib.invalidate_caches()
    yield root
    for name in [m for m in sys.modules if m.startswith("dig_pkg")]:
        del sys.modules[name]


def _digest(layers=("physics",)):
    return digests.digest_files(digests.module_files(
        "dig_pkg", layers, ("shared",)))


def test_the_files_are_every_module_of_the_layers_and_no_other(package):
    names = [name for name, _ in digests.module_files(
        "dig_pkg", ("physics",), ("shared",))]
    assert names == ["dig_pkg.physics", "dig_pkg.physics.deep",
                     "dig_pkg.physics.deep.step", "dig_pkg.physics.law",
                     "dig_pkg.shared"]


@pytest.mark.parametrize("edited, changes", [
    ("physics/law.py", True), ("physics/deep/step.py", True),
    ("shared.py", True), ("talk/message.py", False)])
def test_an_edit_changes_the_digest_where_it_reads(package, edited,
                                                   changes):
    before = _digest()
    path = package / edited
    path.write_text(path.read_text() + "# edited\n")
    assert (_digest() != before) is changes


def test_a_file_renamed_changes_the_digest(package):
    before = _digest()
    (package / "physics" / "law.py").rename(package / "physics" / "rule.py")
    importlib.invalidate_caches()
    assert _digest() != before


def test_the_digest_reads_the_packages_sources_and_compiled_modules():
    files = dict(digests.module_files("contactsep", digests.STUDIES,
                                      ("constants",)))
    # every source of the layers, listed from the directory itself
    source = pathlib.Path(contactsep.__file__).parent
    for layer in digests.STUDIES:
        for path in (source / layer).rglob("*.py"):
            parts = path.relative_to(source).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            assert files.get(".".join(("contactsep", *parts))) == str(path)
    # and the four compiled extension modules, wherever the install
    # keeps them
    for name in ("restored._core_single", "restored._core_double",
                 "model._model", "chatter._chatter"):
        module = importlib.import_module(f"contactsep.{name}")
        assert files[f"contactsep.{name}"] == module.__file__
    assert not any(name.startswith(("contactsep.cli", "contactsep.output"))
                   for name in files)


def test_the_digest_is_the_same_in_another_process():
    code = ("from contactsep.runs.code_digest import code_digest, "
            "STUDIES; print(code_digest(), code_digest(STUDIES))")
    out = subprocess.run([sys.executable, "-c", code], check=True,
                         capture_output=True, text=True).stdout.split()
    assert out == [digests.code_digest(),
                   digests.code_digest(digests.STUDIES)]
    assert out[0] != out[1]
