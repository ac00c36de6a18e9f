"""Vehicle fidelity from Python: per-env vehicle parameters in the simulator, episode
randomisation of friction, mass and lags in the env (seeded), the config's drivetrain
fields, and the F1TENTH Gym single-track reference against its own linear theory."""

import math

import numpy as np
import pytest
from pydantic import ValidationError

from benchmarks import fidelity, fidelity_limit
from benchmarks.f1tenth_st import GYM_PARAMS, SingleTrack
from roboracer_arena import _core
from roboracer_arena.config.sim import PhysicsConfig, SimConfig, VehicleConfig
from roboracer_arena.envs.env_config import RandomisationConfig
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.errors import InvalidArgumentError


def _stop_distances(friction: np.ndarray, mass: np.ndarray) -> np.ndarray:
    """Two envs on a long straight: roll at 5 m/s, then a 0 m/s command for 2 s."""
    walls = [np.array([[-100.0, -5.0], [100.0, -5.0], [100.0, 5.0], [-100.0, 5.0]])]
    centre = np.array([[-50.0, 0.0], [50.0, 0.0], [50.0, 1.0], [-50.0, 1.0]])
    sim = _core.Simulator([(walls, centre)], 2, 1, SimConfig(), 0)
    mask = np.ones(2, bool)
    v = VehicleConfig()
    sim.set_vehicle_params(
        mask, friction, mass, np.full(2, v.steer_time_constant), np.full(2, v.throttle_time_constant)
    )
    sim.reset(mask, np.array([[[-80.0, 0.0, 0.0]], [[-80.0, 0.0, 0.0]]]))
    sim.set_speeds(mask, np.full((2, 1), 5.0))
    state = np.zeros((2, 1, len(sim.state_fields)))
    events = np.zeros((2, 1), np.uint8)
    for _ in range(40):
        sim.step(np.zeros((2, 1, 2)), 10, None, state, events)
    return state[:, 0, sim.state_fields.index("x")] + 80.0


def test_per_env_friction_changes_the_stop_and_bad_values_are_refused():
    d = _stop_distances(np.array([0.83, 0.415]), np.full(2, 4.885))
    # friction-limited: v^2 / (2 mu g) is 1.54 m and 3.07 m
    assert 1.5 < d[0] < 1.9 and d[1] > 1.5 * d[0], d
    sim = _core.Simulator([_core.stadium_track()], 2, 1, {}, 0)
    ok = np.ones(2)
    with pytest.raises(InvalidArgumentError, match="mass"):
        sim.set_vehicle_params(np.ones(2, bool), ok, np.array([4.0, -1.0]), ok * 0.05, ok * 0.02)
    with pytest.raises(InvalidArgumentError, match="friction"):
        sim.set_vehicle_params(np.ones(2, bool), np.ones(3), ok, ok, ok)


def test_env_randomises_vehicle_params_per_episode_seeded(oval):
    """Two envs with the same seed drive identically; another seed (other draws) not."""
    rnd = {"friction_scale": (0.6, 1.0), "mass_scale": (0.8, 1.2), "lag_scale": (0.5, 2.0)}

    def drive(seed):
        env = RoboRacerEnv(track=oval, randomisation=rnd, sim={"lidar": {"num_beams": 31}})
        env.reset(seed=seed)
        for _ in range(30):
            env.step(np.array([0.2, 4.0], np.float32))
        state, f = env.simulator_state
        return state[0, [f["x"], f["y"], f["vx"]]]

    a, b, c = drive(1), drive(1), drive(2)
    assert np.array_equal(a, b)
    assert not np.allclose(a, c)
    with pytest.raises(ValidationError, match="friction_scale"):
        RandomisationConfig(friction_scale=(0.0, 1.0))
    assert not RandomisationConfig().vehicle_active


def test_drivetrain_fields_are_validated():
    with pytest.raises(ValidationError):
        VehicleConfig(max_duty=1.5)
    with pytest.raises(ValidationError):
        VehicleConfig(steer_time_constant=-0.1)
    with pytest.raises(ValidationError):
        PhysicsConfig(dt=0.03)
    assert "F1TENTH" in VehicleConfig.model_fields["max_motor_current"].description


