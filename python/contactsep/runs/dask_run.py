"""A sweep's chunks on a Dask cluster (``contactsep sweep --scheduler``).

What travels: the SweepSpec (a few hundred bytes: linear axes are three
numbers) and two integers to a worker; back, a chunk's summary (a few
numbers, when nothing is written) or its columns as NumPy arrays (Dask
sends their buffers as they are, no pickled rows).  Each worker samples
and evaluates its own designs.  As many chunks are in flight as the
cluster has threads, twice over, so no worker waits for the client.

Faults: an address that accepts connections but never speaks Dask's
protocol (a silent port, an HTTP server) is refused within
PROBE_TIMEOUT_S by a probe that reads the scheduler's first message
before Dask does (Dask would read an HTTP reply as an exabyte-long
frame); a scheduler lost mid-sweep is one :class:`SchedulerLost` line
within SCHEDULER_LOST_S, the chunks finished before it kept (written,
and with ``--resume`` continued by the next run); a worker lost
mid-sweep costs its chunk, which Dask runs again (the same bits: a
chunk's designs do not depend on where they run).
"""

from __future__ import annotations

import contextlib
import ctypes
import json
import logging
import numbers
import os
import re
import socket
import struct
import time

from contactsep.errors import InputError
from contactsep.output import one_line

#: Seconds to wait for a Dask scheduler to answer.
SCHEDULER_TIMEOUT_S = 10
#: Seconds the probe waits for a scheduler's first message (a Dask
#: scheduler sends it as soon as it accepts): the refusal of a silent
#: port, start-up included, comes within SCHEDULER_TIMEOUT_S.
PROBE_TIMEOUT_S = 5
#: Seconds a sweep waits for a scheduler whose connection was lost.
SCHEDULER_LOST_S = 15
#: A client's states while it holds its scheduler's connection.
CONNECTED = ("running", "newly-created")
#: The largest first message a Dask scheduler sends (its handshake is a
#: few hundred bytes): more is another protocol.
_LARGEST_HANDSHAKE = 1 << 20


#: glibc's mallopt parameters, and the values its own dynamic threshold
#: reaches at most on 64-bit (DEFAULT_MMAP_THRESHOLD_MAX; the trim
#: threshold twice that).
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
_MMAP_THRESHOLD = 32 * 1024 * 1024
_TRIM_THRESHOLD = 2 * _MMAP_THRESHOLD
_heap_set = False
#: The variables whose presence turns glibc's dynamic thresholds off.
_STATIC_HEAP = ("MALLOC_TRIM_THRESHOLD_", "MALLOC_MMAP_THRESHOLD_",
                "MALLOC_TOP_PAD_", "MALLOC_MMAP_MAX_")


def heap_as_glibc_default() -> None:
    """Give this process's malloc back the thresholds glibc would reach.

    A Dask nanny starts its workers with ``MALLOC_TRIM_THRESHOLD_=65536``
    (distributed.yaml, pre-spawn-environ), which turns glibc's dynamic
    mmap threshold off: every array over 128 KiB is then a fresh mmap,
    page-faulted in and unmapped again.  A 100,000-design eq. 23 chunk
    makes dozens of such arrays: 4.7 times the page faults and 9-12 %
    more time than in a process started plainly (measured in
    docs/performance.md).  Called at the start of each chunk on a Dask
    worker, once per process; it does nothing where malloc is not
    glibc's or where no MALLOC_*_ variable turned the dynamic threshold
    off (an in-process cluster: the user's process keeps its malloc).
    """
    global _heap_set
    if _heap_set:
        return
    _heap_set = True
    if not any(name in os.environ for name in _STATIC_HEAP):
        return
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):      # not glibc
        return
    mallopt(_M_MMAP_THRESHOLD, _MMAP_THRESHOLD)
    mallopt(_M_TRIM_THRESHOLD, _TRIM_THRESHOLD)


#: A host name or address (an IPv6 one without its brackets).
_HOST = re.compile(r"^[A-Za-z0-9._:%-]+$")


class SchedulerLost(InputError):
    """The Dask scheduler went away during the sweep."""


def _host_port(address: str) -> tuple[str, int] | None:
    """(host, port) of a tcp:// address (Dask's default port 8786), or
    None for another transport (left to Dask)."""
    scheme, sep, rest = address.partition("://")
    if not sep:
        scheme, rest = "tcp", address
    if scheme != "tcp":
        return None
    rest = rest.split("/", 1)[0]
    if rest.startswith("["):                 # [::1]:8786
        host, _, port = rest[1:].partition("]")
        port = port.lstrip(":")
    else:
        host, _, port = rest.rpartition(":") if ":" in rest else \
            (rest, "", "")
    try:
        if not _HOST.match(host):
            raise ValueError(host)
        return host, int(port) if port else 8786
    except ValueError:
        raise InputError(f"--scheduler: found {address!r}, expected a "
                         f"scheduler address such as tcp://HOST:8786"
                         ) from None


