"""Adapters to RL libraries (each needs its own optional extra; importing this package needs none).

* :mod:`.sb3`: a Stable-Baselines3 ``VecEnv`` over the native vector env
  (``pip install 'roboracer-arena[sb3]'``); its numpy-only core is :mod:`.sb3_core`.
"""
