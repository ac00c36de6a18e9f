"""The catalog raceline job ends on SIGTERM within a moment, keeping the tracks it
finished (the index is whole JSON) and leaving no temporary behind."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time

import pytest

CODE = """
import sys
from pathlib import Path
from roboracer_arena.cli._common import raise_interrupt_on_sigterm
from roboracer_arena.library.racelines import build_racelines
raise_interrupt_on_sigterm()
try:
    build_racelines(sys.argv[2:], path=Path(sys.argv[1]), progress=lambda r: print('done', r.id, flush=True))
except KeyboardInterrupt:
    sys.exit(130)
"""


@pytest.mark.slow
def test_sigterm_keeps_finished_tracks(tmp_path):
    index = tmp_path / "racelines.json"
    ids = ["gen-l040-w12-h2c1s1-clo-s0", "gym-berlin", "gym-vegas", "monaco"]
    p = subprocess.Popen([sys.executable, "-c", CODE, str(index), *ids], stdout=subprocess.PIPE, text=True)
    assert p.stdout is not None
    assert p.stdout.readline().startswith("done gen-l040")  # one track finished
    p.send_signal(signal.SIGTERM)
    t0 = time.monotonic()
    p.wait(timeout=30)
    assert p.returncode == 130 and time.monotonic() - t0 < 10
    records = json.loads(index.read_text())["records"]
    assert records[0]["id"] == ids[0] and len(records) < len(ids)
    assert not [f for f in tmp_path.iterdir() if f.name.startswith(".")]
