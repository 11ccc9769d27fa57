"""aerobox bench --sections rl, its peers, in one process:

1. RotorPy 3.0's batched QuadrotorEnv (rotorpy.learning, torch on the CPU) against aerobox's
   vector environment on each physics backend, both stable-baselines3 VecEnvs, at the same 100 Hz control rate,
   collective thrust and body rates, the Crazyflie. RotorPy integrates its batched dynamics once
   per step with torchdiffeq's default solver (dopri5, adaptive), aerobox with MuJoCo at 1 ms
   (10 steps) and its inner loops at each.
2. PyFlyt 0.29.0's PyFlyt/QuadX-Hover-v4 (PyBullet, as gym-pybullet-drones) in Gymnasium's
   SyncVectorEnv (PyFlyt has no vector environment of its own) against aerobox's native vector
   environment (gym.make_vec). PyFlyt's agent rate must divide 120 Hz: it runs at 120 Hz (240 Hz
   physics) and aerobox at 100 Hz, so the ratio is of simulated seconds per wall second.

3. L2F 2.0 ("Learning to Fly in Seconds", C++ through pybind11; no contacts, no obstacles), the
   fastest CPU quadrotor simulator we know, against aerobox's vector environment at 100 Hz, when
   tools/setup.sh --bench has built it (its PyPI package is a source package compiled with
   -march=native, about 6 minutes on two cores, so the default set-up does not take it).
4. crazyflow 0.4 (JAX on the CPU, MuJoCo's MJX for contacts only on demand), run in its own
   environment (.venv-crazyflow, tools/setup.sh --bench) by crazyflow_peer.py: its Sim at its
   fastest (no Gymnasium wrapper, 10 physics steps of 2 ms per attitude command) against aerobox's
   rigid backend through gym.make_vec (observation, reward and autoreset included) at 1 ms and at
   crazyflow's 2 ms. Simulated seconds per wall second.
5. Training: examples/train_hover.py (PPO on 32 worlds) until its policy holds within 10 cm for
   the last 10 s of 15 s episodes from 10 random starts within 1 m: the steps and the wall time
   (the issue's target: under 15 minutes on two cores; RotorPy's README: a working hover in
   under 4 minutes on a laptop's many cores).

Each steps N worlds with a constant action near hover, the episodes ending and restarting as in
training; steps per second are worlds x steps / wall s. Medians of 3. Run by aerobox-bench with
the project environment's python (.venv: RotorPy, torchdiffeq, roma, PyFlyt, PyBullet from PyPI
on Debian's torch and numba) and PYTHONPATH set to the build's package; argv: --smoke for 4
worlds and 5 steps.
"""

import os
import statistics
import sys
import time

import contextlib
import ctypes
import io
import re
import subprocess
import tempfile
import warnings

import gymnasium as gym
import numpy as np
import torch
from rotorpy.learning.quadrotor_environments import make_default_vec_env
from rotorpy.vehicles.crazyflie_params import quad_params

import aerobox.envs  # noqa: F401  (registers aerobox's ids)
from aerobox.sb3 import AeroboxVecEnv

PYFLYT_HZ = 120  # PyFlyt/QuadX-Hover-v4's agent rate (it must divide 120)


def rate(env, n, steps, warm_up=5):
    """Environment steps per second of `env` (n worlds) over `steps` steps, after `warm_up`."""
    env.seed(1)
    env.reset()
    action = np.zeros((n, 4), np.float32)
    action[:, 0] = 0.1  # a little above the middle of the thrust range: near hover for both
    for _ in range(warm_up):
        env.step(action)
    begin = time.perf_counter()
    for _ in range(steps):
        env.step(action)
    return n * steps / (time.perf_counter() - begin)


@contextlib.contextmanager
def quiet():
    """PyBullet prints from C on every world it makes (argv[0]=...): the table's stdout is kept
    clean by pointing file descriptor 1 elsewhere meanwhile."""
    sys.stdout.flush()
    saved = os.dup(1)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
    try:
        with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            yield
    finally:
        ctypes.CDLL(None).fflush(None)  # C's own buffer, before fd 1 is back
        os.dup2(saved, 1)
        os.close(saved)


