"""Rotor order: every built-in vehicle numbers its rotors as RotorPy does, so a motor-level
controller written for RotorPy flies each of them; a user's own quad_params keep the order they
were given in; docs/vehicle.md's figure of the numbering is what the package exports."""

import math
import os
import re
import tempfile
import unittest

import numpy as np

import aerobox

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.environ.get("AEROBOX_SOURCE_DIR", os.path.join(HERE, "..", ".."))
BUILTIN_VEHICLES = ("tello", "crazyflie")

# RotorPy's numbering (rotorpy/vehicles/crazyflie_params.py, and its other vehicles): rotor 1
# front-left, 2 front-right, 3 back-right, 4 back-left (body FLU: x forward, y left), and
# rotor_directions 1, -1, 1, -1 (the sign of each rotor's yaw moment on the body). Written
# here, not read from aerobox: this is what a RotorPy user's controller assumes.
ROTORPY_CORNERS = np.array([[1.0, 1.0], [1.0, -1.0], [-1.0, -1.0], [-1.0, 1.0]]) / math.sqrt(2)
ROTORPY_DIRECTIONS = np.array([1.0, -1.0, 1.0, -1.0])

HOVER = np.array([0.0, 0.0, 1.5])
HOLD_TIME = 6.0  # [s]


def empty_map(folder):
    path = os.path.join(folder, "open.txt")
    with open(path, "w") as file:
        file.write("boundary -4 -4 0 4 4 3\n")
    return path


def rotorpy_layout(quad_params):
    """RotorPy's rotor positions (4, 2) [m] for this vehicle's arm length (the rotors' common
    distance from the centre: the one number taken from the vehicle's layout, whatever its
    order)."""
    arm = np.mean([np.linalg.norm(np.asarray(r)[:2]) for r in quad_params["rotor_pos"].values()])
    return arm * ROTORPY_CORNERS


