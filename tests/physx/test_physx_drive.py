"""The PhysX drive loop's API (issue 36): any ``controller(scan, odometry)`` drives the
PhysX car at the env's control rate with a lidar scan; a built stage's car can be
re-authored for another ``VehicleConfig``; real-car presets map ForzaETH's models."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from roboracer_arena.physx import available

needs_physx = pytest.mark.skipif(
    not available(), reason="the 'physx' extra (ovphysx, physx-usd-schemas) is not installed; CI installs it"
)


@needs_physx
def test_drive_physx_runs_any_controller_with_a_scan(tmp_path):
    from roboracer_arena import _core
    from roboracer_arena.config.sim import SimConfig
    from roboracer_arena.physx.drive import drive_physx, write_flat_stage
    from roboracer_arena.track.drivable import Track

    warnings.simplefilter("ignore")
    walls, centre = _core.stadium_track(6.0, 3.0, 2.0)
    shift = np.array([0.0, 3.0])  # the bottom straight through the origin, heading +x
    track = Track.from_polylines([w + shift for w in walls], centre + shift)
    sim = SimConfig()
    stage = write_flat_stage(tmp_path / "flat.usda", sim, half_size=20.0)
    seen: list[tuple[tuple[int, ...], dict[str, float]]] = []
    nearest: list[float] = []

    def controller(scan: np.ndarray, odo: dict[str, float]) -> tuple[float, float]:
        seen.append((scan.shape, dict(odo)))
        nearest.append(float(scan.min()))
        return 0.0, 2.0

    run = drive_physx(stage, controller, sim, track=track, max_seconds=2.0)
    assert run.control_rate_hz == 20.0 and len(run.t) == len(seen) == 40
    shape, odo = seen[-1]
    assert shape == (sim.lidar.num_beams,)
    assert {"x", "y", "yaw", "vx", "vy", "yaw_rate", "steer", "speed"} <= set(odo)
    # straight ahead at the 2 m/s command: the speed loop holds it, the car stays on its line
    assert run.speed[-1] == pytest.approx(2.0, abs=0.1) and abs(run.y[-1]) < 0.05
    assert run.x[-1] > 2.0 and run.lap_time_s is None
    # on the straight, the scan sees the corridor's walls 1 m to either side
    assert nearest[0] == pytest.approx(1.0, abs=0.05) and run.lateral_error[0] < 0.02


@needs_physx
def test_replace_car_reauthors_the_stage_for_another_config(tmp_path):
    from pxr import Usd

    from roboracer_arena.config.sim import SimConfig, VehicleConfig
    from roboracer_arena.config.vehicle_presets import forzaeth_preset
    from roboracer_arena.physx.drive import write_flat_stage
    from roboracer_arena.usd.vehicle import physx_params, replace_car

    stage = write_flat_stage(tmp_path / "flat.usdc", SimConfig(), half_size=10.0)
    nuc6 = forzaeth_preset("NUC6")
    replace_car(stage, SimConfig(vehicle=nuc6))
    s = Usd.Stage.Open(str(stage))
    car = s.GetPrimAtPath("/World/Car")
    assert car.GetAttribute("physics:mass").Get() == pytest.approx(3.75)
    graph = s.GetPrimAtPath("/World/CarParts/FrontTire").GetAttribute("physxVehicleTire:lateralStiffnessGraph").Get()
    assert graph[1] == pytest.approx(physx_params(nuc6).lateral_graph_front[1], rel=1e-6)
    assert len([p for p in s.Traverse() if p.GetPath().pathString.startswith("/World/Car/")]) >= 5
    assert nuc6 != VehicleConfig()


def test_forzaeth_presets_map_the_identified_cars():
    """NUC6: m 3.75 kg, I_z 0.056, l_f 0.176, l_r 0.149, mu 0.95; our cornering stiffness per
    unit load is the Pacejka fit's slope at zero slip (B C D); its single-track model gives
    about 0.49 rad/s at 5 m/s and 0.05 rad (DESIGN.md, "Two engines, one car")."""
    from roboracer_arena.config.vehicle_presets import FORZAETH_MODELS, forzaeth_preset, pacejka, single_track_yaw_rate
    from roboracer_arena.errors import ConfigError

    v = forzaeth_preset("nuc6")
    assert (v.mass, v.yaw_inertia, v.com_to_front, v.com_to_rear) == (3.75, 0.056, 0.176, 0.149)
    assert v.tyre_friction == pytest.approx(0.9514)
    b, c, d, _ = FORZAETH_MODELS["NUC6"]["C_Pf"]
    assert v.cornering_stiffness_front == pytest.approx(b * c * d)
    slope = float(pacejka(1e-6, FORZAETH_MODELS["NUC6"]["C_Pf"])) / 1e-6
    assert slope == pytest.approx(v.cornering_stiffness_front, rel=1e-4)
    assert single_track_yaw_rate(FORZAETH_MODELS["NUC6"], 5.0, 0.05) == pytest.approx(0.49, abs=0.01)
    with pytest.raises(ConfigError):
        forzaeth_preset("NUC9")


def test_forzaeth_presets_match_the_shared_model_files(sources):
    """The presets' numbers are the published files' (read from ../shared/vehicle-data)."""
    from roboracer_arena.config.vehicle_presets import FORZAETH_MODELS, read_forzaeth_model

    folder = sources.parent / "vehicle-data" / "forzaeth-on-track-sysid"
    if not folder.is_dir():
        pytest.skip(f"{folder} is not here")
    for name, model in FORZAETH_MODELS.items():
        f = read_forzaeth_model(folder / f"{name}_pacejka.txt")
        for key in ("m", "I_z", "l_f", "l_r", "C_Pf", "C_Pr"):
            assert np.allclose(f[key], model[key]), (name, key)


def test_the_drive_loops_lap_is_the_simulators():
    """The PhysX drive loop's lap comes from the core's progress (``_core.ProgressTracker``):
    on our car it ends at the very control step where the env's own lap event fires."""
    from roboracer_arena import _core
    from roboracer_arena.envs.env_config import EnvConfig
    from roboracer_arena.envs.single import RoboRacerEnv
    from roboracer_arena.physx.drive import drive_native, pure_pursuit
    from roboracer_arena.track.drivable import Track

    track = Track.from_polylines(*_core.stadium_track(6.0, 3.0, 2.0))
    run = drive_native(track, pure_pursuit(track), max_seconds=30.0)
    assert run.lap_time_s is not None

    env = RoboRacerEnv(track=track, config=EnvConfig(time_limit_s=None))
    controller = pure_pursuit(track)
    env.reset(seed=0)
    t, lap = 0.0, None
    while lap is None and t < 30.0:
        state, f = env.simulator_state
        odo = {k: float(state[0, i]) for k, i in f.items()}
        _, _, _, _, info = env.step(env.from_ackermann(np.array(controller(np.zeros(0), odo))))
        t += env.config.control_dt
        lap = t if info["lap_completed"] else None
    assert lap is not None and run.lap_time_s == pytest.approx(lap, abs=1e-9)
    # The tracker itself: one lap of travel along its centreline, then the event.
    tracker = _core.ProgressTracker(np.asarray(track.centreline), *track.centreline[0])
    assert tracker.length == pytest.approx(_core.polyline_length(np.asarray(track.centreline)))
    with pytest.raises(_core.InvalidArgumentError):
        tracker.update(float("nan"), 0.0, 0.05, 0.1)
