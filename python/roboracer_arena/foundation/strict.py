"""A pydantic base for specs and configs whose numbers must be numbers: a bool or a
string given for a field that takes a number is refused (pydantic would read ``true`` as
1 and ``"60"`` as 60.0), while ints still count as floats. The rule follows the type
wherever a number sits in it: ``int``, ``float``, ``float | None``, ``tuple[float, ...]``,
``list[int]``, ``dict[str, float]`` alike (a union that also admits text, e.g.
``float | str``, takes the text). NaN and infinities are refused by the models'
``allow_inf_nan=False``.

Also the one-line form of a :class:`pydantic.ValidationError` every reader reports.
"""

from __future__ import annotations

import types
import typing
from typing import Any

from pydantic import BaseModel, ValidationError, ValidationInfo, field_validator

_UNIONS = (typing.Union, types.UnionType)
_SEQUENCES = (list, tuple, set, frozenset)


def _admits_text(tp: Any) -> bool:
    """Whether a str or bool value is a legitimate input of the type ``tp``."""
    if tp in (str, bool, Any, object):
        return True
    origin = typing.get_origin(tp)
    if origin is typing.Literal:
        return any(isinstance(a, (str, bool)) for a in typing.get_args(tp))
    if origin is typing.Annotated:
        return _admits_text(typing.get_args(tp)[0])
    if origin in _UNIONS:
        return any(_admits_text(a) for a in typing.get_args(tp))
    return False


def _number_kind(tp: Any) -> str | None:
    """``"a whole number"`` / ``"a number"`` when ``tp`` (or an arm of its union) is a
    number type, else None."""
    if tp is int:
        return "a whole number"
    if tp is float:
        return "a number"
    origin = typing.get_origin(tp)
    if origin is typing.Annotated:
        return _number_kind(typing.get_args(tp)[0])
    if origin in _UNIONS:
        kinds = [k for k in map(_number_kind, typing.get_args(tp)) if k]
        return "a number" if "a number" in kinds else (kinds[0] if kinds else None)
    return None


def refuse_text_numbers(tp: Any, v: Any, where: str = "") -> None:
    """Raise ``ValueError`` when ``v`` holds a str or bool where ``tp`` takes a number
    (at any depth of a tuple, list, set or dict the type declares)."""
    if isinstance(v, (str, bool)):
        kind = _number_kind(tp)
        if kind and not _admits_text(tp):
            at = f" at {where}" if where else ""
            raise ValueError(f"must be {kind}{at}, not {type(v).__name__} {str(v)[:40]!r}")
        return
    origin = typing.get_origin(tp)
    args = typing.get_args(tp)
    if origin is typing.Annotated:
        refuse_text_numbers(args[0], v, where)
    elif origin in _UNIONS:
        arms = [a for a in args if a is not type(None)]
        if len(arms) == 1:
            refuse_text_numbers(arms[0], v, where)
    elif origin in _SEQUENCES and isinstance(v, (list, tuple)):
        if origin is tuple and args and args[-1] is not Ellipsis:
            for i, (a, x) in enumerate(zip(args, v)):
                refuse_text_numbers(a, x, f"{where}[{i}]")
        elif args:
            for i, x in enumerate(v):
                refuse_text_numbers(args[0], x, f"{where}[{i}]")
    elif origin is dict and isinstance(v, dict) and len(args) == 2:
        for k, x in v.items():
            refuse_text_numbers(args[1], x, f"{where}[{str(k)[:20]!r}]")


class NumbersAreNumbers(BaseModel):
    """Base model refusing a bool or a string wherever its fields take a number."""

    @field_validator("*", mode="before")
    @classmethod
    def _numbers_are_numbers(cls, v: Any, info: ValidationInfo) -> Any:
        field = cls.model_fields.get(info.field_name or "")
        if field is not None:
            refuse_text_numbers(field.annotation, v)
        return v


def _shown(value: Any) -> str:
    if isinstance(value, (dict, list)):
        return ""
    if isinstance(value, int) and value.bit_length() > 100:  # (repr refuses more than 4300 digits)
        text = f"an integer of about {int(value.bit_length() * 0.30103) + 1} digits"
    else:
        text = repr(value)
    return f" (got {text[:60]}{'…' if len(text) > 60 else ''})"


def validation_line(e: ValidationError, top: str = "(whole document)") -> str:
    """One line for all problems of ``e`` (at most five): ``field: message (got value)``,
    joined by ``; ``; a problem with the whole object is named ``top``. Values are cut
    short, so a hostile input never floods the message."""
    parts = []
    errors = e.errors()
    for err in errors[:5]:
        loc = ".".join(str(x)[:40] for x in err["loc"]) or top
        msg = str(err["msg"]).removeprefix("Value error, ")[:160]
        shown = "" if err["type"] == "value_error" else _shown(err.get("input"))  # (ours name the value)
        parts.append(f"{loc}: {msg}{shown}")
    if len(errors) > 5:
        parts.append(f"and {len(errors) - 5} more")
    return "; ".join(parts)


def format_validation_error(e: ValidationError, top: str = "(spec)") -> str:
    """One line for all problems: ``field: message (got value)``, joined by ``; ``; a
    problem with the whole object is named ``top``."""
    parts = []
    for err in e.errors()[:8]:
        loc = ".".join(_short(str(x), 40) for x in err["loc"]) or top
        value = err.get("input")
        if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 100:
            shown = f" (got an integer of about {int(value.bit_length() * 0.30103) + 1} digits)"
        else:
            shown = "" if isinstance(value, dict) else f" (got {_short(repr(value), 80)})"
        msg = str(err["msg"]).removeprefix("Value error, ")
        parts.append(f"{loc}: {_short(msg, 200)}{shown}")
    return "; ".join(parts)


def _short(text: str, n: int) -> str:
    """``text`` cut to ``n`` characters (a hostile key or value never floods a message)."""
    return text if len(text) <= n else text[: n - 1] + "…"
