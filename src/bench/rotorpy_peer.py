"""aerobox bench --sections rotorpy: RotorPy's own Environment against aerobox.rotorpy's, on the
same scripts, in one process.

Each script is a RotorPy user's: RotorPy's Multirotor, SE3Control, trajectory, wind and default
sensors, with the Environment class the only change. Both run it in turn (medians of 3 runs;
RotorPy first); the table gives the wall times, aerobox's speed-up (RotorPy's wall time over
aerobox's), and how far apart the two flights ever were. Run by aerobox-bench with the project
environment's python (.venv: RotorPy from PyPI) and PYTHONPATH set to the build's package;
argv: --smoke for one 1 s run of the first script (aerobox bench --smoke).
"""

import statistics
import sys
import time
import warnings

import numpy as np
from rotorpy.controllers.quadrotor_control import SE3Control
from rotorpy.environments import Environment as RotorPyEnvironment
from rotorpy.trajectories.circular_traj import ThreeDCircularTraj
from rotorpy.trajectories.hover_traj import HoverTraj
from rotorpy.vehicles.crazyflie_params import quad_params as crazyflie
from rotorpy.vehicles.hummingbird_params import quad_params as hummingbird
from rotorpy.vehicles.multirotor import Multirotor
from rotorpy.wind.default_winds import ConstantWind, SinusoidWind

from aerobox.rotorpy import Environment

CIRCLE = ThreeDCircularTraj(center=np.array([0, 0, 1.0]), radius=np.array([1, 1, 0]),
                            freq=np.array([0.2, 0.2, 0]))
# (name, quad_params, hover speed [rad/s], trajectory, wind profile, sim_rate [Hz], t_final [s])
SCRIPTS = [
    ("Crazyflie, 1 m circle, 2 m/s wind", crazyflie, 1788.53, CIRCLE,
     lambda: ConstantWind(2, 0, 0), 100, 10.0),
    ("Crazyflie, hover, gusting wind", crazyflie, 1788.53, HoverTraj(x0=np.array([0, 0, 1.0])),
     lambda: SinusoidWind(amplitudes=np.array([1.0, 1.0, 0.0])), 100, 10.0),
    ("Hummingbird, 1 m circle, no wind", hummingbird, 1788.53, CIRCLE, lambda: None, 100, 10.0),
    ("Crazyflie, 1 m circle, 2 m/s wind, 500 Hz", crazyflie, 1788.53, CIRCLE,
     lambda: ConstantWind(2, 0, 0), 500, 5.0),
]


def run(environment, params, hover, trajectory, wind, rate, t_final):
    start = trajectory.update(0.0)["x"]
    state = {"x": np.array(start, dtype=float), "v": np.zeros(3), "q": np.array([0, 0, 0, 1.0]),
             "w": np.zeros(3), "wind": np.zeros(3), "rotor_speeds": np.full(4, hover)}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # aerobox's vehicle notes, said in the docs
        env = environment(vehicle=Multirotor(params, initial_state=state),
                          controller=SE3Control(params), trajectory=trajectory,
                          wind_profile=wind(), sim_rate=rate)
    begin = time.perf_counter()
    result = env.run(t_final=t_final)
    return time.perf_counter() - begin, result


def main(smoke=False):
    repetitions = 1 if smoke else 3
    scripts = [SCRIPTS[0][:6] + (1.0,)] if smoke else SCRIPTS
    print(f"Medians of {repetitions} runs each, in one process. flightsim is not on PyPI and "
          "not run here.\n")
    print("| script | sim rate [Hz] | flight [s] | RotorPy wall [s] | aerobox wall [s] "
          "| aerobox speed-up | flights apart, max [mm] | exits (RotorPy, aerobox) |")
    print("|---|---|---|---|---|---|---|---|")
    for name, params, hover, trajectory, wind, rate, t_final in scripts:
        walls = {}
        results = {}
        for environment in (RotorPyEnvironment, Environment):
            times = []
            for _ in range(repetitions):
                wall, results[environment] = run(environment, params, hover, trajectory, wind,
                                                 rate, t_final)
                times.append(wall)
            walls[environment] = statistics.median(times)
        theirs, ours = results[RotorPyEnvironment], results[Environment]
        apart = np.linalg.norm(theirs["state"]["x"] - ours["state"]["x"], axis=1).max()
        print(f"| {name} | {rate} | {ours['time'][-1]:.1f} | {walls[RotorPyEnvironment]:.3f} "
              f"| {walls[Environment]:.3f} "
              f"| {walls[RotorPyEnvironment] / walls[Environment]:.1f}x | {apart * 1e3:.1f} "
              f"| {theirs['exit'].name}, {ours['exit'].name} |", flush=True)


if __name__ == "__main__":
    main(smoke=sys.argv[1:] == ["--smoke"])