def test_gym_single_track_reference_matches_its_linear_theory():
    """The reference integrator, in its linear range, turns at the rate its own
    parameters predict: r = v d / (L + K v^2), K = m (lr / Cf - lf / Cr) / L with axle
    stiffness C = mu C_S m g l / L (CommonRoad's tyre, no load transfer at a = 0)."""
    p = GYM_PARAMS
    L = p["lf"] + p["lr"]
    v, d = 3.0, 0.064  # a multiple of the gym's steering step sv_max dt = 0.032 rad (no dither)
    cf = p["mu"] * p["C_Sf"] * p["m"] * 9.81 * p["lr"] / L
    cr = p["mu"] * p["C_Sr"] * p["m"] * 9.81 * p["lf"] / L
    k = p["m"] * (p["lr"] / cf - p["lf"] / cr) / L
    r = fidelity.gym_turn(v, d)["yaw_rate"]
    assert r == pytest.approx(v * d / (L + k * v * v), rel=0.01)
    car = SingleTrack()
    for _ in range(300):
        car.step(0.0, 25.0)
    assert 7.0 < car.speed < p["v_max"] and math.isfinite(car.yaw_rate)


def test_linear_theory_of_our_car_matches_a_gentle_turn():
    """Our model in the linear range agrees with single-track theory within 3 %."""
    res = fidelity.steady_turn(2.0, 0.1)
    assert res["yaw_rate"] == pytest.approx(fidelity.linear_theory(2.0, 0.1), rel=0.03)


def test_recorded_yaw_envelope_bound():
    """Steady, non-sliding yaw rate is at most min(v tan(d_max) / L, mu g / v): the paper's
    car (L 0.3275 m, d_max 0.524 rad, mu 0.83) peaks at sqrt(mu g tan(d_max) / L)."""
    e = fidelity.envelope(VehicleConfig())
    assert e.r_max == pytest.approx(math.sqrt(0.83 * 9.81 * math.tan(0.524) / 0.3275), rel=1e-9)
    assert 3.7 < e.r_max < 3.9 and e.mu_needed_for_recorded == pytest.approx(1.72, abs=0.01)


def test_quasi_static_model_reproduces_linear_theory():
    """The quasi-static steady-turn solver, in the linear range (no tyre near its
    friction limit), gives the yaw rate of linear single-track theory within 1 %."""
    for v, d in [(1.0, 0.064), (2.0, 0.1), (3.0, 0.064)]:
        turn = fidelity_limit.steady_turn(v, d)
        assert turn is not None and max(turn.friction_use) < 0.5
        assert turn.yaw_rate == pytest.approx(fidelity.linear_theory(v, d), rel=0.01)
    with pytest.raises(InvalidArgumentError, match="v must be"):
        fidelity_limit.steady_turn(0.0, 0.1)
    # Too little friction to hold speed: every wheel would spin up.
    with pytest.raises(InvalidArgumentError, match="no steady turn"):
        fidelity_limit.cornering_limit(6.0, VehicleConfig(tyre_friction=0.001))


def test_steady_cornering_peak_is_the_quasi_static_limit():
    """The steady-cornering peak is 0.93-0.94 mu g, not mu g, and that is this car's
    physics: holding speed against the drag of the saturated tyres takes about 7 N of
    drive, a quarter per wheel through the open differentials, and the inner front wheel,
    unloaded by the roll, has too little friction left for its share of the cornering.
    The simulator's turns match the model solved from its equations within 2 % (at the
    measured speed), the peak over steering angles is within 3 % of the quasi-static limit,
    and the same equations with the drive shared by load reach mu g within 3 %."""
    vc = VehicleConfig()
    mu_g = vc.tyre_friction * 9.81
    v = 6.0
    turns = [fidelity.steady_turn(v, d) for d in (0.096, 0.112, 0.128, 0.16)]
    for d, t in zip((0.096, 0.112, 0.128, 0.16), turns):
        qs = fidelity_limit.steady_turn(t["speed"], d, vc)
        assert qs is not None and t["lat_acc"] == pytest.approx(qs.lat_acc, rel=0.02), (d, t, qs)
    limit = fidelity_limit.cornering_limit(v, vc)
    peak = max(t["lat_acc"] for t in turns)
    assert peak == pytest.approx(limit.lat_acc, rel=0.03), (peak, limit)
    assert 0.9 * mu_g < limit.lat_acc < 0.96 * mu_g
    assert limit.friction_use[0] == pytest.approx(1.0) and limit.loads[0] < 0.6 * limit.loads[1]
    shared = fidelity_limit.cornering_limit(v, vc, equal_split=False)
    assert shared.lat_acc == pytest.approx(mu_g, rel=0.03)
