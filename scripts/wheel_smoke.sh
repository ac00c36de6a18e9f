#!/usr/bin/env bash
# Build the release wheel, install it into a fresh venv in a temporary directory outside the
# checkout, and use it there as a user would: `tracks list`, a catalog track in gym.make,
# `generate`, `build`, the demo, `bench physics`, and the checkout's `python -m benchmarks`
# parser and constructors on it. With --pytest, then run the Python test
# suite against that installed wheel (so the tests test what users get, with one compile).
#
# Usage: scripts/wheel_smoke.sh [--pytest] [--wheel FILE.whl] [-- PYTEST ARGS...]
# Env:   PYTHON (default python3), MATURIN (default: .venv/bin/maturin, else maturin on PATH),
#        ROBORACER_ARENA_SOURCES (default ../shared/track-sources beside the checkout),
#        KEEP_WHEEL_ENV=1 keeps the temporary directory,
#        WHEEL_EXTRAS (default test,video,ros2,ros2-test,render3d,ray,physx) the extras installed with the wheel.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/.." && pwd)"
PYTHON="${PYTHON:-python3}"
RUN_PYTEST=0
WHEEL=""
PYTEST_ARGS=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --pytest) RUN_PYTEST=1 ;;
        --wheel) WHEEL="$2"; shift ;;
        --) shift; PYTEST_ARGS=("$@"); break ;;
        *) echo "wheel_smoke.sh: unknown argument $1" >&2; exit 2 ;;
    esac
    shift
done
export ROBORACER_ARENA_SOURCES="${ROBORACER_ARENA_SOURCES:-$(cd "$ROOT/.." && pwd)/shared/track-sources}"
unset ROBORACER_ARENA_TRACKS

step() { echo "== wheel smoke: $* ($(date -u +%H:%M:%S))"; }

if [[ -z "$WHEEL" ]]; then
    MATURIN="${MATURIN:-$ROOT/.venv/bin/maturin}"
    [[ -x "$MATURIN" ]] || MATURIN="$(command -v maturin)"
    rm -rf "$ROOT/dist"
    step "maturin build --release"
    start=$(date +%s)
    (cd "$ROOT" && "$MATURIN" build --release --quiet --out dist)
    echo "   built in $(( $(date +%s) - start )) s"
    WHEEL="$(ls "$ROOT"/dist/roboracer_arena-*.whl | head -n 1)"
fi
WHEEL="$(cd "$(dirname "$WHEEL")" && pwd)/$(basename "$WHEEL")"

WORK="$(mktemp -d "${TMPDIR:-/tmp}/rra-wheel-XXXXXX")"
if [[ "${KEEP_WHEEL_ENV:-0}" != 1 ]]; then trap 'rm -rf "$WORK"' EXIT; fi
case "$WORK/" in "$ROOT"/*) echo "wheel_smoke.sh: $WORK is inside the checkout" >&2; exit 1 ;; esac
EXTRAS="${WHEEL_EXTRAS:-test,video,ros2,ros2-test,render3d,ray,physx}"
step "fresh venv in $WORK, pip install $(basename "$WHEEL")[$EXTRAS]"
"$PYTHON" -m venv "$WORK/venv"
"$WORK/venv/bin/pip" install --quiet --upgrade pip
"$WORK/venv/bin/pip" install --quiet "$WHEEL[$EXTRAS]"
BIN="$WORK/venv/bin"
cd "$WORK"

step "the package is the installed one, with its data"
"$BIN/python" - <<'EOF'
import roboracer_arena, roboracer_arena.foundation.paths as p
assert "site-packages" in roboracer_arena.__file__, roboracer_arena.__file__
assert p.checkout_dir() is None, p.checkout_dir()
assert (p.tracks_dir() / "catalog.json").is_file()
print("  ", roboracer_arena.__file__)
EOF
ls "$BIN"/../lib/python*/site-packages/roboracer_arena-*.dist-info/licenses/ | sed 's/^/   licence file: /'

step "tracks list"
"$BIN/roboracer-arena" tracks list --kind circuit | tail -n 3
step "tracks show (units, no None)"
"$BIN/roboracer-arena" tracks show monaco > show.txt
if grep -q None show.txt || ! grep -Eq "^lap length +333\.[0-9]+ m$" show.txt; then
    echo "tracks show monaco should print units and no None:" >&2; cat show.txt >&2; exit 1
