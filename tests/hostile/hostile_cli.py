"""Helpers of the hostile-input tests: the command in a child process or
in this one, and what every refusal must look like."""

from __future__ import annotations

import json
import os
import stat
import subprocess
import sys


def run(*args, timeout=120, **kwargs) -> subprocess.CompletedProcess:
    """``contactsep ARGS`` in a child process (text output)."""
    return subprocess.run([sys.executable, "-m", "contactsep", *args],
                          capture_output=True, text=True, timeout=timeout,
                          **kwargs)


def main(capsys, *args) -> tuple[int, str, str]:
    """``contactsep ARGS`` in this process: (status, stdout, stderr)."""
    from contactsep.cli import main as cli_main
    status = cli_main(list(args))
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def refusal(status: int, err: str) -> str:
    """The promise: exit 2 and one printable line 'contactsep: error:
    ...' (warnings before it allowed); returns the message."""
    assert status == 2, (status, err)
    lines = err.splitlines()
    assert err.endswith("\n") and lines, err
    assert all(line.startswith("contactsep: warning: ")
               for line in lines[:-1]), err
    last = lines[-1]
    assert last.startswith("contactsep: error: "), err
    assert last.isprintable() and "Traceback" not in err, err
    return last[len("contactsep: error: "):]


def _no_constant(name):
    raise AssertionError(f"not strict JSON: {name}")


def strict_json(text: str):
    """Parse JSON that has no NaN or Infinity (json.loads takes them)."""
    return json.loads(text, parse_constant=_no_constant)


def device(tmp_path, name: str, minor: int) -> str:
    """A character device like /dev/NAME (1, minor): as root a private
    node in tmp_path (a wrong write must not replace the machine's)."""
    if os.geteuid() != 0:
        return f"/dev/{name}"
    path = tmp_path / name
    os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, minor))
    return str(path)


def debris(directory) -> list[str]:
    """Hidden files left in a directory (temporary files, locks)."""
    return sorted(p.name for p in directory.iterdir()
                  if p.name.startswith("."))