def tilted(roll, pitch):
    """[i, j, k, w] of a roll about x, then a pitch about y (body frame)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    return np.array([sr * cp, cr * sp, sr * sp, cr * cp])


class Hold:
    """The flat output of a point held still, for `duration` [s]."""

    def __init__(self, point, duration):
        self.point, self.duration = np.asarray(point, dtype=float), duration

    def update(self, t):
        zero = np.zeros(3)
        return {"x": self.point, "x_dot": zero, "x_ddot": zero, "x_dddot": zero,
                "x_ddddot": zero, "yaw": 0.0, "yaw_dot": 0.0}


class MotorLevelHover:
    """Holds a point commanding the four rotors directly (cmd_motor_thrusts [N] or
    cmd_motor_speeds [rad/s]) and mixing them itself: a PD on position gives the thrust vector,
    a PD on the attitude error (Lee et al. 2010's, yaw 0) the body moments, and the allocation
    matrix of `positions` (4, 2) [m, body x, y] and `directions` (the yaw-moment signs) the
    rotor thrusts. From the vehicle it takes only mass, inertia, k_eta, k_m, the speed limits
    and tau_m: the rotor order is the one it is given."""

    def __init__(self, quad_params, positions, directions, command="cmd_motor_thrusts"):
        self.mass = quad_params["mass"]
        self.inertia = np.diag([quad_params["Ixx"], quad_params["Iyy"], quad_params["Izz"]])
        self.k_eta = quad_params["k_eta"]
        self.min_thrust = self.k_eta * quad_params["rotor_speed_min"] ** 2
        self.max_thrust = self.k_eta * quad_params["rotor_speed_max"] ** 2
        self.command = command
        positions = np.asarray(positions, dtype=float)
        # [thrust; roll, pitch, yaw moments] = allocation @ rotor thrusts; moments r x (0, 0, f)
        allocation = np.vstack([np.ones(4), positions[:, 1], -positions[:, 0],
                                np.asarray(directions, dtype=float) * quad_params["k_m"]
                                / self.k_eta])
        self.to_rotors = np.linalg.inv(allocation)
        # the attitude loop critically damped at most at the motor lag's bandwidth (1 / tau_m:
        # 50 rad/s for the Tello, 14 for the Crazyflie), the position loop 3x slower
        lag = float(np.mean(quad_params["tau_m"]))
        w_attitude = min(20.0, 1.0 / lag)  # [rad/s]
        w_position = w_attitude / 3.0
        self.kr, self.kw = w_attitude**2, 2.0 * w_attitude  # [1/s^2, 1/s]
        self.kp, self.kd = w_position**2, 1.8 * w_position  # damping 0.9

    def update(self, t, state, flat_output):
        x, y, z, w = state["q"]
        R = np.array([
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ])
        accel = (-self.kp * (state["x"] - flat_output["x"])
                 - self.kd * (state["v"] - flat_output["x_dot"]) + [0.0, 0.0, 9.81])
        force = self.mass * accel
        b3 = force / np.linalg.norm(force)
        b2 = np.cross(b3, [1.0, 0.0, 0.0])
        b2 /= np.linalg.norm(b2)
        R_des = np.column_stack([np.cross(b2, b3), b2, b3])
        S = 0.5 * (R_des.T @ R - R.T @ R_des)
        e_R = np.array([S[2, 1], S[0, 2], S[1, 0]])
        moment = self.inertia @ (-self.kr * e_R - self.kw * state["w"])
        wrench = np.concatenate([[force @ R[:, 2]], moment])
        thrusts = np.clip(self.to_rotors @ wrench, self.min_thrust, self.max_thrust)
        if self.command == "cmd_motor_speeds":
            return {"cmd_motor_speeds": np.sqrt(thrusts / self.k_eta)}
        return {"cmd_motor_thrusts": thrusts}


def hold(sim, controller):
    """Released at the hover point tilted 0.03 rad in roll and 0.02 in pitch (both of the
    roll-pitch plane's directions, so a mixer that swaps them is found out), then held for
    HOLD_TIME. Returns the run's result and the largest distance from the point [m]."""
    sim.reset(state={"x": HOVER, "v": np.zeros(3), "q": tilted(0.03, 0.02), "w": np.zeros(3)})
    result = sim.run(controller, Hold(HOVER, HOLD_TIME), t_final=HOLD_TIME, control_rate=500,
                     reset=False)
    deviation = np.linalg.norm(result["state"]["x"] - HOVER, axis=1).max()
    return result, deviation


class RotorPyOrder(unittest.TestCase):
    def test_builtin_vehicles_export_rotorpy_s_order(self):
        with tempfile.TemporaryDirectory() as folder:
            for kind in BUILTIN_VEHICLES:
                with self.subTest(vehicle=kind):
                    params = aerobox.Simulator(empty_map(folder), vehicle=kind).quad_params
                    self.assertEqual(list(params["rotor_pos"]), ["r1", "r2", "r3", "r4"])
                    positions = np.array([r[:2] for r in params["rotor_pos"].values()])
                    np.testing.assert_array_equal(np.sign(positions), np.sign(ROTORPY_CORNERS))
                    np.testing.assert_allclose(positions, rotorpy_layout(params), atol=1e-12)
                    np.testing.assert_array_equal(params["rotor_directions"],
                                                  ROTORPY_DIRECTIONS)

    def test_a_rotorpy_motor_level_controller_hovers_every_builtin_vehicle(self):
        # 2 cm: the tilt at release costs a few millimetres (measured: Tello 3.4 mm, Crazyflie
        # 7.6 mm, its slow motors allowing only a slower attitude loop); a mixer with the
        # rotors in the Tello's former order (front-left, then counter-clockwise) turns roll
        # commands into pitch and back: the Tello hit the floor after 0.72 s
        with tempfile.TemporaryDirectory() as folder:
            for kind in BUILTIN_VEHICLES:
                sim = aerobox.Simulator(empty_map(folder), vehicle=kind, start=HOVER)
                layout = rotorpy_layout(sim.quad_params)
                for command in ("cmd_motor_thrusts", "cmd_motor_speeds"):
                    with self.subTest(vehicle=kind, command=command):
                        controller = MotorLevelHover(sim.quad_params, layout,
                                                     ROTORPY_DIRECTIONS, command)
                        result, deviation = hold(sim, controller)
                        # something happened: the rotors were driven apart to level the body
                        spread = np.ptp(result["control"]["cmd_motor_thrusts"][0])
                        self.assertGreater(spread, 1e-3 * self.max_thrust(sim))
                        print(f"{kind}, {command}: {result['status']} after "
                              f"{result['flight_time']:.2f} s, at most {1000 * deviation:.2f} mm "
                              "from the hover point")
                        self.assertEqual(result["status"], "reached goal")
                        self.assertEqual(result["collisions"], 0)
                        self.assertAlmostEqual(result["flight_time"], HOLD_TIME, places=6)
                        self.assertLess(deviation, 0.02)

    @staticmethod
    def max_thrust(sim):
        return sim.quad_params["k_eta"] * sim.quad_params["rotor_speed_max"] ** 2


class UserRotorOrder(unittest.TestCase):
    """A user's quad_params keep their own rotor order: a Tello-sized vehicle numbered
    front-left, back-left, back-right, front-right (counter-clockwise, not RotorPy's)."""

    ARM = 0.035
    CORNERS = ARM * np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])
    DIRECTIONS = np.array([1.0, -1.0, 1.0, -1.0])

    def quad_params(self, rotor_pos):
        return {
            "mass": 0.08, "Ixx": 7.1e-5, "Iyy": 7.5e-5, "Izz": 1.24e-4, "num_rotors": 4,
            "rotor_pos": rotor_pos, "rotor_directions": self.DIRECTIONS,
            "k_eta": 1.7e-7, "k_m": 1.02e-9, "rotor_speed_min": 0.0, "rotor_speed_max": 1534.0,
            "tau_m": 0.02,
        }

    def test_the_dict_s_order_is_kept_as_given(self):
        as_dict = {f"r{i + 1}": np.array([x, y, 0.0]) for i, (x, y) in enumerate(self.CORNERS)}
        as_array = np.column_stack([self.CORNERS, np.zeros(4)])
        with tempfile.TemporaryDirectory() as folder:
            for rotor_pos in (as_dict, as_array):
                with self.subTest(rotor_pos=type(rotor_pos).__name__):
                    given = self.quad_params(rotor_pos)
                    sim = aerobox.Simulator(empty_map(folder), vehicle=given, start=HOVER)
                    # the user's dict itself is left as it was
                    self.assertIs(given["rotor_pos"], rotor_pos)
                    if isinstance(rotor_pos, dict):
                        self.assertEqual(list(rotor_pos), ["r1", "r2", "r3", "r4"])
                    np.testing.assert_array_equal(np.array(list(as_dict.values())), as_array)
                    exported = np.array(list(sim.quad_params["rotor_pos"].values()))
                    np.testing.assert_array_equal(exported, as_array)
                    np.testing.assert_array_equal(sim.quad_params["rotor_directions"],
                                                  self.DIRECTIONS)

    def test_the_simulation_flies_the_dict_s_order(self):
        # a mixer in the dict's own order holds the point; RotorPy's order, which is not this
        # vehicle's, flips it: the simulation drives rotor i where the dict puts it
        with tempfile.TemporaryDirectory() as folder:
            sim = aerobox.Simulator(empty_map(folder), vehicle=self.quad_params(
                {f"r{i + 1}": np.array([x, y, 0.0]) for i, (x, y) in enumerate(self.CORNERS)}),
                start=HOVER)
            own = MotorLevelHover(sim.quad_params, self.CORNERS, self.DIRECTIONS)
            result, deviation = hold(sim, own)
            self.assertEqual(result["status"], "reached goal")
            self.assertAlmostEqual(result["flight_time"], HOLD_TIME, places=6)
            self.assertLess(deviation, 0.02)
            rotorpy = MotorLevelHover(sim.quad_params, rotorpy_layout(sim.quad_params),
                                      ROTORPY_DIRECTIONS)
            result, deviation = hold(sim, rotorpy)
            self.assertIn(result["status"], ("collision", "fly-away"))
            self.assertLess(result["flight_time"], HOLD_TIME)
            self.assertGreater(deviation, 0.1)


