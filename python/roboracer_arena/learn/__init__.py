"""Learning helpers on the gymnasium envs: a numpy-only evolution-strategies trainer for
a lidar policy (:mod:`.es`), used by ``examples/train_es.py`` and
``roboracer-arena bench generalisation``."""

from .es import ESConfig, MLPPolicy, TrainResult, evaluate_laps, make_training_env, train

__all__ = ["ESConfig", "MLPPolicy", "TrainResult", "evaluate_laps", "make_training_env", "train"]
