"""Issue 38, class D: ``physx-check --json`` prints only JSON on stdout. What the native
engine writes to file descriptor 1 while it runs (PhysX's "GPU broadphase requires a CUDA
context manager" on a CPU-only machine) is routed to stderr at the descriptor level
(``os.dup2``), C stdio buffers included, and fd 1 points at stderr after the JSON so the
engine's teardown cannot follow it."""

from __future__ import annotations

import json
import subprocess
import sys

CHILD = r"""
import ctypes, json, os, sys
from roboracer_arena.physx.runtime import native_stdout_to_stderr
libc = ctypes.CDLL(None)
print("python before", flush=True)
with native_stdout_to_stderr():
    os.write(1, b"native write\n")                      # straight to fd 1
    libc.printf(b"GPU broadphase requires a CUDA context manager\n")   # C stdio, buffered on a pipe
    with native_stdout_to_stderr():                     # re-entrant
        libc.puts(b"nested native")
print(json.dumps({"ok": True}), flush=True)
"""


def test_native_prints_inside_the_block_go_to_stderr():
    r = subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == ["python before", '{"ok": true}'], r.stdout
    for text in ("native write", "GPU broadphase requires a CUDA context manager", "nested native"):
        assert text in r.stderr, r.stderr


def test_physx_check_json_after_the_json_fd1_is_stderr(tmp_path):
    """The CLI's last step: after the JSON, fd 1 goes to stderr (what the engine prints at
    exit lands there); simulated with a native print after ``run`` returns."""
    code = (
        "import ctypes, json, sys\n"
        "from roboracer_arena.cli import physx_check\n"
        "print(json.dumps({'ok': True}))\n"
        "physx_check._stdout_done()\n"
        "ctypes.CDLL(None).printf(b'teardown chatter\\n')\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout) == {"ok": True} and "teardown chatter" in r.stderr
