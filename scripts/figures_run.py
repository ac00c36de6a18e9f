"""Running one documented figure's command and recording where it ran (used by
``scripts/docs_figures.py``): the command's JSON wrapped with the build, the machine, the
UTC time and the 1-minute load average sampled while it ran, so a doc block can say what
it was measured on."""

from __future__ import annotations

import json
import os
import platform
import resource
import shlex
import subprocess
import sys
import tempfile
import threading
import time
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
SOURCES = ("crates", "python", "Cargo.toml", "Cargo.lock", "pyproject.toml")


def _git(*args: str) -> str:
    try:
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def build_info(profile: str) -> dict[str, Any]:
    """The package version, the last commit that changed the package's sources (``+`` when
    they have uncommitted changes) and the build profile the caller states (``make
    docs-figures`` builds ``release``)."""
    from importlib.metadata import version

    # The last commit that changed what the build is made of (docs and scripts commits do not).
    commit = _git("log", "-1", "--format=%h", "--", *SOURCES)
    dirty = bool(_git("status", "--porcelain", "--untracked-files=no", "--", *SOURCES))
    return {"version": version("roboracer-arena"), "commit": commit + ("+" if dirty else ""), "profile": profile}


def machine_info() -> dict[str, Any]:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30 if hasattr(os, "sysconf") else 0.0
    return {"cpu": cpu, "cores": os.cpu_count(), "memory_gib": round(mem), "python": platform.python_version()}


class LoadSampler:
    """The 1-minute load average every ``every`` seconds while a command runs."""

    def __init__(self, every: float = 5.0) -> None:
        self.every, self.samples = every, [os.getloadavg()[0]]
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, daemon=True)

    def _loop(self) -> None:
        while not self._stop.wait(self.every):
            self.samples.append(os.getloadavg()[0])

    def __enter__(self) -> LoadSampler:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()
        self.samples.append(os.getloadavg()[0])

    def summary(self) -> dict[str, float]:
        s = self.samples
        return {"min": round(min(s), 1), "mean": round(sum(s) / len(s), 1), "max": round(max(s), 1)}


def measured(command: str, profile: str, body: Any) -> dict[str, Any]:
    """Run ``body()`` and return ``{"command", "measured": {...}, "result": body()}``."""
    utc = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")

    def cpu() -> float:  # this process and the commands it ran
        kids = resource.getrusage(resource.RUSAGE_CHILDREN)
        return time.process_time() + kids.ru_utime + kids.ru_stime

    t0, c0 = time.perf_counter(), cpu()
    with LoadSampler() as load:
        result = body()
    return {
        "command": command,
        "measured": {
            "utc": utc,
            "build": build_info(profile),
            "machine": machine_info(),
            "load_average": load.summary(),
            "wall_seconds": round(time.perf_counter() - t0, 1),
            "cpu_seconds": round(cpu() - c0, 1),
        },
        "result": result,
    }


def cli_path() -> str:
    """The ``roboracer-arena`` of the running interpreter's environment."""
    exe = Path(sys.executable).with_name("roboracer-arena")
    return str(exe) if exe.exists() else "roboracer-arena"


def command_argv(args: list[str]) -> list[str]:
    """``bench KIND ...`` is the checkout's benchmarks (``python -m benchmarks KIND ...``,
    not in the wheel); anything else is the ``roboracer-arena`` CLI."""
    if args[:1] == ["bench"]:
        return [sys.executable, "-m", "benchmarks", *args[1:]]
    return [cli_path(), *args]


def run_cli_json(args: list[str], log: Path | None = None) -> dict[str, Any]:
    """The command of ``ARGS --json TMP`` (:func:`command_argv`); the JSON it wrote. Its
    stdout goes to ``log`` (or is dropped); a failure raises with the command's last lines."""
    with tempfile.TemporaryDirectory(prefix="docs-figures-") as tmp:
        out = Path(tmp) / "result.json"
        argv = [*command_argv(args), "--json", str(out)]
        path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p)
        proc = subprocess.run(argv, cwd=tmp, capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=path))
        if log is not None:
            log.parent.mkdir(parents=True, exist_ok=True)
            log.write_text(proc.stdout + proc.stderr)
        if proc.returncode != 0:
            tail = "\n".join((proc.stdout + proc.stderr).strip().splitlines()[-5:])
            raise RuntimeError(f"{shlex.join(argv)} exited {proc.returncode}:\n{tail}")
        return dict(json.loads(out.read_text()))


def command_text(args: list[str]) -> str:
    if args[:1] == ["bench"]:
        return shlex.join(["python", "-m", "benchmarks", *args[1:], "--json", "FILE"])
    return shlex.join(["roboracer-arena", *args, "--json", "FILE"])


def header(doc: dict[str, Any], name: str, what: str = "", timed: bool = True) -> str:
    """The first line of a generated block: the command, the build, the machine and its load
    (and, for a block with timings measured under a load above the core count, a warning)."""
    m = doc["measured"]
    b, mach, load = m["build"], m["machine"], m["load_average"]
    loadtxt = (
        f"load average {load['mean']:.1f}"
        if load["max"] - load["min"] < 0.5
        else f"load average {load['min']:.1f}–{load['max']:.1f} (mean {load['mean']:.1f})"
    )
    return (
        f"*Generated by `make docs-figures` (`scripts/docs_figures.py --only {name}`, data "
        f"`{what or f'docs/figures/{name}.json'}`): `{doc['command']}`, run {m['utc']} on the "
        f"{b['profile']} build of {b['version']} at `{b['commit']}`, {mach['cpu']} ({mach['cores']} cores, "
        f"{mach['memory_gib']} GiB), {loadtxt} while it ran, {m['wall_seconds']:.0f} s wall, {m['cpu_seconds']:.0f} s CPU.*"
        + (
            " **Measured under a load above the core count: wall-clock figures show the CPU share the command got,"
            " not the code; rerun `make docs-figures` on a quiet machine.**\n"
            if timed and mach["cores"] and load["mean"] > mach["cores"]
            else "\n"
        )
    )
