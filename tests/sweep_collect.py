"""A sweep writer that keeps the rows in memory, for tests of the runner."""

from __future__ import annotations

import numpy as np


class Collect:
    """Gathers the chunks a sweep writes; ``table()`` joins them."""

    def __init__(self):
        self.parts = []

    def write(self, columns):
        self.parts.append({k: np.array(v) for k, v in columns.items()})

    def close(self):
        pass

    def table(self):
        return {k: np.concatenate([p[k] for p in self.parts])
                for k in self.parts[0]}
