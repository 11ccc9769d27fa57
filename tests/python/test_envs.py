"""aerobox.envs: Gymnasium's own checker for every id, action and attitude, the vector
environment against lone ones (Hover, Track, Navigate), a scripted policy that hovers and a
random one that does not, reset's options, and every bad input. Run with the project
environment's python (.venv: Gymnasium from PyPI)."""

import subprocess
import sys
import unittest
import warnings

import gymnasium as gym
import numpy as np
from gymnasium.utils.env_checker import check_env

import aerobox.envs
from aerobox.envs import AeroboxEnv, AeroboxVectorEnv, HoverEnv, HoverVectorEnv

G = 9.81


def quiet_check(env):
    with warnings.catch_warnings():
        # the unbounded velocity and rate components: Gymnasium warns of any infinite bound
        warnings.simplefilter("error")
        warnings.filterwarnings("ignore", message=".*Box observation space (minimum|maximum)")
        check_env(env)


class Checker(unittest.TestCase):
    def test_gymnasium_s_checker_passes_every_action_and_attitude(self):
        for action in ("thrusts", "ctbm", "ctbr", "ctatt", "velocity"):
            for attitude in ("matrix", "quaternion"):
                with self.subTest(action=action, attitude=attitude):
                    env = gym.make(aerobox.envs.HOVER, action=action, attitude=attitude)
                    quiet_check(env.unwrapped)
                    size = 6 + (9 if attitude == "matrix" else 4) + 3 + 4
                    self.assertEqual(env.observation_space.shape, (size,))
                    self.assertEqual(len(env.unwrapped.observation_names), size)

    def test_gymnasium_s_checker_passes_track_and_navigate(self):
        for env_id, extra in ((aerobox.envs.TRACK, 6 + 3 * 9), (aerobox.envs.NAVIGATE, 16 + 2)):
            with self.subTest(env_id=env_id):
                env = gym.make(env_id, render_mode="rgb_array", width=80, height=60)
                quiet_check(env.unwrapped)
                self.assertEqual(env.observation_space.shape, (22 + extra,))
                env.reset(seed=2)
                self.assertEqual(env.render().shape, (60, 80, 3))
        env = gym.make(aerobox.envs.NAVIGATE)
        self.assertEqual(env.unwrapped.reward_terms,
                         ["alive", "progress", "velocity", "rate", "action", "arrival"])
        self.assertEqual(env.unwrapped.observation_names[-3:],
                         ["range15", "range_down", "range_up"])
        track = gym.make(aerobox.envs.TRACK, track_points=2).unwrapped
        self.assertEqual(track.observation_names[22:28],
                         ["ref_vx", "ref_vy", "ref_vz", "ref_ax", "ref_ay", "ref_az"])
        self.assertEqual(track.observation_names[-3:], ["ref2_ax", "ref2_ay", "ref2_az"])

    def test_gymnasium_s_checker_passes_every_id_on_the_rigid_backend(self):
        for env_id in (aerobox.envs.HOVER, aerobox.envs.TRACK, aerobox.envs.NAVIGATE):
            with self.subTest(env_id=env_id):
                env = gym.make(env_id, backend="rigid", render_mode="rgb_array", width=80,
                               height=60)
                quiet_check(env.unwrapped)
                env.reset(seed=2)
                self.assertEqual(env.render().shape, (60, 80, 3))

    def test_the_observation_is_what_the_docs_say(self):
        env = HoverEnv(attitude="quaternion", target=[1.0, 2.0, 3.0])
        obs, _ = env.reset(seed=4)
        names = env.observation_names
        self.assertEqual(names[:6], ["dx", "dy", "dz", "vx", "vy", "vz"])
        self.assertEqual(names[6:10], ["qw", "qx", "qy", "qz"])
        self.assertGreaterEqual(obs[6], 0.0)  # w >= 0
        self.assertAlmostEqual(float(np.linalg.norm(obs[6:10])), 1.0, places=5)
        self.assertLessEqual(np.linalg.norm(obs[:3]), 1.0)  # within start_radius
        np.testing.assert_array_equal(obs[-4:], 0.0)  # no action yet
        a = np.array([0.1, -0.2, 0.3, -0.4], np.float32)
        obs, reward, _, _, info = env.step(a)
        np.testing.assert_array_equal(obs[-4:], a)
        self.assertEqual(list(info), ["alive", "position", "velocity", "rate", "action"])
        self.assertAlmostEqual(reward, sum(info.values()), places=12)
        self.assertAlmostEqual(info["action"], -0.01 * float(np.sum(a.astype(float)**2)), 9)
        self.assertAlmostEqual(info["position"], -float(np.linalg.norm(obs[:3])), places=6)

    def test_render_gives_a_picture(self):
        env = gym.make(aerobox.envs.HOVER, render_mode="rgb_array", width=160, height=120)
        env.reset(seed=1)
        frame = env.render()
        self.assertEqual(frame.shape, (120, 160, 3))
        self.assertEqual(frame.dtype, np.uint8)
        self.assertGreater(frame.std(), 5.0)  # not a blank picture