class ReadmeFigure(unittest.TestCase):
    """docs/vehicle.md's top view of the rotor numbering (The vehicle) is what the package exports:
    each label r1..r4 sits on the side of the figure's centre its rotor_pos has (nose up, y to
    the left) and says the spin its rotor_directions gives (CW: +1)."""

    LABEL = re.compile(r"\br([1-4]) (CCW|CW)\b")

    def figure(self):
        with open(os.path.join(SOURCE, "docs", "vehicle.md"), encoding="utf-8") as file:
            text = file.read()
        self.assertTrue(text.startswith("# The vehicle\n"), "docs/vehicle.md: not The vehicle")
        blocks = re.findall(r"```text\n(.*?)```", text, re.S)
        figures = [block for block in blocks if self.LABEL.search(block)]
        self.assertTrue(figures, "docs/vehicle.md, The vehicle: no figure with r1..r4")
        return figures[0]

    def test_the_figure_matches_quad_params(self):
        figure = self.figure()
        self.assertIn("y <", figure)  # the axes as read below: x (the nose) up, y to the left
        labels = {}
        for row, line in enumerate(figure.splitlines()):
            for match in self.LABEL.finditer(line):
                labels[int(match.group(1))] = (row, match.start(), match.group(2))
        self.assertEqual(sorted(labels), [1, 2, 3, 4])
        centre_row = np.mean([row for row, _, _ in labels.values()])
        centre_column = np.mean([column for _, column, _ in labels.values()])
        with tempfile.TemporaryDirectory() as folder:
            for kind in BUILTIN_VEHICLES:
                params = aerobox.Simulator(empty_map(folder), vehicle=kind).quad_params
                positions = list(params["rotor_pos"].values())
                for rotor, (row, column, spin) in labels.items():
                    with self.subTest(vehicle=kind, rotor=rotor):
                        x, y = positions[rotor - 1][:2]
                        self.assertEqual(row < centre_row, x > 0, "front or back")
                        self.assertEqual(column < centre_column, y > 0, "left or right")
                        self.assertEqual(params["rotor_directions"][rotor - 1],
                                         1.0 if spin == "CW" else -1.0)


if __name__ == "__main__":
    unittest.main()
