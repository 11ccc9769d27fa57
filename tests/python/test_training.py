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

from aerobox.envs import HoverEnv
from aerobox.sb3 import HoverVecEnv

TOP = os.environ.get("AEROBOX_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLES = os.path.join(TOP, "examples")


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
            self.assertEqual((saved["action"], saved["vehicle"]), ("ctbr", "crazyflie"))
            self.assertAlmostEqual(saved["mass"], 0.03)
            # aerobox fly with the policy as its controller: the active environment's packages
            # (stable-baselines3) are seen by the command's Python
            flight = os.path.join(folder, "flight")
            env = dict(os.environ, VIRTUAL_ENV=sys.prefix, AEROBOX_POLICY=out + ".zip")
            fly = subprocess.run(
                [os.environ["AEROBOX_BIN"], "fly", os.path.join(TOP, "scenes/empty/scenario.toml"),
                 "--set", "vehicle.kind=crazyflie", "--max-speed", "1", "--controller",
                 os.path.join(EXAMPLES, "policy_controller.py") + ":PolicyController",
                 "--command", "cmd_ctbr", "--out", flight, "--no-video", "--quiet"],
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
                 ":PolicyController", "--command", "cmd_ctbr", "--out", flight + "2",
                 "--no-video", "--quiet"], capture_output=True, text=True, timeout=600, env=env)
            self.assertEqual(wrong.returncode, 2)
            self.assertIn("trained on the crazyflie (30 g); this vehicle is 80 g", wrong.stderr)


if __name__ == "__main__":
    unittest.main()
