"""Subcommands of ``contactsep`` for this layer (see contactsep.cli)."""

from __future__ import annotations

import argparse


def register(commands: argparse._SubParsersAction) -> None:
    """Add this layer's subcommands; each sets ``handler=`` as default."""
