"""Connecting to a Ray cluster (the optional ``[ray]`` extra).

``address`` is what ``--ray`` takes: ``auto`` (a running cluster on this machine or the
one ``RAY_ADDRESS`` names), ``local`` (start a throw-away single-machine cluster), or a
cluster address (``HOST:PORT`` or ``ray://HOST:PORT``). If Ray is already initialised in
this process (e.g. a test called ``ray.init(num_cpus=2)``), that connection is used.

Errors name the argument the caller wrote: ``address='auto'`` from the Python API,
``--ray auto`` from the command line (``arg="--ray"``).
"""

from __future__ import annotations

from typing import Any

from ..errors import ArenaError, InvalidArgumentError


def import_ray() -> Any:
    """``import ray``, or a one-line error saying how to install it."""
    try:
        import ray
    except ImportError:
        raise ArenaError("Ray is not installed: pip install 'roboracer-arena[ray]'") from None
    return ray


def connect(address: str, arg: str = "address") -> bool:
    """Make sure this process is connected to a cluster; returns True if this call
    connected (and so the caller should disconnect), False if Ray was already up.
    ``arg`` is how errors name the address: ``"address"`` (the API) or ``"--ray"`` (the CLI)."""
    ray = import_ray()
    if ray.is_initialized():
        return False
    if not address or not isinstance(address, str):
        raise InvalidArgumentError(f"{_named(arg, address)}: expected auto, local or HOST:PORT")
    # logging_level ERROR also keeps Ray 2.60's "Token authentication is enabled for this Ray
    # cluster" notice off the user's terminal: a local cluster started here gets Ray's default
    # (token auth on, token in ~/.ray/auth_token); RAY_AUTH_MODE, if set, is Ray's to honour.
    kwargs: dict[str, Any] = {"include_dashboard": False, "logging_level": "ERROR", "log_to_driver": False}
    try:
        if address == "local":
            ray.init(**kwargs)
        else:
            ray.init(address=address, **kwargs)
    except (ConnectionError, RuntimeError, ValueError) as e:
        if address == "auto" and str(e).startswith("Could not find any running Ray instance"):
            # Ray's own text names its CLI's --address flag, whatever the caller wrote.
            raise ArenaError(
                f"{_named(arg, 'auto')}: no running Ray cluster found on this machine and RAY_ADDRESS is not set; "
                f"{_named(arg, 'local')} starts one here, {_named(arg, 'HOST:PORT')} joins a remote one"
            ) from None
        first = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        raise ArenaError(f"{_named(arg, address)}: cannot connect to a Ray cluster: {first}") from None
    return True


def _named(arg: str, value: object) -> str:
    """``--ray auto`` for a CLI flag, ``address='auto'`` for an API argument."""
    return f"{arg} {value}" if arg.startswith("-") else f"{arg}={value!r}"


def cluster_cpus() -> int:
    """CPUs the connected cluster offers (at least 1)."""
    ray = import_ray()
    return max(1, int(ray.cluster_resources().get("CPU", 1)))
