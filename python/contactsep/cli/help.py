"""How the subcommands' ``--help`` is laid out: descriptions wrapped to
the terminal, the examples of the epilog kept line for line."""

from __future__ import annotations

import argparse


class HelpFormatter(argparse.HelpFormatter):
    """argparse's formatter, except that text starting with 'examples:'
    (every subcommand's epilog) keeps its lines."""

    def _fill_text(self, text, width, indent):
        if text.startswith("examples:"):
            return "".join(indent + line for line in
                           text.splitlines(keepends=True))
        return super()._fill_text(text, width, indent)


def examples(*lines: str) -> dict:
    """``add_parser`` keywords for an epilog of examples, one a line."""
    return {"epilog": "examples:\n" + "".join(f"  {line}\n"
                                              for line in lines),
            "formatter_class": HelpFormatter}
