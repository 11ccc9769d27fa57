"""aerobox.flightsim: a MEAM620-style sandbox (a student's SE3Control computing flightsim's motor
speeds, a trajectory class with no duration, a world in flightsim's JSON) runs with its imports
changed and nothing else, ends with flightsim's statuses, and flies flightsim's vehicle (its "+"
layout, its yaw signs, no motor lag) as flightsim's own equations of motion do."""

import json
import math
import os
import sys
import tempfile
import unittest
import warnings

import numpy as np

import aerobox
from aerobox.flightsim import ExitStatus, Quadrotor, World, simulate

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from se3_controller import rotation_matrix as rotation  # noqa: E402

# flightsim's Crazyflie (MEAM620's crazyflie_params)
QUAD_PARAMS = {
    "mass": 0.030, "Ixx": 1.43e-5, "Iyy": 1.43e-5, "Izz": 2.89e-5,
    "arm_length": 0.046, "rotor_speed_min": 0, "rotor_speed_max": 2500,
    "k_thrust": 2.3e-08, "k_drag": 7.8e-11,
}

WINDOW_WORLD = {
    "bounds": {"extents": [0.0, 6.0, 0.0, 6.0, 0.0, 3.0]},
    "blocks": [
        {"extents": [0.0, 2.2, 2.8, 3.2, 0.0, 3.0], "color": [1, 0, 0]},
        {"extents": [3.8, 6.0, 2.8, 3.2, 0.0, 3.0], "color": [1, 0, 0]},
        {"extents": [2.2, 3.8, 2.8, 3.2, 0.0, 0.7], "color": [1, 0, 0]},
        {"extents": [2.2, 3.8, 2.8, 3.2, 2.3, 3.0], "color": [1, 0, 0]},
    ],
    "start": [1.0, 1.0, 1.0],
    "goal": [5.0, 5.0, 1.5],
}


class SE3Control:
    """A student's controller in flightsim's shapes: motor speeds through the "+" mixer."""

    def __init__(self, quad_params):
        self.mass = quad_params["mass"]
        self.inertia = np.diag([quad_params["Ixx"], quad_params["Iyy"], quad_params["Izz"]])
        L, k = quad_params["arm_length"], quad_params["k_thrust"]
        gamma = quad_params["k_drag"] / k
        self.k_thrust = k
        self.to_forces = np.linalg.inv(np.array([[1, 1, 1, 1], [0, L, 0, -L], [-L, 0, L, 0],
                                                 [gamma, -gamma, gamma, -gamma]]))
        self.kp, self.kd = np.diag([7.0, 7.0, 20.0]), np.diag([4.5, 4.5, 8.0])
        self.kr, self.kw = np.diag([2500.0, 2500.0, 400.0]), np.diag([60.0, 60.0, 40.0])

    def update(self, t, state, flat_output):
        a = (flat_output["x_ddot"] - self.kd @ (state["v"] - flat_output["x_dot"])
             - self.kp @ (state["x"] - flat_output["x"]) + np.array([0, 0, 9.81]))
        force = self.mass * a
        R = rotation(state["q"])
        b3 = force / np.linalg.norm(force)
        yaw = flat_output["yaw"]
        b2 = np.cross(b3, [math.cos(yaw), math.sin(yaw), 0.0])
        b2 /= np.linalg.norm(b2)
        R_des = np.column_stack([np.cross(b2, b3), b2, b3])
        S = 0.5 * (R_des.T @ R - R.T @ R_des)
        e_R = np.array([S[2, 1], S[0, 2], S[1, 0]])
        moment = self.inertia @ (-self.kr @ e_R - self.kw @ state["w"])
        u1 = force @ R[:, 2]
        forces = self.to_forces @ np.concatenate([[u1], moment])
        speeds = np.sqrt(np.clip(forces, 0, None) / self.k_thrust)
        w = math.sqrt(max(1e-12, 1 + np.trace(R_des))) / 2
        cmd_q = np.array([(R_des[2, 1] - R_des[1, 2]) / (4 * w),
                          (R_des[0, 2] - R_des[2, 0]) / (4 * w),
                          (R_des[1, 0] - R_des[0, 1]) / (4 * w), w])
        return {"cmd_motor_speeds": speeds, "cmd_thrust": u1, "cmd_moment": moment,
                "cmd_q": cmd_q}


