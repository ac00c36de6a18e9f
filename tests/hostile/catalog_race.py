"""Race two ``tracks verify --update-catalog`` runs on one library, many rounds.

``python catalog_race.py CATALOG ID_A ID_B ROUNDS SEED [MAX_DELAY_S]``: each round
restores CATALOG, forks two processes that each sleep a random 0..MAX_DELAY_S (seeded)
and then run ``roboracer-arena tracks verify --update-catalog`` on one of the ids (in a
random order), waits for both, and records whether each id's verdict landed. Prints one
JSON line: ``{"rounds": N, "exit_codes": [...], "lost": [[round, id], ...], "seconds": S}``.

The checks of this tiny library take a few milliseconds, far less than a real verify;
so that the runs overlap between reading and writing the catalog as real ones do, each
child's verify work is stretched by another random 0..MAX_DELAY_S (a sleep after the
real checks, before the write).

The heavy imports happen once, here, before any fork; this process never runs core work
itself, so the children start with no worker-thread pool to inherit half-made (a fork
of a process whose rayon pool is running would hang).
"""

from __future__ import annotations

import json
import os
import random
import sys
import time
from pathlib import Path

import roboracer_arena.library.open_maps  # (imported before forking: fast children)
import roboracer_arena.library.verify
from roboracer_arena.cli import main, make_parser

make_parser()  # every sub-command imported once, before the forks

CHECKS = ["--no-usd", "--no-drive", "--no-physx", "--jobs", "1"]


def _child(catalog: str, track_id: str, delay: float, work: float) -> None:
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)
    real = roboracer_arena.library.verify.verify

    def slow_verify(*args, **kwargs):  # a verify as long as a real one, of random length
        summary = real(*args, **kwargs)
        time.sleep(work)
        return summary

    roboracer_arena.library.verify.verify = slow_verify
    time.sleep(delay)
    try:
        code = main(["tracks", "verify", "--catalog", catalog, "--update-catalog", "--ids", track_id, *CHECKS])
    except BaseException:
        code = 99
    os._exit(code)


def race(catalog: Path, ids: list[str], rounds: int, seed: int, max_delay: float) -> dict:
    pristine = catalog.read_bytes()
    rng = random.Random(seed)
    codes: list[int] = []
    lost: list[tuple[int, str]] = []
    t0 = time.perf_counter()
    for k in range(rounds):
        catalog.write_bytes(pristine)
        pids = []
        for track_id in rng.sample(ids, len(ids)):
            delay, work = rng.uniform(0.0, max_delay), rng.uniform(0.0, max_delay)
            pid = os.fork()
            if pid == 0:
                _child(str(catalog), track_id, delay, work)
            pids.append(pid)
        for pid in pids:
            _, status = os.waitpid(pid, 0)
            codes.append(os.waitstatus_to_exitcode(status))
        doc = json.loads(catalog.read_text(encoding="utf-8"))
        verified = {t["id"]: t.get("verified") for t in doc["tracks"]}
        lost += [(k, i) for i in ids if not verified.get(i)]
    return {"rounds": rounds, "exit_codes": codes, "lost": lost, "seconds": time.perf_counter() - t0}


if __name__ == "__main__":
    cat, a, b, n, seed = sys.argv[1:6]
    delay = float(sys.argv[6]) if len(sys.argv) > 6 else 0.1
    print(json.dumps(race(Path(cat), [a, b], int(n), int(seed), delay)))
