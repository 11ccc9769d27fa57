"""A geometric SE(3) controller (Lee, Leok and McClamroch 2010) in RotorPy's contract, written
for the tests: SE3Control(quad_params).update(t, state, flat_output) -> dict. It knows aerobox
only through the quad_params dict and the state and flat-output dicts."""

import math

import numpy as np


def cross(a, b):
    """a x b for 3-vectors (numpy's cross is general, and slow on one pair)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])


def rotation_matrix(q):
    """Body-to-world rotation from a quaternion [i, j, k, w]."""
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def quaternion(R):
    """[i, j, k, w] of a rotation matrix (Shepperd's method, w >= 0 branch first)."""
    trace = np.trace(R)
    if trace > 0:
        s = 2.0 * np.sqrt(1.0 + trace)
        return np.array([(R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s,
                         (R[1, 0] - R[0, 1]) / s, 0.25 * s])
    i = int(np.argmax(np.diag(R)))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * np.sqrt(1.0 + R[i, i] - R[j, j] - R[k, k])
    q = np.zeros(4)
    q[i] = 0.25 * s
    q[j] = (R[j, i] + R[i, j]) / s
    q[k] = (R[k, i] + R[i, k]) / s
    q[3] = (R[k, j] - R[j, k]) / s
    return q


class SE3Control:
    GRAVITY = 9.81

    def __init__(self, quad_params):
        self.mass = quad_params["mass"]
        self.inertia = np.diag([quad_params["Ixx"], quad_params["Iyy"], quad_params["Izz"]])
        k_eta, k_m = quad_params["k_eta"], quad_params["k_m"]
        positions = np.array(list(quad_params["rotor_pos"].values()))
        directions = np.asarray(quad_params["rotor_directions"], dtype=float)
        # [thrust; moments] = allocation @ rotor thrusts
        allocation = np.vstack([np.ones(4), positions[:, 1], -positions[:, 0],
                                directions * k_m / k_eta])
        self.to_rotors = np.linalg.inv(allocation)
        self.min_thrust = k_eta * quad_params["rotor_speed_min"] ** 2
        self.max_thrust = k_eta * quad_params["rotor_speed_max"] ** 2
        self.k_eta = k_eta
        # position loop [1/s^2, 1/s] and attitude loop [1/s^2, 1/s], scaled by mass and inertia
        self.kp = np.array([6.5, 6.5, 15.0])
        self.kd = np.array([4.0, 4.0, 9.0])
        self.kr = 544.0
        self.kw = 46.6

    def update(self, t, state, flat_output):
        e_p = state["x"] - flat_output["x"]
        e_v = state["v"] - flat_output["x_dot"]
        force = self.mass * (-self.kp * e_p - self.kd * e_v + flat_output["x_ddot"]
                             + np.array([0.0, 0.0, self.GRAVITY]))
        R = rotation_matrix(state["q"])
        thrust = float(force @ R[:, 2])
        b3 = force / math.sqrt(force @ force)
        yaw = flat_output["yaw"]
        c1 = np.array([math.cos(yaw), math.sin(yaw), 0.0])
        b2 = cross(b3, c1)
        b2 /= math.sqrt(b2 @ b2)
        R_des = np.column_stack([cross(b2, b3), b2, b3])
        S = 0.5 * (R_des.T @ R - R.T @ R_des)
        e_R = np.array([S[2, 1], S[0, 2], S[1, 0]])
        # the desired body rates from the jerk (the thrust axis turns with the jerk across it)
        jerk = flat_output["x_dddot"]
        h = self.mass / float(force @ b3) * (jerk - (b3 @ jerk) * b3)
        b1 = R_des[:, 0]
        w_des = np.array([-(h @ b2), h @ b1, flat_output["yaw_dot"] * b3[2]])
        w = state["w"]
        e_w = w - R.T @ (R_des @ w_des)
        moment = self.inertia @ (-self.kr * e_R - self.kw * e_w) + cross(w, self.inertia @ w)
        thrusts = self.to_rotors @ np.concatenate([[thrust], moment])
        thrusts = np.minimum(np.maximum(thrusts, self.min_thrust), self.max_thrust)
        return {
            "cmd_motor_thrusts": thrusts,
            "cmd_motor_speeds": np.sqrt(thrusts / self.k_eta),
            "cmd_thrust": thrust,
            "cmd_moment": moment,
            "cmd_q": quaternion(R_des),
            "cmd_w": w_des,
        }
