"""aerobox.rotorpy.Environment: RotorPy scripts with one import changed, flown with RotorPy's own
classes from PyPI (its Multirotor, SE3Control, trajectories, winds, IMU, mocap, estimator and
World), and checked against RotorPy's own Environment on the same script."""

import os
import tempfile
import unittest
import warnings

import numpy as np
from rotorpy.controllers.quadrotor_control import SE3Control
from rotorpy.environments import Environment as RotorPyEnvironment
from rotorpy.sensors.camera import PinholeCamera
from rotorpy.simulate import ExitStatus as RotorPyExitStatus
from rotorpy.trajectories.circular_traj import ThreeDCircularTraj
from rotorpy.trajectories.hover_traj import HoverTraj
from rotorpy.vehicles.crazyflie_params import quad_params
from rotorpy.vehicles.multirotor import Multirotor
from rotorpy.wind.default_winds import ConstantWind
from rotorpy.world import World

from aerobox.rotorpy import Environment, ExitStatus

CIRCLE = ThreeDCircularTraj(center=np.array([0, 0, 1.0]), radius=np.array([1, 1, 0]),
                            freq=np.array([0.2, 0.2, 0]))


def at(position, speeds=1788.53):
    """A Crazyflie state at rest at `position` [m], its rotors at `speeds` [rad/s]."""
    return {"x": np.array(position, dtype=float), "v": np.zeros(3), "q": np.array([0, 0, 0, 1.0]),
            "w": np.zeros(3), "wind": np.zeros(3), "rotor_speeds": np.full(4, speeds)}


