"""Vehicle limits for a speed profile, as TUM's and ForzaETH's planners take them: a top
speed ``v_max``, a ggv table (speed -> largest longitudinal and lateral acceleration the
tyres give) and a motor curve ``ax_max_machines`` (speed -> largest forward acceleration
the drivetrain gives). ``dyn_model_exp`` shapes how the two tyre limits combine: 1 a
diamond (TUM's default), 2 the friction ellipse.

Limits come from a preset (:data:`PRESETS`: ``car`` -- measured from this project's
simulator, ``f1tenth-racetracks``, ``forzaeth``), a JSON or YAML file
(:func:`load_limits`), or a preset with some numbers replaced (:meth:`VehicleLimits.with_overrides`).
A bad file is a :class:`~roboracer_arena.errors.ConfigError` naming the file and the field.
"""

from __future__ import annotations

import hashlib
import json
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import Field, ValidationError, field_validator

from ..errors import ConfigError
from ..foundation.fileio import parse_json, read_text
from ..foundation.frozen_model import FrozenModel

#: Names of the shipped presets (``raceline/presets/<name>.json``).
PRESETS: tuple[str, ...] = ("car", "f1tenth-racetracks", "forzaeth")


class VehicleLimits(FrozenModel):
    """The limits a speed profile obeys (SI units; speeds in m/s, accelerations in m/s^2)."""

    name: str = Field("custom", max_length=200, description="What these limits are (a preset name or a file).")
    v_max: float = Field(gt=0, le=100, allow_inf_nan=False, description="Top speed (m/s).")
    ggv: list[tuple[float, float, float]] = Field(
        min_length=1,
        max_length=1000,
        description="Rows (v, ax_max, ay_max): tyre limits by speed, v strictly increasing; held flat outside.",
    )
    ax_max_machines: list[tuple[float, float]] = Field(
        min_length=1,
        max_length=1000,
        description="Rows (v, ax): largest forward acceleration of the drivetrain by speed, v increasing.",
    )
    dyn_model_exp: float = Field(
        1.0, ge=1.0, le=2.0, allow_inf_nan=False, description="Exponent of the combined tyre limit (1 to 2)."
    )
    source: str | None = Field(None, max_length=2000, description="Where the numbers come from.")

    @field_validator("ggv")
    @classmethod
    def _ggv_rows(cls, rows: list[tuple[float, float, float]]) -> list[tuple[float, float, float]]:
        a = np.asarray(rows, dtype=np.float64)
        _check_table(a, "ggv")
        if (a[:, 1:] <= 0).any():
            raise ValueError("ax_max and ay_max must be > 0 m/s^2")
        if (a[:, 1:] > 100).any():
            raise ValueError("ax_max and ay_max must be <= 100 m/s^2")
        return rows

    @field_validator("ax_max_machines")
    @classmethod
    def _machine_rows(cls, rows: list[tuple[float, float]]) -> list[tuple[float, float]]:
        a = np.asarray(rows, dtype=np.float64)
        _check_table(a, "ax_max_machines")
        if (a[:, 1] <= 0).any() or (a[:, 1] > 100).any():
            raise ValueError("ax must be in (0, 100] m/s^2")
        return rows

    # -- lookups (vectorised, held flat beyond the table) --------------------------------
    def ax_tyre(self, v: Any) -> np.ndarray:
        """Largest longitudinal tyre acceleration (braking and driving) at speed ``v``."""
        g = np.asarray(self.ggv, dtype=np.float64)
        return np.interp(v, g[:, 0], g[:, 1])

    def ay_tyre(self, v: Any) -> np.ndarray:
        """Largest lateral acceleration at speed ``v``."""
        g = np.asarray(self.ggv, dtype=np.float64)
        return np.interp(v, g[:, 0], g[:, 2])

    def ax_machine(self, v: Any) -> np.ndarray:
        """Largest forward acceleration of the drivetrain at speed ``v``."""
        m = np.asarray(self.ax_max_machines, dtype=np.float64)
        return np.interp(v, m[:, 0], m[:, 1])

    def sha1(self) -> str:
        """SHA-1 of the limits' numbers (canonical JSON): the ``# ggv sha1`` line of a TUM CSV."""
        doc = {k: v for k, v in self.model_dump(mode="json").items() if k not in ("name", "source")}
        return hashlib.sha1(json.dumps(doc, sort_keys=True).encode()).hexdigest()

    def scaled(self, factor: float, longitudinal: float | None = None) -> VehicleLimits:
        """A copy with the lateral limit times ``factor`` and the longitudinal ones (tyre and
        motor) times ``longitudinal`` (default ``factor``), each in (0, 1]: the share of the
        car's grip a driver is to use."""
        lon = factor if longitudinal is None else longitudinal
        if not (0.0 < factor <= 1.0 and 0.0 < lon <= 1.0):
            raise ConfigError(f"limits scales must be in (0, 1], got {factor} and {lon}")
        return type(self).model_validate(
            {
                **self.to_json_dict(),
                "name": f"{self.name} x{factor:g}" + ("" if lon == factor else f"/x{lon:g}"),
                "ggv": [(v, ax * lon, ay * factor) for v, ax, ay in self.ggv],
                "ax_max_machines": [(v, a * lon) for v, a in self.ax_max_machines],
            }
        )

    def with_overrides(
        self,
        *,
        v_max: float | None = None,
        ax_max: float | None = None,
        ay_max: float | None = None,
        ax_machines: float | None = None,
    ) -> VehicleLimits:
        """A copy with flat values replacing the table columns given (flags ``--v-max`` ...)."""
        fields: dict[str, Any] = {}
        if v_max is not None:
            fields["v_max"] = v_max
        if ax_max is not None or ay_max is not None:
            fields["ggv"] = [
                (v, ax if ax_max is None else ax_max, ay if ay_max is None else ay_max) for v, ax, ay in self.ggv
            ]
        if ax_machines is not None:
            fields["ax_max_machines"] = [(0.0, ax_machines)]
        if not fields:
            return self
        name = self.name + " (overridden: " + ", ".join(sorted(fields)) + ")"
        try:
            return type(self).model_validate({**self.to_json_dict(), **fields, "name": name})
        except ValidationError as e:
            raise ConfigError(f"limits: {_first_error(e)}") from None


