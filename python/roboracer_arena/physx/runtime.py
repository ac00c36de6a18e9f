"""A USD stage loaded into PhysX (ovphysx, CPU): single-sided raycasts, stepping,
rigid-body reads and writes. The one place that talks to ovphysx/ovstage.

ovphysx consumes a USD file through ovstage population; the PhysX schemas of
``physx-usd-schemas`` must be registered with ovstage before the first population of
the process (:func:`_register_schemas`).
"""

from __future__ import annotations

import ctypes
import os
import sys
import threading
import time
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from types import TracebackType
from typing import Any

import numpy as np

from ..errors import ConfigError, MapIOError
from ..foundation.fileio import require_regular

EXTRA_HINT = "pip install 'roboracer-arena[physx]' (ovphysx + physx-usd-schemas, CPU PhysX, ~1.3 GB)"
_REGISTERED: dict[str, bool] = {}


def _quiet_warp() -> None:
    """Keep Warp (an ovphysx dependency) off stdout: its start-up banner would corrupt
    ``--json`` output. Its note that a CUDA build of Warp opens the (absent) CUDA driver in
    CPU-only mode is harmless here and is not repeated to every user."""
    warnings.filterwarnings("ignore", message="ovphysx is in CPU-only mode", category=RuntimeWarning)
    try:
        import warp
    except ImportError:
        return
    warp.config.log_level = max(warp.config.log_level, getattr(warp, "LOG_WARNING", 30))


_REDIRECT = threading.Lock()
_DEPTH = [0]


def _flush_c_stdio() -> None:
    """Flush the C library's stdio buffers (the engine's ``printf`` output waits there)."""
    try:
        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):
        pass


@contextmanager
def native_stdout_to_stderr() -> Iterator[None]:
    """Point file descriptor 1 at stderr for the block (``os.dup2``), so whatever native
    code prints to stdout meanwhile (PhysX's "GPU broadphase requires a CUDA context
    manager" on a CPU-only machine, Warp's banner) lands on stderr: ``--json`` output
    stays the only text on stdout. Python's own ``sys.stdout`` is flushed first and the C
    library's buffers before fd 1 is restored. Re-entrant; a no-op when stdout or stderr
    has no file descriptor (e.g. under a test's capture)."""
    try:
        out_fd, err_fd = sys.__stdout__.fileno(), sys.__stderr__.fileno()  # type: ignore[union-attr]
    except (AttributeError, ValueError, OSError):
        yield
        return
    with _REDIRECT:
        _DEPTH[0] += 1
        first = _DEPTH[0] == 1
        if first:
            sys.stdout.flush()
            _flush_c_stdio()
            saved = os.dup(out_fd)
            os.dup2(err_fd, out_fd)
    try:
        yield
    finally:
        with _REDIRECT:
            _DEPTH[0] -= 1
            if first:
                _flush_c_stdio()
                os.dup2(saved, out_fd)
                os.close(saved)


def require() -> tuple[Any, Any]:
    """``(ovphysx, ovstage)``, or :class:`ConfigError` naming the extra to install."""
    _quiet_warp()
    try:
        import ovphysx
        import ovstage
        from ovphysx.samples.python_samples.schema_support import physx_schema_paths  # noqa: F401
    except ImportError as e:
        raise ConfigError(f"the PhysX check needs the 'physx' extra: {EXTRA_HINT} ({e.name or e} is missing)") from e
    try:
        import physx_usd_schemas  # noqa: F401
    except ImportError as e:
        raise ConfigError(
            f"the PhysX check needs the 'physx' extra: {EXTRA_HINT} (physx-usd-schemas is missing)"
        ) from e
    return ovphysx, ovstage


def available() -> bool:
    """True when ovphysx, ovstage and physx-usd-schemas import."""
    try:
        require()
    except ConfigError:
        return False
    return True


def _register_schemas(ovstage: Any) -> None:
    if _REGISTERED.get("ovstage"):
        return
    from ovphysx.samples.python_samples.schema_support import physx_schema_paths

    ovstage.population.register_usd_schemas([str(p) for p in physx_schema_paths()])
    _REGISTERED["ovstage"] = True


def _configure_process(ovphysx: Any) -> None:
    """CPU-only PhysX, simulated on the calling thread (``NUM_THREADS = 0``): on a small
    shared machine the worker pool's hand-offs cost far more than they save (measured on
    2 busy cores: 54 steps/s with the default pool, 1,278 steps/s inline, the berlin stage
    with the car). Process-wide, so set once before the first instance."""
    if _REGISTERED.get("process"):
        return
    from ovphysx.types import GlobalConfigKey

    ovphysx.set_global_config(GlobalConfigKey.CPU_ONLY, True)
    ovphysx.set_global_config(GlobalConfigKey.NUM_THREADS, 0)
    _REGISTERED["process"] = True


