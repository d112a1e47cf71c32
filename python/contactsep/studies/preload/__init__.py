"""The preload family: the command, the chart, the search, convergence,
robustness, the answer, its checks, verification and verdict."""