fi
head -n 3 show.txt | sed 's/^/   /'
step "a catalog track in gym.make (clockwise monza, and reversed)"
"$BIN/python" - <<'EOF'
import gymnasium as gym
import roboracer_arena  # noqa: F401  registers the env
env = gym.make("RoboRacerArena-v0", track="monza")
obs, info = env.reset(seed=0)
t = env.unwrapped.tracks[0]
assert t.direction == "clockwise", t.direction
env.step(env.action_space.sample())
rev = gym.make("RoboRacerArena-v0", track="monza", reverse=True).unwrapped.tracks[0]
assert rev.direction == "counterclockwise", rev.direction
print(f"   monza: {t.length:.1f} m, {t.direction}; reversed {rev.direction}; scan {obs['scan'].shape}")
EOF
step "generate"
"$BIN/roboracer-arena" generate "a 40 m lap with one hairpin in a 20 by 15 m hall, clockwise" -o gen --seed 0
step "build"
"$BIN/roboracer-arena" build gen/map.yaml -o gen/track.usdc
step "drive (the generated track runs clockwise, as requested)"
"$BIN/roboracer-arena" drive gen/map.yaml
"$BIN/python" -c "
from roboracer_arena.envs.track_argument import track_from_map_path
d = track_from_map_path('gen/map.yaml').direction
assert d == 'clockwise', d
print('   gen/map.yaml runs', d)"
step "train a policy from the wheel (tiny budget, no torch) and drive the user's map with it"
"$BIN/roboracer-arena" train --tracks gen/map.yaml --generations 2 --pairs 2 --no-eval --out policy.npz | tail -n 1
"$BIN/roboracer-arena" drive gen/map.yaml --policy policy.npz --max-time 30 || [[ $? == 5 ]]
"$BIN/python" -c "
import roboracer_arena as ra
p = ra.load_policy('policy.npz')
print('   policy.npz:', p.spec.base, p.spec.num_beams, 'beams,', p.training['generation'], 'generations')"
step "demo"
"$BIN/python" -m roboracer_arena.demo --out demo
ls demo
step "bench physics (the wheel's machine benchmark, tiny budget)"
"$BIN/roboracer-arena" bench physics --vehicles 1 4 --seconds 0.05 | tail -n 3
step "the checkout's benchmarks on the installed wheel: parser, constructors (lattice, seed 0)"
PYTHONPATH="$ROOT" "$BIN/python" -m benchmarks parser --backend rules --repeats 1 | tail -n 6
PYTHONPATH="$ROOT" "$BIN/python" -m benchmarks constructors --seeds 0 --constructors lattice --json constructors.json | tail -n 4
step "recorded maps need the sources: the message names the setting"
if ROBORACER_ARENA_SOURCES= "$BIN/roboracer-arena" drive racetracks-spa 2> err.txt; then
    echo "drive of a recorded map without the sources should fail" >&2; exit 1
fi
grep -q ROBORACER_ARENA_SOURCES err.txt && sed 's/^/   /' err.txt

step "examples/train_es.py from the wheel, outside the checkout (a short run, then without the sources)"
"$BIN/python" "$ROOT/examples/train_es.py" --generations 2 --pairs 4 --episode-steps 20 --no-lap | tail -n 1
if ROBORACER_ARENA_SOURCES= "$BIN/python" "$ROOT/examples/train_es.py" --generations 1 2> err.txt; then
    echo "train_es.py on gym-berlin without the sources should fail" >&2; exit 1
fi
if [[ $(wc -l < err.txt) != 1 ]] || ! grep -q ROBORACER_ARENA_SOURCES err.txt; then
    echo "train_es.py without the sources should say so in one line naming ROBORACER_ARENA_SOURCES:" >&2
    cat err.txt >&2; exit 1
fi
sed 's/^/   /' err.txt

step "smoke test passed"
if [[ "$RUN_PYTEST" == 1 ]]; then
    # Last, so pytest's summary line closes the output.
    step "pytest against the installed wheel"
    ROBORACER_ARENA_EXPECT_INSTALLED=1 "$BIN/python" -m pytest "$ROOT/tests" --rootdir "$ROOT" -c "$ROOT/pyproject.toml" \
        -p no:cacheprovider "${PYTEST_ARGS[@]}"
fi
