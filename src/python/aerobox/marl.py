"""Several vehicles in one world for multi-agent learning: PettingZoo's Parallel API.

    from aerobox.marl import parallel_env

    env = parallel_env(agents=4)                  # aerobox_swap_v0
    observations, infos = env.reset(seed=1)
    while env.agents:
        actions = {a: policy(observations[a]) for a in env.agents}
        observations, rewards, terminations, truncations, infos = env.step(actions)

The task, aerobox_swap_v0: `agents` vehicles start at rest on a horizontal circle of `radius`
[m] at `height` [m] (turned by a random angle each episode), each bound for the point opposite,
so that all must pass the middle at once. The world is MuJoCo at a 1 ms step with every
vehicle's inner loops below its action (as aerobox.envs' worlds, in still air, without sensor
models); one step() is 1/control_rate seconds for every agent.

Action (per agent): four numbers in [-1, 1] (float32 Box), at the level `action` names, scaled as
aerobox.envs' ("ctbr" by default: collective thrust and body rates; "velocity" is not available).
Observation (per agent, float32): its position minus its goal [m], its velocity [m/s], R_WB row by
row, its body rates [rad/s], its last action; then, for every other agent in the order of
possible_agents, that agent's position and velocity relative to its own [m, m/s].
Reward (per agent and step): reward_alive - reward_position |p - goal| - reward_rate |w_B|
    - reward_action |a|^2; on a contact (another agent, the floor) -reward_collision, and the
    agent is out of the game (terminated, its rotors off), as it is when it leaves the room.
    `info` names what it touched ("touched") and its distance to its goal ("distance").
truncated: episode_time has passed.
The world's keyword arguments are aerobox.envs' of the same names: vehicle, action,
control_rate, physics_rate, max_rate, max_tilt (aerobox.envs.keys() gives their units and
ranges). A bad value raises ValueError naming it; an unknown argument, TypeError.
"""

import functools
import math

import numpy as np

try:
    from gymnasium import spaces
    from pettingzoo import ParallelEnv
except ImportError as e:  # pragma: no cover - said to the user
    raise ImportError("aerobox.marl needs PettingZoo and Gymnasium: pip install pettingzoo "
                      "gymnasium") from e

from . import _aerobox

NAME = "aerobox_swap_v0"
_WHO = "aerobox.marl.parallel_env"
# the task's own parameters and their defaults (the rest go to the world)
_TASK = dict(agents=4, radius=1.0, height=1.0, episode_time=10.0, reward_alive=1.0,
             reward_position=1.0, reward_rate=0.05, reward_action=0.05, reward_collision=10.0)
# the world's parameters it takes (aerobox.envs' of the same names)
_WORLD = ("vehicle", "action", "control_rate", "physics_rate", "max_rate", "max_tilt")


def parallel_env(**kwargs):
    """The swap task's environment (PettingZoo's Parallel API); see the module's text."""
    return SwapEnv(**kwargs)


