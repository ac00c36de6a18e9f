"""The bad-value errors are ``ValueError``s as well as ``ArenaError``s (issue 37), as
pydantic's ``ValidationError`` is: code that caught ``ValueError`` for a wrong action
shape keeps working now that the check runs in the core. The classes are real
two-base types made by the core, mirrored by ``roboracer_arena.errors`` and the stub."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from roboracer_arena import _core, errors
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.envs.vector import RoboRacerVectorEnv

SMALL = {"sim": {"lidar": {"num_beams": 109}}}
VALUE_ERRORS = ["MapFormatError", "InvalidArgumentError", "ConfigError", "SpecError"]
OTHER_ERRORS = ["MapIOError", "CorridorError", "SimulationError", "InternalError"]


@pytest.mark.parametrize("name", VALUE_ERRORS)
def test_bad_value_errors_have_both_bases(name):
    cls = getattr(errors, name)
    assert cls is getattr(_core, name)
    assert cls.__bases__ == (errors.ArenaError, ValueError)
    assert cls.__module__ == "roboracer_arena._core"
    e = pickle.loads(pickle.dumps(cls("bad")))  # crosses a process pool unchanged
    assert type(e) is cls and str(e) == "bad"


@pytest.mark.parametrize("name", OTHER_ERRORS)
def test_other_errors_are_not_value_errors(name):
    cls = getattr(errors, name)
    assert issubclass(cls, errors.ArenaError) and not issubclass(cls, ValueError)


@pytest.mark.parametrize("action", [np.zeros(3), np.zeros((2, 2))])
def test_except_value_error_catches_a_bad_action_shape(oval, action):
    env = RoboRacerEnv(track=oval, **SMALL)
    env.reset(seed=0)
    with pytest.raises(ValueError, match="actions must be 2 numbers") as info:
        env.step(action)
    assert isinstance(info.value, errors.InvalidArgumentError)


def test_except_value_error_catches_a_bad_action_shape_in_the_vector_env(oval):
    env = RoboRacerVectorEnv(track=oval, num_envs=2, **SMALL)
    env.reset(seed=0)
    with pytest.raises(ValueError, match="actions must be 4 numbers"):
        env.step(np.zeros((3, 2)))


def test_except_value_error_catches_a_bad_config(oval):
    with pytest.raises(ValueError, match="num_beams") as info:
        RoboRacerEnv(track=oval, sim={"lidar": {"num_beams": 0}})
    assert isinstance(info.value, errors.ConfigError)
    with pytest.raises(ValueError) as core:  # the core's own check of the same document
        _core.check_config("sim", {"lidar": {"num_beams": 0}})
    assert isinstance(core.value, errors.ConfigError)


def test_except_value_error_catches_a_bad_spec():
    with pytest.raises(ValueError) as info:
        _core.screen({"lap_length_m": -1})
    assert isinstance(info.value, errors.SpecError)
