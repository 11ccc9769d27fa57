"""aerobox's learning environments for Gymnasium (1.x API), registered when this module is
imported:

    import gymnasium as gym
    import aerobox.envs  # registers aerobox/Hover-v0

    env = gym.make("aerobox/Hover-v0", action="ctbr")           # one world
    envs = gym.make_vec("aerobox/Hover-v0", num_envs=64)        # 64 worlds stepped in C++ threads

aerobox/Hover-v0: reach and hold `target` from a random start (uniform within start_radius of
it, a random speed, tilt, yaw and body rate). The worlds are MuJoCo at a 1 ms step with
aerobox's inner loops below the action's level; one step() is 1/control_rate seconds.

Action: four numbers in [-1, 1] (float32 Box), by `action`:
    "thrusts": each rotor's thrust, T_i = T_min + (a_i + 1) / 2 (T_max - T_min), rotors in
        aerobox's (RotorPy's) order: front-left, front-right, back-right, back-left;
    "ctbm": a_0 the collective thrust (4 x the rotor's scaling above), a_1..a_3 body moments
        [N m]: roll and pitch a_i T_max l (l the arm length), yaw a_3 2 T_max k_m / k_eta;
    "ctbr" (default): a_0 the collective thrust, a_1..a_3 body rates [rad/s] a_i max_rate;
    "ctatt": a_0 the collective thrust, attitude R_z(pi a_3) R_y(max_tilt a_2) R_x(max_tilt a_1).
Observation (float32 Box), in this order (observation_names gives the names):
    p - target [m] (world ENU, z up), v [m/s] (world), the attitude (attitude="matrix": R_WB, the
    body's FLU axes in the world, row by row; attitude="quaternion": w, x, y, z with w >= 0),
    body rates w_B [rad/s] (FLU), the last action.
Reward per step: reward_alive - reward_position |p - target| - reward_velocity |v|
    - reward_rate |w_B| - reward_action |a|^2; the terms are in `info` by name.
terminated: a contact (the floor included), further than bounds_radius from the target, a
    non-finite state or a MuJoCo warning; truncated: episode_time has passed.
Every parameter is a keyword argument of gym.make (see `keys()` for units, defaults, ranges).

Seeds: reset(seed=s) starts the world's own stream at s; reset() goes on from it. A vector
environment's reset(seed=s) seeds world i with s + i and resets a world whose episode ended on
the step after (Gymnasium 1.x's autoreset: that step returns the new start, reward 0, neither
flag, and ignores the world's action). World i of a vector seeded with s gives the same
numbers, bit for bit, as a lone environment seeded with s + i, whatever the number of threads.
"""

import os

import numpy as np

try:
    import gymnasium as gym
    from gymnasium import spaces
    from gymnasium.vector import VectorEnv
    from gymnasium.vector.utils import batch_space
except ImportError as e:  # pragma: no cover - said to the user
    raise ImportError("aerobox.envs needs Gymnasium 1.x: pip install gymnasium") from e

from . import _aerobox

HOVER = "aerobox/Hover-v0"
_SEED_LIMIT = 2**63


def keys():
    """The environments' parameters: (key, unit, default, range, meaning) rows."""
    return _aerobox.env_keys()


def _spaces(params, core):
    names = _aerobox.env_observation_names(params)
    observation = spaces.Box(-np.inf, np.inf, (core.observation_size,), np.float32)
    action = spaces.Box(-1.0, 1.0, (core.action_size,), np.float32)
    return names, observation, action


def _check_options(who, options):
    if options is not None and (not isinstance(options, dict) or options):
        raise ValueError(f"{who}: reset: options {options!r}: this environment takes none yet "
                         "(its parameters are gym.make's keyword arguments)")


def _seed(who, seed):
    if seed is None:
        return None
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)) \
            or not 0 <= seed < _SEED_LIMIT:
        raise ValueError(f"{who}: reset: seed {seed!r}: expected an integer in [0, 2**63)")
    return int(seed)


