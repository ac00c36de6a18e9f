"""The machine benchmarks behind ``roboracer-arena bench``: ``physics`` (the native
simulator) and ``env`` (the gymnasium env), each with ``register(subparsers)`` (its CLI)
and ``run_quick()``. The paper's benchmarks, the peer comparisons and the baselines are
not in the package: they run from a checkout (``python -m benchmarks``)."""
