"""aerobox's learning environments for Gymnasium (1.x API), registered when this module is
imported:

    import gymnasium as gym
    import aerobox.envs  # registers aerobox/Hover-v0, aerobox/Track-v0, aerobox/Navigate-v0

    env = gym.make("aerobox/Hover-v0", action="ctbr")           # one world
    envs = gym.make_vec("aerobox/Track-v0", num_envs=64)        # 64 worlds stepped in C++ threads

aerobox/Hover-v0: reach and hold `target` from a random start (uniform within start_radius of
it, a random speed, tilt, yaw and body rate).
aerobox/Track-v0: follow a random circle or figure-8 around `target` (size up to track_size, top
speed up to track_speed, random heading and phase), given now and track_points samples ahead.
aerobox/Navigate-v0: reach a random goal through a map of boxes (`map`, an aerobox map file, or
a seeded random forest), seeing the boxes through range rays; commands a velocity by default.
The worlds are MuJoCo at a 1 ms step with aerobox's inner loops below the action's level; one
step() is 1/control_rate seconds.

Action: four numbers in [-1, 1] (float32 Box), by `action`:
    "thrusts": each rotor's thrust, T_i = T_min + (a_i + 1) / 2 (T_max - T_min), rotors in
        aerobox's (RotorPy's) order: front-left, front-right, back-right, back-left;
    "ctbm": a_0 the collective thrust (4 x the rotor's scaling above), a_1..a_3 body moments
        [N m]: roll and pitch a_i T_max l (l the arm length), yaw a_3 2 T_max k_m / k_eta;
    "ctbr" (default): a_0 the collective thrust, a_1..a_3 body rates [rad/s] a_i max_rate;
    "ctatt": a_0 the collective thrust, attitude R_z(pi a_3) R_y(max_tilt a_2) R_x(max_tilt a_1);
    "velocity": a_0..a_2 the world velocity [m/s] a_i max_speed, a_3 the yaw pi a_3 [rad],
        through aerobox's velocity loop (its cascade's, without the position gain).
Observation (float32 Box), in this order (observation_names gives the names):
    p - reference [m] (world ENU, z up; the target, the trajectory now, or the goal), v [m/s]
    (world), the attitude (attitude="matrix": R_WB, the body's FLU axes in the world, row by row;
    attitude="quaternion": w, x, y, z with w >= 0), body rates w_B [rad/s] (FLU), the last
    action; then the task's own: track: the reference's velocity and acceleration now, and for
    each sample ahead its position minus the vehicle's, velocity and acceleration; navigate: the
    range [m] along range_rays horizontal world directions (from +x anticlockwise), then down and
    up, up to range_max, to the nearest box or the map's bounds; with depth_width x depth_height
    > 0, a depth image (rows from the top): the depth [m] along the optical axis of a camera
    looking along body x (87 x 58 deg), range_max where nothing is within reach.
Reward per step (the terms are in `info` by name): hover and track: reward_alive -
    reward_position |p - reference| - reward_velocity |v - v_reference| - reward_rate |w_B|
    - reward_action |a|^2; navigate: reward_alive + reward_progress (the step's approach to the
    goal) - the same velocity (|v|), rate and action terms + reward_arrival on arriving.
terminated: a contact (the floor included), a non-finite state or a MuJoCo warning; hover and
    track: further than bounds_radius from the reference; navigate: outside the map's bounds,
    or arrived (within arrival_radius of the goal); truncated: episode_time has passed.
Every parameter is a keyword argument of gym.make (see `keys()` for units, defaults, ranges);
each id sets a few defaults of its own (ENVIRONMENTS).
reset(options={"start": [x, y, z], "target": [x, y, z]}) sets the episode's start position
    and its target (Track: the trajectory's centre; Navigate: the goal), each optional.

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
TRACK = "aerobox/Track-v0"
NAVIGATE = "aerobox/Navigate-v0"
# each id's task and the defaults it sets (the rest are the parameters' own, `keys()`)
ENVIRONMENTS = {
    HOVER: dict(task="hover"),
    TRACK: dict(task="track", start_radius=0.25, start_speed=0.25, start_tilt=0.2,
                start_rate=0.5, bounds_radius=2.0),
    NAVIGATE: dict(task="navigate", action="velocity", start_speed=0.0, start_tilt=0.1,
                   start_rate=0.2, episode_time=20.0),
}
_SEED_LIMIT = 2**63


def keys():
    """The environments' parameters: (key, unit, default, range, meaning) rows."""
    return _aerobox.env_keys()


def _core(env_id, params, num_envs, threads):
    """The C++ worlds of `env_id` with `params` over the id's defaults."""
    if env_id not in ENVIRONMENTS:
        raise ValueError(f"env_id {env_id!r}: expected one of {', '.join(ENVIRONMENTS)}")
    return _aerobox.EnvCore(dict(ENVIRONMENTS[env_id], **params), num_envs, threads, env_id)


def _spaces(core):
    observation = spaces.Box(-np.inf, np.inf, (core.observation_size,), np.float32)
    action = spaces.Box(-1.0, 1.0, (core.action_size,), np.float32)
    return core.observation_names, observation, action


