"""Headless Chromium for the tests that open a page as a person would
(Debian's package; CI installs it)."""

from __future__ import annotations

import shutil


def chromium() -> str | None:
    """The browser's path, or None where none is installed."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if shutil.which(name):
            return shutil.which(name)
    return None


def headless(profile) -> list[str]:
    """The command that runs it headless with its own profile directory
    (``profile``: a folder the test made), so that runs beside it share
    nothing."""
    return [chromium(), "--headless", "--no-sandbox", "--disable-gpu",
            f"--user-data-dir={profile}"]
