"""Runs hostile cases in a worker subprocess under a memory cap and a time limit, and
checks every result: an allowed exit code, no traceback, no panic text, nothing left
behind on failure."""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
from pathlib import Path

#: Address-space cap of the worker: the interpreter, numpy, usd-core and rayon start well
#: below it, and an allocation bomb that slips through dies here instead of the machine.
MEMORY_CAP_BYTES = 3 << 30
WORKER = Path(__file__).with_name("worker.py")
#: A caught panic is reported as ``InternalError`` ("internal error on this input"): the
#: boundary keeps the process alive, but for the fuzz suite it is still a bug.
PANIC_TEXT = ("panicked", "PanicException", "Traceback", "internal error", "InternalError")


def _cap_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP_BYTES, MEMORY_CAP_BYTES))


def run_cases(cases: list[dict], timeout_s: float = 240.0) -> dict[str, dict]:
    """Results by case id. A worker that dies or overruns fails with the case it was on."""
    # Few threads, so the address space the cap measures does not grow with the CI's cores.
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "RAYON_NUM_THREADS": "2", "PXR_WORK_THREAD_LIMIT": "2"}
    proc = subprocess.run(
        [sys.executable, str(WORKER)],
        input=json.dumps(cases),
        capture_output=True,
        text=True,
        timeout=timeout_s,
        preexec_fn=_cap_memory,
        env=env,
    )
    results, current = {}, None
    for line in proc.stdout.splitlines():
        if line.startswith("START "):
            current = line[6:]
        elif line.startswith("{"):
            r = json.loads(line)
            results[r["id"]] = r
            current = None
    if proc.returncode != 0 or current is not None:
        raise AssertionError(f"worker died (exit {proc.returncode}) on case {current!r}: {proc.stderr[-1500:]}")
    # Whatever reached the process's own stderr (Rust writes there directly) must be clean too.
    leaked = [t for t in PANIC_TEXT if t in proc.stderr]
    assert not leaked, f"panic text on the worker's stderr: {proc.stderr[-1500:]}"
    return results


def problems(case: dict, r: dict) -> list[str]:
    """What is wrong with result ``r`` of ``case`` (empty when it passed)."""
    out = []
    allowed = set(case.get("codes", [0, 2, 3, 4]))
    if r["exc"]:
        out.append(f"exception escaped: {r['exc']}")
    if r["code"] not in allowed:
        out.append(f"exit {r['code']} not in {sorted(allowed)}; stderr: {r['err'][-400:]}")
    if any(t in r["err"] for t in PANIC_TEXT):
        out.append(f"panic/traceback text on stderr: {r['err'][-400:]}")
    if r["code"] != 0:
        stray = [p for p in r["left"] if p == case.get("target") or ".arena-" in p or p.startswith("textures")]
        if stray:
            out.append(f"left behind after a failure: {stray}")
    if case.get("one_line") and r["code"] == 2 and r["err"].strip().count("\n") > 0:
        out.append(f"error is not one line: {r['err']!r}")
    for needle in case.get("says", []):
        if needle not in r["err"]:
            out.append(f"stderr lacks {needle!r}: {r['err'][-400:]}")
    return out


def check_all(cases: list[dict], timeout_s: float = 240.0) -> None:
    results = run_cases(cases, timeout_s)
    bad = {c["id"]: problems(c, results[c["id"]]) for c in cases}
    bad = {k: v for k, v in bad.items() if v}
    assert not bad, json.dumps(bad, indent=1)[:6000]