class WorldTraj:
    """A student's trajectory: rest-to-rest quintic legs through waypoints at 1 m/s average,
    with no `duration` (flightsim asks update(inf) for the end)."""

    def __init__(self, points, speed=1.0, yaw=0.0):
        self.points = np.asarray(points, dtype=float)
        lengths = np.linalg.norm(np.diff(self.points, axis=0), axis=1)
        self.times = np.concatenate([[0.0], np.cumsum(np.maximum(lengths / speed, 0.5))])
        self.yaw = yaw

    def update(self, t):
        out = {"x": self.points[-1].copy(), "x_dot": np.zeros(3), "x_ddot": np.zeros(3),
               "x_dddot": np.zeros(3), "x_ddddot": np.zeros(3), "yaw": self.yaw, "yaw_dot": 0.0}
        if t >= self.times[-1]:
            return out
        i = int(np.searchsorted(self.times, t, side="right")) - 1
        T = self.times[i + 1] - self.times[i]
        s = (t - self.times[i]) / T
        a, b = self.points[i], self.points[i + 1]
        out["x"] = a + (b - a) * (10 * s**3 - 15 * s**4 + 6 * s**5)
        out["x_dot"] = (b - a) * (30 * s**2 - 60 * s**3 + 30 * s**4) / T
        out["x_ddot"] = (b - a) * (60 * s - 180 * s**2 + 120 * s**3) / T**2
        return out


def at_rest(x):
    return {"x": np.asarray(x, dtype=float), "v": np.zeros(3), "q": np.array([0, 0, 0, 1.0]),
            "w": np.zeros(3)}


