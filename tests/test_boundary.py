"""The one door between Python and the core: a Rust panic becomes a typed, one-line
``InternalError`` (an ``ArenaError``), never pyo3's ``PanicException``, and the process
(and the extension) keep working afterwards."""

from __future__ import annotations

import subprocess
import sys

import pytest

from roboracer_arena import _core
from roboracer_arena.errors import ArenaError, InternalError


@pytest.mark.parametrize("budgeted", [False, True], ids=["call", "worker-thread"])
def test_a_core_panic_is_an_internal_error_not_a_panic_exception(budgeted):
    # budgeted: the generator's time-bounded calls run on a worker thread through the
    # same door, with the same one-line message naming the entry point and location.
    with pytest.raises(InternalError) as e:
        _core._boundary_self_test(budgeted)
    assert isinstance(e.value, ArenaError)
    msg = str(e.value)
    assert "_boundary_self_test" in msg and "deliberate panic" in msg and "\n" not in msg
    assert "boundary.rs:" in msg
    assert type(e.value).__name__ != "PanicException"
    # The extension still works after the panic was caught.
    assert _core.config_defaults("constructor")


def test_the_panic_prints_nothing_to_stderr():
    code = "from roboracer_arena import _core\ntry:\n    _core._boundary_self_test()\nexcept Exception as e:\n    print(type(e).__name__)"
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, env={"PATH": "/usr/bin:/bin"}
    )
    assert out.returncode == 0 and out.stdout.strip() == "InternalError"
    assert "panicked" not in out.stderr


def test_the_cli_reports_an_internal_error_with_exit_1(monkeypatch, capsys):
    """A caught panic is a bug, not bad input: exit 1 and one line, never a traceback."""
    import roboracer_arena.cli.validate as validate_cmd
    from roboracer_arena.cli import EXIT_INTERNAL, main

    def panics(args):
        _core._boundary_self_test()

    monkeypatch.setattr(validate_cmd, "run", panics)
    assert main(["validate", "m.yaml", "--spec", "s.json"]) == EXIT_INTERNAL == 1
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "internal error" in err and "Traceback" not in err