def run_single(seed, actions, env_id=aerobox.envs.HOVER, **params):
    """A lone environment's rows for `actions` (steps x 4), resetting (no seed) when an
    episode ends, as a vector world does on the next step."""
    env = AeroboxEnv(env_id, **params)
    obs, _ = env.reset(seed=seed)
    rows, ended = [], False
    for a in actions:
        if ended:
            obs, _ = env.reset()
            rows.append((obs, 0.0, False, False))
            ended = False
            continue
        obs, reward, terminated, truncated, _ = env.step(a)
        rows.append((obs, reward, terminated, truncated))
        ended = terminated or truncated
    return rows


class Vector(unittest.TestCase):
    PARAMS = dict(episode_time=0.8, start_radius=1.2, start_tilt=1.0)  # many episodes

    def actions(self, n, steps):
        # thrust mostly low: some fall to the floor
        a = np.random.default_rng(7).uniform(-1.0, 1.0, (steps, n, 4))
        a[..., 0] = np.clip(a[..., 0] - 0.5, -1, 1)
        return a

    def run_vector(self, n, seed, actions, threads, env_id=aerobox.envs.HOVER, params=None):
        params = self.PARAMS if params is None else params
        envs = gym.make_vec(env_id, num_envs=n, threads=threads, **params)
        self.assertIsInstance(envs, AeroboxVectorEnv)
        obs, _ = envs.reset(seed=seed)
        rows = []
        for a in actions:
            rows.append(envs.step(a)[:4])
        return obs, rows

    def test_world_i_is_a_lone_environment_seeded_s_plus_i(self):
        n, seed, steps = 4, 11, 240
        actions = self.actions(n, steps)
        _, rows = self.run_vector(n, seed, actions, threads=2)
        ends = sum(int(np.sum(r[2] | r[3])) for r in rows)
        self.assertGreater(ends, 8)  # episodes ended and were reset along the way
        self.assertTrue(any(np.any(r[2]) for r in rows))  # some crashed, too
        for i in range(n):
            single = run_single(seed + i, actions[:, i], **self.PARAMS)
            for k, (mine, theirs) in enumerate(zip(single, rows)):
                np.testing.assert_array_equal(mine[0], theirs[0][i], err_msg=f"world {i} step {k}")
                self.assertEqual(mine[1], theirs[1][i])
                self.assertEqual((mine[2], mine[3]), (theirs[2][i], theirs[3][i]))

    def test_track_and_navigate_worlds_are_lone_environments_too(self):
        # Track with every domain randomisation on: the episodes' draws are the world's own
        randomised = dict(episode_time=0.5, vary_mass=0.2, vary_thrust=0.1, vary_motor_lag=0.3,
                          wind_speed=3.0, wind_turbulence=0.5, sensors=True,
                          vary_sensor_noise=0.5)
        for env_id, params in ((aerobox.envs.TRACK, randomised),
                               (aerobox.envs.NAVIGATE, dict(episode_time=0.5, forest_trees=60,
                                                            goal_distance=2.0))):
            with self.subTest(env_id=env_id):
                n, seed, steps = 3, 21, 120
                actions = self.actions(n, steps)
                envs = gym.make_vec(env_id, num_envs=n, threads=2, **params)
                self.assertIsInstance(envs, AeroboxVectorEnv)
                envs.reset(seed=seed)
                rows = [envs.step(a)[:4] for a in actions]
                self.assertGreater(sum(int(np.sum(r[2] | r[3])) for r in rows), 3)
                for i in range(n):
                    single = run_single(seed + i, actions[:, i], env_id, **params)
                    for k, (mine, theirs) in enumerate(zip(single, rows)):
                        np.testing.assert_array_equal(mine[0], theirs[0][i],
                                                      err_msg=f"world {i} step {k}")
                        self.assertEqual(mine[1], theirs[1][i])

    def test_the_rigid_backend_s_worlds_are_lone_environments_and_fly_as_mujoco_s(self):
        n, seed, steps = 4, 31, 160
        actions = self.actions(n, steps)
        params = dict(self.PARAMS, backend="rigid")
        _, rows = self.run_vector(n, seed, actions, threads=2, params=params)
        self.assertTrue(any(np.any(r[2]) for r in rows))  # some crashed on the floor
        for i in range(n):
            single = run_single(seed + i, actions[:, i], **params)
            for k, (mine, theirs) in enumerate(zip(single, rows)):
                np.testing.assert_array_equal(mine[0], theirs[0][i], err_msg=f"world {i} step {k}")
                self.assertEqual((mine[2], mine[3]), (theirs[2][i], theirs[3][i]))
        # MuJoCo's worlds from the same seeds under the same actions: the same episodes, ending
        # at the same steps (the step that touches the floor ends both; MuJoCo's has pushed back
        # in it, so its last observation differs)
        _, reference = self.run_vector(n, seed, actions, threads=1)
        for k, (mine, theirs) in enumerate(zip(rows, reference)):
            np.testing.assert_array_equal(mine[2], theirs[2], err_msg=f"step {k}")
            np.testing.assert_array_equal(mine[3], theirs[3], err_msg=f"step {k}")
            flying = ~mine[2]
            np.testing.assert_allclose(mine[0][flying], theirs[0][flying], atol=1e-4,
                                       err_msg=f"step {k}")

    def test_the_number_of_threads_and_a_busy_machine_change_nothing(self):
        n, steps = 9, 120
        actions = self.actions(n, steps)
        # Hover, and Navigate in a forest with every randomisation and the sensors on
        navigate = dict(episode_time=0.6, forest_trees=60, goal_distance=2.0, vary_mass=0.2,
                        vary_thrust=0.1, wind_speed=3.0, wind_turbulence=0.5, sensors=True)
        busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(2)]
        try:
            runs = [(self.run_vector(n, 5, actions, threads=1),
                     self.run_vector(n, 5, actions, threads=3))]
            runs.append((self.run_vector(n, 5, actions, 1, aerobox.envs.NAVIGATE, navigate),
                         self.run_vector(n, 5, actions, 3, aerobox.envs.NAVIGATE, navigate)))
        finally:
            for p in busy:
                p.kill()
                p.wait()
        for one, three in runs:
            np.testing.assert_array_equal(one[0], three[0])
            for a, b in zip(one[1], three[1]):
                for x, y in zip(a, b):
                    np.testing.assert_array_equal(x, y)

    def test_spaces_and_seeds(self):
        envs = HoverVectorEnv(num_envs=3)
        self.assertEqual(envs.action_space.shape, (3, 4))
        self.assertEqual(envs.observation_space.shape, (3, 22))
        a, _ = envs.reset(seed=[4, 5, 6])
        b, _ = envs.reset(seed=4)
        np.testing.assert_array_equal(a, b)
        c, _ = envs.reset()  # goes on: new starts
        self.assertFalse(np.array_equal(b, c))
        obs, rewards, terminated, truncated, infos = envs.step(np.zeros((3, 4), np.float32))
        self.assertEqual((obs.dtype, rewards.shape, terminated.dtype), (np.float32, (3,), bool))
        self.assertEqual(infos["position"].shape, (3,))
        self.assertTrue(infos["_position"].all())


