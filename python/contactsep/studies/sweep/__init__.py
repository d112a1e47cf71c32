"""The sweep engine: its spec and axes, the checks, the chatter sweeps,
the chunked run, the writers, the frames and the result."""
