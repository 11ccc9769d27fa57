"""aerobox bench --sections python: a Python controller against the C++ ones, in one process.

Flies the window scenario's trajectory with the built-in C++ controllers and with a Python
SE(3) controller (the tests' own, tests/python/se3_controller.py) at 100 and 500 Hz, and with a
Python object that only forwards to the built-in cascade (the price of crossing into Python and
back, per call). Prints one Markdown table: control steps per wall second, real-time factor
(flight time / wall time), and the cost of one Python call against the same call in C++.
Run by aerobox-bench with PYTHONPATH set to the build's package; argv: scenario, tests folder,
and --smoke for one flight per controller at 100 Hz (aerobox bench --smoke).
"""

import statistics
import sys
import time

import aerobox


def main(scenario_path, tests_folder, smoke=False):
    repetitions = 1 if smoke else 3
    sys.path.insert(0, tests_folder)
    from se3_controller import SE3Control

    scenario = aerobox.load_scenario(scenario_path)
    trajectory = aerobox.min_snap(scenario, aerobox.plan(scenario, seed=scenario.seed))
    sim = aerobox.Simulator(scenario)

    class Forwarding:
        """A Python controller that asks the built-in cascade: only the crossing costs."""

        def __init__(self, rate):
            self.inner = aerobox.builtin_controller(sim, "cascade", rate)

        def update(self, t, state, flat_output):
            return self.inner.update(t, state, flat_output)

    def fly(controller, rate, command="auto"):
        """Median wall time [s] of `repetitions` flights, and the last flight."""
        walls = []
        for _ in range(repetitions):
            made = controller() if callable(controller) and not isinstance(controller, str) else controller
            begin = time.perf_counter()
            result = sim.run(made, trajectory, control_rate=rate, command=command)
            walls.append(time.perf_counter() - begin)
        return statistics.median(walls), result

    rows = []
    native = {}
    for rate in (100,) if smoke else (100, 500):
        for name, controller, command in (
                ("C++ cascade", "cascade", "auto"),
                ("C++ SE(3)", "se3", "auto"),
                ("Python SE(3)", lambda: SE3Control(sim.quad_params), "cmd_motor_thrusts"),
                ("Python forwarding to the C++ cascade", lambda r=rate: Forwarding(r), "cmd_ctatt")):
            wall, result = fly(controller, rate, command)
            steps = len(result["time"])
            if name == "C++ cascade":
                native[rate] = wall / steps
            rows.append((name, rate, steps / wall, result["flight_time"] / wall, wall / steps,
                         wall / steps - native[rate], result["status"], result["tracking_rms"]))
    print(f"Window scenario, {trajectory.duration:.1f} s trajectory; medians of {repetitions} "
          "flights each, in one process.\n")
    print("| controller | rate [Hz] | control steps / s | real-time factor | wall per step [us] "
          "| over the C++ cascade [us] | status | tracking RMS [cm] |")
    print("|---|---|---|---|---|---|---|---|")
    for name, rate, per_second, factor, per_step, extra, status, rms in rows:
        print(f"| {name} | {rate} | {per_second:,.0f} | {factor:.1f}x | {per_step * 1e6:.1f} | "
              f"{extra * 1e6:+.1f} | {status} | {rms * 100:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], smoke=sys.argv[3:] == ["--smoke"])
