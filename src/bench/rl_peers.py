"""aerobox bench --sections rl, its peers: RotorPy 3.0's batched QuadrotorEnv (rotorpy.learning,
torch on the CPU) against aerobox's vector environment, both stable-baselines3 VecEnvs, in one
process, at the same 100 Hz control rate, collective thrust and body rates, the Crazyflie.

Each steps N worlds with a constant action for the same number of steps, its episodes ending
and restarting as in training (RotorPy's after 5 s, aerobox's after 10 s); the table gives
environment steps per second (worlds x steps / wall s) and aerobox's over RotorPy's. RotorPy
integrates its batched dynamics once per step with torchdiffeq's default solver (dopri5,
adaptive), aerobox with MuJoCo at 1 ms (10 steps) and its inner loops at each. Medians of 3.
Run by aerobox-bench with the project environment's python (.venv: RotorPy, torchdiffeq and
roma from PyPI on Debian's torch) and PYTHONPATH set to the build's package; argv: --smoke for
4 worlds and 5 steps.
"""

import os
import statistics
import sys
import time

import numpy as np
import torch
from rotorpy.learning.quadrotor_environments import make_default_vec_env
from rotorpy.vehicles.crazyflie_params import quad_params

from aerobox.sb3 import AeroboxVecEnv


def rate(env, n, steps):
    """Environment steps per second of `env` (n worlds) over `steps` steps."""
    env.seed(1)
    env.reset()
    action = np.zeros((n, 4), np.float32)
    action[:, 0] = 0.1  # a little above the middle of the thrust range: near hover for both
    begin = time.perf_counter()
    for _ in range(steps):
        env.step(action)
    return n * steps / (time.perf_counter() - begin)


def main(argv):
    smoke = "--smoke" in argv
    threads = os.cpu_count() or 1
    torch.set_num_threads(threads)
    sizes, repetitions = ([4], 1) if smoke else ([16, 64, 256], 3)
    print(f"RotorPy 3.0's batched QuadrotorEnv (torch {torch.__version__.split('+')[0]}, "
          f"{threads} threads) and aerobox's vector environment (aerobox/Hover-v0, {threads} "
          "threads), both stable-baselines3 VecEnvs at 100 Hz, action cmd_ctbr / ctbr, the "
          f"Crazyflie. Medians of {repetitions}.\n")
    print("| worlds | RotorPy: env steps/s | aerobox: env steps/s | aerobox / RotorPy |")
    print("|---|---|---|---|")
    for n in sizes:
        steps = 5 if smoke else max(20, 6400 // n)
        theirs, ours = [], []
        for _ in range(repetitions):
            peer = make_default_vec_env(n, quad_params, "cmd_ctbr", torch.device("cpu"))
            theirs.append(rate(peer, n, steps))
            ours.append(rate(AeroboxVecEnv("aerobox/Hover-v0", n, action="ctbr"), n, steps))
        a, b = statistics.median(theirs), statistics.median(ours)
        print(f"| {n} | {a:.0f} | {b:.0f} | {b / a:.1f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