def hover_policy(obs, action="ctbr", mass=0.03, thrust_max=0.144):
    """A scripted hover from the observation alone (matrix attitude): a PD on the position
    gives the acceleration, its direction the body z axis, the error to it the body rates (or
    the attitude), each scaled into the action's [-1, 1] as the docs say."""
    d, v, R, w = obs[:3], obs[3:6], obs[6:15].reshape(3, 3).astype(float), obs[15:18]
    acc = -4.0 * d - 3.0 * v + np.array([0, 0, G])
    z_b = R[:, 2]
    thrust = mass * float(acc @ z_b)
    a0 = np.clip(2.0 * thrust / (4 * thrust_max) - 1.0, -1, 1)
    z_des = acc / np.linalg.norm(acc)
    if action == "ctbr":
        err = R.T @ np.cross(z_b, z_des)  # the tilt to remove, in the body frame
        rates = 8.0 * err
        return np.array([a0, *(np.clip(rates / 10.0, -1, 1))], np.float32)
    # R_z(yaw) R_y(pitch) R_x(roll) puts the body z axis at R_z(yaw) (cos r sin p, -sin r, ...)
    yaw = np.arctan2(R[1, 0], R[0, 0])
    c, s = np.cos(yaw), np.sin(yaw)
    z = np.array([c * z_des[0] + s * z_des[1], -s * z_des[0] + c * z_des[1], z_des[2]])
    roll = np.arcsin(np.clip(-z[1], -1, 1))
    pitch = np.arctan2(z[0], z[2])
    return np.array([a0, np.clip(roll / 0.6, -1, 1), np.clip(pitch / 0.6, -1, 1), yaw / np.pi],
                    np.float32)


