"""The native batched simulator binding (`_core.Simulator`): shapes, errors, in-place
outputs, determinism across num_envs, bad actions, lidar against an exact reference."""

from __future__ import annotations

import math

import numpy as np
import pytest

from roboracer_arena import _core
from roboracer_arena.envs import LidarConfig, SimConfig
from roboracer_arena.errors import ConfigError, InvalidArgumentError

# Straights 6 m, centreline radius 3 m, corridor 2 m: walls are stadiums of radius 4 and 2.
STADIUM = _core.stadium_track(6.0, 3.0, 2.0)


def make(num_envs=2, vehicles=2, config=None, seed=0, tracks=(STADIUM,)):
    return _core.Simulator(list(tracks), num_envs, vehicles, (config or SimConfig()), seed)


def buffers(sim):
    e, v = sim.num_envs, sim.vehicles_per_env
    return (
        np.zeros((e, v, sim.num_beams), np.float32),
        np.zeros((e, v, len(sim.state_fields)), np.float64),
        np.zeros((e, v), np.uint8),
    )


def straight_poses(sim):
    """Vehicles on the stadium's bottom straight, 1.2 m apart, heading +x."""
    length = sim.centreline_length(0)
    poses = np.zeros((sim.num_envs, sim.vehicles_per_env, 3))
    for v in range(sim.vehicles_per_env):
        poses[:, v] = sim.centreline_pose(0, length - 5.5 + 1.2 * v)
    return poses


def test_properties_and_reset_observe():
    sim = make()
    assert (sim.num_envs, sim.vehicles_per_env, sim.num_beams) == (2, 2, 1081)
    assert sim.state_fields[:3] == ("x", "y", "yaw") and sim.state_fields == _core.STATE_FIELDS
    assert sim.centreline_length(0) == pytest.approx(12 + 2 * math.pi * 3.0, rel=1e-3)
    x, y, yaw = sim.centreline_pose(0, sim.centreline_length(0) - 3.0)
    assert (x, y, yaw) == pytest.approx((0.0, -3.0, 0.0), abs=1e-9)
    sim.reset(np.ones(2, bool), straight_poses(sim))
    scans, state, events = buffers(sim)
    sim.observe(scans, state, events)
    assert state[0, 0, :3] == pytest.approx((-2.5, -3.0, 0.0))
    assert state[1, 1, :3] == pytest.approx((-1.3, -3.0, 0.0))
    # Beam straight left (+90 deg) from the bottom straight sees the inner wall 1 m away.
    mid = sim.num_beams // 2
    assert scans[0, 0, mid + 360] == pytest.approx(1.0, abs=1e-4)
    assert np.all(events == 0)


def test_step_drives_and_writes_in_place():
    sim = make()
    sim.reset(np.ones(2, bool), straight_poses(sim))
    scans, state, events = buffers(sim)
    actions = np.zeros((2, 2, 2))
    actions[..., 1] = 2.0
    for _ in range(20):
        sim.step(actions, 10, None, state, events)
    vx = state[..., sim.state_fields.index("vx")]
    assert np.all(np.abs(vx - 2.0) < 0.2)
    assert np.all(state[..., sim.state_fields.index("travel")] > 1.0)
    sim.step(actions, 1, scans, state, events)
    assert np.all(scans > 0) and np.all(scans <= 30.0)


def test_wrong_shapes_and_dtypes_raise():
    sim = make()
    scans, state, events = buffers(sim)
    good = np.zeros((2, 2, 2))
    with pytest.raises(InvalidArgumentError, match="actions"):
        sim.step(np.zeros((2, 2, 3)), 1, None, state, events)
    with pytest.raises(InvalidArgumentError, match="actions"):
        sim.step(good.astype(np.float32), 1, None, state, events)
    with pytest.raises(InvalidArgumentError, match="state"):
        sim.step(good, 1, None, state[:, :, :5], events)
    with pytest.raises(InvalidArgumentError, match="scans"):
        sim.step(good, 1, scans.astype(np.float64), state, events)
    with pytest.raises(InvalidArgumentError, match="events"):
        sim.observe(None, state, events.astype(np.int64))
    with pytest.raises(InvalidArgumentError, match="contiguous"):
        sim.observe(None, np.zeros((2, 2, 2 * len(sim.state_fields)))[:, :, ::2], events)
    with pytest.raises(InvalidArgumentError, match="substeps"):
        sim.step(good, 0, None, state, events)
    with pytest.raises(InvalidArgumentError):
        sim.set_tracks(np.array([0, 3]))
    with pytest.raises(InvalidArgumentError, match="not finite"):
        sim.reset(np.ones(2, bool), np.full((2, 2, 3), np.nan))
    with pytest.raises(InvalidArgumentError):
        sim.centreline_length(5)
    with pytest.raises(ConfigError, match="config"):  # a config mistake is a ConfigError on either side
        _core.Simulator([STADIUM], 1, 1, {"vehicle": {"mas": 1}}, 0)
    with pytest.raises(InvalidArgumentError):
        _core.Simulator([([np.zeros((3, 3))], STADIUM[1])], 1, 1, {}, 0)
    with pytest.raises(InvalidArgumentError):
        _core.Simulator([STADIUM], 0, 1, {}, 0)


