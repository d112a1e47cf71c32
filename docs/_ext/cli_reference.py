"""The ``contactsep-cli`` directive: the command line reference, generated
from the parser the command builds (``contactsep.cli.build_parser``).

Each subcommand gets a section (so the page's table of contents lists
them) holding its description and its full ``--help`` text, verbatim, as
the command prints it: every option, its default and the examples, with
nothing lost to reStructuredText's reading of ``--`` or indentation.
"""

from __future__ import annotations

import argparse
import os

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

#: Width of the help text on the page (argparse reads $COLUMNS).
WIDTH = "88"


def _subcommands(parser: argparse.ArgumentParser) -> dict:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _help(parser: argparse.ArgumentParser) -> str:
    before = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = WIDTH
    try:
        return parser.format_help()
    finally:
        if before is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = before


class CliReference(SphinxDirective):
    """``.. contactsep-cli::`` (no arguments): the whole command line."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        from contactsep.cli import build_parser

        parser = build_parser()
        top = nodes.section(ids=["contactsep-command"])
        top += nodes.title(text="contactsep")
        top += nodes.literal_block(text=_help(parser))
        for name, sub in _subcommands(parser).items():
            section = nodes.section(ids=[f"contactsep-{name}"])
            section += nodes.title(text=f"contactsep {name}")
            section += nodes.literal_block(text=_help(sub))
            top += section
        return [top]


def setup(app):
    app.add_directive("contactsep-cli", CliReference)
    return {"version": "1", "parallel_read_safe": True}