class SwapEnv(ParallelEnv):
    metadata = {"name": NAME, "render_modes": [], "is_parallelizable": True}

    def __init__(self, **kwargs):
        task = dict(_TASK)
        world = {}
        for key, value in kwargs.items():
            if key not in _TASK and key not in _WORLD:
                raise TypeError(f"{_WHO}: unknown argument '{key}' (arguments: "
                                f"{', '.join(list(_TASK) + list(_WORLD))})")
            (task if key in _TASK else world)[key] = value
        n = task["agents"]
        if not isinstance(n, int) or isinstance(n, bool) or not 2 <= n <= 64:
            raise ValueError(f"{_WHO}: agents={n!r}: expected a whole number from 2 to 64")
        for key in ("radius", "height", "episode_time") + tuple(k for k in _TASK
                                                                  if k.startswith("reward_")):
            value = task[key]
            if not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0 or (
                    key in ("radius", "height", "episode_time") and value <= 0):
                raise ValueError(f"{_WHO}: {key}={value!r}: expected a positive number")
        self._task = task
        r, h = float(task["radius"]), float(task["height"])
        margin = 2.0
        self._room = (-r - margin, -r - margin, 0.0, r + margin, r + margin, h + margin)
        world["episode_time"] = float(task["episode_time"])
        self._core = _aerobox.SwarmCore(world, n, list(self._room), _WHO)
        apart = 2 * r * math.sin(math.pi / n)  # [m] between neighbours on the circle
        least = 2 * self._core.vehicle_radius + 0.05
        if apart < least:
            raise ValueError(f"{_WHO}: agents={n}, radius={r!r}: neighbours would start "
                             f"{apart:.3f} m apart, less than two vehicles and 5 cm ({least:.3f} "
                             "m); give a larger radius or fewer agents")
        self.render_mode = None
        self.possible_agents = [f"agent_{i}" for i in range(n)]
        self.agents = []
        self._index = {a: i for i, a in enumerate(self.possible_agents)}
        size = 18 + self._core.action_size + 6 * (n - 1)
        self._observation_space = spaces.Box(-np.inf, np.inf, (size,), np.float32)
        self._action_space = spaces.Box(-1.0, 1.0, (self._core.action_size,), np.float32)
        self._rng = np.random.default_rng()
        self._goals = np.zeros((n, 3))
        self._last = np.zeros((n, self._core.action_size))
        self._steps = 0
        self._max_steps = int(round(task["episode_time"] * float(world.get("control_rate", 100.0))))

    @functools.lru_cache(maxsize=None)
    def observation_space(self, agent):
        return self._observation_space

    @functools.lru_cache(maxsize=None)
    def action_space(self, agent):
        return self._action_space

    @property
    def quad_params(self):
        """The vehicle as RotorPy's quad_params dict."""
        return self._core.quad_params

    def reset(self, seed=None, options=None):
        if seed is not None:
            self._rng = np.random.default_rng(seed)
        n = len(self.possible_agents)
        turn = self._rng.uniform(-math.pi, math.pi)
        angles = turn + 2 * math.pi * np.arange(n) / n
        r, h = self._task["radius"], self._task["height"]
        starts = np.stack([r * np.cos(angles), r * np.sin(angles), np.full(n, h)], axis=1)
        self._goals = np.stack([-starts[:, 0], -starts[:, 1], starts[:, 2]], axis=1)
        self._core.reset(starts)
        self._last[:] = 0.0
        self._steps = 0
        self.agents = list(self.possible_agents)
        states = self._core.states()
        return ({a: self._observe(states, self._index[a]) for a in self.agents},
                {a: {} for a in self.agents})

    def step(self, actions):
        n = len(self.possible_agents)
        rows = np.full((n, self._core.action_size), np.nan)
        for agent in self.agents:
            if agent not in actions:
                raise ValueError(f"{_WHO}: step: no action for {agent}")
            a = np.asarray(actions[agent], dtype=np.float64).reshape(-1)
            if a.shape != (self._core.action_size,) or not np.all(np.isfinite(a)):
                raise ValueError(f"{_WHO}: step: {agent}'s action {actions[agent]!r}: expected "
                                 f"{self._core.action_size} finite numbers in [-1, 1]")
            rows[self._index[agent]] = np.clip(a, -1.0, 1.0)
        touched = self._core.step(rows)
        self._steps += 1
        states = self._core.states()
        t = self._task
        observations, rewards, terminations, truncations, infos = {}, {}, {}, {}, {}
        low, high = np.array(self._room[:3]), np.array(self._room[3:])
        for agent in self.agents:
            i = self._index[agent]
            self._last[i] = rows[i]
            p, w = states[i, 0:3], states[i, 10:13]
            distance = float(np.linalg.norm(p - self._goals[i]))
            out = (not np.all(np.isfinite(states[i])) or np.any(p < low) or np.any(p > high))
            crashed = bool(touched[i]) or out
            reward = (t["reward_alive"] - t["reward_position"] * distance
                      - t["reward_rate"] * float(np.linalg.norm(w))
                      - t["reward_action"] * float(np.dot(rows[i], rows[i])))
            if crashed:
                reward -= t["reward_collision"]
            observations[agent] = self._observe(states, i)
            rewards[agent] = float(reward)
            terminations[agent] = crashed
            truncations[agent] = self._steps >= self._max_steps
            infos[agent] = {"touched": touched[i] or ("the room's bounds" if out else ""),
                            "distance": distance}
        self.agents = [a for a in self.agents if not (terminations[a] or truncations[a])]
        return observations, rewards, terminations, truncations, infos

    def _observe(self, states, i):
        own = states[i]
        rotation = _rotation(own[6:10])
        others = [np.concatenate([states[j, 0:3] - own[0:3], states[j, 3:6] - own[3:6]])
                  for j in range(len(self.possible_agents)) if j != i]
        parts = [own[0:3] - self._goals[i], own[3:6], rotation.reshape(-1), own[10:13],
                 self._last[i]] + others
        return np.nan_to_num(np.concatenate(parts)).astype(np.float32)

    def render(self):
        return None

    def close(self):
        pass


def _rotation(q):
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])
