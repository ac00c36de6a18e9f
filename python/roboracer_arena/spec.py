"""The typed track specification: the paper's 12 fields (``S``) and the optional speed
cap ``max_straight_m`` (issue 28).

Every field has an indoor default, chosen for a typical RoboRacer venue (a sports hall
or corridor in a university building) and the 1:10 car; the reason for each default is
in the field's description. Values are SI (metres). Parsers fill only the fields a
request states; the rest keep these defaults.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Literal

from pydantic import (
    ConfigDict,
    Field,
    SerializationInfo,
    SerializerFunctionWrapHandler,
    ValidationError,
    field_validator,
    model_serializer,
    model_validator,
)

from .errors import ArenaError, SpecError
from .foundation.fileio import parse_json, read_text
from .foundation.strict import NumbersAreNumbers, format_validation_error

FeatureName = Literal["hairpin", "chicane", "sweeper"]
Direction = Literal["clockwise", "counterclockwise"]


class TrackSpec(NumbersAreNumbers):
    """A requirement specification for one closed racing corridor."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    name: str = Field(
        "generated-track",
        min_length=1,
        max_length=120,
        description="Track name; default is a neutral placeholder so unnamed requests still get a stable id.",
    )
    lap_length_m: float = Field(
        60.0,
        ge=1,
        le=2_000,
        description="Centreline lap length (m). 60 m is a typical RoboRacer competition lap in a sports hall.",
    )
    corridor_width_m: float = Field(
        1.5,
        ge=0.2,
        le=20,
        description=(
            "Free corridor width between walls (m). 1.5 m lets two 0.3 m-wide cars pass, as on"
            " most RoboRacer tracks, and gives the paper's pitch p = 2.15 m with the default walls."
        ),
    )
    hall_x_m: float = Field(
        20.0, ge=1, le=1_000, description="Hall length (m). A 20 m x 15 m hall is the paper's reference venue."
    )
    hall_y_m: float = Field(
        15.0, ge=1, le=1_000, description="Hall width (m). A 20 m x 15 m hall is the paper's reference venue."
    )
    direction: Direction = Field(
        "counterclockwise",
        description="Driving direction seen from above; counter-clockwise is the mathematical positive sense and the convention of F1TENTH maps.",
    )
    hairpins: int = Field(0, ge=0, le=50, description="Number of hairpins (~180 deg turns). 0: none unless requested.")
    chicanes: int = Field(
        0, ge=0, le=50, description="Number of chicanes (opposite-sense turn pairs). 0: none unless requested."
    )
    sweepers: int = Field(
        0, ge=0, le=50, description="Number of sweepers (long, large-radius turns). 0: none unless requested."
    )
    feature_order: list[FeatureName] = Field(
        default_factory=list,
        description="Order of named features along the lap; empty (any order) unless the request orders them.",
    )
    min_radius_m: float = Field(
        0.0,
        ge=0,
        le=100,
        description="Requested minimum centreline radius (m); 0 means unstated, the constructor then uses max(0.9 m, 0.75 w).",
    )
    longest_straight_m: float = Field(
        0.0,
        ge=0,
        le=1_000,
        description="Required longest straight (m); 0 means unstated (no requirement).",
    )
    max_straight_m: float | None = Field(
        None,
        gt=0,
        le=1_000,
        description=(
            "Upper bound on every straight (m), a speed cap for small halls; None means unstated"
            " (no cap). The validator checks it with no tolerance."
        ),
    )

    @field_validator(
        "lap_length_m",
        "corridor_width_m",
        "hall_x_m",
        "hall_y_m",
        "hairpins",
        "chicanes",
        "sweepers",
        "min_radius_m",
        "longest_straight_m",
        "max_straight_m",
        mode="before",
    )
    @classmethod
    def _no_bool_numbers(cls, v: object) -> object:
        # pydantic's lax mode would read true as 1 (a 1 m lap); a bool is never a quantity.
        if isinstance(v, bool):
            raise ValueError("must be a finite number (metres or a count), not a boolean")
        return v

    @model_serializer(mode="wrap")
    def _leave_out_an_unset_cap(self, handler: SerializerFunctionWrapHandler, info: SerializationInfo) -> Any:
        # Specs written before the cap existed stay byte for byte what they were (the
        # packaged library and every spec.json users keep): in JSON an unstated cap is left
        # out (it reads back as None); Python dumps keep every field.
        data = handler(self)
        if info.mode_is_json() and isinstance(data, dict) and data.get("max_straight_m", 0) is None:
            del data["max_straight_m"]
        return data

    @field_validator("name")
    @classmethod
    def _name_is_printable(cls, v: str) -> str:
        if not v.strip() or any(ord(c) < 32 for c in v):
            raise ValueError("name must be non-blank printable text")
        return v.strip()

    @model_validator(mode="after")
    def _order_matches_counts(self) -> TrackSpec:
        if self.feature_order:
            wanted: tuple[tuple[FeatureName, int], ...] = (
                ("hairpin", self.hairpins),
                ("chicane", self.chicanes),
                ("sweeper", self.sweepers),
            )
            for feat, count in wanted:
                listed = self.feature_order.count(feat)
                if listed != count:
                    raise ValueError(
                        f"feature_order lists {listed} {feat}(s) but {feat}s = {count}; "
                        "the order must name every requested feature exactly once"
                    )
        return self

    # -- conveniences -----------------------------------------------------------------
    @property
    def feature_count(self) -> int:
        return self.hairpins + self.chicanes + self.sweepers

    @classmethod
    def json_schema(cls) -> dict:
        """JSON schema of the fields (used for schema-constrained LLM output)."""
        return cls.model_json_schema()

    @classmethod
    def from_file(cls, path: str | Path) -> TrackSpec:
        """Load a spec from a JSON file; errors name the file and the offending field."""
        p = Path(path)
        try:
            text = read_text(p, "spec file")
        except ArenaError as e:
            raise SpecError(str(e)) from None
        data = parse_json(text, p, "spec file", SpecError)
        return cls.from_dict(data, source=str(p))

    @classmethod
    def from_dict(cls, data: object, source: str = "spec") -> TrackSpec:
        """Validate a mapping, raising :class:`SpecError` that names the field."""
        if not isinstance(data, dict):
            raise SpecError(f"{source}: a spec must be a JSON object, got {type(data).__name__}")
        try:
            return cls.model_validate(data)
        except ValidationError as e:
            raise SpecError(f"{source}: {format_validation_error(e)}") from e
