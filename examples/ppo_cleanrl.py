#!/usr/bin/env python3
"""PPO for RoboRacerArena-v0 in the style of CleanRL's ``ppo_continuous_action.py``
(one file, torch, no framework). Needs ``pip install torch``; not run in CI.

    python examples/ppo_cleanrl.py --track gym-berlin --num-envs 32 --total-steps 2000000
    python examples/ppo_cleanrl.py --sources DIR       # recorded maps (gym-berlin) from an installed wheel

Env set-up an RL library can use as is: the native vector env (``make_vec`` with
``vectorization_mode="vector_entry_point"``), ``observation="normalise"`` (lidar ranges
clipped to 10 m and scaled to [0, 1], speeds scaled, no map-specific pose),
``action_mode="normalised"`` (both actions in [-1, 1]) and ``autoreset_mode=SAME_STEP``
(the step that ends an episode returns the next episode's first observation, as CleanRL
expects). Like CleanRL, truncation is treated as termination (no bootstrap).
"""

from __future__ import annotations

import argparse
import sys
import time

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode

import roboracer_arena  # noqa: F401  (registers RoboRacerArena-v0)
from roboracer_arena.scripting import add_sources_argument, apply_sources, run_script

try:
    import torch
    import torch.nn as nn
    from torch.distributions.normal import Normal
except ImportError:
    print("ppo_cleanrl.py: error: needs torch (pip install torch)", file=sys.stderr)
    sys.exit(2)


def parse_args() -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--track", default="gym-berlin")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--num-envs", type=int, default=32)
    p.add_argument("--num-steps", type=int, default=128, help="rollout length per env per update")
    p.add_argument("--total-steps", type=int, default=2_000_000)
    p.add_argument("--learning-rate", type=float, default=3e-4)
    p.add_argument("--gamma", type=float, default=0.99)
    p.add_argument("--gae-lambda", type=float, default=0.95)
    p.add_argument("--minibatches", type=int, default=8)
    p.add_argument("--update-epochs", type=int, default=10)
    p.add_argument("--clip-coef", type=float, default=0.2)
    p.add_argument("--ent-coef", type=float, default=0.0)
    p.add_argument("--vf-coef", type=float, default=0.5)
    p.add_argument("--max-grad-norm", type=float, default=0.5)
    p.add_argument("--num-beams", type=int, default=108, help="lidar beams (fewer = faster)")
    add_sources_argument(p)
    return p.parse_args()


def flatten(obs: dict[str, np.ndarray]) -> np.ndarray:
    return np.concatenate([obs["scan"], obs["odometry"]], axis=1)


def layer(i: int, o: int, std: float = np.sqrt(2)) -> nn.Linear:
    lin = nn.Linear(i, o)
    nn.init.orthogonal_(lin.weight, std)
    nn.init.constant_(lin.bias, 0.0)
    return lin


class Agent(nn.Module):
    def __init__(self, obs_dim: int, act_dim: int) -> None:
        super().__init__()
        self.critic = nn.Sequential(layer(obs_dim, 64), nn.Tanh(), layer(64, 64), nn.Tanh(), layer(64, 1, 1.0))
        self.actor_mean = nn.Sequential(
            layer(obs_dim, 64), nn.Tanh(), layer(64, 64), nn.Tanh(), layer(64, act_dim, 0.01)
        )
        self.actor_logstd = nn.Parameter(torch.full((1, act_dim), -0.5))

    def value(self, x: torch.Tensor) -> torch.Tensor:
        return self.critic(x)

    def act(self, x: torch.Tensor, action: torch.Tensor | None = None):
        mean = self.actor_mean(x)
        dist = Normal(mean, self.actor_logstd.expand_as(mean).exp())
        if action is None:
            action = dist.sample()
        return action, dist.log_prob(action).sum(1), dist.entropy().sum(1), self.critic(x)


def main() -> int:
    args = parse_args()
    return run_script("ppo_cleanrl.py", lambda: train(args))


