"""import aerobox: the package flies Python controllers and trajectories in aerobox's physics,
with the success checks of the command's flights (DESIGN.md: reached, no contact, clearance,
tracking), and refuses bad commands with the key and the time."""

import math
import os
import sys
import tempfile
import unittest

import numpy as np

import aerobox

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from se3_controller import SE3Control  # noqa: E402
from user_parts import Smoothstep, WindowPlanner  # noqa: E402

SOURCE = os.environ.get("AEROBOX_SOURCE_DIR", os.path.join(HERE, "..", ".."))
WINDOW = os.path.join(SOURCE, "scenes", "window", "scenario.toml")


def assert_success(test, result):
    """The scenario tests' criteria: the goal reached, no contact, a positive clearance,
    tracking RMS under 6 cm and at most 15 cm."""
    test.assertEqual(result["status"], "reached goal")
    test.assertEqual(result["collisions"], 0)
    test.assertGreater(result["min_clearance"], 0.0)
    test.assertLess(result["tracking_rms"], 0.06)
    test.assertLess(result["tracking_max"], 0.15)


def empty_map(folder, size=6.0, height=4.0):
    path = os.path.join(folder, "open.txt")
    with open(path, "w") as file:
        file.write(f"boundary {-size} {-size} 0 {size} {size} {height}\n")
    return path


class Circle:
    """A horizontal circle of radius r [m] at height z [m] and period T [s], its angular speed
    rising over the first `ramp` seconds (a quintic smoothstep), so that it starts at rest."""

    def __init__(self, r=1.0, z=1.5, period=4.0, laps=2, ramp=2.0):
        self.r, self.z, self.omega, self.ramp = r, z, 2 * math.pi / period, ramp
        self.duration = laps * period + ramp / 2

    def _angle(self, t):
        """The angle [rad] and its first two derivatives."""
        w, ramp = self.omega, self.ramp
        if t >= ramp:
            return w * (t - ramp / 2), w, 0.0
        s = t / ramp
        return (w * ramp * (2.5 * s**4 - 3 * s**5 + s**6),
                w * (10 * s**3 - 15 * s**4 + 6 * s**5),
                w * (30 * s**2 - 60 * s**3 + 30 * s**4) / ramp)

    def update(self, t):
        a, da, dda = self._angle(t)
        r, c, s = self.r, math.cos(a), math.sin(a)
        return {
            "x": np.array([r * c, r * s, self.z]),
            "x_dot": np.array([-r * s * da, r * c * da, 0.0]),
            "x_ddot": np.array([-r * c * da * da - r * s * dda, -r * s * da * da + r * c * dda,
                                0.0]),
            "x_dddot": np.zeros(3), "x_ddddot": np.zeros(3), "yaw": 0.0, "yaw_dot": 0.0,
        }


