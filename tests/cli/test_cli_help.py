"""Every subcommand's --help ends with two or three examples, and each
example is a command line the parser accepts (issue 19, item 8)."""

from __future__ import annotations

import shlex

import pytest

from contactsep.cli import build_parser

#: Subcommands whose module another branch rewrites (contactsep chatter:
#: the chatter layer's issue 16); their examples are added there.
OWNED_ELSEWHERE: set = set()


def subcommands() -> dict:
    return build_parser()._subparsers._group_actions[0].choices


def examples(name: str) -> list[str]:
    text = subcommands()[name].format_help()
    assert "\nexamples:\n" in text, f"{name} --help has no examples"
    block = text.split("\nexamples:\n", 1)[1]
    return [line.strip() for line in block.splitlines() if line.strip()]


def command_lines(example: str) -> list[list[str]]:
    """The contactsep invocations of an example line (pipes, &&, a
    comment and redirections taken apart)."""
    words = shlex.split(example, comments=True)
    found, current = [], None
    skip = False
    for word in words + ["|"]:
        if skip:
            skip = False
        elif word in ("|", "&&", "||"):
            if current is not None:
                found.append(current)
            current = None
        elif word in (">", "<", "2>"):
            skip = True
        elif word == "contactsep" and current is None:
            current = []
        elif current is not None:
            current.append(word)
    return found


@pytest.mark.parametrize("name", sorted(set(subcommands()) - OWNED_ELSEWHERE))
def test_help_ends_with_examples_the_parser_accepts(name):
    lines = examples(name)
    assert 2 <= len(lines) <= 3, lines
    for line in lines:
        invocations = command_lines(line)
        assert any(argv[0] == name for argv in invocations), line
        for argv in invocations:
            try:
                args = build_parser().parse_args(argv)
            except SystemExit:
                pytest.fail(f"{name}: the example {line!r} does not parse")
            assert args.command == argv[0]