def run(num_envs: int, seed: int = 3):
    config = SimConfig(lidar=LidarConfig(num_beams=91, noise_std=0.02))
    sim = make(num_envs, 2, config, seed)
    sim.reset(np.ones(num_envs, bool), straight_poses(sim))
    scans, state, events = buffers(sim)
    for t in range(25):
        env = np.arange(num_envs)[:, None]
        veh = np.arange(2)[None, :]
        actions = np.stack(np.broadcast_arrays(0.3 * np.sin(0.3 * (t + env)), 2.0 + veh + 0.1 * env), axis=-1)
        sim.step(np.ascontiguousarray(actions, dtype=np.float64), 4, scans, state, events)
    return scans, state


def test_determinism_across_num_envs_and_seed():
    s3, st3 = run(3)
    s5, st5 = run(5)
    assert np.array_equal(st3, st5[:3]) and np.array_equal(s3, s5[:3])
    again, _ = run(3)
    assert np.array_equal(s3, again)
    other, _ = run(3, seed=4)
    assert not np.array_equal(s3, other)  # noise follows the seed


def test_bad_actions_are_clipped_never_nan():
    sim = make()
    sim.reset(np.ones(2, bool), straight_poses(sim))
    scans, state, events = buffers(sim)
    bad = np.array([np.nan, np.inf, -np.inf, 1e300, -1e300, 0.0, 5.0, -5.0])
    for t in range(30):
        actions = np.roll(bad, t)[:8].reshape(2, 2, 2)
        sim.step(actions, 5, scans, state, events)
        assert np.isfinite(state).all() and np.isfinite(scans).all()
        assert np.all(np.abs(state[..., sim.state_fields.index("steer")]) <= 0.524 + 1e-12)
    assert not np.any(events & 8)


