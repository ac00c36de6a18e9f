"""The base of the package's typed reports and records (catalog entries, verify results,
circuit reports): a frozen pydantic model that refuses unknown keys and writes JSON with
only the fields it was given, so a report written, read back and written again is the
same text. Numbers are numbers here too (:class:`~roboracer_arena.foundation.strict.NumbersAreNumbers`):
a catalog entry or report read back with ``"40"`` for a length is refused, not read as 40."""

from __future__ import annotations

from typing import Any, TypeVar

from pydantic import ConfigDict

from .strict import NumbersAreNumbers

M = TypeVar("M", bound="FrozenModel")


class FrozenModel(NumbersAreNumbers):
    """Immutable, ``extra="forbid"``; see the module doc."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    def to_json_dict(self) -> dict[str, Any]:
        """The JSON object for this model: fields in declaration order, only those set."""
        return self.model_dump(mode="json", exclude_unset=True)

    def with_fields(self: M, **fields: Any) -> M:
        """A copy with ``fields`` set (validated, and written to its JSON)."""
        return type(self).model_validate({**self.to_json_dict(), **fields})
