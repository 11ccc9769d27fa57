"""aerobox bench --sections rl's crazyflow peer, run in crazyflow's own environment
(.venv-crazyflow, made by tools/setup.sh --bench: JAX and MuJoCo's MJX from PyPI, which the
project environment does not take).

crazyflow 0.4's Sim (JAX on the CPU, its default dynamics, attitude control at its 500 Hz
physics), its fastest path: no Gymnasium wrapper, no observation or reward, `sim.step(k)` of k
physics steps per control command (a jitted loop). Prints one line per world count:
"rate <worlds> <simulated seconds per wall second>" (crazyflow prints too), the median of the repetitions.

argv: repetitions, physics steps per command, then the world counts; --smoke for 5 calls.
"""

import statistics
import sys
import time
import warnings

warnings.filterwarnings("ignore")

import jax  # noqa: E402
import numpy as np  # noqa: E402
from crazyflow.control import Control  # noqa: E402
from crazyflow.sim import Sim  # noqa: E402


def simulated_per_wall(n, per_call, calls):
    sim = Sim(n_worlds=n, control=Control.attitude, freq=500, device="cpu")
    sim.reset()
    command = np.zeros((n, 1, 4), dtype=np.float32)
    command[..., 3] = 0.3  # collective thrust [N], about the Crazyflie's hover
    for _ in range(3):  # compiles
        sim.attitude_control(command)
        sim.step(per_call)
    jax.block_until_ready(sim.data)
    begin = time.perf_counter()
    for _ in range(calls):
        sim.attitude_control(command)
        sim.step(per_call)
    jax.block_until_ready(sim.data)
    return n * calls * per_call / sim.freq / (time.perf_counter() - begin)


def main(argv):
    smoke = "--smoke" in argv
    numbers = [int(a) for a in argv if not a.startswith("--")]
    repetitions, per_call, sizes = numbers[0], numbers[1], numbers[2:]
    for n in sizes:
        calls = 5 if smoke else max(20, 400000 // (n * per_call))
        rates = [simulated_per_wall(n, per_call, calls) for _ in range(repetitions)]
        print("rate", n, statistics.median(rates), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