class Policies(unittest.TestCase):
    def fly(self, policy, seed, action):
        env = HoverEnv(action=action)
        obs, _ = env.reset(seed=seed)
        distances = []
        for _ in range(1000):  # 10 s
            obs, _, terminated, truncated, _ = env.step(policy(obs))
            distances.append(float(np.linalg.norm(obs[:3])))
            if terminated or truncated:
                break
        return terminated, truncated, distances

    def test_a_scripted_policy_hovers_and_a_random_one_does_not(self):
        for action in ("ctbr", "ctatt"):
            for seed in range(5):
                with self.subTest(action=action, seed=seed):
                    terminated, truncated, d = self.fly(
                        lambda o: hover_policy(o, action), seed, action)
                    self.assertFalse(terminated)
                    self.assertTrue(truncated)
                    self.assertLess(max(d[500:]), 0.05)  # held within 5 cm from 5 s on
        rng = np.random.default_rng(0)
        for seed in range(5):
            terminated, _, d = self.fly(lambda o: rng.uniform(-1, 1, 4), seed, "ctbr")
            self.assertTrue(terminated)
            self.assertLess(len(d), 300)


class Options(unittest.TestCase):
    def test_reset_s_options_set_the_start_and_the_target(self):
        env = HoverEnv()
        obs, _ = env.reset(seed=3, options={"start": [0.5, 0.0, 1.0], "target": [0, 0, 2]})
        np.testing.assert_allclose(obs[:3], [0.5, 0.0, -1.0], atol=1e-6)
        nav = gym.make(aerobox.envs.NAVIGATE, forest_trees=0).unwrapped
        obs, _ = nav.reset(seed=1, options={"start": [2, 2, 1], "target": [6, 2, 1]})
        np.testing.assert_allclose(obs[:3], [-4.0, 0.0, 0.0], atol=1e-6)
        # the ranges from (2, 2, 1) in the empty 10 m forest: its bounds and floor
        ranges = dict(zip(nav.observation_names[22:], obs[22:]))
        self.assertAlmostEqual(ranges["range0"], 4.0, places=5)   # +x: the reach
        self.assertAlmostEqual(ranges["range8"], 2.0, places=5)   # -x: the bound at x = 0
        self.assertAlmostEqual(ranges["range_down"], 1.0, places=5)  # the floor
        with self.assertRaisesRegex(ValueError, r"is not free"):
            nav.reset(options={"target": [0.01, 5, 1]})  # against the bound
        # a depth image after the ranges, in metres, range_max where nothing is within reach
        seeing = gym.make(aerobox.envs.NAVIGATE, depth_width=8, depth_height=6).unwrapped
        obs, _ = seeing.reset(seed=1)
        self.assertEqual(seeing.observation_space.shape, (22 + 18 + 48,))
        self.assertEqual(seeing.observation_names[-1], "depth_5_7")
        depth = obs[-48:]
        self.assertTrue(np.all((depth > 0) & (depth <= 4.0 + 1e-6)))
        self.assertLess(depth.min(), 4.0)  # the floor, at least
        with self.assertRaisesRegex(ValueError, r"depth_height"):
            gym.make(aerobox.envs.NAVIGATE, depth_width=8)


