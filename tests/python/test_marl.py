"""aerobox.marl: PettingZoo's own Parallel API and seed tests, two agents flown into each other
(both out of the game, each told whom it hit), determinism by seed, and bad input. Run with the
project environment's python (.venv: PettingZoo and Gymnasium from PyPI)."""

import math
import unittest
import warnings

import numpy as np
from pettingzoo.test import parallel_api_test, parallel_seed_test

from aerobox.marl import NAME, parallel_env

G = 9.81


def toward_centre(env, observations, tilt=0.2):
    """ctatt actions that tilt every agent toward the circle's centre, its height held."""
    q = env.quad_params
    low, high = q["k_eta"] * q["rotor_speed_min"] ** 2, q["k_eta"] * q["rotor_speed_max"] ** 2
    per_rotor = q["mass"] * G / math.cos(tilt) / 4
    thrust = 2 * (per_rotor - low) / (high - low) - 1
    actions = {}
    for agent, o in observations.items():
        goal_from_here = -o[0:3]  # the observation starts with p - goal
        # the centre is half way: tilt toward it, about the body axes (yaw 0)
        direction = goal_from_here[:2] / max(np.linalg.norm(goal_from_here[:2]), 1e-9)
        max_tilt = 0.6
        actions[agent] = np.array([thrust, -direction[1] * tilt / max_tilt,
                                   direction[0] * tilt / max_tilt, 0.0], np.float32)
    return actions


class ParallelApi(unittest.TestCase):
    def test_pettingzoo_s_parallel_api_test_passes(self):
        for agents in (2, 4):
            with self.subTest(agents=agents):
                env = parallel_env(agents=agents)
                with warnings.catch_warnings():
                    warnings.simplefilter("error")
                    parallel_api_test(env, num_cycles=300)
                self.assertEqual(env.metadata["name"], NAME)
                self.assertEqual(env.observation_space("agent_0").shape,
                                 (18 + 4 + 6 * (agents - 1),))

    def test_pettingzoo_s_seed_test_passes(self):
        parallel_seed_test(lambda: parallel_env(agents=3), num_cycles=100)

    def test_the_same_seed_gives_the_same_episode(self):
        def episode(seed):
            env = parallel_env(agents=3)
            observations, _ = env.reset(seed=seed)
            out = [np.concatenate([observations[a] for a in sorted(observations)])]
            rng = np.random.default_rng(7)
            for _ in range(50):
                if not env.agents:
                    break
                actions = {a: rng.uniform(-1, 1, 4).astype(np.float32) for a in env.agents}
                observations, *_ = env.step(actions)
                out.append(np.concatenate([observations[a] for a in sorted(observations)]))
            return out

        first, again, other = episode(5), episode(5), episode(6)
        self.assertEqual(len(first), len(again))
        for a, b in zip(first, again):
            np.testing.assert_array_equal(a, b)
        self.assertFalse(np.array_equal(first[0], other[0]))


class Physics(unittest.TestCase):
    def test_the_physics_rate_is_the_world_s_step(self):
        def after(rate):
            env = parallel_env(agents=2, physics_rate=rate)
            env.reset(seed=1)
            observations, *_ = env.step({a: np.full(4, 0.3, np.float32) for a in env.agents})
            return observations["agent_0"]
        fine, coarse = after(1000), after(200)
        self.assertFalse(np.array_equal(fine, coarse))
        np.testing.assert_allclose(fine[:6], coarse[:6], atol=5e-3)  # the same flight, roughly


class Contacts(unittest.TestCase):
    def test_two_agents_flown_into_each_other_are_both_out_naming_the_other(self):
        env = parallel_env(agents=2, action="ctatt", radius=1.0)
        observations, _ = env.reset(seed=1)
        hit = {}
        for _ in range(300):
            actions = toward_centre(env, observations)
            observations, rewards, terminations, truncations, infos = env.step(actions)
            for agent, done in terminations.items():
                if done:
                    hit[agent] = (infos[agent]["touched"], rewards[agent])
            if not env.agents:
                break
        self.assertEqual(set(hit), {"agent_0", "agent_1"})
        self.assertEqual(hit["agent_0"][0], "agent_1")
        self.assertEqual(hit["agent_1"][0], "agent_0")
        self.assertLess(hit["agent_0"][1], -5)  # the collision's penalty
        self.assertEqual(env.agents, [])

    def test_an_agent_out_of_the_game_gets_no_more_actions(self):
        env = parallel_env(agents=2)
        env.reset(seed=2)
        for _ in range(1000):  # zero actions: below hover thrust, both sink to the floor
            if not env.agents:
                break
            _, _, terminations, _, infos = env.step({a: np.zeros(4) for a in env.agents})
        self.assertEqual(env.agents, [])
        self.assertTrue(all(i["touched"] == "floor" for i in infos.values()))


class BadInputs(unittest.TestCase):
    def test_bad_parameters_and_actions_are_refused_naming_them(self):
        cases = [(dict(agents=1), "agents=1"), (dict(radius=-1), "radius=-1"),
                 (dict(agents=64, radius=1.0), "neighbours would start"),
                 (dict(vehicle="blimp"), "vehicle"), (dict(action="velocity"), "velocity")]
        for kwargs, named in cases:
            with self.subTest(**kwargs):
                with self.assertRaises(ValueError) as caught:
                    parallel_env(**kwargs)
                self.assertIn(named, str(caught.exception))
        with self.assertRaisesRegex(TypeError, "unknown argument 'agnts'"):
            parallel_env(agnts=3)
        env = parallel_env(agents=2)
        env.reset(seed=1)
        with self.assertRaisesRegex(ValueError, "no action for agent_1"):
            env.step({"agent_0": np.zeros(4)})
        with self.assertRaisesRegex(ValueError, "agent_0's action"):
            env.step({"agent_0": np.array([np.nan, 0, 0, 0]), "agent_1": np.zeros(4)})


if __name__ == "__main__":
    unittest.main()
