"""aerobox.Swarm: several vehicles in one world, each with its own controller (RotorPy's contract
per vehicle): one vehicle flies as Simulator flies it, to the bit; crossing vehicles collide and
each names the other; apart, both arrive; scenarios with [[vehicles]]; bad input."""

import os
import unittest

import numpy as np

import aerobox

SOURCE = os.environ.get("AEROBOX_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
ROOM = os.path.join(SOURCE, "scenes", "swarm_swap", "map.json")


class Line:
    """A straight line from a to b in `duration` seconds, a quintic in time, as RotorPy's
    trajectories give it (update(t) -> flat outputs)."""

    def __init__(self, a, b, duration):
        self.a, self.b, self.duration = np.array(a, float), np.array(b, float), duration

    def update(self, t):
        u = min(max(t / self.duration, 0.0), 1.0)
        s = u ** 3 * (10 - 15 * u + 6 * u * u)
        inside = 0 < t < self.duration
        ds = 30 * u ** 2 * (1 - u) ** 2 / self.duration if inside else 0.0
        dds = 60 * u * (1 - u) * (1 - 2 * u) / self.duration ** 2 if inside else 0.0
        d = self.b - self.a
        return {"x": self.a + s * d, "x_dot": ds * d, "x_ddot": dds * d}


class TwoVehicles(unittest.TestCase):
    def swarm(self):
        return aerobox.Swarm(ROOM, vehicles=[
            dict(name="a", start=[1, 0, 1], vehicle="crazyflie"),
            dict(name="b", start=[-1, 0, 1], vehicle="crazyflie")])

    def test_crossing_vehicles_collide_and_each_names_the_other(self):
        result = self.swarm().run(["se3", "se3"], [Line([1, 0, 1], [-1, 0, 1], 3),
                                                   Line([-1, 0, 1], [1, 0, 1], 3)])
        self.assertFalse(result["all_reached"])
        a, b = result["vehicles"]["a"], result["vehicles"]["b"]
        self.assertEqual((a["status"], a["collision_with"]), ("collision", "b"))
        self.assertEqual((b["status"], b["collision_with"]), ("collision", "a"))
        self.assertEqual(result["closest_pair"], "a and b")

    def test_apart_both_arrive_each_with_its_own_controller(self):
        result = self.swarm().run({"a": "se3", "b": "cascade"},
                                  {"a": Line([1, 0, 1], [-1, 0.5, 1], 3),
                                   "b": Line([-1, 0, 1], [1, -0.5, 1], 3)})
        self.assertTrue(result["all_reached"])
        for name in ("a", "b"):
            r = result["vehicles"][name]
            self.assertEqual(r["status"], "reached goal")
            self.assertLess(r["tracking_rms"], 0.05)
            self.assertEqual(r["state"]["x"].shape[1], 3)  # RotorPy's result, per vehicle
        self.assertGreater(result["min_separation"], 0.4)

    def test_a_user_controller_per_vehicle(self):
        hover = aerobox.Simulator(ROOM, vehicle="crazyflie", start=[1, 0, 1])
        mine = aerobox.builtin_controller(hover, "se3")  # an object with update(t, s, flat)
        result = self.swarm().run([mine, "cascade"], [Line([1, 0, 1], [1, 0, 1.5], 2),
                                                      Line([-1, 0, 1], [-1, 0, 1.5], 2)])
        self.assertTrue(result["all_reached"])


class Settle(unittest.TestCase):
    def test_t_final_gives_each_vehicle_its_own_settle_time(self):
        # a short and a long trajectory: t_final is each one's end, whatever the order
        for order in (("short", "long"), ("long", "short")):
            with self.subTest(order=order):
                starts = {"short": [1, 0, 1], "long": [-1, 0, 1]}
                lines = {"short": Line([1, 0, 1], [1, 0.3, 1], 1.0),
                         "long": Line([-1, 0, 1], [-1, 2, 1], 4.0)}
                swarm = aerobox.Swarm(ROOM, vehicles=[
                    dict(name=n, start=starts[n], vehicle="crazyflie") for n in order])
                result = swarm.run({n: "se3" for n in order}, lines, t_final=6.0)
                for name in order:
                    self.assertEqual(result["vehicles"][name]["status"], "reached goal", name)


class OneVehicle(unittest.TestCase):
    def test_one_vehicle_of_a_swarm_flies_as_the_simulator_flies_it(self):
        line = Line([0.5, 0.5, 1], [1.5, -0.5, 1.5], 3)
        alone = aerobox.Simulator(ROOM, vehicle="crazyflie", start=[0.5, 0.5, 1]).run("se3", line)
        swarm = aerobox.Swarm(ROOM, vehicles=[dict(name="solo", start=[0.5, 0.5, 1],
                                                   vehicle="crazyflie")])
        one = swarm.run(["se3"], [line])["vehicles"]["solo"]
        self.assertEqual(one["status"], alone["status"])
        np.testing.assert_array_equal(one["state"]["x"], alone["state"]["x"])
        np.testing.assert_array_equal(one["control"]["cmd_motor_thrusts"],
                                      alone["control"]["cmd_motor_thrusts"])


class Scenarios(unittest.TestCase):
    def test_a_scenario_s_vehicles(self):
        swarm = aerobox.Swarm(os.path.join(SOURCE, "scenes", "swarm_swap", "scenario.toml"))
        self.assertEqual(swarm.names, [f"cf{i}" for i in range(1, 9)])
        self.assertEqual(len(swarm.quad_params), 8)
        self.assertAlmostEqual(swarm.quad_params[0]["mass"], 0.03, places=3)


class BadInputs(unittest.TestCase):
    def test_bad_vehicles_and_runs_are_refused_naming_them(self):
        one = dict(name="a", start=[1, 0, 1])
        with self.assertRaisesRegex(Exception, "already the name"):
            aerobox.Swarm(ROOM, vehicles=[one, dict(name="a", start=[-1, 0, 1])])
        with self.assertRaisesRegex(Exception, "vehicles.b.start.*outside the map"):
            aerobox.Swarm(ROOM, vehicles=[one, dict(name="b", start=[0, 9, 1])])
        with self.assertRaisesRegex(Exception, "vehicles.b.start: starts 0.02 m from a"):
            aerobox.Swarm(ROOM, vehicles=[one, dict(name="b", start=[1.02, 0, 1])])
        with self.assertRaisesRegex(TypeError, "unknown key 'speed'"):
            aerobox.Swarm(ROOM, vehicles=[dict(name="a", start=[1, 0, 1], speed=2)])
        swarm = aerobox.Swarm(ROOM, vehicles=[one, dict(name="b", start=[-1, 0, 1])])
        line = Line([1, 0, 1], [1, 0, 1], 1)
        with self.assertRaisesRegex(ValueError, "one per vehicle"):
            swarm.run(["se3"], [line])
        with self.assertRaisesRegex(ValueError, "none for 'b'"):
            swarm.run({"a": "se3"}, {"a": line, "b": line})


if __name__ == "__main__":
    unittest.main()
