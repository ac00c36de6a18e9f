"""Times F1TENTH Gym's env for ``python -m benchmarks peer``. Runs under the *peer's*
interpreter (a venv where ``f110_gym`` imports), so it imports nothing of ours: numpy and
f110_gym only, and prints one JSON line.

The workload is ``bench env``'s ``constant`` single-env cell: the action [steer 0 rad,
speed 1 m/s] every 0.01 s step, F1TENTH Gym's own 1080-beam scan on every step, a reset
to the given start pose whenever the env reports ``done`` (a collision, or its two laps).
A first untimed run of the same length lets numba compile before the clock starts.

    PEER_PYTHON f1tenth_gym_driver.py MAP.yaml X Y YAW SECONDS
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path


def main(argv: list[str]) -> int:
    if len(argv) != 5:
        print(__doc__, file=sys.stderr)
        return 2
    map_yaml = Path(argv[0])
    x, y, yaw, seconds = (float(a) for a in argv[1:])
    import numpy as np
    from f110_gym.envs.f110_env import F110Env

    images = [p for p in map_yaml.parent.glob(map_yaml.stem + ".*") if p.suffix.lower() in (".png", ".pgm")]
    if not images:  # F1TENTH Gym loads MAP + map_ext, so the image must share the YAML's stem
        print(f"{map_yaml}: no {map_yaml.stem}.png or .pgm beside it (F1TENTH Gym's naming)", file=sys.stderr)
        return 2
    env = F110Env(map=str(map_yaml.with_suffix("")), map_ext=images[0].suffix, num_agents=1, timestep=0.01)
    pose = np.array([[x, y, yaw]])
    action = np.array([[0.0, 1.0]])

    def run(budget: float) -> tuple[int, int, float, float, int]:
        obs, _, done, _ = env.reset(pose)
        steps = resets = 0
        t0, c0 = time.perf_counter(), time.process_time()
        while True:
            obs, _, done, _ = env.step(action)
            steps += 1
            if done:
                env.reset(pose)
                resets += 1
            if steps % 64 == 0 and time.perf_counter() - t0 >= budget:
                return steps, resets, time.perf_counter() - t0, time.process_time() - c0, len(obs["scans"][0])

    run(min(seconds, 1.0))  # numba's compilation, untimed
    steps, resets, wall, cpu, beams = run(seconds)
    print(json.dumps({"steps": steps, "resets": resets, "seconds": wall, "cpu_seconds": cpu, "beams": beams}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
