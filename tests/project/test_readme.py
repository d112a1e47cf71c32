"""README.md's set-up commands stay true: CI runs the same test command, and
the deck the first command runs exists."""

from __future__ import annotations

import re

import contactsep
from conftest import ROOT


def setup_commands() -> list[str]:
    readme = (ROOT / "README.md").read_text()
    section = readme.split("## Set-up", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```sh\n(.*?)\n```", section, flags=re.S)


def test_exactly_two_setup_commands():
    commands = setup_commands()
    assert len(commands) == 2
    assert all("\n" not in c for c in commands)


def test_ci_runs_the_readme_test_command():
    ci = (ROOT / ".ci" / "run").read_text()
    assert setup_commands()[1] in ci.splitlines()


def test_install_command_runs_a_thesis_deck():
    install = setup_commands()[0]
    deck = re.search(r"contactsep legacy (\S+)", install).group(1)
    assert (ROOT / deck).is_file()
    assert "gfortran" in install


def test_python_example_runs(monkeypatch, capsys):
    """The README's Python example runs as written, from the checkout."""
    readme = (ROOT / "README.md").read_text()
    example = re.search(r"```python\n(.*?)\n```", readme, flags=re.S).group(1)
    monkeypatch.chdir(ROOT)
    exec(compile(example, "README.md", "exec"), {})
    printed = capsys.readouterr().out.splitlines()
    assert printed[0].split()[0] == "2.500000000"   # echo of card 2: XL2
    extremes = [float(line.split()[1]) for line in printed[-3:]]
    # the decks' numbers: the loop builds the data sets the decks hold
    for h2, value in zip(("0125", "0250", "0500"), extremes):
        deck = contactsep.replay(ROOT / "data" / "decks" /
                                 f"thesis_d{h2}.dat", precision="double")
        assert value == deck[0].extreme_ty3
    # thicker separators kick the lower contact less (Figure 5)
    assert abs(extremes[0]) > abs(extremes[1]) > abs(extremes[2]) > 0


def test_model_example_runs(monkeypatch, capsys):
    readme = (ROOT / "README.md").read_text()
    example = re.findall(r"```python\n(.*?)\n```", readme, flags=re.S)[1]
    monkeypatch.chdir(ROOT)
    exec(compile(example, "README.md", "exec"), {})
    printed = capsys.readouterr().out
    design = contactsep.thesis_design(d=0.25, x3=0.78 * 19.0, n_modes=20,
                                      end2="clamped-pinned")
    assert repr(float(contactsep.evaluate(design).y3_max)) in printed


def test_readme_commands_are_commands():
    """Every `contactsep ...` line of the README names a real command."""
    readme = (ROOT / "README.md").read_text()
    from contactsep.cli import build_parser
    choices = build_parser()._subparsers._group_actions[0].choices
    for name in re.findall(r"^contactsep (\w+)", readme, flags=re.M):
        assert name in choices


def test_designers_loop_gives_the_decks_numbers():
    """The README's loop (thesis_data_set(d), double) gives what each
    thickness's deck gives when replayed in double."""
    import numpy as np
    import pytest

    import contactsep
    from contactsep.restored import thesis_decks
    from contactsep.restored.dataset import MODE_GROUPS
    for d, name in ((0.125, "thesis_d0125"), (0.25, "thesis_d0250"),
                    (0.5, "thesis_d0500")):
        deck = contactsep.replay(ROOT / "data" / "decks" / f"{name}.dat",
                                 precision="double")[0]
        ds = thesis_decks.thesis_data_set(d)
        # every card field but the mode constants is the deck's, XL2C
        # included; the mode constants are the deck's to its 9 decimals
        modes = {name: getattr(deck.inputs, name) for group in MODE_GROUPS
                 for name in group}
        assert ds.replace(**modes) == deck.inputs
        for name in modes:
            np.testing.assert_allclose(getattr(ds, name), modes[name],
                                       rtol=0, atol=5e-10 + 1e-15)
        loop = contactsep.solve(ds, "double")
        # 9-decimal ALPHA moves A_4 by <= 1.4e-3 relative (reference.py)
        assert loop.extreme_ty3 == pytest.approx(deck.extreme_ty3, rel=1.4e-3)
        assert loop.extreme_time == deck.extreme_time