class Sandbox(unittest.TestCase):
    """MEAM620's sandbox.py, with aerobox.flightsim's imports."""

    def test_window_completes_with_flightsim_status(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "test_window.json")
            with open(path, "w") as file:
                json.dump(WINDOW_WORLD, file)
            world = World.from_file(path)
        start, goal = np.array(world.world["start"]), np.array(world.world["goal"])
        route = [start, [3.0, 2.0, 1.5], [3.0, 4.0, 1.5], goal]
        self.assertEqual(len(world.path_collisions(np.array(route), 0.25)), 0)
        quadrotor = Quadrotor(QUAD_PARAMS)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            (time, state, control, flat, exit) = simulate(
                at_rest(start), quadrotor, SE3Control(QUAD_PARAMS), WorldTraj(route), t_final=60)
        # flightsim's own dict: what aerobox adds is flightsim's meaning, and not said; the one
        # change is (flightsim's Crazyflie has Izz 1 % above Ixx + Iyy, which MuJoCo refuses)
        self.assertEqual(len(caught), 1, [str(w.message) for w in caught])
        self.assertRegex(str(caught[0].message), r"^aerobox.flightsim: .*\n  adjusted Izz "
                         r"2.89e-05 -> 2.86e-05 kg m\^2 \(MuJoCo needs[^\n]*$")
        self.assertIs(exit, ExitStatus.COMPLETE)
        self.assertEqual(exit.value, "Success: End reached.")
        end = WorldTraj(route).times[-1]
        self.assertGreater(time[-1], end)
        self.assertLess(time[-1], end + 3.0)  # ends when done, not at t_final
        self.assertAlmostEqual(time[1] - time[0], 1 / 500)
        self.assertEqual(state["x"].shape, (len(time), 3))
        self.assertEqual(state["q"].shape, (len(time), 4))
        self.assertEqual(control["cmd_motor_speeds"].shape, (len(time), 4))
        self.assertEqual(flat["x"].shape, (len(time), 3))
        np.testing.assert_array_equal(state["x"][0], start)
        # sandbox.py's checks
        self.assertEqual(len(world.path_collisions(state["x"], 0.25)), 0)
        self.assertLess(np.linalg.norm(state["x"][-1] - goal), 0.05)
        tracking = np.linalg.norm(state["x"] - flat["x"], axis=1)
        self.assertLess(tracking.max(), 0.10)

    def test_terminate_false_callable_and_failures(self):
        quadrotor = Quadrotor(QUAD_PARAMS)
        hover = WorldTraj([[0, 0, 1.0], [0, 0, 1.0]])
        (time, _, _, _, exit) = simulate(at_rest([0, 0, 1.0]), quadrotor, SE3Control(QUAD_PARAMS),
                                         hover, t_final=1.5, terminate=False)
        self.assertIs(exit, ExitStatus.TIMEOUT)
        self.assertAlmostEqual(time[-1], 1.5, places=6)
        # a start at the trajectory's end: not complete before 1 s
        (time, _, _, _, exit) = simulate(at_rest([0, 0, 1.0]), quadrotor, SE3Control(QUAD_PARAMS),
                                         hover, t_final=5)
        self.assertIs(exit, ExitStatus.COMPLETE)
        self.assertAlmostEqual(time[-1], 1.0, delta=0.003)
        stop = lambda t, s: ExitStatus.TIMEOUT if t >= 0.3 else None  # noqa: E731
        (time, _, _, _, exit) = simulate(at_rest([0, 0, 1.0]), quadrotor, SE3Control(QUAD_PARAMS),
                                         hover, t_final=5, terminate=stop)
        self.assertIs(exit, ExitStatus.TIMEOUT)
        self.assertAlmostEqual(time[-1], 0.3, delta=0.003)

        class Broken:
            def __init__(self, value):
                self.value = value

            def update(self, t, state, flat):
                return {"cmd_motor_speeds": np.full(4, self.value if t > 0.1 else 1000.0)}

        for value, status in ((np.nan, ExitStatus.NAN_VALUE), (np.inf, ExitStatus.INF_VALUE)):
            (time, _, _, _, exit) = simulate(at_rest([0, 0, 1.0]), quadrotor, Broken(value),
                                             hover, t_final=5)
            self.assertIs(exit, status)
            self.assertAlmostEqual(time[-1], 0.102, delta=0.003)
        # 1000 rad/s for 0.1 s, then the rotors stopped: it falls, and is out of control 20 m
        # below its trajectory
        (time, state, _, _, exit) = simulate(at_rest([0, 0, 1.0]), quadrotor, Broken(0.0),
                                             hover, t_final=10)
        self.assertIs(exit, ExitStatus.FLY_AWAY)
        a = 9.81 - 4 * QUAD_PARAMS["k_thrust"] * 1000.0**2 / QUAD_PARAMS["mass"]  # [m/s^2]
        v, d = 0.1 * a, 0.5 * a * 0.1**2
        fall = 0.1 + (-v + math.sqrt(v * v + 2 * 9.81 * (20 - d))) / 9.81
        self.assertAlmostEqual(time[-1], fall, delta=0.005)

    def test_world_helpers(self):
        world = World.grid_forest(n_rows=4, n_cols=3, width=0.5, height=3.0, spacing=2.0)
        self.assertEqual(world.world["bounds"]["extents"], [0.0, 4.5, 0.0, 6.5, 0.0, 3.0])
        self.assertEqual(len(world.world["blocks"]), 12)
        points, distances = world.closest_points(np.array([[1.0, 0.25, 1.0], [0.25, 0.25, 1]]))
        np.testing.assert_allclose(points[0], [0.5, 0.25, 1.0])
        np.testing.assert_allclose(distances, [0.5, 0.0])
        np.testing.assert_allclose(world.min_dist_boundary(np.array([[1.0, 3.0, 1.0]])), [1.0])
        hits = world.path_collisions(np.array([[1.0, 0.25, 1.0], [1.0, 1.0, 1.0]]), 0.6)
        self.assertGreater(len(hits), 0)
        self.assertTrue(np.all(hits[:, 1] < 1.1 - 1e-9))
        self.assertEqual(world.path_collisions(np.array([[1.0, 1.0, 1.0]]), 0.2).shape, (0, 3))
        forest = World.random_forest([10, 10, 4], 0.5, 3.0, 20, seed=3)
        self.assertEqual(forest.world, World.random_forest([10, 10, 4], 0.5, 3.0, 20,
                                                           seed=3).world)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "forest.json")
            forest.to_file(path)
            self.assertEqual(World.from_file(path).world, forest.world)
            # and aerobox reads it as a map
            self.assertEqual(len(aerobox.read_map(path).boxes), 20)
            with open(path, "w") as file:
                file.write('{"bounds": {"extents": [0, 1, 0, 1, 0, 1]},\n "blocks": [,]}')
            with self.assertRaisesRegex(ValueError, "forest.json: line 2"):
                World.from_file(path)


