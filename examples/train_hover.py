"""Trains a hover policy on aerobox/Hover-v0 with stable-baselines3's PPO, on aerobox's vector
environment (C++ threads), and saves it with the environment's parameters beside it.

    tools/python.sh examples/train_hover.py --out hover_policy     # .venv with build/python
    aerobox fly scenes/empty/scenario.toml --set vehicle.kind=crazyflie --set controller.rate=100 \\
        --max-speed 1 --controller examples/policy_controller.py:PolicyController

The policy commands collective thrust and attitude (action "ctatt"); aerobox's attitude and
rate loops run below it at 1 kHz. Observations and rewards are normalised by SB3's VecNormalize
(running mean and variance), and the observation's statistics are saved: the controller needs
them. Every --eval-every steps it flies the policy for 15 s from 10 random starts (within 1 m, as
in training) on both physics backends (--backend: the one it trains on) and prints how many it
held within 10 cm for the last 10 s, and the wall time; it stops when all 10 hold on both (or at
--steps). On two cores that took 1.1 to 1.8 million steps and 2 to 6 minutes on MuJoCo, 1.1
million steps and about 3 minutes on the rigid backend (with OpenBLAS, which tools/setup.sh installs: without it, torch's updates take 8 times
longer). Writes OUT.zip (the policy) and OUT.json (the environment's parameters, the
observation's normalisation and the vehicle's mass [kg], which the controller checks against
the vehicle it flies). Runs in the project environment (.venv: Debian's CPU torch,
stable-baselines3 from PyPI).
"""

import argparse
import json
import sys
import time

import numpy as np
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.logger import Logger
from stable_baselines3.common.vec_env import VecNormalize

from aerobox.envs import HoverEnv, HoverVectorEnv
from aerobox.sb3 import HoverVecEnv

# the environment the policy learns; policy_controller.py reads these back. reward_alive 4 keeps
# a step inside the bounds worth more than its penalties, so that staying in the air pays.
PARAMS = dict(action="ctatt", vehicle="crazyflie", control_rate=100.0, max_tilt=0.6,
              reward_alive=4.0)

# PPO's settings: long rollouts over many worlds, large batches, and a narrow start for the
# policy's noise (log std -1), which keeps early episodes from tumbling at once
PPO_SETTINGS = dict(n_steps=256, batch_size=4096, n_epochs=10, learning_rate=3e-4,
                    policy_kwargs=dict(log_std_init=-1.0, net_arch=[128, 128]))


def held(model, normalise, backend="mujoco", starts=10, tolerance=0.10, hold=10.0):
    """How many of `starts` seeded 15 s episodes the policy ends within `tolerance` [m] of the
    target for the last `hold` seconds, without a crash, on `backend`: the episodes side by side
    in one vector environment (world i seeded 10,000 + i), the policy asked once per step for
    all."""
    envs = HoverVectorEnv(num_envs=starts, backend=backend, **dict(PARAMS, episode_time=hold + 5.0))
    obs, _ = envs.reset(seed=[10_000 + i for i in range(starts)])
    steps = int((hold + 5.0) * PARAMS["control_rate"])
    distances = np.zeros((steps, starts))
    crashed = np.zeros(starts, bool)
    for k in range(steps):
        actions, _ = model.predict(normalise.normalize_obs(obs), deterministic=True)
        obs, _, terminated, _, _ = envs.step(actions)
        crashed |= terminated
        distances[k] = np.linalg.norm(obs[:, :3], axis=1)
    last = int(hold * PARAMS["control_rate"])
    return int(np.sum(~crashed & (distances[-last:].max(axis=0) < tolerance)))


def save(model, normalise, out):
    model.save(out)
    rms = normalise.obs_rms
    saved = dict(PARAMS, mass=HoverEnv(**PARAMS).quad_params["mass"],
                 obs_mean=rms.mean.tolist(), obs_var=rms.var.tolist(),
                 obs_clip=normalise.clip_obs, obs_epsilon=normalise.epsilon)
    with open(out + ".json", "w") as file:
        json.dump(saved, file, indent=2)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="hover_policy", help="OUT.zip and OUT.json")
    parser.add_argument("--steps", type=int, default=3_000_000, help="environment steps at most")
    parser.add_argument("--envs", type=int, default=32, help="worlds stepped together")
    parser.add_argument("--eval-every", type=int, default=100_000, help="steps between checks")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--backend", choices=["mujoco", "rigid"], default="mujoco",
                        help="the physics it trains on (the checks fly on both)")
    args = parser.parse_args(argv)
    if args.steps < 1 or args.envs < 1 or args.eval_every < 1:
        parser.error("--steps, --envs and --eval-every must be positive")
    torch.set_num_threads(2)  # PPO updates and the worlds take turns: both use the two cores
    normalise = VecNormalize(HoverVecEnv(num_envs=args.envs, backend=args.backend, **PARAMS),
                             norm_obs=True, norm_reward=True, clip_obs=10.0)
    settings = dict(PPO_SETTINGS, n_steps=min(PPO_SETTINGS["n_steps"],
                                              max(1, args.steps // args.envs)))
    settings["batch_size"] = min(settings["batch_size"], settings["n_steps"] * args.envs)
    model = PPO("MlpPolicy", normalise, seed=args.seed, verbose=0, **settings)
    # a logger of its own, with no outputs: learn() otherwise makes an empty SB3-<time> folder
    # in the temporary directory at each call
    model.set_logger(Logger(folder=None, output_formats=[]))
    begin, done = time.perf_counter(), 0
    while done < args.steps:
        chunk = min(args.eval_every, args.steps - done)
        model.learn(chunk, reset_num_timesteps=False)
        done += chunk
        ok = {backend: held(model, normalise, backend) for backend in ("mujoco", "rigid")}
        print(f"{done} steps, {time.perf_counter() - begin:.0f} s: held 10 cm for the last 10 s "
              f"from {ok[args.backend]}/10 starts (on MuJoCo {ok['mujoco']}/10, on the rigid "
              f"backend {ok['rigid']}/10)", flush=True)
        save(model, normalise, args.out)
        if min(ok.values()) == 10:
            break
    print(f"saved {args.out}.zip and {args.out}.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
