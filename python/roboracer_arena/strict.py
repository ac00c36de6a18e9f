"""A pydantic base for specs and configs whose numbers must be numbers: a bool or a
string given for an ``int``/``float`` field is refused (pydantic would read ``true`` as
1 and ``"60"`` as 60.0), while ints still count as floats. NaN and infinities are refused
by the models' ``allow_inf_nan=False``."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ValidationInfo, field_validator


class NumbersAreNumbers(BaseModel):
    """Base model refusing a bool or a string where an ``int`` or ``float`` belongs."""

    @field_validator("*", mode="before")
    @classmethod
    def _numbers_are_numbers(cls, v: Any, info: ValidationInfo) -> Any:
        field = cls.model_fields.get(info.field_name or "")
        if field is not None and field.annotation in (int, float) and isinstance(v, (bool, str)):
            kind = "a whole number" if field.annotation is int else "a number"
            raise ValueError(f"must be {kind}, not {type(v).__name__} {v!r}")
        return v