class RunEnds(unittest.TestCase):
    """Simulator.run() ends a run when the flight is done, also for a trajectory object with no
    duration (a student's: its end is update(inf)), unless told otherwise."""

    @classmethod
    def setUpClass(cls):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "world.json")
            with open(path, "w") as file:
                json.dump(WINDOW_WORLD, file)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # the Izz note, tested above
                cls.sim = aerobox.Simulator(path, vehicle=QUAD_PARAMS, start=[1.0, 1.0, 1.0])
        cls.route = [[1.0, 1.0, 1.0], [3.0, 2.0, 1.5], [3.0, 4.0, 1.5], [5.0, 5.0, 1.5]]

    def fly(self, **options):
        return self.sim.run(SE3Control(QUAD_PARAMS), WorldTraj(self.route), t_final=60,
                            control_rate=500, command="cmd_motor_speeds", **options)

    def test_ends_when_done(self):
        end = WorldTraj(self.route).times[-1]
        result = self.fly()
        self.assertEqual(result["status"], "reached goal")
        self.assertEqual(result["collisions"], 0)
        # flightsim's rule: within 2 cm below 3 cm/s, which a quintic's last leg meets a
        # little before its end
        self.assertGreater(result["flight_time"], end - 0.3)
        self.assertLess(result["flight_time"], end + 2.0)  # not 60 s
        self.assertLess(np.linalg.norm(result["state"]["x"][-1] - self.route[-1]), 0.02)

    def test_terminate_false_and_a_function(self):
        result = self.fly(terminate=False)
        self.assertEqual(result["status"], "completed")
        self.assertAlmostEqual(result["flight_time"], 60.0, delta=0.0015)  # a physics step
        seen = []

        def past_the_window(t, state):
            seen.append(sorted(state))
            return state["x"][1] > 3.5

        result = self.fly(terminate=past_the_window)
        self.assertEqual(result["status"], "terminated")
        self.assertGreater(result["state"]["x"][-1][1], 3.5)
        self.assertLess(result["state"]["x"][-1][1], 3.6)
        self.assertEqual(seen[0], ["q", "v", "w", "x"])

        def broken(t, state):
            raise KeyError("no such key")

        with self.assertRaises(KeyError):
            self.fly(terminate=broken)
        with self.assertRaisesRegex(ValueError, "terminate: expected None, False or a function"):
            self.fly(terminate="soon")