def test_tracks_switch_per_env():
    square = ([np.array([[-5.0, -5], [5, -5], [5, 5], [-5, 5]])], np.array([[-2.0, -2], [2, -2], [2, 2], [-2, 2]]))
    sim = make(2, 1, tracks=(STADIUM, square))
    sim.set_tracks(np.array([1, 0]))
    assert list(sim.track_ids()) == [1, 0]
    assert sim.centreline_length(1) == pytest.approx(16.0)
    sim.reset(np.ones(2, bool), np.array([[[0.0, 0.0, 0.0]], [[0.0, -3.0, 0.0]]]))
    cfg_mount = SimConfig().lidar.mount_x
    scans, state, events = buffers(sim)
    sim.observe(scans, state, events)
    # Env 0 sits in the 10 m square room: straight ahead the wall is 5 m - mount offset away.
    assert scans[0, 0, sim.num_beams // 2] == pytest.approx(5.0 - cfg_mount, abs=1e-4)


# --- a real recorded map (f1tenth-gym berlin) through the builder's corridor ----------


@pytest.fixture(scope="module")
def berlin_geometry(sources):
    from roboracer_arena.maps.corridor import extract_corridor

    return extract_corridor(sources / "f1tenth-gym" / "maps" / "berlin.yaml")


@pytest.fixture(scope="module")
def berlin(berlin_geometry):
    return berlin_geometry.walls, berlin_geometry.centreline


def test_physics_walls_are_the_builders_wall_mesh(berlin_geometry, sources):
    """The collision mesh in every world is exactly the mesh the USD stage gets: the
    track carries the build's wall height (one knob), at its default and when changed."""
    from roboracer_arena.maps.corridor import extract_corridor
    from roboracer_arena.track.drivable import track_from_corridor

    for geo in (
        berlin_geometry,
        extract_corridor(sources / "f1tenth-gym" / "maps" / "berlin.yaml", {"wall_height_m": 0.8}),
    ):
        track = track_from_corridor(geo, "berlin")
        assert track.wall_height == geo.params["wall_height_m"]
        sim = _core.Simulator([track.native()], 2, 1, SimConfig(), 0)
        vertices, triangles = sim.wall_mesh(0)
        usd_vertices, usd_triangles = geo.meshes["walls"]
        assert np.array_equal(vertices, usd_vertices) and np.array_equal(triangles, usd_triangles)


def _reference_ranges(walls, origin, angles, range_max):
    """Brute force: every beam against every wall segment (numpy, float64)."""
    a = np.concatenate([w for w in walls])
    b = np.concatenate([np.roll(w, -1, axis=0) for w in walls])
    e = b - a  # (S, 2)
    d = np.stack([np.cos(angles), np.sin(angles)], axis=1)  # (B, 2)
    w = a - origin  # (S, 2)
    den = d[:, None, 0] * e[None, :, 1] - d[:, None, 1] * e[None, :, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (w[None, :, 0] * e[None, :, 1] - w[None, :, 1] * e[None, :, 0]) / den
        u = (w[None, :, 0] * d[:, None, 1] - w[None, :, 1] * d[:, None, 0]) / den
    hit = (np.abs(den) > 1e-14) & (t >= 0) & (u >= 0) & (u <= 1)
    return np.minimum(np.where(hit, t, np.inf).min(axis=1), range_max)


def test_lidar_on_berlin_matches_brute_force(berlin):
    walls, centre = berlin
    sim = _core.Simulator([(walls, centre)], 1, 1, SimConfig(), 0)
    lidar = SimConfig().lidar
    scans, state, events = buffers(sim)
    for s in np.linspace(0.0, sim.centreline_length(0), 7, endpoint=False):
        x, y, yaw = sim.centreline_pose(0, s)
        sim.reset(np.ones(1, bool), np.array([[[x, y, yaw + 0.2]]]))
        sim.observe(scans, state, events)
        yaw = state[0, 0, 2]
        origin = np.array([x + lidar.mount_x * np.cos(yaw), y + lidar.mount_x * np.sin(yaw)])
        angles = yaw - lidar.fov / 2 + np.arange(lidar.num_beams) * lidar.fov / (lidar.num_beams - 1)
        ref = _reference_ranges(walls, origin, angles, lidar.range_max)
        # float32 output of float64 geometry: within 1e-5 m (plus rounding of the pose
        # through float32 physics: the reset pose is what the state reports).
        assert np.max(np.abs(scans[0, 0] - ref)) < 1e-4


def test_drives_a_lap_of_berlin_without_touching_a_wall(berlin):
    from roboracer_arena.bench.physics import _Driver

    sim = _core.Simulator([berlin], 1, 1, SimConfig(), 0)
    sim.reset(np.ones(1, bool), np.array([[sim.centreline_pose(0, 0.0)]]))
    scans, state, events = buffers(sim)
    sim.observe(None, state, events)
    driver = _Driver(sim, speed=2.5)
    actions = np.zeros((1, 1, 2))
    laps = state[..., sim.state_fields.index("laps")]
    lap_events = 0
    for _ in range(int(60 / 0.05)):  # at most 60 s of driving, 20 Hz control
        driver.actions(state, actions)
        sim.step(actions, 10, None, state, events)
        assert not events[0, 0] & 1, f"wall contact at {state[0, 0, :3]}"
        lap_events += int(events[0, 0] & 4 != 0)
        if laps[0, 0] >= 1:
            break
    assert lap_events == 1 and state[0, 0, sim.state_fields.index("laps")] == 1
    lap_time = state[0, 0, sim.state_fields.index("last_lap_time")]
    assert sim.centreline_length(0) / 2.6 < lap_time < sim.centreline_length(0) / 1.5


@pytest.mark.parametrize("height", [math.nan, math.inf, -1.0, 0.0, 1e300, True, "x"])
def test_a_bad_wall_height_is_refused_naming_it(height):
    walls, centre = _core.stadium_track()
    with pytest.raises(InvalidArgumentError, match=r"tracks\[0\]:? wall_height"):
        _core.Simulator([(walls, centre, height)], 1, 1, {}, 0)
