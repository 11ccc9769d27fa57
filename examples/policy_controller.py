"""Flies a policy trained on aerobox/Hover-v0 (examples/train_hover.py) as a controller with
RotorPy's contract, so that `aerobox fly` and aerobox.Simulator fly it with their usual outputs:

    aerobox fly scenes/empty/scenario.toml --set vehicle.kind=crazyflie --set controller.rate=100 \\
        --max-speed 1 --controller examples/policy_controller.py:PolicyController

Each update builds the environment's observation with the setpoint's position as the target
(docs/learning.md: p - target, v, R_WB row by row, w_B, the last action), normalises it as in
training (the saved mean and variance), asks the policy, and turns its action into a command by
the environment's scaling: cmd_thrust [N] with cmd_q [i, j, k, w] (action "ctatt") or cmd_w
[rad/s] (action "ctbr"). Fly it at the rate it was trained at (controller.rate, 100 Hz by
default): the observation holds the last action. The policy is hover_policy.zip in the current
folder, or the file AEROBOX_POLICY names, with its .json.
"""

import json
import os

import numpy as np
from stable_baselines3 import PPO

LEVELS = ("ctatt", "ctbr")  # the actions this controller turns into commands


def rotation(q):
    """R_WB of RotorPy's quaternion [x, y, z, w]."""
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def about(axis, angle):
    """The quaternion [x, y, z, w] of a rotation by angle [rad] about a unit axis."""
    return np.append(np.sin(0.5 * angle) * np.asarray(axis, float), np.cos(0.5 * angle))


def product(p, q):
    """The quaternion p q, both [x, y, z, w]."""
    pv, pw, qv, qw = p[:3], p[3], q[:3], q[3]
    return np.append(pw * qv + qw * pv + np.cross(pv, qv), pw * qw - pv @ qv)


def load(path, quad_params):
    """The saved policy's parameters, checked against the vehicle flown."""
    if not os.path.exists(path):
        raise FileNotFoundError(f"{path}: no policy; train one with examples/train_hover.py")
    with open(os.path.splitext(path)[0] + ".json") as file:
        params = json.load(file)
    if params.get("action") not in LEVELS:
        raise ValueError(f"{path}: trained with action {params.get('action')!r}; this "
                         f"controller flies {' or '.join(map(repr, LEVELS))} policies")
    if abs(params.get("mass", quad_params["mass"]) - quad_params["mass"]) > 1e-9:
        raise ValueError(f"{path}: trained on the {params.get('vehicle')} "
                         f"({params['mass'] * 1e3:.0f} g); this vehicle is "
                         f"{quad_params['mass'] * 1e3:.0f} g: fly the same vehicle "
                         "(--set vehicle.kind=...)")
    return params


class PolicyController:
    """policy, params: a model with SB3's predict(obs, deterministic) and the environment's
    parameters (OUT.json's), in place of the saved ones (to fly a scripted policy)."""

    def __init__(self, quad_params, policy=None, params=None):
        if policy is None:
            path = os.environ.get("AEROBOX_POLICY", "hover_policy.zip")
            params = load(path, quad_params)
            policy = PPO.load(path, device="cpu")
        self.model = policy
        self.action = params["action"]
        self.mean = np.asarray(params.get("obs_mean", 0.0))
        self.scale = 1.0 / np.sqrt(np.asarray(params.get("obs_var", 1.0)) +
                                   params.get("obs_epsilon", 0.0))
        self.clip = params.get("obs_clip", np.inf)
        k = quad_params["k_eta"]
        self.t_min = k * quad_params["rotor_speed_min"] ** 2  # [N] a rotor's least thrust
        self.t_max = k * quad_params["rotor_speed_max"] ** 2  # [N] and its most
        self.max_rate = params.get("max_rate", 10.0)  # [rad/s] ctbr's rate at +-1
        self.max_tilt = params.get("max_tilt", 0.6)  # [rad] ctatt's roll and pitch at +-1
        self.last = np.zeros(4)

    def update(self, t, state, flat_output):
        obs = np.concatenate([state["x"] - flat_output["x"], state["v"],
                              rotation(state["q"]).ravel(), state["w"], self.last])
        obs = np.clip((obs - self.mean) * self.scale, -self.clip, self.clip)
        action, _ = self.model.predict(obs.astype(np.float32), deterministic=True)
        a = np.clip(np.asarray(action, dtype=float), -1.0, 1.0)
        self.last = a
        thrust = 4.0 * (self.t_min + 0.5 * (a[0] + 1.0) * (self.t_max - self.t_min))
        if self.action == "ctbr":
            return {"cmd_thrust": thrust, "cmd_w": a[1:] * self.max_rate}
        # R_z(pi a3) R_y(max_tilt a2) R_x(max_tilt a1), as the environment builds it
        q = product(about([0, 0, 1], np.pi * a[3]),
                    product(about([0, 1, 0], self.max_tilt * a[2]),
                            about([1, 0, 0], self.max_tilt * a[1])))
        return {"cmd_thrust": thrust, "cmd_q": q}
