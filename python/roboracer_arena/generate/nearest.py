"""Nearest specs that build, after a generation failure (issue 28).

The core (``arena_core::generate::nearest``) changes one field at a time -- the lap, the
hall (same aspect), the corridor width, the feature count -- and runs Algorithm 1 on each
changed spec, nearest first, within its own time budget; per field it keeps the first
spec that builds and the seed that built it. Running that spec with that seed builds it
again (candidate ``k`` never depends on the candidate cap or on earlier candidates).

These are constructions found, not proofs: a spec nearer to the request may build with
another seed, and a field without a suggestion may still have one beyond the search's
steps or budget.
"""

from __future__ import annotations

import time
from typing import Literal

from pydantic import BaseModel, ConfigDict

from .. import _core
from ..config.constructor import ConstructorConfig
from ..errors import InternalError
from ..spec import TrackSpec

DEFAULT_SUGGEST_TIMEOUT_S = 20.0
"""Default wall-clock budget of the nearest-spec search (seconds)."""

DISCLAIMER = "constructions found by a bounded search, not proofs that nothing nearer builds"

Field = Literal["lap_length_m", "hall", "corridor_width_m", "features"]
_CHANGED = {
    "lap_length_m": ("lap_length_m",),
    "hall": ("hall_x_m", "hall_y_m"),
    "corridor_width_m": ("corridor_width_m",),
    "features": ("hairpins", "chicanes", "sweepers", "feature_order"),
}


class Suggestion(BaseModel):
    """One changed spec that built: the direction searched (``field``), the spec, the
    seed and candidate index that built it, and the changed fields with their values."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    field: Field
    spec: TrackSpec
    seed: int
    candidate_index: int
    changes: dict[str, float | int | list[str]]

    def text(self) -> str:
        """``lap_length_m = 48 (built with seed 2)``: the changed fields, as a spec file
        names them, and the seed to give ``generate --seed``."""
        parts = [f"{k} = {_show(v)}" for k, v in self.changes.items()]
        return f"{', '.join(parts)} (built with seed {self.seed})"


class NearestSpecs(BaseModel):
    """What the search found, how many changed specs it tried, and whether its budget
    ran out before every probe was tried."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    suggestions: tuple[Suggestion, ...]
    probes: int
    exhausted: bool
    seconds: float

    def lines(self) -> list[str]:
        """The CLI's lines: one ``try:`` per suggestion and what they are (or why none)."""
        if not self.suggestions:
            why = "its time budget ran out" if self.exhausted else "none of its probes built"
            return [f"no nearby spec found ({self.probes} changed spec(s) tried; {why})"]
        return [f"try: {s.text()}" for s in self.suggestions] + [f"({DISCLAIMER})"]


def _show(v: object) -> str:
    if isinstance(v, float):
        return f"{v:g}"
    if isinstance(v, list):
        return "[" + ", ".join(str(x) for x in v) + "]"
    return str(v)


def nearest_specs(
    spec: TrackSpec,
    seed: int = 0,
    config: ConstructorConfig | None = None,
    timeout: float = DEFAULT_SUGGEST_TIMEOUT_S,
) -> NearestSpecs:
    """Search the nearest specs that build (see the module doc); ``timeout`` seconds bound
    the search, which then reports what it found so far."""
    cfg = config or ConstructorConfig()
    t0 = time.perf_counter()
    raw = _core.nearest_specs(spec, cfg, seed, timeout)
    found = []
    for s in raw.suggestions:
        new = TrackSpec.model_validate({**s.spec, "name": spec.name})
        field = s.field
        if field not in _CHANGED:
            raise InternalError(f"nearest_specs: unknown field {field!r} from the core")
        changes = {k: getattr(new, k) for k in _CHANGED[field] if getattr(new, k) != getattr(spec, k)}
        found.append(Suggestion(field=field, spec=new, seed=s.seed, candidate_index=s.candidate_index, changes=changes))
    return NearestSpecs(
        suggestions=tuple(found),
        probes=raw.probes,
        exhausted=raw.exhausted,
        seconds=time.perf_counter() - t0,
    )
