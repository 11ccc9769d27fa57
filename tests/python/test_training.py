"""Training on aerobox's worlds: the stable-baselines3 vector environment's same-step resets, a
short training run of examples/train_hover.py that saves a policy (no reward threshold: that is
the benchmark's), and `aerobox fly` flying the saved policy through examples/policy_controller.py
with the usual outputs. Run with the project environment's python (.venv: SB3 from PyPI on
Debian's torch)."""

import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
from stable_baselines3 import PPO

import aerobox
from aerobox.envs import HoverEnv
from aerobox.sb3 import AeroboxVecEnv, HoverVecEnv
from test_envs import hover_policy

TOP = os.environ.get("AEROBOX_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLES = os.path.join(TOP, "examples")
sys.path.insert(0, EXAMPLES)
from policy_controller import PolicyController  # noqa: E402  (the example, as users run it)


class Sb3VecEnv(unittest.TestCase):
    def test_a_world_that_ends_starts_again_in_the_same_step(self):
        env = HoverVecEnv(num_envs=3, episode_time=0.05)  # 5 steps
        env.seed(20)
        obs = env.reset()
        lone = [HoverEnv(episode_time=0.05) for _ in range(3)]
        for i, e in enumerate(lone):
            np.testing.assert_array_equal(obs[i], e.reset(seed=20 + i)[0])
        for step in range(5):
            action = np.full((3, 4), 0.05 * step, np.float32)
            obs, rewards, dones, infos = env.step(action)
            expected = [e.step(action[i]) for i, e in enumerate(lone)]
            for i in range(3):
                self.assertEqual(rewards[i], np.float32(expected[i][1]))
        self.assertTrue(dones.all())
        for i, e in enumerate(lone):
            # the last observation in the info, the world's next start in the observation
            np.testing.assert_array_equal(infos[i]["terminal_observation"], expected[i][0])
            self.assertTrue(infos[i]["TimeLimit.truncated"])
            np.testing.assert_array_equal(obs[i], e.reset()[0])
        self.assertEqual(env.get_attr("num_envs"), [3, 3, 3])
        self.assertEqual(env.env_is_wrapped(object), [False] * 3)


    def test_any_id_with_its_defaults(self):
        env = AeroboxVecEnv("aerobox/Navigate-v0", num_envs=2, forest_trees=5)
        self.assertEqual(env.observation_space.shape, (22 + 18,))
        self.assertEqual(env.reward_terms[-1], "arrival")
        env.seed(1)
        obs = env.reset()
        obs, rewards, dones, infos = env.step(np.zeros((2, 4), np.float32))
        self.assertEqual(obs.shape, (2, 40))
        with self.assertRaisesRegex(ValueError, "env_id 'aerobox/Hover-v9'"):
            AeroboxVecEnv("aerobox/Hover-v9")


class PolicyAsController(unittest.TestCase):
    """The example controller builds the environment's observation and turns an action into a
    command as the environment does: a policy that hovers in the environment (the scripted one
    of test_envs, ctatt) hovers through it in aerobox.Simulator."""

    def test_a_policy_that_hovers_in_the_environment_hovers_as_a_controller(self):
        class Scripted:  # stable-baselines3's predict contract
            def predict(self, obs, deterministic=True):
                return hover_policy(obs, "ctatt"), None

        class Hold:
            duration = 6.0

            def update(self, t):
                return {"x": np.array([1.3, 1.2, 1.4])}

        sim = aerobox.Simulator(os.path.join(TOP, "scenes/empty/scenario.toml"),
                                vehicle="crazyflie", start=[1.0, 1.0, 1.0])
        params = dict(action="ctatt", vehicle="crazyflie", mass=0.03, max_tilt=0.6)
        controller = PolicyController(sim.quad_params, Scripted(), params)
        result = sim.run(controller, Hold(), t_final=6.0, control_rate=100, terminate=False)
        late = result["state"]["x"][result["time"] > 4.0]
        error = np.linalg.norm(late - [1.3, 1.2, 1.4], axis=1)
        self.assertLess(error.max(), 0.05)


class Training(unittest.TestCase):
    def test_training_runs_saves_and_the_saved_policy_flies_a_map(self):
        with tempfile.TemporaryDirectory() as folder:
            out = os.path.join(folder, "policy")
            run = subprocess.run(
                [sys.executable, os.path.join(EXAMPLES, "train_hover.py"), "--out", out,
                 "--steps", "4096", "--envs", "4", "--eval-every", "4096"],
                capture_output=True, text=True, timeout=600)
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertIn("4096 steps", run.stdout)
            model = PPO.load(out + ".zip")
            self.assertEqual(model.observation_space.shape, (22,))
            with open(out + ".json") as file:
                saved = json.load(file)
            self.assertEqual((saved["action"], saved["vehicle"]), ("ctatt", "crazyflie"))
            self.assertAlmostEqual(saved["mass"], 0.03)
            # the observation's normalisation, which the controller needs, is saved with it
            self.assertEqual(len(saved["obs_mean"]), 22)
            self.assertEqual(len(saved["obs_var"]), 22)
            self.assertGreater(min(saved["obs_var"]), 0.0)
            # aerobox fly with the policy as its controller: the active environment's packages
            # (stable-baselines3) are seen by the command's Python
            flight = os.path.join(folder, "flight")
            env = dict(os.environ, VIRTUAL_ENV=sys.prefix, AEROBOX_POLICY=out + ".zip")
            fly = subprocess.run(
                [os.environ["AEROBOX_BIN"], "fly", os.path.join(TOP, "scenes/empty/scenario.toml"),
                 "--set", "vehicle.kind=crazyflie", "--set", "controller.rate=100",
                 "--max-speed", "1", "--controller",
                 os.path.join(EXAMPLES, "policy_controller.py") + ":PolicyController",
                 "--command", "cmd_ctatt", "--out", flight, "--no-video", "--quiet"],
                capture_output=True, text=True, timeout=600, env=env)
            # 4096 steps of training do not hover: the flight runs and reports how it ended
            self.assertIn(fly.returncode, (0, 5), fly.stderr + fly.stdout)  # 5: the flight failed
            with open(os.path.join(flight, "summary.json")) as file:
                summary = json.load(file)
            self.assertTrue(summary["controller"].endswith("policy_controller.py:PolicyController"))
            self.assertTrue(os.path.exists(os.path.join(flight, "telemetry.csv")))
            self.assertTrue(os.path.exists(os.path.join(flight, "report.html")))
            # a policy trained on another vehicle is refused, naming both
            wrong = subprocess.run(
                [os.environ["AEROBOX_BIN"], "fly", os.path.join(TOP, "scenes/empty/scenario.toml"),
                 "--controller", os.path.join(EXAMPLES, "policy_controller.py") +
                 ":PolicyController", "--out", flight + "2",
                 "--no-video", "--quiet"], capture_output=True, text=True, timeout=600, env=env)
            self.assertEqual(wrong.returncode, 2)
            self.assertIn("trained on the crazyflie (30 g); this vehicle is 80 g", wrong.stderr)


if __name__ == "__main__":
    unittest.main()