def script(environment, trajectory=CIRCLE, start=None, **keys):
    """A RotorPy user's script, with the Environment class given."""
    start = start if start is not None else trajectory.update(0.0)["x"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # aerobox's notes on the Crazyflie's Izz and rotor drag
        return environment(vehicle=Multirotor(quad_params, initial_state=at(start)),
                           controller=SE3Control(quad_params), trajectory=trajectory, **keys)


def hover_jitter(environment, noise, seed):
    """A Crazyflie hovering at sim_rate 100 with motor_noise_std `noise` [rad/s], numpy seeded
    with `seed`: its RMS distance from the hover point after 1 s [m], and the standard deviation
    of its rotor speeds' change from one step to the next [rad/s]."""
    np.random.seed(seed)
    params = dict(quad_params, motor_noise_std=noise)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        env = environment(vehicle=Multirotor(params, initial_state=at([0, 0, 1.0])),
                          controller=SE3Control(params),
                          trajectory=HoverTraj(x0=np.array([0, 0, 1.0])), sim_rate=100)
    result = env.run(t_final=5)
    x, speeds = result["state"]["x"][100:], result["state"]["rotor_speeds"][100:]
    return (np.sqrt(np.mean(np.sum((x - [0, 0, 1.0])**2, axis=1))),
            np.std(np.diff(speeds, axis=0)))


class SameScript(unittest.TestCase):
    def test_a_camera_sees_what_it_sees_in_rotorpy(self):
        # RotorPy's PinholeCamera looking ahead at a wall with features, 10 frames a second
        world = World({"bounds": {"extents": [-3, 3, -3, 3, 0, 3]},
                       "blocks": [{"extents": [1.5, 2.0, -1, 1, 0, 2.5], "color": [1, 0, 0]}]},
                      add_features=True)
        ahead = np.array([0.5, -0.5, 0.5, 0.5])  # body to camera: the camera's z is the body's x
        results = []
        for environment in (Environment, RotorPyEnvironment):
            camera = PinholeCamera(
                frame_rate=10, extrinsics={"position": np.zeros(3), "orientation": ahead},
                intrinsics={"fx": 100.0, "fy": 100.0, "width": 160, "height": 120, "cx": 80.0,
                            "cy": 60.0, "dist_coeffs": np.zeros(5)})
            env = script(environment, trajectory=HoverTraj(x0=np.array([0, 0, 1.0])),
                         world=world, camera=camera, sim_rate=100)
            results.append((env, env.run(t_final=1)["camera_measurements"]))
        (ours_env, ours), (_, theirs) = results
        self.assertEqual(set(ours), set(theirs))
        np.testing.assert_allclose(ours["time"], np.arange(11) * 0.1, atol=1e-9)
        np.testing.assert_array_equal(ours["time"], theirs["time"])
        self.assertEqual(ours["image"].shape, (11, 120, 160, 3))
        self.assertEqual([len(k) for k in ours["keypoints"]],
                         [len(k) for k in theirs["keypoints"]])
        self.assertGreater(len(ours["keypoints"][0]), 50)  # the wall is in view
        # the same hover to a millimetre: the same pictures (measured: identical)
        self.assertLess((ours["image"] != theirs["image"]).mean(), 0.01)
        with tempfile.TemporaryDirectory() as folder:
            path = ours_env.save_camera_data(os.path.join(folder, "frames"), save_pngs=True)
            self.assertEqual(path, os.path.join(folder, "frames.npz"))
            with np.load(path, allow_pickle=True) as saved:
                np.testing.assert_array_equal(saved["image"], ours["image"])
            self.assertEqual(len(os.listdir(os.path.join(folder, "frames_frames"))), 11)
        with self.assertRaisesRegex(ValueError, "no camera frames"):
            script(Environment).save_camera_data()

    def test_motor_noise_shakes_the_vehicle_as_in_rotorpy(self):
        # RotorPy adds N(0, sigma^2) to the rotor speeds after each simulation step; aerobox at
        # each control period's end. Over four seeds each, 20 rad/s on a Crazyflie: the rotor
        # speeds jitter alike (measured: the means 2 % apart), and the hover wanders alike
        # (measured 2.4 to 4.3 cm RMS in RotorPy, 3.9 to 5.2 cm in aerobox)
        ours = np.array([hover_jitter(Environment, 20.0, seed) for seed in range(4)])
        theirs = np.array([hover_jitter(RotorPyEnvironment, 20.0, seed) for seed in range(4)])
        self.assertAlmostEqual(ours[:, 1].mean() / theirs[:, 1].mean(), 1.0, delta=0.1)
        self.assertLess(ours[:, 0].mean(), 2.0 * theirs[:, 0].mean())
        self.assertGreater(ours[:, 0].mean(), 0.5 * theirs[:, 0].mean())
        # numpy's seed is the run's: the same seed flies the same run, another another
        self.assertEqual(ours[0, 0], hover_jitter(Environment, 20.0, 0)[0])
        self.assertNotEqual(ours[0, 0], ours[1, 0])
        # without noise the rotors hold their hover speed
        self.assertLess(hover_jitter(Environment, 0.0, 0)[1], 0.1)

    def test_the_circle_in_wind_flies_as_in_rotorpy(self):
        results = [script(e, wind_profile=ConstantWind(2, 0, 0), sim_rate=100).run(t_final=5)
                   for e in (Environment, RotorPyEnvironment)]
        ours, theirs = results
        self.assertEqual(set(ours), set(theirs))
        for part in ("state", "control", "flat", "imu_measurements", "imu_gt",
                     "mocap_measurements", "state_estimate"):
            with self.subTest(part=part):
                self.assertEqual(set(ours[part]), set(theirs[part]))
                for key in ours[part]:
                    self.assertEqual(ours[part][key].shape, theirs[part][key].shape, key)
        np.testing.assert_array_equal(ours["time"], theirs["time"])
        self.assertIs(ours["exit"], RotorPyExitStatus.TIMEOUT)
        self.assertIs(ExitStatus, RotorPyExitStatus)
        self.assertIsNone(ours["camera_measurements"])
        # the same flight in another physics: within 1 cm all along (measured 3.3 mm)
        apart = np.linalg.norm(ours["state"]["x"] - theirs["state"]["x"], axis=1)
        self.assertLess(apart.max(), 0.01)
        # the wind blew, and the IMU read the specific force in the body frame
        np.testing.assert_allclose(ours["state"]["wind"][1:], [[2.0, 0, 0]] * (len(apart) - 1))
        np.testing.assert_allclose(ours["imu_gt"]["accel"][-1], theirs["imu_gt"]["accel"][-1],
                                   atol=0.2)
        self.assertAlmostEqual(float(np.mean(ours["imu_gt"]["accel"][:, 2])), 9.81, delta=0.5)

    def test_terminate_as_rotorpy_means_it(self):
        hover = HoverTraj(x0=np.array([0, 0, 1.0]))
        complete = script(Environment, hover).run(t_final=5, terminate=None)
        self.assertIs(complete["exit"], RotorPyExitStatus.COMPLETE)
        self.assertAlmostEqual(complete["time"][-1], 1.0, places=9)  # at the end from the start
        never = script(Environment, hover).run(t_final=2)  # RotorPy's default: False
        self.assertIs(never["exit"], RotorPyExitStatus.TIMEOUT)
        self.assertAlmostEqual(never["time"][-1], 2.0, places=6)
        told = script(Environment).run(
            t_final=5, terminate=lambda t, s: RotorPyExitStatus.COMPLETE if s["x"][1] > 0.5
            else None)
        self.assertIs(told["exit"], RotorPyExitStatus.COMPLETE)
        self.assertGreater(told["state"]["x"][-1, 1], 0.5)
        self.assertLess(told["time"][-1], 2.0)

    def test_a_block_of_the_world_is_a_collision(self):
        world = World({"bounds": {"extents": [-3, 3, -3, 3, 0, 3]},
                       "blocks": [{"extents": [-0.2, 0.2, 0.6, 1.2, 0, 2], "color": [1, 0, 0]}]})
        result = script(Environment, world=world, sim_rate=100).run(t_final=5)
        self.assertIs(result["exit"], RotorPyExitStatus.COLLISION)
        reached = result["state"]["x"][-1]
        self.assertGreater(world.path_collisions(reached, 0.25).size, 0)

    def test_the_controller_flies_on_the_mocap_when_asked(self):
        class Seeing(SE3Control):
            def __init__(self, params):
                super().__init__(params)
                self.seen = []

            def update(self, t, state, flat_output):
                self.seen.append(np.array(state["x"]))
                return super().update(t, state, flat_output)

        env = script(Environment)
        env.controller = Seeing(quad_params)
        result = env.run(t_final=1, use_mocap=True)
        np.testing.assert_array_equal(np.array(env.controller.seen),
                                      result["mocap_measurements"]["x"])
        self.assertFalse(np.array_equal(result["mocap_measurements"]["x"], result["state"]["x"]))

    def test_what_aerobox_cannot_fly_is_refused(self):
        with self.assertRaises(ValueError) as raised:
            script(Environment, sim_rate=300)
        self.assertIn("sim_rate 300 Hz must divide", str(raised.exception))
        vehicle = Multirotor(quad_params, control_abstraction="cmd_vel")
        with self.assertRaises(ValueError) as raised:
            Environment(vehicle=vehicle, controller=SE3Control(quad_params), trajectory=CIRCLE)
        self.assertIn("'cmd_vel' has no aerobox inner loop", str(raised.exception))
        with self.assertRaises(TypeError):
            Environment(vehicle=quad_params, controller=SE3Control(quad_params),
                        trajectory=CIRCLE)


if __name__ == "__main__":
    unittest.main()