class WindowFlights(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.scenario = aerobox.load_scenario(WINDOW)
        cls.path = aerobox.plan(cls.scenario, seed=cls.scenario.seed)
        cls.trajectory = aerobox.min_snap(cls.scenario, cls.path)
        cls.sim = aerobox.Simulator(cls.scenario)

    def test_api_shapes_and_units(self):
        self.assertEqual(self.path.shape[1], 3)
        np.testing.assert_allclose(self.path[0], self.scenario.start, atol=0.2)
        self.assertGreater(self.trajectory.duration, 5.0)
        flat = self.trajectory.update(0.0)
        self.assertEqual(set(flat), {"x", "x_dot", "x_ddot", "x_dddot", "x_ddddot", "yaw",
                                     "yaw_dot"})
        np.testing.assert_allclose(flat["x"], self.path[0], atol=1e-9)
        state = self.sim.reset()
        self.assertEqual(state["q"].shape, (4,))
        self.assertAlmostEqual(state["q"][3], 1.0)  # [i, j, k, w]: level at rest
        doc = aerobox.Simulator.__doc__ + aerobox.Simulator.run.__doc__
        for words in ("ENU", "[i, j, k, w]", "body", "[m]", "[N]", "[rad/s]", "[Hz]"):
            self.assertIn(words, aerobox.__doc__ + doc)

    def test_python_se3_controller_flies_the_window(self):
        result = self.sim.run(SE3Control(self.sim.quad_params), self.trajectory, control_rate=500)
        assert_success(self, result)
        n = len(result["time"])
        self.assertEqual(result["state"]["x"].shape, (n, 3))
        self.assertEqual(result["state"]["q"].shape, (n, 4))
        self.assertEqual(result["control"]["cmd_motor_thrusts"].shape, (n, 4))
        self.assertAlmostEqual(result["time"][1] - result["time"][0], 1 / 500, places=9)
        # the flight ends at the goal
        np.testing.assert_allclose(result["state"]["x"][-1], self.path[-1], atol=0.1)

    def test_the_same_seed_gives_the_same_flight(self):
        controller = SE3Control(self.sim.quad_params)
        a = self.sim.run(controller, self.trajectory, control_rate=250)
        b = self.sim.run(controller, self.trajectory, control_rate=250)
        np.testing.assert_array_equal(a["state"]["x"], b["state"]["x"])

    def test_each_command_key_flies_the_cascade_s_own_commands(self):
        # the built-in cascade at 1 kHz is the reference; the same cascade as a Python object
        # answers with every level at once, and each level, flown alone, gives the same flight
        reference = self.sim.run("cascade", self.trajectory, t_final=6.0, control_rate=1000)
        self.assertEqual(reference["collisions"], 0)
        for command in ("cmd_ctatt", "cmd_ctbr", "cmd_ctbm", "cmd_motor_thrusts",
                        "cmd_motor_speeds"):
            with self.subTest(command=command):
                wrapped = aerobox.builtin_controller(self.sim, "cascade", rate=1000)
                flown = self.sim.run(wrapped, self.trajectory, t_final=6.0, control_rate=1000,
                                     command=command)
                self.assertEqual(len(flown["time"]), len(reference["time"]))
                gap = np.abs(flown["state"]["x"] - reference["state"]["x"]).max()
                self.assertLess(gap, 1e-6, f"{command}: {gap} m from the cascade's flight")

    def test_python_planner_and_python_trajectory(self):
        world = self.scenario.map.world()
        self.assertEqual(len(world["blocks"]), len(self.scenario.map.boxes))
        start, goal = self.path[0], self.path[-1]
        waypoints = WindowPlanner().plan(world, start, goal)
        for a, b in zip(waypoints[:-1], waypoints[1:]):
            for s in np.linspace(0, 1, 50):
                self.assertGreater(self.scenario.map.clearance(a + s * (b - a)), 0.0)
        # the user's waypoints through aerobox's min-snap, and the user's own trajectory
        ours = aerobox.min_snap(self.scenario, waypoints)
        assert_success(self, self.sim.run(SE3Control(self.sim.quad_params), ours))
        theirs = Smoothstep(waypoints)
        result = self.sim.run(SE3Control(self.sim.quad_params), theirs)
        assert_success(self, result)

    def test_write_outputs_writes_what_fly_writes(self):
        result = self.sim.run(SE3Control(self.sim.quad_params), self.trajectory, t_final=3.0)
        with tempfile.TemporaryDirectory() as folder:
            out = aerobox.write_outputs(result, os.path.join(folder, "run"), video=True,
                                        size=(160, 120), fps=10)
            names = set(os.listdir(out))
            for name in ("path.csv", "trajectory.csv", "telemetry.csv", "summary.json",
                         "overview.png", "video.mp4", "report.html"):
                self.assertIn(name, names)
            with open(os.path.join(out, "report.html"), encoding="utf-8") as file:
                page = file.read()
            self.assertIn('"controller":"python:SE3Control"', page.replace(" ", ""))
            import json
            with open(os.path.join(out, "summary.json")) as file:
                summary = json.load(file)
            self.assertEqual(summary["controller"], "python:SE3Control")
            self.assertAlmostEqual(summary["tracking_rms_m"], result["tracking_rms"])
            with open(os.path.join(out, "telemetry.csv")) as file:
                rows = file.read().splitlines()
            self.assertEqual(len(rows) - 1, len(result["time"]))
            with self.assertRaises(ValueError):
                aerobox.write_outputs(result, os.path.join(folder, "bad"), size=(161, 120))
            self.assertFalse(os.path.exists(os.path.join(folder, "bad", "summary.json")))

    def test_write_outputs_of_a_built_in_controller_keeps_its_own_columns(self):
        # the cascade reports six columns of its own: the written table has them, row by row
        result = self.sim.run("cascade", self.trajectory, t_final=2.0)
        with tempfile.TemporaryDirectory() as folder:
            out = aerobox.write_outputs(result, os.path.join(folder, "run"), video=False)
            with open(os.path.join(out, "telemetry.csv")) as file:
                rows = file.read().splitlines()
        header = rows[0].split(",")
        for column in ("vx_sp", "vy_sp", "vz_sp", "ax_sp", "ay_sp", "az_sp"):
            self.assertIn(column, header)
        self.assertEqual(len(rows) - 1, len(result["time"]))
        self.assertTrue(all(len(row.split(",")) == len(header) for row in rows[1:]))
        # the result's telemetry has the same columns, from the same schema, and is one
        # pandas.DataFrame call away
        table = result["telemetry"]
        self.assertEqual(list(table), header)
        np.testing.assert_array_equal(table["x"], result["state"]["x"][:, 0])
        np.testing.assert_array_equal(table["f3"], result["rotor_thrusts"][:, 2])
        import pandas
        frame = pandas.DataFrame(table)
        self.assertEqual(frame.shape, (len(result["time"]), len(header)))
        np.testing.assert_allclose(frame["vx_sp"].to_numpy(),
                                   [float(row.split(",")[header.index("vx_sp")])
                                    for row in rows[1:]], atol=1e-5)


class WindAndSensors(unittest.TestCase):
    """The scenario's [wind], [aero] and [sensors] as keywords: a Python controller flies the
    circle in a breeze on the estimate, and the result carries the wind and the estimate."""

    def test_a_python_controller_flies_on_the_estimate_in_wind(self):
        with tempfile.TemporaryDirectory() as folder:
            keys = dict(
                start=[1.0, 0.0, 1.5],
                wind={"mean": [1.5, 0.0, 0.0], "turbulence": "dryden", "intensity": 0.3,
                      "gusts": [{"start": 2.0, "peak": 1.0, "direction": [0, 1, 0]}]},
                sensors={"imu": True, "position": {"kind": "mocap", "latency": 0.02}})
            sim = aerobox.Simulator(empty_map(folder), **keys)
            controller = SE3Control(sim.quad_params)
            result = sim.run(controller, Circle(), control_rate=500)
            self.assertEqual(result["status"], "reached goal")
            n = len(result["time"])
            self.assertEqual(result["wind"].shape, (n, 3))
            self.assertGreater(result["max_wind"], 1.0)
            self.assertGreater(np.abs(result["drag"][:, 0]).max(), 0.0)  # the wind brought drag
            self.assertEqual(result["estimate"]["x"].shape, (n, 3))
            self.assertEqual(result["imu"]["accel"].shape, (n, 3))
            self.assertLess(result["estimate_rms"], 0.005)
            # the test's SE3 controller has no integral term and knows nothing of drag: the
            # breeze leaves it a steady offset downwind (about 11 cm)
            self.assertLess(result["tracking_rms"], 0.2)
            offset = result["state"]["x"] - result["flat"]["x"]
            self.assertGreater(offset[n // 2:, 0].mean(), 0.05)
            # the controller saw the estimate, not the truth: they differ a little
            self.assertGreater(np.abs(result["estimate"]["x"] - result["state"]["x"]).max(), 0)
            # the same seed repeats, another seed does not
            again = sim.run(controller, Circle(), control_rate=500)
            np.testing.assert_array_equal(result["wind"], again["wind"])
            sim.reset(seed=2)
            other = sim.run(controller, Circle(), control_rate=500)
            self.assertFalse(np.array_equal(result["wind"], other["wind"]))
            out = aerobox.write_outputs(result, os.path.join(folder, "run"), video=False)
            with open(os.path.join(out, "telemetry.csv")) as file:
                header = file.readline()
            for column in ("wind_x", "drag_x", "est_x", "est_nees", "imu_gx", "meas_x"):
                self.assertIn(column, header)

    def test_indi_by_name_holds_the_circle_in_wind(self):
        # in this breeze se3 without its position integral (built in, as the Python one above)
        # is held downwind by about 5 cm; INDI, by name, measures the IMU's acceleration and the
        # rotors' thrusts and is not (measured: 5.3 cm and -0.4 cm, the mean over the second
        # half). It cannot be wrapped as a Python object (a state dict carries no acceleration),
        # and says so. se3 by default, its integral on in wind, is held within 2 cm (-1.7 cm).
        with tempfile.TemporaryDirectory() as folder:
            breeze = dict(start=[1.0, 0.0, 1.5],
                          wind={"mean": [1.5, 0.0, 0.0], "turbulence": "dryden", "intensity": 0.3},
                          sensors={"imu": True, "position": True})
            default = aerobox.Simulator(empty_map(folder), **breeze).run("se3", Circle(),
                                                                          control_rate=500)
            half = len(default["time"]) // 2
            self.assertLess(abs((default["state"]["x"][half:, 0]
                                 - default["flat"]["x"][half:, 0]).mean()), 0.02)
            sim = aerobox.Simulator(empty_map(folder), controller={"se3_position_integral": 0},
                                    **breeze)
            offsets = {}
            for kind in ("se3", "indi"):
                result = sim.run(kind, Circle(), control_rate=500)
                self.assertEqual(result["status"], "reached goal")
                half = len(result["time"]) // 2
                offset = result["state"]["x"][half:, 0] - result["flat"]["x"][half:, 0]
                offsets[kind] = offset.mean()
            self.assertGreater(offsets["se3"], 0.04)
            self.assertLess(abs(offsets["indi"]), 0.015)
            with self.assertRaisesRegex(ValueError, "indi.*acceleration.*Simulator.run"):
                aerobox.builtin_controller(sim, "indi")

    def test_the_controller_sees_the_wind_and_the_rotors(self):
        # RotorPy's state['wind'] is the wind at the vehicle [m/s] (it was always zero), and
        # state['rotor_speeds'] the rotors' speeds [rad/s], also under an attitude command
        class Seeing(SE3Control):
            def __init__(self, quad_params):
                super().__init__(quad_params)
                self.seen = []

            def update(self, t, state, flat_output):
                self.seen.append((np.array(state["wind"]), np.array(state["rotor_speeds"])))
                return super().update(t, state, flat_output)

        with tempfile.TemporaryDirectory() as folder:
            sim = aerobox.Simulator(empty_map(folder), start=[1.0, 0.0, 1.5],
                                    wind={"mean": [2.0, 0.0, 0.0]})
        controller = Seeing(sim.quad_params)
        result = sim.run(controller, Circle(r=0.0, laps=1), control_rate=500)
        self.assertEqual(result["status"], "reached goal")
        wind = np.array([w for w, _ in controller.seen])
        speeds = np.array([s for _, s in controller.seen])
        np.testing.assert_allclose(wind[1:], np.tile([2.0, 0.0, 0.0], (len(wind) - 1, 1)))
        # the rotors' speeds: what the produced thrusts need through k_eta, near hover
        k_eta = sim.quad_params["k_eta"]
        produced = np.sqrt(result["rotor_thrusts"] / k_eta)
        np.testing.assert_allclose(speeds[1:], produced[:-1], rtol=0.05)
        hover = math.sqrt(sim.quad_params["mass"] * 9.81 / 4 / k_eta)
        self.assertLess(abs(np.median(speeds) - hover) / hover, 0.1)

    def test_bad_wind_keys_name_the_key(self):
        with tempfile.TemporaryDirectory() as folder:
            with self.assertRaisesRegex(ValueError, "wind.turbulence"):
                aerobox.Simulator(empty_map(folder), wind={"turbulence": "karman"})
            # a keyword is named as the Python argument it is, with its scenario key, not by a
            # line of a file the package wrote
            with self.assertRaises(ValueError) as raised:
                aerobox.Simulator(empty_map(folder), wind={"intensty": 1.0})
            self.assertTrue(str(raised.exception).startswith(
                "aerobox.Simulator: wind['intensty'] (wind.intensty): unknown key"),
                str(raised.exception))
            self.assertIn("did you mean intensity?", str(raised.exception))
            with self.assertRaises(ValueError) as raised:
                aerobox.plan(empty_map(folder), max_iterations=-3)
            self.assertTrue(str(raised.exception).startswith(
                "aerobox.plan: max_iterations (planner.max_iterations): expected a whole number"),
                str(raised.exception))
            with self.assertRaises(ValueError) as raised:
                aerobox.Simulator(empty_map(folder), vehicle="blimp")
            self.assertIn("aerobox.Simulator: vehicle (vehicle.kind): expected", str(raised.exception))


class StepIsRun(unittest.TestCase):
    """step() is run()'s world a control step at a time: the same wind, drag, sensors,
    estimator and inner loops with the same seeds, so a loop of step() calls flies run()'s
    flight to the bit."""

    KEYS = dict(
        start=[1.0, 0.0, 1.5],
        wind={"mean": [1.5, 0.0, 0.0], "turbulence": "dryden", "intensity": 0.3,
              "gusts": [{"start": 0.5, "peak": 1.0, "direction": [0, 1, 0]}]},
        aero={"drag": True},
        sensors={"imu": True, "position": {"kind": "mocap", "latency": 0.02}})

    def fly_both(self, sim, seed, rate=250, t_final=1.5):
        circle = Circle()
        sim.reset(seed=seed)
        run = sim.run(SE3Control(sim.quad_params), circle, t_final=t_final, control_rate=rate,
                      terminate=False)
        controller = SE3Control(sim.quad_params)
        state = sim.reset(seed=seed)
        rows = []
        for _ in range(len(run["time"])):
            t = sim.time
            truth = sim.state
            rows.append((t, truth["x"], truth["q"], state["x"], state["wind"]))
            state = sim.step(controller.update(t, state, circle.update(t)), 1 / rate)
        return run, rows

    def test_a_step_loop_flies_as_run_does_in_wind_with_sensors(self):
        with tempfile.TemporaryDirectory() as folder:
            sim = aerobox.Simulator(empty_map(folder), **self.KEYS)
            run, rows = self.fly_both(sim, seed=3)
            self.assertEqual(run["status"], "completed")
            self.assertGreater(len(rows), 300)
            np.testing.assert_array_equal([r[0] for r in rows], run["time"])
            np.testing.assert_array_equal([r[1] for r in rows], run["state"]["x"])
            np.testing.assert_array_equal([r[2] for r in rows], run["state"]["q"])
            # the controller flew on the estimate, in the wind, both times
            np.testing.assert_array_equal([r[3] for r in rows], run["estimate"]["x"])
            np.testing.assert_array_equal([r[4] for r in rows], run["wind"])
            self.assertGreater(np.abs(run["wind"][:, 1]).max(), 0.5)  # the gust blew
            self.assertGreater(np.abs(run["estimate"]["x"] - run["state"]["x"]).max(), 0)
            # another seed is another flight, for step() as for run()
            other, other_rows = self.fly_both(sim, seed=4)
            self.assertFalse(np.array_equal(other["wind"], run["wind"]))
            np.testing.assert_array_equal([r[1] for r in other_rows], other["state"]["x"])

    def test_with_motor_noise_too(self):
        # the rotors' noise is drawn at each control period's end, in step() as in run()
        with tempfile.TemporaryDirectory() as folder:
            noisy = dict(RotorPyVehicle.QUAD_PARAMS, motor_noise_std=20.0)
            sim = aerobox.Simulator(empty_map(folder), vehicle=noisy, start=[1.0, 0.0, 1.5])
            run, rows = self.fly_both(sim, seed=3, rate=100)
            np.testing.assert_array_equal([r[1] for r in rows], run["state"]["x"])
            np.testing.assert_array_equal([r[2] for r in rows], run["state"]["q"])
            other, _ = self.fly_both(sim, seed=4, rate=100)
            quiet = aerobox.Simulator(empty_map(folder), start=[1.0, 0.0, 1.5],
                                      vehicle=dict(noisy, motor_noise_std=0.0))
            still, _ = self.fly_both(quiet, seed=3, rate=100)
            # the noise moved the vehicle, and another seed drew other noise
            self.assertGreater(np.abs(run["state"]["x"] - still["state"]["x"]).max(), 1e-4)
            self.assertGreater(np.abs(run["state"]["x"] - other["state"]["x"]).max(), 1e-4)

    def test_the_seed_given_to_the_simulator_is_the_run_s(self):
        with tempfile.TemporaryDirectory() as folder:
            a = aerobox.Simulator(empty_map(folder), seed=7, **self.KEYS)
            b = aerobox.Simulator(empty_map(folder), **self.KEYS)
            b.reset(seed=7)
            flown = [sim.run(SE3Control(sim.quad_params), Circle(), t_final=1.0, terminate=False)
                     for sim in (a, b)]
            self.assertEqual(flown[0]["seed"], 7)
            np.testing.assert_array_equal(flown[0]["wind"], flown[1]["wind"])

    def test_a_vehicle_reset_in_the_air_hovers(self):
        # the rotors start at hover thrust, as RotorPy's: held level at hover thrust for 50 ms
        # it neither drops nor climbs by more than a millimetre
        with tempfile.TemporaryDirectory() as folder:
            sim = aerobox.Simulator(empty_map(folder), start=[0.0, 0.0, 1.0])
            state = sim.reset()
            hover = sim.quad_params["mass"] * 9.81
            for _ in range(10):
                state = sim.step({"cmd_thrust": hover, "cmd_q": [0, 0, 0, 1]}, 0.005)
            self.assertLess(abs(state["x"][2] - 1.0), 1e-3)
            self.assertLess(np.linalg.norm(state["v"]), 0.02)


class PythonWind(unittest.TestCase):
    """wind= an object with update(t, position) (RotorPy's wind profiles): asked every physics
    step with the time and the vehicle's position, it blows through the drag, in run() and in
    step() alike, and the state carries it."""

    class Ramp:
        def __init__(self):
            self.calls = []

        def update(self, t, position):
            self.calls.append((t, np.array(position)))
            return np.array([2.0 * min(t, 1.0), 0.0, 0.0])

    def test_a_wind_object_blows(self):
        with tempfile.TemporaryDirectory() as folder:
            wind = self.Ramp()
            sim = aerobox.Simulator(empty_map(folder), start=[1.0, 0.0, 1.5], wind=wind,
                                    aero={"drag": True})
            still = aerobox.Simulator(empty_map(folder), start=[1.0, 0.0, 1.5],
                                      aero={"drag": True})
            wind.calls.clear()
            flown = [s.run(SE3Control(s.quad_params), Circle(), t_final=3.0, terminate=False)
                     for s in (sim, still)]
            n = len(flown[0]["time"])
            self.assertEqual(flown[0]["status"], "completed")
            # the start, then every 1 ms physics step, asked the wind where the vehicle was
            self.assertGreaterEqual(len(wind.calls), 3000)
            times = np.array([t for t, _ in wind.calls[1:]])
            np.testing.assert_allclose(np.diff(times), 0.001, atol=1e-9)
            np.testing.assert_allclose(wind.calls[-1][1], flown[0]["state"]["x"][-1], atol=0.01)
            np.testing.assert_allclose(flown[0]["wind"][n // 2:], [[2.0, 0.0, 0.0]] * (n - n // 2))
            # downwind of the still-air flight (the test's SE3 has no integral term)
            offset = flown[0]["state"]["x"][n // 2:, 0] - flown[1]["state"]["x"][n // 2:, 0]
            self.assertGreater(offset.mean(), 0.02)
            # step() flies in it too, and the state says so
            state = sim.reset()
            for _ in range(300):
                state = sim.step({"cmd_thrust": sim.quad_params["mass"] * 9.81,
                                  "cmd_q": [0, 0, 0, 1]}, 0.005)
            np.testing.assert_allclose(state["wind"], [2.0, 0.0, 0.0])
            self.assertGreater(state["v"][0], 0.05)

    def test_a_bad_wind_names_the_call_and_the_time(self):
        class Broken:
            def update(self, t, position):
                return [1.0, 2.0] if t > 0.5 else [0.0, 0.0, 0.0]

        with tempfile.TemporaryDirectory() as folder:
            sim = aerobox.Simulator(empty_map(folder), start=[1.0, 0.0, 1.5], wind=Broken(),
                                    aero={"drag": True})
            with self.assertRaises(ValueError) as raised:
                sim.run(SE3Control(sim.quad_params), Circle(), t_final=1.0, terminate=False)
            self.assertIn("wind.update at t = 0.5 s: the wind has shape (2,)",
                          str(raised.exception))
            with self.assertRaises(TypeError) as raised:
                aerobox.Simulator(empty_map(folder), wind=3.0)
            self.assertIn("wind: expected a dict of [wind] keys or an object with update(t, "
                          "position)", str(raised.exception))

    def test_statedot_is_the_last_step_s_acceleration(self):
        with tempfile.TemporaryDirectory() as folder:
            sim = aerobox.Simulator(empty_map(folder), start=[0.0, 0.0, 1.0])
            sim.reset()
            np.testing.assert_allclose(sim.statedot["vdot"], np.zeros(3), atol=1e-6)
            before = sim.state["v"]
            sim.step({"cmd_motor_thrusts": np.zeros(4)}, 0.001, "cmd_motor_thrusts")
            # the rotors' lag keeps most of the thrust over one step: the acceleration flown
            # is the velocity's change
            np.testing.assert_allclose(sim.statedot["vdot"] * 0.001, sim.state["v"] - before,
                                       atol=1e-9)
            self.assertEqual(sim.statedot["wdot"].shape, (3,))


class WholeRun(unittest.TestCase):
    """aerobox.fly is `aerobox fly` from Python: a mission through several goals, and unknown
    boxes found by the sensor with replanning, fly as the command flies them."""

    AEROBOX = os.environ.get("AEROBOX_BIN", os.path.join(SOURCE, "build", "aerobox"))

    def command(self, scenario, folder):
        import json
        import subprocess

        subprocess.run([self.AEROBOX, "fly", scenario, "--out", folder, "--no-video", "--quiet"],
                       check=True, capture_output=True)
        with open(os.path.join(folder, "summary.json")) as file:
            summary = json.load(file)
        path = np.loadtxt(os.path.join(folder, "path.csv"), delimiter=",", skiprows=1)
        return summary, path

    def test_unknown_boxes_and_replanning_as_the_command(self):
        scenario = os.path.join(SOURCE, "scenes", "maze_unknown", "scenario.toml")
        result = aerobox.fly(scenario)
        with tempfile.TemporaryDirectory() as folder:
            summary, path = self.command(scenario, folder)
        self.assertEqual(result["status"], "reached goal")
        self.assertEqual(result["mission_status"], "reached goal")
        self.assertEqual((result["unknown_boxes"], result["revealed_boxes"]),
                         (summary["unknown_boxes"], summary["revealed_boxes"]))
        self.assertGreaterEqual(len(result["replans"]), 1)
        self.assertEqual([(r["t"], r["trigger"], r["outcome"]) for r in result["replans"]],
                         [(r["t_s"], r["trigger"], r["outcome"]) for r in summary["replans"]])
        np.testing.assert_array_equal(result["path"], path)
        self.assertEqual(result["tracking_rms"], summary["tracking_rms_m"])
        self.assertEqual(len(result["revealed_at"]), len(aerobox.read_map(
            os.path.join(SOURCE, "scenes", "maze", "map.json")).boxes))

    def test_a_depth_camera_from_keywords(self):
        scenario = os.path.join(SOURCE, "scenes", "maze_unknown", "scenario.toml")
        result = aerobox.fly(scenario, sensing={"kind": "depth", "range": 4.0, "width": 80,
                                                "height": 60, "resolution": 0.1})
        # the keywords reach the camera and the map (whether the maze is flown through with a
        # depth camera is the navigation benchmark's question, not this test's)
        self.assertGreater(len(result["time"]), 100)
        boxes = len(aerobox.read_map(os.path.join(SOURCE, "scenes", "maze", "map.json")).boxes)
        self.assertEqual(len(result["revealed_distance"]), boxes)
        seen = [d for d, t in zip(result["revealed_distance"], result["revealed_at"]) if t >= 0]
        self.assertEqual(len(seen), result["revealed_boxes"])
        self.assertTrue(all(0 < d <= 4.0 for d in seen))
        occupancy = result["occupancy"]
        self.assertEqual(occupancy["resolution"], 0.1)
        self.assertGreater(occupancy["occupied"], 0)
        self.assertEqual(occupancy["occupied_boxes"].shape[1], 6)
        # per sample, the map's size as it grew, to its final size
        self.assertEqual(len(result["map_occupied"]), len(result["time"]))
        self.assertEqual(result["map_occupied"][-1], occupancy["occupied"])
        self.assertEqual(result["map_free"][-1], occupancy["free"])
        self.assertLess(result["map_free"][0], result["map_free"][-1])
        with self.assertRaises(ValueError) as raised:
            aerobox.fly(scenario, sensing={"kind": "depth", "fov": 190})
        self.assertIn("sensing.fov", str(raised.exception))

    def test_a_mission_from_keywords_with_a_python_controller(self):
        scenario = os.path.join(SOURCE, "scenes", "maze", "scenario.toml")
        goals = [[1.5, 3.0, 1.5], [5.0, 4.0, 1.5], [9.0, 7.0, 1.5]]
        sim = aerobox.Simulator(scenario)
        result = aerobox.fly(scenario, controller=SE3Control(sim.quad_params), goals=goals)
        self.assertEqual(result["status"], "reached goal")
        self.assertEqual(len(result["goal_times"]), 2)
        self.assertLess(result["goal_times"][0], result["goal_times"][1])
        for goal, t in zip(goals, result["goal_times"]):
            i = int(np.searchsorted(result["time"], t))
            self.assertLess(np.linalg.norm(result["state"]["x"][i] - goal), 0.15)
        with tempfile.TemporaryDirectory() as folder:
            out = aerobox.write_outputs(result, os.path.join(folder, "mission"), video=False)
            self.assertTrue(os.path.exists(os.path.join(out, "telemetry.csv")))

    def test_no_path_is_a_status_and_bad_keys_are_named(self):
        result = aerobox.fly(os.path.join(SOURCE, "scenes", "impossible", "scenario.toml"),
                             planner={"time_budget": 0.2})
        self.assertEqual(result["mission_status"], "no path")
        self.assertEqual(result["status"], "no path")
        self.assertEqual(len(result["time"]), 0)
        with self.assertRaises(ValueError) as raised:
            aerobox.fly(WINDOW, unknown_fraction=2.0)
        self.assertIn("unknown_fraction", str(raised.exception))


class BadCommands(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory()
        cls.sim = aerobox.Simulator(empty_map(cls.folder.name), start=[0, 0, 1])
        cls.hover = Circle(r=0.0)

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def fly(self, answer):
        class Controller:
            def update(self, t, state, flat_output):
                return answer(t)

        return self.sim.run(Controller(), self.hover, t_final=1.0)

    def test_an_exception_in_update_is_the_user_s_own_with_the_time(self):
        def answer(t):
            if t >= 0.499:
                raise ZeroDivisionError("boom")
            return {"cmd_motor_thrusts": np.full(4, 0.196)}

        with self.assertRaises(ZeroDivisionError) as raised:
            self.fly(answer)
        notes = " ".join(getattr(raised.exception, "__notes__", []))
        self.assertIn("controller.update at t = 0.5 s", notes)

    def test_nan_wrong_key_wrong_shape_and_not_a_dict(self):
        cases = {
            "'cmd_motor_thrusts' is not finite": lambda t: {"cmd_motor_thrusts": np.full(4, math.nan)},
            "none of cmd_motor_thrusts": lambda t: {"thrusts": np.ones(4)},
            "'cmd_moment' has shape (2,), expected (3,)": lambda t: {"cmd_thrust": 0.8,
                                                                     "cmd_moment": np.zeros(2)},
            "no key 'cmd_thrust'": lambda t: {"cmd_w": np.zeros(3)},
            "returned a list, expected a dict": lambda t: [0.2, 0.2, 0.2, 0.2],
        }
        for message, answer in cases.items():
            with self.subTest(message=message):
                with self.assertRaises(ValueError) as raised:
                    self.fly(answer)
                self.assertIn(message, str(raised.exception))
                self.assertIn("at t = 0 s", str(raised.exception))

    def test_extra_keys_are_ignored_and_step_works(self):
        result = self.fly(lambda t: {"cmd_motor_thrusts": np.full(4, 0.08 * 9.81 / 4),
                                     "cmd_v": "anything"})
        self.assertEqual(result["collisions"], 0)
        self.sim.reset()
        state = self.sim.step({"cmd_thrust": 0.08 * 9.81, "cmd_q": [0, 0, 0, 1]}, 0.01)
        self.assertAlmostEqual(self.sim.time, 0.01, places=9)
        self.assertLess(np.linalg.norm(state["x"] - [0, 0, 1]), 1e-3)
        with self.assertRaises(ValueError):
            self.sim.step({"cmd_thrust": 0.8, "cmd_q": [0, 0, 0, 1]}, 0.0015)


class RotorPyVehicle(unittest.TestCase):
    # a Crazyflie-class vehicle as RotorPy's quad_params dict lists it (values from RotorPy's
    # crazyflie_params: Foerster 2015 and Bitcraze's measurements)
    ARM = 0.043
    QUAD_PARAMS = {
        "mass": 0.03, "Ixx": 1.43e-5, "Iyy": 1.43e-5, "Izz": 2.89e-5,
        "Ixy": 0.0, "Iyz": 0.0, "Ixz": 0.0,
        "num_rotors": 4,
        "rotor_pos": {
            "r1": ARM * np.array([0.70710678118, 0.70710678118, 0]),
            "r2": ARM * np.array([0.70710678118, -0.70710678118, 0]),
            "r3": ARM * np.array([-0.70710678118, -0.70710678118, 0]),
            "r4": ARM * np.array([-0.70710678118, 0.70710678118, 0]),
        },
        "rotor_directions": np.array([1, -1, 1, -1]),
        "rotor_radius": 0.025,
        "c_Dx": 0.5e-2, "c_Dy": 0.5e-2, "c_Dz": 1e-2,
        "k_eta": 2.3e-08, "k_m": 7.8e-10, "k_d": 10.2506e-07, "k_z": 7.553e-07,
        "k_h": 1.69e-2, "k_flap": 0.0,
        "tau_m": 0.005, "rotor_speed_min": 0, "rotor_speed_max": 2500, "motor_noise_std": 100,
    }

    def test_hovers_and_tracks_a_circle(self):
        with tempfile.TemporaryDirectory() as folder:
            sim = aerobox.Simulator(empty_map(folder), vehicle=self.QUAD_PARAMS, start=[1, 0, 1.5])
            # what has no counterpart, with why; a zero off-diagonal inertia loses nothing
            self.assertEqual(sim.ignored_vehicle_keys, ["k_h"])
            self.assertIn("ignored k_h: translational lift: not modelled", sim.vehicle_notes)
            # the drag terms are read: body drag term for term, rotor drag at hover; the motor
            # noise once per control period
            self.assertEqual(sim.added_vehicle_keys, [])
            self.assertEqual(len(sim.adjusted_vehicle_keys), 4, sim.adjusted_vehicle_keys)
            self.assertRegex(sim.adjusted_vehicle_keys[1],
                             r"^motor_noise_std 100 rad/s -> added to each rotor's speed once per "
                             r"control period \(.*\)$")
            self.assertRegex(sim.adjusted_vehicle_keys[2],
                             r"^k_d, k_z -> rotor drag 0.0249, 0.0184 s/m per newton of thrust "
                             r"\(.* equal at hover, 1789 rad/s\)$")
            self.assertIn("only with aero={'drag': True}", sim.adjusted_vehicle_keys[3])
            self.assertAlmostEqual(sim.quad_params["mass"], 0.03)
            self.assertEqual(sim.quad_params["motor_noise_std"], 100)
            # the flights below are the noiseless vehicle's (the noise: test_motor_noise)
            sim = aerobox.Simulator(empty_map(folder), vehicle=dict(self.QUAD_PARAMS,
                                                                   motor_noise_std=0.0),
                                    start=[1, 0, 1.5])
            controller = SE3Control(sim.quad_params)
            hover = sim.run(controller, Circle(r=0.0, laps=1))
            self.assertEqual(hover["status"], "reached goal")
            self.assertGreater(hover["flight_time"], 4.0)
            self.assertLess(hover["tracking_max"], 0.005)
            circle = sim.run(controller, Circle(r=1.0, period=6.0, laps=1), t_final=7.0)
            # a circle does not end at rest: the run ends at t_final, with no contact
            self.assertEqual(circle["collisions"], 0)
            self.assertAlmostEqual(circle["flight_time"], 7.0, places=6)
            self.assertLess(circle["tracking_rms"], 0.03)
            # the rotor thrusts stayed within the dict's k_eta * rotor_speed_max^2
            self.assertLessEqual(circle["rotor_thrusts"].max(), 2.3e-8 * 2500**2 + 1e-12)

    def test_a_bad_dict_names_the_key(self):
        bad = dict(self.QUAD_PARAMS)
        del bad["k_eta"]
        with tempfile.TemporaryDirectory() as folder:
            with self.assertRaisesRegex(ValueError, "k_eta"):
                aerobox.Simulator(empty_map(folder), vehicle=bad)
            with self.assertRaisesRegex(ValueError, "num_rotors"):
                aerobox.Simulator(empty_map(folder), vehicle=dict(self.QUAD_PARAMS, num_rotors=6))


if __name__ == "__main__":
    unittest.main()
