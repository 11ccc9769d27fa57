"""aerobox's vector environments for stable-baselines3 (its own VecEnv API, which resets a world
in the same step its episode ends):

    from stable_baselines3 import PPO
    from aerobox.sb3 import AeroboxVecEnv, HoverVecEnv

    env = HoverVecEnv(num_envs=16)               # gym.make's keyword arguments as well
    model = PPO("MlpPolicy", env).learn(200_000)
    env = AeroboxVecEnv("aerobox/Track-v0", num_envs=16)   # any of aerobox.envs' ids

The same worlds as aerobox.envs (C++ threads, no Python per world). When a world's episode ends,
step_wait returns its new start and puts the last observation in info["terminal_observation"],
with info["TimeLimit.truncated"] when time, not a crash, ended it (what SB3's algorithms read to
bootstrap). seed(s) seeds world i with s + i at the next reset, as SB3's own VecEnvs do.
"""

import os

import numpy as np

try:
    from stable_baselines3.common.vec_env.base_vec_env import VecEnv
except ImportError as e:  # pragma: no cover - said to the user
    raise ImportError("aerobox.sb3 needs stable-baselines3: pip install stable-baselines3") from e

from .envs import HOVER, _core, _num_envs, _spaces


class AeroboxVecEnv(VecEnv):
    """The worlds of aerobox.envs' `env_id` as an SB3 VecEnv; threads: default the machine's
    cores; params: gym.make's keyword arguments."""

    def __init__(self, env_id=HOVER, num_envs=1, threads=None, **params):
        self.env_id = env_id
        num_envs = _num_envs(env_id, num_envs)
        threads = (os.cpu_count() or 1) if threads is None else threads
        self._core = _core(env_id, params, num_envs, int(threads))
        self.params = dict(params)
        self.observation_names, observation, action = _spaces(self._core)
        self.render_mode = None
        super().__init__(num_envs, observation, action)
        self.reward_terms = self._core.reward_terms
        self._actions = None
        self._seeded = False

    def reset(self):
        seeds = list(self._seeds)
        if not self._seeded and any(s is None for s in seeds):
            seeds = [int(s) if s is not None else int(np.random.randint(2**31)) for s in seeds]
        self._seeded = True
        obs = self._core.reset(seeds)
        self._reset_seeds()
        self._reset_options()
        return obs

    def step_async(self, actions):
        self._actions = np.asarray(actions, dtype=np.float64).reshape(self.num_envs, -1)

    def step_wait(self):
        obs, rewards, terminated, truncated, terms = self._core.step(self._actions)
        done = terminated | truncated
        infos = [dict(zip(self.reward_terms, row)) for row in terms.tolist()]
        ended = np.flatnonzero(done)
        if ended.size:
            for i in ended:
                infos[i]["terminal_observation"] = obs[i].copy()
                infos[i]["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
            obs[ended] = self._core.reset_some(ended.tolist())
        return obs, rewards.astype(np.float32), done, infos

    def close(self):
        pass

    def get_attr(self, attr_name, indices=None):
        return [getattr(self, attr_name)] * len(self._indices(indices))

    def set_attr(self, attr_name, value, indices=None):
        raise AttributeError(f"{self.env_id}: set_attr: the worlds' parameters are fixed when made")

    def env_method(self, method_name, *args, indices=None, **kwargs):
        raise AttributeError(f"{self.env_id}: env_method: the worlds are C++ objects, with no methods "
                             "to call one by one")

    def env_is_wrapped(self, wrapper_class, indices=None):
        return [False] * len(self._indices(indices))

    def _indices(self, indices):
        if indices is None:
            return range(self.num_envs)
        return [indices] if isinstance(indices, int) else indices


class HoverVecEnv(AeroboxVecEnv):
    """aerobox/Hover-v0's worlds as an SB3 VecEnv."""

    def __init__(self, num_envs=1, threads=None, **params):
        super().__init__(HOVER, num_envs, threads, **params)
