"""What a user brings, written for the tests: a planner, a trajectory class and controllers that
go wrong. Each knows aerobox only through its contract."""

import numpy as np


class WindowPlanner:
    """Through the window map's opening, by hand: plan(world, start, goal) -> (N, 3) [m]."""

    def plan(self, world, start, goal):
        assert len(world["blocks"]) == 8 and len(world["bounds"]["extents"]) == 6
        return np.array([start, [5, -1, 1.8], [5, 4, 2.2], [5, 13, 4], [7, 17, 4], goal])


class Smoothstep:
    """Straight lines between the waypoints, each a quintic smoothstep in time (at rest at every
    waypoint), at `speed` [m/s] on average: Smoothstep(path), update(t), duration [s]."""

    def __init__(self, points, speed=1.0):
        self.points = np.asarray(points, dtype=float)
        lengths = np.linalg.norm(np.diff(self.points, axis=0), axis=1)
        self.times = np.concatenate([[0.0], np.cumsum(lengths / speed)])
        self.duration = float(self.times[-1])

    def update(self, t):
        t = min(max(t, 0.0), self.duration)
        i = min(int(np.searchsorted(self.times, t, side="right")) - 1, len(self.points) - 2)
        T = self.times[i + 1] - self.times[i]
        s = (t - self.times[i]) / T
        d = self.points[i + 1] - self.points[i]
        p = 10 * s**3 - 15 * s**4 + 6 * s**5
        v = (30 * s**2 - 60 * s**3 + 30 * s**4) / T
        a = (60 * s - 180 * s**2 + 120 * s**3) / T**2
        j = (60 - 360 * s + 360 * s**2) / T**3
        return {"x": self.points[i] + p * d, "x_dot": v * d, "x_ddot": a * d, "x_dddot": j * d,
                "x_ddddot": np.zeros(3), "yaw": 0.0, "yaw_dot": 0.0}


class Hover:
    """Holds the rotors at hover thrust until `fail_at` [s], then fails as `how` says."""

    how = "raise"
    fail_at = 0.3

    def __init__(self, quad_params):
        self.hover = quad_params["mass"] * 9.81 / 4

    def update(self, t, state, flat_output):
        if t >= self.fail_at:
            if self.how == "raise":
                raise RuntimeError("the user's controller broke")
            if self.how == "nan":
                return {"cmd_motor_thrusts": np.full(4, np.nan)}
        return {"cmd_motor_thrusts": np.full(4, self.hover)}


class Raising(Hover):
    how = "raise"


class ReturnsNaN(Hover):
    how = "nan"
