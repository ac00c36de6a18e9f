"""Learning on the gymnasium envs: policies that drive tracks never seen.

* :mod:`.policy` -- the network, its features and its commands (plain or a residual on
  the reference pure pursuit);
* :mod:`.policy_file` -- the versioned policy file (``.npz`` with a JSON header) and
  :func:`load_policy`;
* :mod:`.trainer` -- ES training with checkpoints and resume (``roboracer-arena train``);
* :mod:`.recipe` -- the default recipe and the held-out maps it is judged on;
* :mod:`.evaluate` -- laps from the grid start, as a user meets the policy;
* :mod:`.runner` -- a policy acting in our envs; :mod:`.pursuit_base` -- its base;
* :mod:`.es` -- the earlier plain-MLP ES trainer of ``examples/train_es.py``.
"""

from .es import ESConfig, MLPPolicy, TrainResult, evaluate_laps, make_training_env, train
from .evaluate import evaluate_policy, policy_env_kwargs
from .policy import PolicySpec
from .policy_file import Policy, load_policy
from .recipe import HELD_OUT, Recipe
from .runner import PolicyDriver, PolicyRunner
from .trainer import train_policy

__all__ = [
    "HELD_OUT",
    "ESConfig",
    "MLPPolicy",
    "Policy",
    "PolicyDriver",
    "PolicyRunner",
    "PolicySpec",
    "Recipe",
    "TrainResult",
    "evaluate_laps",
    "evaluate_policy",
    "load_policy",
    "make_training_env",
    "policy_env_kwargs",
    "train",
    "train_policy",
]