def gym_rate(envs, action, steps, warm_up=10):
    """Environment steps per second of a Gymnasium vector environment over `steps` steps, after
    `warm_up` (PyFlyt compiles its controllers with numba at its first steps)."""
    actions = np.repeat(action[None], envs.num_envs, axis=0).astype(np.float32)
    with quiet():  # PyFlyt prints on its resets
        envs.reset(seed=1)
        for _ in range(warm_up):
            envs.step(actions)
        begin = time.perf_counter()
        for _ in range(steps):
            envs.step(actions)
        return envs.num_envs * steps / (time.perf_counter() - begin)


def pyflyt_envs(n):
    with quiet():  # PyBullet prints its build on import
        import PyFlyt.gym_envs  # noqa: F401  (registers PyFlyt/*)

        return gym.make_vec("PyFlyt/QuadX-Hover-v4", num_envs=n, vectorization_mode="sync",
                            agent_hz=PYFLYT_HZ)


def medians(repetitions, theirs, ours):
    """The medians of `repetitions` rates of a peer and of aerobox, timed in turn."""
    a, b = [], []
    for _ in range(repetitions):
        a.append(theirs())
        b.append(ours())
    return statistics.median(a), statistics.median(b)


def pyflyt_rate(n, steps):
    peer = pyflyt_envs(n)
    hover = np.zeros(peer.single_action_space.shape)
    hover[-1] = 0.5  # rates 0, thrust near hover
    try:
        return gym_rate(peer, hover, steps)
    finally:
        peer.close()