def probe(address: str, timeout: float | None = None,
          label: str | None = None) -> None:
    """Refuse (InputError) an address where no Dask scheduler speaks:
    nothing listening, nothing said within ``timeout`` s (a Dask
    scheduler sends its handshake as soon as it accepts), or a first
    message that is not a Dask frame; ``label`` names the address in
    messages (default ``--scheduler ADDRESS``)."""
    label = label or f"--scheduler {address}"
    where = _host_port(address)
    if where is None:
        return
    if timeout is None:
        timeout = PROBE_TIMEOUT_S
    deadline = time.monotonic() + timeout
    try:
        with socket.create_connection(where, timeout=timeout) as sock:
            data = b""
            while len(data) < 8:
                left = deadline - time.monotonic()
                if left <= 0:
                    raise TimeoutError
                sock.settimeout(left)
                more = sock.recv(8 - len(data))
                if not more:
                    raise InputError(f"{label}: the server "
                                     f"closed the connection without "
                                     f"answering; not a Dask scheduler")
                data += more
    except (TimeoutError, socket.timeout):
        raise InputError(f"{label}: accepts connections but "
                         f"said nothing within {timeout:g} s; not a Dask "
                         f"scheduler (or one that does not answer)"
                         ) from None
    except OSError as error:
        raise InputError(f"{label}: no scheduler answered "
                         f"({error.strerror or error})") from None
    (length,) = struct.unpack("Q", data)
    if not 0 < length <= _LARGEST_HANDSHAKE:
        raise InputError(f"{label}: answers another protocol"
                         f" ({data!r}...), not Dask's")


def read_scheduler_file(path) -> str:
    """The address in a Dask scheduler file (``dask scheduler
    --scheduler-file FILE`` writes it: JSON with an "address"); a file
    missing, unreadable or not one is one InputError.  (Dask's own
    ``Client(scheduler_file=...)`` waits for a missing file to appear:
    here it is refused at once.)"""
    option = f"--scheduler-file {path}"
    try:
        with open(path, encoding="utf-8") as handle:
            text = handle.read(_LARGEST_HANDSHAKE)
    except FileNotFoundError:
        raise InputError(f"{option}: no such file (a Dask scheduler "
                         f"started with --scheduler-file FILE writes it)"
                         ) from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{option}: cannot be read "
                         f"({one_line(error)})") from None
    try:
        address = json.loads(text)["address"]
    except (ValueError, KeyError, TypeError):
        address = None
    if not isinstance(address, str) or not address.strip():
        raise InputError(f"{option}: not a Dask scheduler file (JSON "
                         f"naming the scheduler's \"address\")")
    return address


def connect(address: str | None = None, scheduler_file=None):
    """A Client of the scheduler at ``address``, or of the one a Dask
    scheduler file names (``scheduler_file``); an address Dask cannot
    read, or a scheduler that does not answer, is one InputError naming
    the option (--scheduler or --scheduler-file)."""
    option = "--scheduler" if scheduler_file is None else \
        "--scheduler-file"
    try:
        from distributed import Client
    except ImportError:
        raise InputError(f"{option} needs dask.distributed: pip install "
                         f"'contactsep[scale]'") from None
    if scheduler_file is not None:
        address = read_scheduler_file(scheduler_file)
        label = f"--scheduler-file {scheduler_file} (scheduler {address})"
    else:
        label = f"--scheduler {address}"
    if not isinstance(address, str) or not address.strip():
        raise InputError(f"--scheduler: found {address!r}, expected a "
                         f"scheduler address such as tcp://HOST:8786")
    probe(address, label=label)
    # Dask's log lines (ERROR ... failed to reconnect) stay off stderr
    # for the rest of the command: the sweep says what happened
    silence_dask()
    try:
        return Client(address, timeout=SCHEDULER_TIMEOUT_S)
    except (ValueError, TypeError) as error:
        raise InputError(f"{option}: found {address!r}, expected a "
                         f"scheduler address such as tcp://HOST:8786 "
                         f"({error})") from None
    except (OSError, TimeoutError) as error:
        raise InputError(f"{label}: no scheduler answered "
                         f"within {SCHEDULER_TIMEOUT_S} s "
                         f"({error})") from None


def is_client(value) -> bool:
    """Whether ``value`` is a ``distributed.Client`` (without importing
    Dask for a number or None)."""
    if value is None or isinstance(value, (bool, numbers.Number, str)):
        return False
    try:
        from distributed import Client
    except ImportError:
        return False
    return isinstance(value, Client)


def _dask_loggers() -> list:
    names = [name for name in logging.root.manager.loggerDict
             if name == "distributed" or name.startswith("distributed.")]
    return [logging.getLogger(name) for name in names + ["distributed"]]


def silence_dask() -> None:
    """Dask's loggers and their handlers off, for good (the command's
    process: Dask's own config gives each logger its level, and a
    handler on "distributed" prints what they pass)."""
    for logger in _dask_loggers():
        logger.setLevel(logging.CRITICAL + 1)
        for handler in logger.handlers:
            handler.setLevel(logging.CRITICAL + 1)


@contextlib.contextmanager
def quiet_dask():
    """Dask's own log lines (ERROR ... connection lost) off stderr while
    the block runs: the sweep says what happened in one line."""
    loggers = _dask_loggers()
    levels = [(logger, logger.level) for logger in loggers]
    for logger in loggers:
        logger.setLevel(logging.CRITICAL + 1)
    try:
        yield
    finally:
        for logger, level in levels:
            logger.setLevel(level)


def threads(client) -> int:
    """Worker threads of the cluster (at least 1)."""
    try:
        return max(1, sum(client.nthreads().values()))
    except Exception:        # noqa: BLE001 - a cluster still starting
        return 1


def scheduler_where(client) -> str:
    """" ADDRESS" of the client's scheduler, for messages ("" unknown)."""
    try:
        return f" {client.scheduler.address}"
    except Exception:        # noqa: BLE001 - only a name in a message
        return ""


def scheduler_lost(where: str, done_designs: int,
                   kept: str | None = None) -> SchedulerLost:
    """The one line of a scheduler lost at ``where``
    (:func:`scheduler_where`); ``kept``: what became of the work
    finished before it (default: the ``done_designs`` designs)."""
    if kept is None:
        kept = (f"the {done_designs} designs finished before it are kept "
                f"(rerun with --resume to continue)")
    return SchedulerLost(f"the Dask scheduler{where} was lost (its "
                         f"connection closed); {kept}")