def train(args: argparse.Namespace) -> None:
    apply_sources(args.sources)
    torch.manual_seed(args.seed)
    envs = gym.make_vec(
        "RoboRacerArena-v0",
        num_envs=args.num_envs,
        vectorization_mode="vector_entry_point",
        track=args.track,
        observation="normalise",
        action_mode="normalised",
        autoreset_mode=AutoresetMode.SAME_STEP,
        sim={"lidar": {"num_beams": args.num_beams}},
    )
    obs_dim = flatten(envs.observation_space.sample()).shape[1]
    act_dim = envs.single_action_space.shape[0]
    agent = Agent(obs_dim, act_dim)
    opt = torch.optim.Adam(agent.parameters(), lr=args.learning_rate, eps=1e-5)
    n, T = args.num_envs, args.num_steps
    obs_buf = torch.zeros((T, n, obs_dim))
    act_buf = torch.zeros((T, n, act_dim))
    logp_buf, rew_buf, done_buf, val_buf = (torch.zeros((T, n)) for _ in range(4))

    next_obs = torch.tensor(flatten(envs.reset(seed=args.seed)[0]), dtype=torch.float32)
    next_done = torch.zeros(n)
    updates = args.total_steps // (n * T)
    step, start, returns = 0, time.time(), []
    ep_ret = np.zeros(n)
    for update in range(1, updates + 1):
        for g in opt.param_groups:  # linear learning-rate annealing
            g["lr"] = (1.0 - (update - 1.0) / updates) * args.learning_rate
        for t in range(T):
            step += n
            obs_buf[t], done_buf[t] = next_obs, next_done
            with torch.no_grad():
                action, logp, _, value = agent.act(next_obs)
            val_buf[t], act_buf[t], logp_buf[t] = value.flatten(), action, logp
            obs, reward, term, trunc, _ = envs.step(np.clip(action.numpy(), -1.0, 1.0))
            done = term | trunc
            ep_ret += reward
            returns.extend(ep_ret[done].tolist())
            ep_ret[done] = 0.0
            rew_buf[t] = torch.tensor(reward, dtype=torch.float32)
            next_obs = torch.tensor(flatten(obs), dtype=torch.float32)
            next_done = torch.tensor(done, dtype=torch.float32)
        with torch.no_grad():  # generalised advantage estimation
            next_value = agent.value(next_obs).reshape(1, -1)
            adv = torch.zeros_like(rew_buf)
            last = 0.0
            for t in reversed(range(T)):
                nonterminal = 1.0 - (next_done if t == T - 1 else done_buf[t + 1])
                nv = next_value if t == T - 1 else val_buf[t + 1]
                delta = rew_buf[t] + args.gamma * nv * nonterminal - val_buf[t]
                adv[t] = last = delta + args.gamma * args.gae_lambda * nonterminal * last
            ret = adv + val_buf
        b_obs, b_act = obs_buf.reshape(-1, obs_dim), act_buf.reshape(-1, act_dim)
        b_logp, b_adv, b_ret = logp_buf.reshape(-1), adv.reshape(-1), ret.reshape(-1)
        batch = n * T
        mb = batch // args.minibatches
        for _ in range(args.update_epochs):
            idx = np.random.permutation(batch)
            for s in range(0, batch, mb):
                i = idx[s : s + mb]
                _, logp, ent, value = agent.act(b_obs[i], b_act[i])
                ratio = (logp - b_logp[i]).exp()
                a = (b_adv[i] - b_adv[i].mean()) / (b_adv[i].std() + 1e-8)
                pg = torch.max(-a * ratio, -a * ratio.clamp(1 - args.clip_coef, 1 + args.clip_coef)).mean()
                v_loss = 0.5 * ((value.flatten() - b_ret[i]) ** 2).mean()
                loss = pg - args.ent_coef * ent.mean() + args.vf_coef * v_loss
                opt.zero_grad()
                loss.backward()
                nn.utils.clip_grad_norm_(agent.parameters(), args.max_grad_norm)
                opt.step()
        recent = np.mean(returns[-50:]) if returns else float("nan")
        print(
            f"update {update}/{updates}  env-steps {step}  mean return (last 50 episodes) {recent:.2f}  "
            f"{step / (time.time() - start):,.0f} env-steps/s",
            flush=True,
        )
    envs.close()


if __name__ == "__main__":
    sys.exit(main())