def rotorpy_table(sizes, repetitions, smoke, threads):
    print(f"RotorPy 3.0's batched QuadrotorEnv (torch {torch.__version__.split('+')[0]}, "
          f"{threads} threads) and aerobox's vector environment (aerobox/Hover-v0, {threads} "
          "threads), both stable-baselines3 VecEnvs at 100 Hz, action cmd_ctbr / ctbr, the "
          f"Crazyflie. Medians of {repetitions}.\n")
    print("| worlds | RotorPy: env steps/s | aerobox MuJoCo: env steps/s | aerobox / RotorPy | "
          "aerobox rigid: env steps/s | rigid / RotorPy |")
    print("|---|---|---|---|---|---|")
    for n in sizes:
        steps = 5 if smoke else max(20, 6400 // n)
        a, b = medians(
            repetitions,
            lambda: rate(make_default_vec_env(n, quad_params, "cmd_ctbr", torch.device("cpu")), n,
                         steps),
            lambda: rate(AeroboxVecEnv("aerobox/Hover-v0", n, action="ctbr"), n, steps))
        c = statistics.median(
            rate(AeroboxVecEnv("aerobox/Hover-v0", n, action="ctbr", backend="rigid"), n,
                 steps * 10) for _ in range(repetitions))
        print(f"| {n} | {a:.0f} | {b:.0f} | {b / a:.1f} | {c:.0f} | {c / a:.1f} |", flush=True)


def pyflyt_table(sizes, repetitions, smoke):
    print(f"\nPyFlyt 0.29.0's PyFlyt/QuadX-Hover-v4 (PyBullet; {PYFLYT_HZ} Hz, Gymnasium's "
          "SyncVectorEnv, one thread) and aerobox/Hover-v0 (100 Hz, its own vector environment, "
          f"gym.make_vec), body rates and thrust. Medians of {repetitions}.\n")
    print("| worlds | PyFlyt: env steps/s | PyFlyt: simulated s per wall s | aerobox: env steps/s "
          "| aerobox: simulated s per wall s | aerobox / PyFlyt (simulated s) | aerobox rigid: "
          "simulated s per wall s | rigid / PyFlyt |")
    print("|---|---|---|---|---|---|---|---|")
    hover = np.array([0.1, 0.0, 0.0, 0.0])
    for n in sizes:
        steps = 5 if smoke else max(20, 3200 // n)
        a, b = medians(
            repetitions, lambda: pyflyt_rate(n, steps),
            lambda: gym_rate(gym.make_vec("aerobox/Hover-v0", num_envs=n, action="ctbr"), hover,
                             steps))
        c = statistics.median(
            gym_rate(gym.make_vec("aerobox/Hover-v0", num_envs=n, action="ctbr", backend="rigid"),
                     hover, steps * 10) for _ in range(repetitions))
        print(f"| {n} | {a:.0f} | {a / PYFLYT_HZ:.0f} | {b:.0f} | {b / 100:.0f} | "
              f"{(b / 100) / (a / PYFLYT_HZ):.1f} | {c / 100:.0f} | "
              f"{(c / 100) / (a / PYFLYT_HZ):.1f} |", flush=True)


def l2f_rate(n, steps, warm_up=5):
    """Environment steps per second of L2F's vector environment of n worlds: observe and step,
    the motors at mid-command, every world started again from a sampled state every 500 steps
    (5 s episodes)."""
    import l2f

    vector = getattr(l2f, f"vector{n}")
    device, rng, env = l2f.Device(), vector.VectorRng(), vector.VectorEnvironment()
    params, state, after = vector.VectorParameters(), vector.VectorState(), vector.VectorState()
    vector.initialize_rng(device, rng, 1)
    vector.initialize_environment(device, env)
    vector.sample_initial_parameters(device, env, params, rng)
    observation = np.zeros((n, env.OBSERVATION_DIM), np.float32)
    action = np.zeros((n, 4), np.float32)
    begin = None
    for k in range(warm_up + steps):
        if k == warm_up:
            begin = time.perf_counter()
        if k % 500 == 0:
            vector.sample_initial_state(device, env, params, state, rng)
        vector.observe(device, env, params, state, observation, rng)
        vector.step(device, env, params, state, action, after, rng)
        state.assign(after)
    return n * steps / (time.perf_counter() - begin)


def l2f_table(sizes, repetitions, smoke):
    try:
        import l2f  # noqa: F401
    except ImportError:
        print("\nL2F (`l2f` from PyPI) is not in the project environment: tools/setup.sh --bench "
              "(run by tools/bench.sh) builds it.")
        return
    print(f"\nL2F 2.0's vector environment (\"Learning to Fly in Seconds\", C++ through pybind11, "
          "100 Hz, one 10 ms integration step per step, observe and step, no contacts or "
          "obstacles) and aerobox/Hover-v0 (100 Hz, its own vector environment, gym.make_vec), "
          "motor commands: on MuJoCo at 1 ms, and on the rigid backend at L2F's 10 ms. Medians "
          f"of {repetitions}.\n")
    print("| worlds | L2F: env steps/s | aerobox MuJoCo: env steps/s | aerobox rigid, 10 ms: env "
          "steps/s | MuJoCo / L2F | rigid / L2F |")
    print("|---|---|---|---|---|---|")
    for n in sizes:
        steps = 5 if smoke else max(200, 400000 // n)
        a, b = medians(
            repetitions, lambda: l2f_rate(n, steps),
            lambda: gym_rate(gym.make_vec("aerobox/Hover-v0", num_envs=n, action="thrusts"),
                             np.zeros(4), max(5, steps // 100)))
        c = statistics.median(
            gym_rate(gym.make_vec("aerobox/Hover-v0", num_envs=n, action="thrusts",
                                  backend="rigid", physics_rate=100), np.zeros(4), steps)
            for _ in range(repetitions))
        print(f"| {n} | {a:.0f} | {b:.0f} | {c:.0f} | {b / a:.3f} | {c / a:.3f} |", flush=True)


CRAZYFLOW_PYTHON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                ".venv-crazyflow", "bin", "python")


def crazyflow_rates(sizes, repetitions, smoke):
    """{worlds: simulated s per wall s} of crazyflow's Sim, from its own environment."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "crazyflow_peer.py")
    argv = [CRAZYFLOW_PYTHON, script, str(repetitions), "10"] + [str(n) for n in sizes]
    with tempfile.TemporaryDirectory() as folder:  # MuJoCo's MUJOCO_LOG.TXT lands there
        done = subprocess.run(argv + (["--smoke"] if smoke else []), capture_output=True,
                              text=True, check=True, cwd=folder)
    rows = [line.split()[1:] for line in done.stdout.splitlines() if line.startswith("rate ")]
    return {int(n): float(r) for n, r in rows}


def crazyflow_table(sizes, repetitions, smoke):
    if not os.path.exists(CRAZYFLOW_PYTHON):
        print("\ncrazyflow is not installed in its environment (.venv-crazyflow): tools/setup.sh "
              "--bench (run by tools/bench.sh) makes it.")
        return
    print("\ncrazyflow 0.4's Sim (JAX on the CPU, its own environment; attitude control, 10 "
          "physics steps of 2 ms per command, no wrapper) and aerobox/Hover-v0 on the rigid "
          "backend (gym.make_vec, 100 Hz, rates and thrust; its physics at 1 ms and at 2 ms). "
          f"Simulated seconds per wall second, medians of {repetitions}.\n")
    print("| worlds | crazyflow | aerobox rigid, 1 ms | aerobox rigid, 2 ms | aerobox / crazyflow "
          "(1 ms, 2 ms) |\n|---|---|---|---|---|")
    theirs = crazyflow_rates(sizes, repetitions, smoke)
    for n in sizes:
        steps = 5 if smoke else max(100, 200000 // n)
        ours = []
        for physics in (1000, 500):
            envs = gym.make_vec("aerobox/Hover-v0", num_envs=n, backend="rigid",
                                physics_rate=physics)
            ours.append(statistics.median(gym_rate(envs, np.zeros(4), steps)
                                          for _ in range(repetitions)) / 100.0)
        print(f"| {n} | {theirs[n]:.0f} | {ours[0]:.0f} | {ours[1]:.0f} | "
              f"{ours[0] / theirs[n]:.2f}, {ours[1] / theirs[n]:.2f} |", flush=True)


def training_row(smoke):
    """Runs examples/train_hover.py in this process on each backend and prints what it took and
    how the policy holds on both."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                    "examples"))
    import train_hover

    args = ["--steps", "4096", "--envs", "4", "--eval-every", "4096"] if smoke else []
    print("\nTraining a hover policy (examples/train_hover.py: PPO, 32 worlds, ctatt; until 10 of "
          "10 starts hold within 10 cm for the last 10 s of 15 s on both backends), trained on "
          "each backend.\n")
    print("| trained on | environment steps | wall time [s] | held on MuJoCo | held on the rigid "
          "backend |\n|---|---|---|---|---|")
    for backend in ("mujoco", "rigid"):
        with tempfile.TemporaryDirectory() as folder:
            log = io.StringIO()
            begin = time.perf_counter()
            with contextlib.redirect_stdout(log):
                train_hover.main(args + ["--out", os.path.join(folder, "policy"), "--backend",
                                         backend])
            wall = time.perf_counter() - begin
        checks = re.findall(r"(\d+) steps, \d+ s: .*on MuJoCo (\d+)/10, on the rigid backend "
                            r"(\d+)/10", log.getvalue())
        steps, mujoco, rigid = checks[-1]
        print(f"| {backend} | {int(steps)} | {wall:.0f} | {mujoco}/10 | {rigid}/10 |", flush=True)


def main(argv):
    smoke = "--smoke" in argv
    threads = os.cpu_count() or 1
    torch.set_num_threads(threads)
    sizes, repetitions = ([4], 1) if smoke else ([16, 64, 256], 3)
    rotorpy_table(sizes, repetitions, smoke, threads)
    pyflyt_table([4] if smoke else [1, 16, 64], repetitions, smoke)
    l2f_table([4] if smoke else [64, 1024], repetitions, smoke)
    crazyflow_table([4] if smoke else [64, 1024], repetitions, smoke)
    training_row(smoke)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
