"""``roboracer-arena drive MAP --engine physx``: the same drive on the PhysX car (see
:mod:`roboracer_arena.physx.laps`). Exit codes as ``drive``: 0 a clean lap, 5 a contact
or no lap in the time allowed, 2 bad input (the [physx] extra missing included)."""

from __future__ import annotations

import argparse
from typing import Any

from ..errors import ConfigError, InvalidArgumentError
from . import EXIT_LAP_FAILED, EXIT_OK
from ._common import print_json


def run_physx(args: argparse.Namespace, policy: Any, params: Any) -> int:
    from ..drivers import PurePursuitDriver
    from ..envs.env_config import EnvConfig
    from ..physx import available

    if not available():
        raise ConfigError("--engine physx needs the optional extra: pip install 'roboracer-arena[physx]'")
    for flag in ("gif", "mcap"):
        if getattr(args, flag, None) is not None:
            raise InvalidArgumentError(f"--{flag} is not available with --engine physx")
    if args.laps != 1 or args.reverse:
        raise InvalidArgumentError("--engine physx drives one lap in the racing direction (no --laps, --reverse)")
    from ..physx.laps import physx_lap

    if policy is not None:
        from ..learn import policy_env_kwargs
        from ..learn.runner import policy_controller

        config = EnvConfig.build(policy_env_kwargs(policy))
        lid = config.sim.lidar

        def controller_for(track: Any) -> Any:
            return policy_controller(policy, track, lid.num_beams, lid.fov, config)

        name = f"policy {args.policy.name}"
    else:
        config = EnvConfig()

        def controller_for(track: Any) -> Any:
            driver = PurePursuitDriver(track.centreline, params)

            def act(_scan: Any, odo: Any) -> tuple[float, float]:
                steer, speed = driver.act_pose(odo["x"], odo["y"], odo["yaw"], odo["vx"])
                return float(steer), float(speed)

            return act

        name = "pure pursuit"
    res = physx_lap(
        args.map,
        controller_for,
        config.sim,
        config.control_rate_hz,
        stage=args.stage,
        name=name,
        max_seconds=args.max_time,
    )
    status = EXIT_OK if res.clean else EXIT_LAP_FAILED
    if args.json:
        print_json(res.to_json_dict())
        return status
    verdict = "clean lap" if res.clean else ("CONTACT" if res.contact else "did not finish")
    t = f"{res.lap_time_s:.2f} s" if res.lap_time_s is not None else f"{res.sim_time_s:.1f} s simulated"
    print(
        f"{res.track} on PhysX ({res.controller}): {verdict}, {t} ({res.wall_seconds:.1f} s wall), "
        f"closest wall {res.min_clearance_m:.3f} m, max lateral error {res.max_lateral_error_m:.2f} m"
    )
    return status
