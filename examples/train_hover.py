"""Trains a hover policy on aerobox/Hover-v0 with stable-baselines3's PPO, on aerobox's vector
environment (C++ threads), and saves it with the environment's parameters beside it.

    .venv/bin/python examples/train_hover.py --out hover_policy
    aerobox fly scenes/empty/scenario.toml --set vehicle.kind=crazyflie --max-speed 1 \\
        --controller examples/policy_controller.py:PolicyController --command cmd_ctbr

Every --eval-every steps it flies the policy from 10 random starts (within 1 m, as in training)
and prints how many it held within 10 cm for the episode's last 5 s, and the wall time; it stops
when all 10 hold (or at --steps). Writes OUT.zip (the policy) and OUT.json (the environment's
parameters: the controller needs the action's scaling). Runs in the project environment
(.venv: Debian's CPU torch, stable-baselines3 from PyPI). OUT.json also holds the vehicle's
mass [kg], which the controller checks against the vehicle it flies.
"""

import argparse
import json
import sys
import time

import numpy as np
import torch
from stable_baselines3 import PPO

from aerobox.envs import HoverEnv
from aerobox.sb3 import HoverVecEnv

# the environment the policy learns; policy_controller.py reads these back
PARAMS = dict(action="ctbr", vehicle="crazyflie", control_rate=100.0, max_rate=10.0)


def held(model, starts=10, tolerance=0.10):
    """How many of `starts` seeded episodes the policy ends within `tolerance` [m] of the target
    for the last 5 s, without a crash."""
    count = 0
    for seed in range(starts):
        env = HoverEnv(**PARAMS)
        obs, _ = env.reset(seed=10_000 + seed)
        distances, terminated, truncated = [], False, False
        while not (terminated or truncated):
            action, _ = model.predict(obs, deterministic=True)
            obs, _, terminated, truncated, _ = env.step(action)
            distances.append(float(np.linalg.norm(obs[:3])))
        count += (not terminated) and max(distances[-500:]) < tolerance
    return count


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="hover_policy", help="OUT.zip and OUT.json")
    parser.add_argument("--steps", type=int, default=3_000_000, help="environment steps at most")
    parser.add_argument("--envs", type=int, default=32, help="worlds stepped together")
    parser.add_argument("--eval-every", type=int, default=100_000, help="steps between checks")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    if args.steps < 1 or args.envs < 1 or args.eval_every < 1:
        parser.error("--steps, --envs and --eval-every must be positive")
    torch.set_num_threads(1)  # the worlds use the other core
    env = HoverVecEnv(num_envs=args.envs, **PARAMS)
    model = PPO("MlpPolicy", env, n_steps=128, batch_size=2048, n_epochs=5, seed=args.seed,
                verbose=0)
    begin, done = time.perf_counter(), 0
    while done < args.steps:
        chunk = min(args.eval_every, args.steps - done)
        model.learn(chunk, reset_num_timesteps=False)
        done += chunk
        ok = held(model)
        print(f"{done} steps, {time.perf_counter() - begin:.0f} s: held 10 cm for the last 5 s "
              f"from {ok}/10 starts", flush=True)
        model.save(args.out)
        with open(args.out + ".json", "w") as file:
            json.dump(dict(PARAMS, mass=HoverEnv(**PARAMS).quad_params["mass"]), file, indent=2)
        if ok == 10:
            break
    print(f"saved {args.out}.zip and {args.out}.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
