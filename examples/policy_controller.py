"""Flies a policy trained on aerobox/Hover-v0 (examples/train_hover.py) as a controller with
RotorPy's contract, so that `aerobox fly` and aerobox.Simulator fly it with their usual outputs:

    aerobox fly scenes/empty/scenario.toml --set vehicle.kind=crazyflie --max-speed 1 \\
        --controller examples/policy_controller.py:PolicyController --command cmd_ctbr

Each update builds the environment's observation with the setpoint's position as the target
(docs/learning.md: p - target, v, R_WB row by row, w_B, the last action), asks the policy, and
turns its action into cmd_thrust [N] and cmd_w [rad/s] by the environment's scaling. The policy
is hover_policy.zip in the current folder, or the file AEROBOX_POLICY names, with its .json.
"""

import json
import os

import numpy as np
from stable_baselines3 import PPO


def rotation(q):
    """R_WB of RotorPy's quaternion [x, y, z, w]."""
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


class PolicyController:
    def __init__(self, quad_params):
        path = os.environ.get("AEROBOX_POLICY", "hover_policy.zip")
        if not os.path.exists(path):
            raise FileNotFoundError(f"{path}: no policy; train one with examples/train_hover.py")
        with open(os.path.splitext(path)[0] + ".json") as file:
            params = json.load(file)
        if params.get("action") != "ctbr":
            raise ValueError(f"{path}: trained with action {params.get('action')!r}; this "
                             "controller flies 'ctbr' policies")
        if abs(params.get("mass", quad_params["mass"]) - quad_params["mass"]) > 1e-9:
            raise ValueError(f"{path}: trained on the {params.get('vehicle')} "
                             f"({params['mass'] * 1e3:.0f} g); this vehicle is "
                             f"{quad_params['mass'] * 1e3:.0f} g: fly the same vehicle "
                             "(--set vehicle.kind=...)")
        self.model = PPO.load(path, device="cpu")
        k = quad_params["k_eta"]
        self.t_min = k * quad_params["rotor_speed_min"] ** 2  # [N] a rotor's least thrust
        self.t_max = k * quad_params["rotor_speed_max"] ** 2  # [N] and its most
        self.max_rate = params.get("max_rate", 10.0)
        self.last = np.zeros(4)

    def update(self, t, state, flat_output):
        obs = np.concatenate([state["x"] - flat_output["x"], state["v"],
                              rotation(state["q"]).ravel(), state["w"], self.last])
        action, _ = self.model.predict(obs.astype(np.float32), deterministic=True)
        a = np.clip(np.asarray(action, dtype=float), -1.0, 1.0)
        self.last = a
        thrust = 4.0 * (self.t_min + 0.5 * (a[0] + 1.0) * (self.t_max - self.t_min))
        return {"cmd_thrust": thrust, "cmd_w": a[1:] * self.max_rate}