class HoverEnv(gym.Env):
    """aerobox/Hover-v0, one world (module doc)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 30}

    def __init__(self, render_mode=None, width=320, height=240, **params):
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"{HOVER}: render_mode {render_mode!r}: expected None or 'rgb_array'")
        self._core = _aerobox.EnvCore(params, 1, 1, HOVER)
        self.observation_names, self.observation_space, self.action_space = \
            _spaces(params, self._core)
        self.reward_terms = _aerobox.env_reward_terms()
        self.quad_params = self._core.quad_params  # the vehicle, as RotorPy's dict
        self.render_mode, self._size = render_mode, (int(width), int(height))
        self._seeded = False
        self._ended = None  # None: never reset

    def reset(self, *, seed=None, options=None):
        seed = _seed(HOVER, seed)
        _check_options(HOVER, options)
        super().reset(seed=seed)
        if seed is None and not self._seeded:
            seed = int(self.np_random.integers(_SEED_LIMIT))
        self._seeded = True
        self._ended = False
        return self._core.reset([seed])[0], {}

    def step(self, action):
        if self._ended is None:
            raise gym.error.ResetNeeded(f"{HOVER}: step before reset(): call reset() first")
        if self._ended:
            raise gym.error.ResetNeeded(f"{HOVER}: the episode has ended: call reset()")
        a = np.asarray(action, dtype=np.float64)
        if a.shape != self.action_space.shape:
            raise ValueError(f"{HOVER}: step: the action has shape {a.shape}, expected "
                             f"{self.action_space.shape}")
        obs, reward, terminated, truncated, terms = self._core.step(a.reshape(1, -1))
        self._ended = bool(terminated[0] or truncated[0])
        info = dict(zip(self.reward_terms, terms[0].tolist()))
        return obs[0], float(reward[0]), bool(terminated[0]), bool(truncated[0]), info

    def render(self):
        if self.render_mode != "rgb_array":
            return None
        return self._core.render(0, *self._size)


class HoverVectorEnv(VectorEnv):
    """aerobox/Hover-v0, num_envs worlds stepped in one call in C++ threads (module doc);
    threads: how many (default: the machine's cores)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 30, "autoreset_mode": "next_step"}

    def __init__(self, num_envs=1, threads=None, render_mode=None, width=320, height=240,
                 **params):
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"{HOVER}: render_mode {render_mode!r}: expected None or 'rgb_array'")
        if isinstance(num_envs, bool) or not isinstance(num_envs, (int, np.integer)) \
                or num_envs < 1:
            raise ValueError(f"{HOVER}: num_envs {num_envs!r}: expected an integer >= 1")
        threads = os.cpu_count() or 1 if threads is None else threads
        self._core = _aerobox.EnvCore(params, int(num_envs), int(threads), HOVER)
        self.num_envs = int(num_envs)
        self.observation_names, self.single_observation_space, self.single_action_space = \
            _spaces(params, self._core)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.reward_terms = _aerobox.env_reward_terms()
        self.render_mode, self._size = render_mode, (int(width), int(height))
        self._seeded = False
        self._reset = False

    def reset(self, *, seed=None, options=None):
        _check_options(HOVER, options)
        if seed is None:
            seeds = [None] * self.num_envs
        elif isinstance(seed, (list, tuple)):
            if len(seed) != self.num_envs:
                raise ValueError(f"{HOVER}: reset: {len(seed)} seeds for {self.num_envs} worlds")
            seeds = [_seed(HOVER, s) for s in seed]
        else:
            first = _seed(HOVER, seed)
            seeds = [first + i for i in range(self.num_envs)]
        if seed is not None:
            self._np_random, _ = gym.utils.seeding.np_random(seeds[0])
        if not self._seeded:
            draw = self.np_random
            seeds = [s if s is not None else int(draw.integers(_SEED_LIMIT)) for s in seeds]
        self._seeded = self._reset = True
        return self._core.reset(seeds), {}

    def step(self, actions):
        if not self._reset:
            raise gym.error.ResetNeeded(f"{HOVER}: step before reset(): call reset() first")
        obs, rewards, terminated, truncated, terms = self._core.step(actions)
        infos = {}
        for j, name in enumerate(self.reward_terms):
            infos[name] = terms[:, j]
            infos["_" + name] = np.ones(self.num_envs, dtype=bool)
        return obs, rewards, terminated, truncated, infos

    def render(self):
        if self.render_mode != "rgb_array":
            return None
        return self._core.render(0, *self._size)


def _register():
    if HOVER not in gym.registry:
        gym.register(id=HOVER, entry_point="aerobox.envs:HoverEnv",
                     vector_entry_point="aerobox.envs:HoverVectorEnv")


_register()
