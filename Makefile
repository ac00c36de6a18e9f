# RoboRacer Arena. Every target creates/updates .venv itself; only python3, pip, cargo
# and a C compiler are assumed.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
export VIRTUAL_ENV := $(abspath $(VENV))
export PATH := $(abspath $(BIN)):$(PATH)
# Where the public track data lives (see ../shared/track-sources/SOURCES.md).
export ROBORACER_ARENA_SOURCES ?= $(abspath ../shared/track-sources)

.PHONY: demo test test-rust test-python test-dev wheel bench lint develop release clean docs-figures

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip "maturin>=1.7,<2"

# Dev-profile build (dependencies at opt-level 3) plus runtime and test dependencies.
develop: $(BIN)/python
	$(BIN)/maturin develop -q --extras test,video,ros2,ros2-test,render3d,ray,physx

# Optimised build for benchmarks.
release: $(BIN)/python
	$(BIN)/maturin develop -q --release --extras test,video,ros2,ros2-test,render3d,ray,physx

demo: develop
	$(BIN)/python -m roboracer_arena.demo --out out/demo

test: test-rust test-python

# --include-ignored: the stress tests (12,240 wall hits, ~10 s) prove issue claims too.
test-rust:
	cargo test -p arena_core --quiet -- --include-ignored

# The release wheel users install, built once (dist/), installed into a fresh venv in a
# temporary directory outside the checkout, smoke-tested there (CLI, gym.make, generate,
# build, demo, bench physics, the benchmarks' parser), then the Python suite runs against it: tests test what
# users get, and CI compiles the extension once.
test-python: $(BIN)/python
	MATURIN=$(abspath $(BIN))/maturin scripts/wheel_smoke.sh --pytest -- -q

# Dev loop: the suite against the editable dev build in .venv.
test-dev: develop
	$(BIN)/python -m pytest -q

wheel: $(BIN)/python
	rm -rf dist && $(BIN)/maturin build --release --quiet --out dist

# The criterion benches and every benchmark of the checkout's benchmarks/ package (the
# paper's tables, the peer comparisons; not in the wheel) with their quick defaults.
bench: release
	cargo bench -p arena_core --quiet -- --quick
	$(BIN)/python -m benchmarks all --json out/bench.json

# Every figure in README.md / BENCHMARKS.md a script produces (the bench tables, catalog counts,
# ES curve and lap, generalisation, PhysX laps), rerun on the current release build and written
# with their data (docs/figures/, docs/learning/) and pictures; `scripts/docs_figures.py --list`
# names them, FIGURES="--only NAME" picks some. tests/docs/test_docs_figures.py holds the
# deterministic ones. About an hour on 2 cores (the sweep, Table 3's DE, generalisation).
FIGURES ?=
docs-figures: release
	$(BIN)/python scripts/docs_figures.py --build release $(FIGURES)

# Every gate: clippy and rustfmt on the crates, no module cycle in the Rust core, no function
# over 100 lines in the crates or the package; ruff (lint and format), mypy (pydantic plugin)
# on the package; stubtest checks _core.pyi against the built extension; import-linter holds
# the package's floors and finds no cycle (.importlinter); import_hygiene refuses
# function-local own imports and private cross-package access.
lint: develop
	$(BIN)/pip install -q "ruff>=0.8" "mypy>=1.13" "import-linter>=2.17"
	cargo clippy -p arena_core -p arena_py --quiet -- -D warnings
	cargo fmt --all -- --check
	$(BIN)/python scripts/rust_module_cycles.py crates/arena_core/src
	$(BIN)/python scripts/long_functions.py --max 100
	$(BIN)/lint-imports --no-cache
	$(BIN)/python scripts/import_hygiene.py python/roboracer_arena
	$(BIN)/ruff check --no-cache python tests examples benchmarks
	$(BIN)/ruff format --no-cache --check python tests examples benchmarks
	$(BIN)/mypy
	$(BIN)/python -m mypy.stubtest roboracer_arena._core

clean:
	rm -rf $(VENV) target out dist
