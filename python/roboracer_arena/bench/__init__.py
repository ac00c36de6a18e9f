"""Benchmark drivers behind ``roboracer-arena bench``. Each module ``<kind>.py``
provides ``register(subparsers)`` (its CLI) and ``run_quick() -> dict`` (used by
``bench all`` and ``make bench``), prints a table and compares with the paper."""
