"""The Ollama backend: the official ``ollama`` client with the TrackSpec JSON schema as
``format``, temperature 0 and a fixed seed (the paper's setting, default model
``gemma4:31b``).

Every way the call can fail becomes a typed :class:`~roboracer_arena.errors.BackendError`:
the client raises the built-in ``ConnectionError`` when nothing listens,
``ollama.ResponseError`` (with ``status_code``) for HTTP errors -- 404 is a model the
server does not have -- and lets raw ``httpx`` timeouts and transport errors through; a
reply that is not JSON, or JSON that is not a valid TrackSpec, is malformed output.
"""

from __future__ import annotations

import json
import os
from typing import Any

import httpx
import ollama

from ..errors import (
    BackendError,
    BackendTimeoutError,
    BackendUnavailableError,
    MalformedOutputError,
    ModelNotFoundError,
    SpecError,
)
from ..foundation.fileio import MAX_JSON_DEPTH, json_depth
from ..spec import TrackSpec
from .result import DEFAULTS

DEFAULT_MODEL = "gemma4:31b"
DEFAULT_HOST = "http://127.0.0.1:11434"
DEFAULT_TIMEOUT_S = 120.0
SEED = 0

SYSTEM_PROMPT = (
    "You convert a request for an indoor RoboRacer (1:10 scale) race track into a JSON object "
    "with exactly these fields: " + ", ".join(TrackSpec.model_fields) + ". "
    "Rules: fill a field only if the request states it; every field the request does not state "
    "keeps its default, which is: " + json.dumps(DEFAULTS) + ". "
    "Convert every length to metres (1 ft = 0.3048 m, 1 yd = 0.9144 m, 1 cm = 0.01 m). "
    "hall_x_m is the hall's length, hall_y_m its width; '15 by 12' means hall_x_m=15, hall_y_m=12. "
    "direction is 'clockwise' or 'counterclockwise'. feature_order stays [] unless the request "
    "orders the features; when it does, list every hairpin, chicane and sweeper in order. "
    "Never add a constraint the request does not state."
)


def resolve_host(host: str | None) -> str:
    """The server to use: the argument, else ``$OLLAMA_HOST``, else the local default."""
    return host or os.environ.get("OLLAMA_HOST") or DEFAULT_HOST


def _call(client: ollama.Client, text: str, model: str, host: str, timeout: float) -> str:
    try:
        resp = client.chat(
            model=model,
            messages=[{"role": "system", "content": SYSTEM_PROMPT}, {"role": "user", "content": text}],
            format=TrackSpec.json_schema(),
            options={"temperature": 0, "seed": SEED},
            stream=False,
        )
    except ollama.ResponseError as e:
        if e.status_code == 404:
            raise ModelNotFoundError(
                f"Ollama at {host} has no model {model!r} ({e.error}); run `ollama pull {model}` or pass --model"
            ) from None
        raise BackendError(f"Ollama at {host} refused the request: {e.error} (HTTP {e.status_code})") from None
    except ConnectionError as e:
        raise BackendUnavailableError(f"cannot reach an Ollama server at {host}: {e}") from None
    except httpx.TimeoutException:
        raise BackendTimeoutError(f"Ollama at {host} did not answer within {timeout:g} s (model {model!r})") from None
    except httpx.HTTPError as e:
        raise BackendUnavailableError(f"talking to Ollama at {host} failed: {type(e).__name__}: {e}") from None
    except (json.JSONDecodeError, ValueError, TypeError) as e:
        # the server's HTTP body was not an Ollama chat response
        raise MalformedOutputError(f"Ollama at {host} sent a reply that is not a chat response: {e}") from None
    content = resp.message.content if resp.message is not None else None
    if not content:
        raise MalformedOutputError(f"Ollama model {model!r} at {host} returned an empty answer")
    return content


def ask_ollama(
    text: str,
    *,
    host: str | None = None,
    model: str = DEFAULT_MODEL,
    timeout: float = DEFAULT_TIMEOUT_S,
) -> tuple[TrackSpec, dict[str, Any]]:
    """Ask an Ollama model to fill the TrackSpec for ``text``.

    Returns the validated spec and the raw JSON object the model produced. Raises a
    :class:`BackendError` subclass on any failure. The output is *not* grounded here;
    :func:`roboracer_arena.parse.parse_request` applies the guard.
    """
    url = resolve_host(host)
    client = ollama.Client(host=url, timeout=timeout)
    try:
        content = _call(client, text, model, url, timeout)
    finally:
        client.close()
    try:
        data = json.loads(content)
    except json.JSONDecodeError as e:
        raise MalformedOutputError(
            f"model {model!r} returned text that is not JSON ({e.msg} at column {e.colno}): {content[:200]!r}"
        ) from None
    except (RecursionError, ValueError):  # nested too deeply; an integer of more than 4300 digits
        raise MalformedOutputError(
            f"model {model!r} returned JSON nested too deeply or a number too long to read"
        ) from None
    if json_depth(data) > MAX_JSON_DEPTH:
        raise MalformedOutputError(f"model {model!r} returned JSON nested more than {MAX_JSON_DEPTH} levels deep")
    try:
        spec = TrackSpec.from_dict(data, source=f"model {model!r} output")
    except SpecError as e:
        raise MalformedOutputError(str(e)) from None
    return spec, data


def reachable(host: str | None = None, timeout: float = 1.0) -> bool:
    """Whether an Ollama server answers at ``host`` (a quick ``GET /api/tags``)."""
    try:
        with ollama.Client(host=resolve_host(host), timeout=timeout) as client:
            client.list()
        return True
    except (ConnectionError, ollama.ResponseError, httpx.HTTPError, ValueError):
        return False