def _check_table(a: np.ndarray, what: str) -> None:
    if not np.isfinite(a).all():
        raise ValueError(f"{what} must hold finite numbers")
    if (a[:, 0] < 0).any():
        raise ValueError(f"{what} speeds must be >= 0")
    if len(a) > 1 and (np.diff(a[:, 0]) <= 0).any():
        raise ValueError(f"{what} speeds must be strictly increasing")


def _first_error(e: ValidationError) -> str:
    err = e.errors()[0]
    loc = ".".join(str(p) for p in err["loc"]) or "(document)"
    return f"field {loc}: {err['msg']}"


def limits_from_dict(doc: Any, where: str) -> VehicleLimits:
    """Validated limits from a parsed document; a :class:`ConfigError` naming ``where`` and the field."""
    if not isinstance(doc, dict):
        raise ConfigError(f"{where}: limits must be a mapping with v_max, ggv and ax_max_machines")
    try:
        return VehicleLimits.model_validate(doc)
    except ValidationError as e:
        raise ConfigError(f"{where}: {_first_error(e)}") from None


def load_limits(path: str | Path) -> VehicleLimits:
    """Limits from a JSON or YAML file (``.yaml``/``.yml``: needs PyYAML)."""
    p = Path(path)
    text = read_text(p, "limits file")
    if p.suffix.lower() in (".yaml", ".yml"):
        try:
            import yaml
        except ImportError:  # pragma: no cover - PyYAML is present wherever the extras are
            raise ConfigError(f"{p}: reading YAML limits needs PyYAML (pip install pyyaml); or write JSON") from None
        try:
            doc = yaml.safe_load(text)
        except yaml.YAMLError as e:
            raise ConfigError(f"{p}: limits file is not valid YAML: {str(e).splitlines()[0]}") from None
    else:
        doc = parse_json(text, p, "limits file", ConfigError)
    lim = limits_from_dict(doc, str(p))
    return lim if "name" in doc else lim.with_fields(name=p.name)


def preset(name: str) -> VehicleLimits:
    """A shipped preset by name (:data:`PRESETS`)."""
    if name not in PRESETS:
        raise ConfigError(f"unknown limits preset {name!r}: choose one of {', '.join(PRESETS)} or give a file")
    text = resources.files(__package__).joinpath("presets").joinpath(f"{name}.json").read_text(encoding="utf-8")
    return limits_from_dict(json.loads(text), f"preset {name}")


def resolve_limits(spec: str | Path | None) -> VehicleLimits:
    """``None`` -> the car's measured limits; a preset name; else a file path."""
    if spec is None:
        return preset("car")
    if str(spec) in PRESETS:
        return preset(str(spec))
    return load_limits(spec)


def limits_json(lim: VehicleLimits) -> str:
    """The JSON text a limits file holds (what :func:`load_limits` reads back)."""
    return json.dumps(lim.to_json_dict(), indent=1) + "\n"
