"""The one builder of spec sweeps: the generation requests ``(id, spec, seed)`` of a
sweep, drawn from ranges (:class:`SweepFile`, ``tracks generate --sweep``) or crossed
on a grid (:class:`GridSweep`: the shipped generated library,
:mod:`roboracer_arena.library.generated`, and the checkout's generator acceptance sweep,
``benchmarks/constructor_sweep.py``).

Sweep files for ``roboracer-arena tracks generate --sweep SWEEP.json`` hold the spec
ranges and seed scheme of a generated-track library (example: ``examples/sweep.json``).

Format (JSON object)::

    {
      "name": "hall-sweep",            # id prefix: track k is "<name>-<k:05d>"
      "base_seed": 0,                  # the whole library follows from it
      "decimals": 1,                   # float draws are rounded to this many decimals
      "ranges": {                      # TrackSpec fields drawn per request
        "lap_length_m": [40, 80],      #   [lo, hi]: uniform float, or uniform integer
        "hairpins": [0, 2],            #   (inclusive) for an integer field
        "direction": {"choice": ["clockwise", "counterclockwise"]}   # one of a list
      },
      "fixed": {"chicanes": 0}         # TrackSpec fields set for every request
    }

Seed scheme: request ``k`` (k = 0, 1, 2, ...) draws its ranged fields, in sorted field
order, from ``numpy.random.default_rng([base_seed, k])``; its generation seed is
``SeedSequence([base_seed, k, 1]).generate_state(1)[0]`` (a uint32). So request ``k``
is the same spec and the same track whatever the number of workers, the wave it ran in
or the ``--count`` asked for; a library of N tracks is the first N acceptances in ``k``
order.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from ..errors import SpecError
from ..foundation.fileio import read_json
from ..foundation.strict import format_validation_error
from ..spec import TrackSpec


class SweepRequest(NamedTuple):
    """One generation request of a sweep: the track id, its spec and its generation seed."""

    id: str
    spec: TrackSpec
    seed: int


#: The example sweep (also ``examples/sweep.json``): varied halls, lap lengths and features.
EXAMPLE_SWEEP: dict[str, Any] = {
    "name": "hall-sweep",
    "base_seed": 0,
    "decimals": 1,
    "ranges": {
        "lap_length_m": [40, 120],
        "corridor_width_m": [1.2, 2.0],
        "hall_x_m": [18, 30],
        "hall_y_m": [14, 22],
        "hairpins": [0, 2],
        "chicanes": [0, 1],
        "sweepers": [0, 1],
        "direction": {"choice": ["clockwise", "counterclockwise"]},
    },
    "fixed": {},
}


#: Most corners of a sweep's ranges checked at load (fields x bounds x choices).
MAX_CORNERS = 1 << 14


class Choice(BaseModel):
    """``{"choice": [...]}``: one of the listed values, uniformly."""

    model_config = ConfigDict(extra="forbid")
    choice: list[Any] = Field(min_length=1)


def _is_int_field(name: str) -> bool:
    return TrackSpec.model_fields[name].annotation is int


class SweepFile(BaseModel):
    """A parsed, checked sweep file (see the module docstring for the format)."""

    model_config = ConfigDict(extra="forbid", frozen=True)
    name: str = Field("sweep", min_length=1, max_length=60, pattern=r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")
    base_seed: int = Field(0, ge=0)
    decimals: int = Field(1, ge=0, le=6)
    ranges: dict[str, tuple[float, float] | Choice] = Field(default_factory=dict)
    fixed: dict[str, Any] = Field(default_factory=dict)

    @model_validator(mode="after")
    def _fields_exist(self) -> SweepFile:
        fields = set(TrackSpec.model_fields) - {"name"}
        for where, keys in (("ranges", self.ranges), ("fixed", self.fixed)):
            bad = sorted(set(keys) - fields)
            if bad:
                raise ValueError(
                    f"{where}: unknown TrackSpec field(s) {', '.join(bad)}; known: {', '.join(sorted(fields))}"
                )
        both = sorted(set(self.ranges) & set(self.fixed))
        if both:
            raise ValueError(f"field(s) {', '.join(both)} are in both ranges and fixed")
        for k, r in self.ranges.items():
            if isinstance(r, tuple):
                if not all(math.isfinite(v) for v in r):
                    raise ValueError(f"ranges.{k}: bounds must be finite numbers, got [{r[0]}, {r[1]}]")
                if r[0] > r[1]:
                    raise ValueError(f"ranges.{k}: lower bound {r[0]:g} is above upper bound {r[1]:g}")
                if _is_int_field(k) and (r[0] != int(r[0]) or r[1] != int(r[1])):
                    raise ValueError(f"ranges.{k}: an integer field takes integer bounds, got [{r[0]:g}, {r[1]:g}]")
        self._check_every_draw()
        return self

    def _check_every_draw(self) -> None:
        """Whole-range validation at load: every request the ranges can draw must be a valid
        TrackSpec, not only request 0. TrackSpec's limits are per-field bounds and count
        equalities, so it is enough to try every corner of the ranges (each float bound
        rounded to ``decimals`` as draws are; every listed choice)."""
        names = sorted(self.ranges)
        options: list[list[Any]] = []
        for name in names:
            r = self.ranges[name]
            if isinstance(r, Choice):
                options.append(list(r.choice))
            elif _is_int_field(name):
                options.append(sorted({int(r[0]), int(r[1])}))
            else:
                options.append(sorted({round(float(r[0]), self.decimals), round(float(r[1]), self.decimals)}))
        corners = math.prod(len(o) for o in options)
        if corners > MAX_CORNERS:
            raise ValueError(
                f"ranges: {corners} combinations of bounds and choices, more than the {MAX_CORNERS} checked"
            )
        for combo in itertools.product(*options):
            drawn = dict(zip(names, combo))
            try:
                TrackSpec(name=self.track_id(0), **{**self.fixed, **drawn})
            except ValidationError as e:
                what = ", ".join(f"{k}={v!r}" for k, v in drawn.items()) or "the fixed fields"
                raise ValueError(
                    f"a request can draw {what}, which is not a valid spec: {format_validation_error(e)}"
                ) from None

    def draw(self, k: int) -> dict[str, Any]:
        """The ranged field values of request ``k``."""
        rng = np.random.default_rng([self.base_seed, k])
        out: dict[str, Any] = {}
        for name in sorted(self.ranges):
            r = self.ranges[name]
            if isinstance(r, Choice):
                out[name] = r.choice[int(rng.integers(len(r.choice)))]
            elif _is_int_field(name):
                out[name] = int(rng.integers(int(r[0]), int(r[1]) + 1))
            else:
                out[name] = round(float(rng.uniform(r[0], r[1])), self.decimals)
        return out

    def track_id(self, k: int) -> str:
        return f"{self.name}-{k:05d}"

    def seed(self, k: int) -> int:
        """Generation seed of request ``k``."""
        return int(np.random.SeedSequence([self.base_seed, k, 1]).generate_state(1)[0])

    def spec(self, k: int) -> TrackSpec:
        return TrackSpec(name=self.track_id(k), **{**self.fixed, **self.draw(k)})

    def requests(self, start: int, stop: int) -> list[SweepRequest]:
        """The requests ``start .. stop - 1``."""
        return [SweepRequest(self.track_id(k), self.spec(k), self.seed(k)) for k in range(start, stop)]


@dataclass(frozen=True)
class GridSweep:
    """Every combination of ``axes`` (the last axis varies fastest). Each axis is a list of
    points; a point is some TrackSpec fields, and may hold ``"seed"``, the request's
    generation seed. A combination's points are merged in axis order, then:

    * ``directions``: when given, grid combination ``i`` (counted before ``admit``) runs in
      ``directions[i % len(directions)]``;
    * ``name(fields)`` names the request (its id and its spec's name) from the merged fields;
    * ``admit(spec)``: only the specs it accepts are kept (e.g. the admissibility screen);
    * ``count``: the kept requests thinned evenly to at most ``count``;
    * a request without a ``"seed"`` gets ``k % seed_cycle``, ``k`` its place after thinning.

    The list is a pure function of these fields: the same sweep always gives the same
    requests in the same order."""

    axes: Sequence[Sequence[Mapping[str, Any]]]
    name: Callable[[Mapping[str, Any]], str]
    directions: Sequence[str] = ()
    admit: Callable[[TrackSpec], bool] | None = None
    count: int | None = None
    seed_cycle: int = 1

    def requests(self) -> list[SweepRequest]:
        """The sweep's requests, in grid order."""
        grid: list[tuple[str, TrackSpec, int | None]] = []
        for i, points in enumerate(itertools.product(*self.axes)):
            fields: dict[str, Any] = {}
            for point in points:
                fields.update(point)
            if self.directions:
                fields["direction"] = self.directions[i % len(self.directions)]
            tid = self.name(fields)
            seed = fields.pop("seed", None)
            spec = TrackSpec(name=tid, **fields)
            if self.admit is None or self.admit(spec):
                grid.append((tid, spec, seed))
        if self.count is not None:
            step = max(1.0, len(grid) / self.count)
            grid = [grid[int(k * step)] for k in range(min(self.count, len(grid)))]
        return [
            SweepRequest(tid, spec, k % self.seed_cycle if seed is None else seed)
            for k, (tid, spec, seed) in enumerate(grid)
        ]


def load_sweep(path: str | Path) -> SweepFile:
    """Read and check a sweep file; errors name the file and the field."""
    p = Path(path)
    doc = read_json(p, "sweep file", SpecError)
    try:
        return SweepFile.model_validate(doc)
    except ValidationError as e:
        raise SpecError(f"{p}: {format_validation_error(e, top='(top level)')}") from None
    except SpecError as e:
        raise SpecError(f"{p}: {e}") from None