def _seed(who, seed):
    if seed is None:
        return None
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)) \
            or not 0 <= seed < _SEED_LIMIT:
        raise ValueError(f"{who}: reset: seed {seed!r}: expected an integer in [0, 2**63)")
    return int(seed)


class AeroboxEnv(gym.Env):
    """One world of `env_id` (module doc); params: gym.make's keyword arguments."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 30}

    def __init__(self, env_id=HOVER, render_mode=None, width=320, height=240, **params):
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"{env_id}: render_mode {render_mode!r}: expected None or "
                             "'rgb_array'")
        self.env_id = env_id
        self._core = _core(env_id, params, 1, 1)
        self.observation_names, self.observation_space, self.action_space = _spaces(self._core)
        self.reward_terms = self._core.reward_terms
        self.quad_params = self._core.quad_params  # the vehicle, as RotorPy's dict
        self.render_mode, self._size = render_mode, (int(width), int(height))
        self._seeded = False
        self._ended = None  # None: never reset

    def reset(self, *, seed=None, options=None):
        seed = _seed(self.env_id, seed)
        super().reset(seed=seed)
        if seed is None and not self._seeded:
            seed = int(self.np_random.integers(_SEED_LIMIT))
        obs = self._core.reset([seed], options)[0]  # bad options leave the world as it was
        self._seeded = True
        self._ended = False
        return obs, {}

    def step(self, action):
        if self._ended is None:
            raise gym.error.ResetNeeded(f"{self.env_id}: step before reset(): call reset() first")
        if self._ended:
            raise gym.error.ResetNeeded(f"{self.env_id}: the episode has ended: call reset()")
        a = np.asarray(action, dtype=np.float64)
        if a.shape != self.action_space.shape:
            raise ValueError(f"{self.env_id}: step: the action has shape {a.shape}, expected "
                             f"{self.action_space.shape}")
        obs, reward, terminated, truncated, terms = self._core.step(a.reshape(1, -1))
        self._ended = bool(terminated[0] or truncated[0])
        info = dict(zip(self.reward_terms, terms[0].tolist()))
        return obs[0], float(reward[0]), bool(terminated[0]), bool(truncated[0]), info

    def render(self):
        if self.render_mode != "rgb_array":
            return None
        return self._core.render(0, *self._size)


class AeroboxVectorEnv(VectorEnv):
    """num_envs worlds of `env_id` stepped in one call in C++ threads (module doc); threads:
    how many (default: the machine's cores)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 30, "autoreset_mode": "next_step"}

    def __init__(self, num_envs=1, env_id=HOVER, threads=None, render_mode=None, width=320,
                 height=240, **params):
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"{env_id}: render_mode {render_mode!r}: expected None or "
                             "'rgb_array'")
        self.env_id = env_id
        self.num_envs = _num_envs(env_id, num_envs)
        threads = (os.cpu_count() or 1) if threads is None else threads
        self._core = _core(env_id, params, self.num_envs, int(threads))
        self.observation_names, self.single_observation_space, self.single_action_space = \
            _spaces(self._core)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.reward_terms = self._core.reward_terms
        self.render_mode, self._size = render_mode, (int(width), int(height))
        self._seeded = False
        self._reset = False

    def reset(self, *, seed=None, options=None):
        who = self.env_id
        if seed is None:
            seeds = [None] * self.num_envs
        elif isinstance(seed, (list, tuple)):
            if len(seed) != self.num_envs:
                raise ValueError(f"{who}: reset: {len(seed)} seeds for {self.num_envs} worlds")
            seeds = [_seed(who, s) for s in seed]
        else:
            first = _seed(who, seed)
            seeds = [first + i for i in range(self.num_envs)]
        if seed is not None:
            self._np_random, _ = gym.utils.seeding.np_random(seeds[0])
        if not self._seeded:
            draw = self.np_random
            seeds = [s if s is not None else int(draw.integers(_SEED_LIMIT)) for s in seeds]
        obs = self._core.reset(seeds, options)  # options apply to every world
        self._seeded = self._reset = True
        return obs, {}

    def step(self, actions):
        if not self._reset:
            raise gym.error.ResetNeeded(f"{self.env_id}: step before reset(): call reset() "
                                        "first")
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


class HoverEnv(AeroboxEnv):
    """aerobox/Hover-v0, one world."""

    def __init__(self, render_mode=None, width=320, height=240, **params):
        super().__init__(HOVER, render_mode, width, height, **params)


class HoverVectorEnv(AeroboxVectorEnv):
    """aerobox/Hover-v0's worlds stepped together."""

    def __init__(self, num_envs=1, threads=None, render_mode=None, width=320, height=240,
                 **params):
        super().__init__(num_envs, HOVER, threads, render_mode, width, height, **params)


def _num_envs(who, num_envs):
    if isinstance(num_envs, bool) or not isinstance(num_envs, (int, np.integer)) \
            or num_envs < 1:
        raise ValueError(f"{who}: num_envs {num_envs!r}: expected an integer >= 1")
    return int(num_envs)


def _register():
    for env_id in ENVIRONMENTS:
        if env_id not in gym.registry:
            gym.register(id=env_id, entry_point="aerobox.envs:AeroboxEnv",
                         vector_entry_point="aerobox.envs:AeroboxVectorEnv",
                         kwargs={"env_id": env_id})


_register()