class PhysxScene:
    """A stage file simulated by PhysX on the CPU. Use as a context manager.

    ``load_seconds`` is the wall time from population to an attached scene.
    """

    def __init__(self, usd_path: str | Path) -> None:
        ovphysx, ovstage = require()
        path = Path(usd_path)
        require_regular(path, "USD stage")  # a directory, a FIFO or a symlink loop is named as such
        _register_schemas(ovstage)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # ovphysx's deprecation notes on scene queries
            _configure_process(ovphysx)
            t0 = time.perf_counter()
            self._physx = ovphysx.PhysX()
            self._stage = ovstage.Stage(f"roboracer-arena-{id(self)}")
            try:
                ovstage.population.open_usd(self._stage, str(path), ordinal=1, domains=ovstage.PopulationDomain.ALL)
                self._stage.advance_write_floor(ordinal=1).wait()
                self._physx.wait_task(self._physx.attach_ovstage(self._stage, read_ordinal=1))
            except Exception as e:
                self.close()
                raise MapIOError(f"{path}: PhysX could not load the stage: {e}") from e
            self.load_seconds = time.perf_counter() - t0

    @property
    def physx(self) -> Any:
        """The ``ovphysx.PhysX`` instance simulating the stage (for scene queries)."""
        return self._physx

    def __enter__(self) -> PhysxScene:
        return self

    def __exit__(self, et: type[BaseException] | None, ev: BaseException | None, tb: TracebackType | None) -> None:
        self.close()

    def close(self) -> None:
        """Detach and destroy (idempotent)."""
        physx, stage = getattr(self, "_physx", None), getattr(self, "_stage", None)
        self._physx = self._stage = None
        try:
            if physx is not None and stage is not None and physx.is_stage_attached(stage):
                physx.wait_task(physx.detach_ovstage())
        finally:
            if physx is not None:
                physx.destroy()
            if stage is not None:
                stage.destroy()

    def raycast(
        self, origin: Any, direction: Any, max_distance: float, both_sides: bool = False, ignore: str | None = None
    ) -> float:
        """Distance to the closest hit (``inf`` for none); single-sided as a PhysX lidar
        casts. ``ignore``: a prim path whose shapes (and their descendants') the ray passes
        through, e.g. the car carrying the sensor."""
        from ovphysx.types import SceneQueryMode

        o, d = [float(v) for v in origin], [float(v) for v in direction]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if ignore is None:
                hits = self._physx.raycast(o, d, float(max_distance), both_sides=both_sides)
            else:
                hits = self._physx.raycast(o, d, float(max_distance), mode=SceneQueryMode.ALL, both_sides=both_sides)
                hits = [h for h in hits if not self._path_of(h["collision"]).startswith(ignore)]
        return min((float(h["distance"]) for h in hits), default=float("inf"))

    def _path_of(self, collision_id: int) -> str:
        cache: dict[int, str] = self.__dict__.setdefault("_paths", {})
        if collision_id not in cache:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                cache[collision_id] = str(self._physx.get_scene_query_paths_from_ids([collision_id])[0])
        return cache[collision_id]

    def step(self, dt: float, n: int = 1) -> None:
        """``n`` synchronous steps of ``dt`` seconds."""
        for _ in range(n):
            self._physx.step_sync(float(dt))

    def read_bodies(self, attributes: list[str]) -> dict[str, dict[str, np.ndarray]]:
        """``{prim path: {attribute: values}}`` of every rigid body (host copies; the
        borrowed arrays are dropped before returning, as ovphysx's teardown requires)."""
        from ovphysx.types import ObjectScope, SimObjectType

        out: dict[str, dict[str, np.ndarray]] = {}
        with self._physx.read_sync(SimObjectType.RIGID_BODY, attributes, scope=ObjectScope.ALL) as result:
            paths = result.dictionary
            for g in result.groups:
                name = paths.token_to_string(g.attribute)
                prims = paths.get_path_strings(g.prim_list)[g.prim_offset : g.prim_offset + g.prim_count]
                for tensor in g.tensors:
                    arr = tensor.numpy().copy()
                    for k, prim in enumerate(prims):
                        out.setdefault(str(prim), {})[name] = arr[k]
                del tensor, g
            del result
        self._physx.wait_all()
        return out

    def write_bodies(self, attribute: str, values: dict[str, Any]) -> None:
        """Set one rigid-body attribute (e.g. ``linearVelocity``) of every body; ``values``
        maps each body's prim path to its new value (every body must be named)."""
        from ovphysx.types import SimObjectType

        with self._physx.query(SimObjectType.RIGID_BODY).wait() as query:
            paths = query.dictionary
            with self._physx.write(query, [attribute]).wait() as w:
                while (g := w.fetch_next().wait()) is not None:
                    prims = [str(p) for p in paths.get_path_strings(g.prim_list)]
                    prims = prims[g.prim_offset : g.prim_offset + g.prim_count]
                    for tensor in g.tensors:
                        buf = np.array([values[p] for p in prims], dtype=np.float32).reshape(tuple(tensor.shape))
                        tensor.assign(buf)
                    w.commit(g).wait()
        self._physx.wait_all()