class BadInputs(unittest.TestCase):
    def test_each_names_the_environment_the_field_and_the_value(self):
        cases = [
            (dict(episode_tim=3), TypeError, r"aerobox/Hover-v0: unknown argument 'episode_tim'; "
                                             r"did you mean 'episode_time'\?"),
            (dict(episode_time=-1), ValueError,
             r"argument 'episode_time' = -1 s: expected 0.01 to 3600"),
            (dict(action="motors"), ValueError, r"argument 'action' = 'motors': expected"),
            (dict(target=[0, 0]), ValueError, r"argument 'target' .* expected three numbers"),
            (dict(control_rate=300), ValueError, r"control_rate 300.* must divide"),
            (dict(backend="bullet"), ValueError, r"argument 'backend' = 'bullet': expected "
                                                 r"'mujoco' or 'rigid'"),
            (dict(target=[0, 0, 0.5]), ValueError, r"target's height"),
            (dict(task="navigate", map="no/such.json"), ValueError, r"map 'no/such.json'"),
            (dict(task="fly"), ValueError, r"argument 'task' = 'fly': expected 'hover', "
                                           r"'navigate' or 'track'"),
        ]
        for params, error, pattern in cases:
            with self.subTest(params=params):
                with self.assertRaisesRegex(error, pattern):
                    HoverEnv(**params)
        with self.assertRaisesRegex(ValueError, "num_envs 0"):
            HoverVectorEnv(num_envs=0)

    def test_bad_actions_seeds_and_order(self):
        env = HoverEnv()
        with self.assertRaisesRegex(gym.error.ResetNeeded, "step before reset"):
            env.step(np.zeros(4))
        env.reset(seed=1)
        with self.assertRaisesRegex(ValueError, r"the action has shape \(3,\), expected \(4,\)"):
            env.step(np.zeros(3))
        with self.assertRaisesRegex(ValueError, r"action\[0\]\[2\] = nan: expected a number in"):
            env.step([0, 0, np.nan, 0])
        with self.assertRaisesRegex(ValueError, r"action\[0\]\[0\] = 1.5"):
            env.step([1.5, 0, 0, 0])
        with self.assertRaisesRegex(ValueError, r"unknown option 'targt'; did you mean 'target'"):
            env.reset(options={"targt": [0, 0, 1]})
        with self.assertRaisesRegex(ValueError, r"options\['start'\] \[0, 0\]: expected three"):
            env.reset(options={"start": [0, 0]})
        with self.assertRaisesRegex(ValueError, r"options\[\"start\"\] \[0, 0, -1\]"):
            env.reset(options={"start": [0, 0, -1]})
        with self.assertRaisesRegex(ValueError, r"seed -1: expected an integer"):
            env.reset(seed=-1)
        envs = HoverVectorEnv(num_envs=2)
        envs.reset(seed=0)
        with self.assertRaisesRegex(ValueError, r"actions have shape \(4,\), expected \(2, 4\)"):
            envs.step(np.zeros(4))
        with self.assertRaisesRegex(ValueError, r"action\[1\]\[3\] = inf"):
            envs.step([[0, 0, 0, 0], [0, 0, 0, np.inf]])
        # an episode that ended must be reset
        env = HoverEnv(episode_time=0.02)
        env.reset(seed=1)
        env.step(np.zeros(4))
        env.step(np.zeros(4))
        with self.assertRaisesRegex(gym.error.ResetNeeded, "the episode has ended"):
            env.step(np.zeros(4))


if __name__ == "__main__":
    unittest.main()