class Equations(unittest.TestCase):
    """flightsim's vehicle flown by aerobox against flightsim's equations of motion (a rigid
    body, rotor forces k_thrust w^2 along body z at the "+" arms, yaw moments +-k_drag w^2, no
    motor lag, no drag), integrated here with RK4 at 0.1 ms, for the same motor speeds."""

    def reference(self, x0, speeds_of, t_end, dt=1e-4):
        p = QUAD_PARAMS
        m, I = p["mass"], np.diag([p["Ixx"], p["Iyy"], p["Izz"]])
        L, k, kd = p["arm_length"], p["k_thrust"], p["k_drag"]
        to_tm = np.array([[1, 1, 1, 1], [0, L, 0, -L], [-L, 0, L, 0], [kd / k, -kd / k, kd / k,
                                                                       -kd / k]])

        def derivative(s, speeds):
            v, q, w = s[3:6], s[6:10], s[10:13]
            tm = to_tm @ (k * np.clip(speeds, 0, 2500) ** 2)
            R = rotation(q)
            x, y, z, qw = q
            omega = np.array([[0, w[2], -w[1], w[0]], [-w[2], 0, w[0], w[1]],
                              [w[1], -w[0], 0, w[2]], [-w[0], -w[1], -w[2], 0]])
            return np.concatenate([v, R @ [0, 0, tm[0]] / m - [0, 0, 9.81], 0.5 * omega @ q,
                                   np.linalg.solve(I, tm[1:] - np.cross(w, I @ w))])

        s = np.concatenate([x0, np.zeros(3), [0, 0, 0, 1.0], np.zeros(3)])
        for i in range(int(round(t_end / dt))):
            speeds = speeds_of(i * dt)
            k1 = derivative(s, speeds)
            k2 = derivative(s + dt / 2 * k1, speeds)
            k3 = derivative(s + dt / 2 * k2, speeds)
            k4 = derivative(s + dt * k3, speeds)
            s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            s[6:10] /= np.linalg.norm(s[6:10])
        return s

    def test_layout_yaw_signs_and_no_lag(self):
        hover = math.sqrt(QUAD_PARAMS["mass"] * 9.81 / 4 / QUAD_PARAMS["k_thrust"])

        def speeds_of(t):
            # rotors 1 and 3 faster for 0.2 s (a yaw), then rotor 1 faster for 0.05 s (a pitch)
            speeds = np.full(4, hover)
            if t < 0.2:
                speeds += np.array([40.0, -40.0, 40.0, -40.0])
            elif t < 0.25:
                speeds[0] += 30.0
            return speeds

        x0 = np.array([0.0, 0.0, 2.0])
        expected = self.reference(x0, speeds_of, 0.5)
        quadrotor = Quadrotor(QUAD_PARAMS)
        state = at_rest(x0)
        for i in range(250):  # flightsim's 2 ms steps
            state = quadrotor.step(state, speeds_of(i * 0.002), 0.002)
        # over 0.5 s the vehicle yaws about 0.2 rad and pitches over: aerobox's physics (1 ms
        # steps, the thrust one step behind) against the reference
        yaw = 2 * math.atan2(expected[8], expected[9])
        self.assertGreater(abs(yaw), 0.1)
        np.testing.assert_allclose(state["q"] * np.sign(state["q"][3]), expected[6:10],
                                   atol=0.01)
        np.testing.assert_allclose(state["w"], expected[10:13], atol=0.05 * max(1, np.abs(
            expected[10:13]).max()))
        np.testing.assert_allclose(state["x"], expected[0:3], atol=2e-3)

    def test_negative_speeds_are_the_slowest(self):
        # clipped to the rotors' range before squaring, in the command and in the rotors' state
        quadrotor = Quadrotor(QUAD_PARAMS)
        stopped = quadrotor.step(at_rest([0, 0, 2.0]), np.zeros(4), 0.01)
        negative = quadrotor.step(at_rest([0, 0, 2.0]), np.full(4, -900.0), 0.01)
        np.testing.assert_array_equal(negative["v"], stopped["v"])
        self.assertAlmostEqual(stopped["v"][2], -9.81 * 0.01, delta=1e-6)

    def test_flightsim_dict_in_the_simulator(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "world.json")
            with open(path, "w") as file:
                json.dump(WINDOW_WORLD, file)
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                sim = aerobox.Simulator(path, vehicle=QUAD_PARAMS)
        self.assertAlmostEqual(sim.quad_params["tau_m"][0], 0.001)
        self.assertTrue(any(n.startswith("tau_m 0.001 s") for n in sim.added_vehicle_keys),
                        sim.added_vehicle_keys)
        self.assertEqual(len(caught), 1)
        self.assertIn("flightsim's vehicle has no motor lag", str(caught[0].message))
        np.testing.assert_array_equal(sim.quad_params["rotor_directions"], [1, -1, 1, -1])


if __name__ == "__main__":
    unittest.main()
