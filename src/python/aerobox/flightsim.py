"""flightsim's contract (the MEAM620 course simulator), flown in aerobox's MuJoCo physics.

A course sandbox runs with its imports changed and nothing else:

    from aerobox.flightsim import simulate, Quadrotor, World, ExitStatus

    world = World.from_file("test_window.json")     # world.world: bounds, blocks, start, goal
    quadrotor = Quadrotor(quad_params)               # flightsim's dict (arm_length, k_thrust, ...)
    (time, state, control, flat, exit) = simulate(initial_state, quadrotor, SE3Control(quad_params),
                                                  WorldTraj(world, start, goal), t_final=60)
    collisions = world.path_collisions(state["x"], 0.25)

As flightsim: a fixed step of 1/500 s, the controller called every step with (t, state, flat)
and its cmd_motor_speeds [rad/s] flown until the next (clipped to the rotors' range); states
x [m], v [m/s], q [i, j, k, w], w [rad/s, body]; sample 0 is the initial state. The run ends on
the first of: a safety failure (inf or nan motor speeds, a speed above 100 m/s, a body rate
above 100 rad/s, a position 20 m off the trajectory's), the normal exit (`terminate`), t_final.
flightsim's vehicle has no motor lag and no drag, and neither has this one unless the dict
gives tau_m (Simulator: the vehicle). flightsim has no obstacles in the flight: the world is
for the planner and for path_collisions afterwards; here too the flight is in an empty world.
"""

import enum
import json
import math
import os
import tempfile

import numpy as np

__all__ = ["ExitStatus", "Quadrotor", "World", "simulate"]

T_STEP = 1 / 500  # [s] flightsim's step


class ExitStatus(enum.Enum):
    """Why a simulate() run ended (flightsim's statuses and messages)."""

    COMPLETE = "Success: End reached."
    TIMEOUT = "Timeout: Simulation end time reached."
    INF_VALUE = "Failure: Your controller returned inf motor speeds."
    NAN_VALUE = "Failure: Your controller returned nan motor speeds."
    OVER_SPEED = ("Failure: Your quadrotor is out of control; it is going faster than 100 m/s. "
                  "The Guinness World Speed Record is 73 m/s.")
    OVER_SPIN = ("Failure: Your quadrotor is out of control; it is spinning faster than 100 "
                 "rad/s. The onboard IMU can only measure up to 52 rad/s (3000 deg/s).")
    FLY_AWAY = ("Failure: Your quadrotor is out of control; it flew away with a position error "
                "greater than 20 meters.")


# ---------------------------------------------------------------------------------------------
# the world


def _box(extents):
    """flightsim's extents [xmin, xmax, ymin, ymax, zmin, zmax] as (lo, hi), each (3,)."""
    e = np.asarray(extents, dtype=float)
    return e[0::2], e[1::2]


def _distance_to_box(points, lo, hi):
    """Distance [m] from each point (N, 3) to the box (0 inside), and the box's nearest points."""
    nearest = np.clip(points, lo, hi)
    return np.linalg.norm(points - nearest, axis=1), nearest


class World:
    """flightsim's world: `world` is its dict, {"bounds": {"extents": [6]}, "blocks": [{"extents":
    [6], "color": [3]}, ...]} with extents [xmin, xmax, ymin, ymax, zmin, zmax] [m], plus what a
    map file holds besides (MEAM620's start, goal, resolution, margin)."""

    def __init__(self, world_data):
        if not isinstance(world_data, dict) or "bounds" not in world_data:
            raise ValueError("World: expected flightsim's world dict, with 'bounds' and 'blocks'")
        self.world = world_data

    @classmethod
    def from_file(cls, filename):
        """Reads a flightsim world JSON file; ValueError names the file and line of bad JSON."""
        with open(filename) as file:
            try:
                return cls(json.load(file))
            except json.JSONDecodeError as error:
                raise ValueError(f"{filename}: line {error.lineno}: {error.msg}") from None

    def to_file(self, filename):
        """Writes the world as flightsim's JSON (numbers as lists of floats)."""
        with open(filename, "w") as file:
            json.dump(_plain(self.world), file, indent=4)

    @classmethod
    def empty(cls, extents):
        """A world of no blocks inside extents [xmin, xmax, ymin, ymax, zmin, zmax] [m]."""
        return cls({"bounds": {"extents": [float(e) for e in extents]}, "blocks": []})

    @classmethod
    def grid_forest(cls, n_rows, n_cols, width, height, spacing):
        """Square trees of side `width` and `height` [m], n_rows x n_cols of them `spacing` [m]
        apart from the origin; the bounds hold them exactly."""
        x_max = (n_cols - 1) * spacing + width
        y_max = (n_rows - 1) * spacing + width
        blocks = [{"extents": [x, x + width, y, y + width, 0.0, height], "color": [1, 0, 0]}
                  for x in spacing * np.arange(n_cols) for y in spacing * np.arange(n_rows)]
        return cls({"bounds": {"extents": [0.0, x_max, 0.0, y_max, 0.0, height]},
                    "blocks": _plain(blocks)})

    @classmethod
    def random_forest(cls, world_dims, tree_width, tree_height, num_trees, seed=None):
        """`num_trees` square trees placed uniformly in [0, world_dims] [m] (x, y, z);
        `seed` (numpy's) makes the same forest again."""
        rng = np.random.default_rng(seed)
        dims = np.asarray(world_dims, dtype=float)
        xs = rng.uniform(0, dims[0] - tree_width, num_trees)
        ys = rng.uniform(0, dims[1] - tree_width, num_trees)
        blocks = [{"extents": [x, x + tree_width, y, y + tree_width, 0.0, tree_height],
                   "color": [1, 0, 0]} for x, y in zip(xs, ys)]
        return cls({"bounds": {"extents": [0.0, dims[0], 0.0, dims[1], 0.0, dims[2]]},
                    "blocks": _plain(blocks)})

    def _blocks(self):
        return [_box(b["extents"]) for b in self.world.get("blocks", [])]

    def closest_points(self, points):
        """For each point (N, 3) [m], the nearest point of any block and the distance to it [m]
        (0 inside a block; inf and nan points when there are no blocks)."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        best = np.full(len(points), np.inf)
        closest = np.full(points.shape, np.nan)
        for lo, hi in self._blocks():
            distance, nearest = _distance_to_box(points, lo, hi)
            nearer = distance < best
            best[nearer] = distance[nearer]
            closest[nearer] = nearest[nearer]
        return closest, best

    def min_dist_boundary(self, points):
        """For each point (N, 3) [m], its distance to the nearest face of the bounds [m]
        (negative outside them)."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        lo, hi = _box(self.world["bounds"]["extents"])
        return np.min(np.minimum(points - lo, hi - points), axis=1)

    def path_collisions(self, path, margin):
        """The points of `path` (N, 3) [m], sampled every 1 mm along its legs, that come
        within `margin` [m] of a block: an (M, 3) array, empty when the path is clear."""
        path = np.atleast_2d(np.asarray(path, dtype=float))
        if len(path) == 0 or not self.world.get("blocks"):
            return np.empty((0, 3))
        samples = [path[:1]]
        for a, b in zip(path[:-1], path[1:]):
            n = max(1, int(math.ceil(np.linalg.norm(b - a) / 1e-3)))
            samples.append(a + np.outer(np.arange(1, n + 1) / n, b - a))
        dense = np.concatenate(samples)
        hit = np.zeros(len(dense), dtype=bool)
        for lo, hi in self._blocks():
            hit |= _distance_to_box(dense, lo, hi)[0] < margin
        return dense[hit]

    def draw_empty_world(self, ax):
        """Sets a matplotlib 3-D axis to the bounds, with equal scales and labels [m]."""
        lo, hi = _box(self.world["bounds"]["extents"])
        centre, half = (lo + hi) / 2, max(hi - lo) / 2
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[1] - half, centre[1] + half)
        ax.set_zlim(centre[2] - half, centre[2] + half)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
        return []

    def draw(self, ax, alpha=0.6):
        """The bounds and every block on a matplotlib 3-D axis; returns the blocks' artists."""
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        self.draw_empty_world(ax)
        artists = []
        for block in self.world.get("blocks", []):
            lo, hi = _box(block["extents"])
            corner = lambda i: [hi[k] if (i >> k) & 1 else lo[k] for k in range(3)]
            faces = [[corner(i) for i in face] for face in
                     ((0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4),
                      (1, 3, 7, 5))]
            artist = Poly3DCollection(faces, alpha=alpha,
                                      facecolor=block.get("color", [1, 0, 0]), edgecolor="k",
                                      linewidth=0.3)
            ax.add_collection3d(artist)
            artists.append(artist)
        return artists

    def draw_line(self, ax, points, color=None, linewidth=2):
        """A polyline through points (N, 3) [m]."""
        points = np.atleast_2d(points)
        return ax.plot(points[:, 0], points[:, 1], points[:, 2], color=color,
                       linewidth=linewidth)

    def draw_points(self, ax, points, color=None, markersize=4):
        """Markers at points (N, 3) [m]."""
        points = np.atleast_2d(points)
        return ax.plot(points[:, 0], points[:, 1], points[:, 2], linestyle="none", marker=".",
                       markersize=markersize, color=color)


def _plain(value):
    """numpy numbers and arrays as Python floats and lists (for JSON)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if hasattr(value, "tolist"):
        return _plain(value.tolist())
    return value


# ---------------------------------------------------------------------------------------------
# the vehicle and the run


class Quadrotor:
    """flightsim's vehicle from its quad_params dict (mass, Ixx, Iyy, Izz, arm_length,
    rotor_speed_min, rotor_speed_max, k_thrust, k_drag: a "+" layout, rotors on +x, +y, -x, -y,
    no motor lag, no drag), or RotorPy's. Its attributes are the dict's keys, as flightsim's."""

    def __init__(self, quad_params):
        if not isinstance(quad_params, dict):
            raise TypeError("Quadrotor: expected a quad_params dict")
        self.quad_params = dict(quad_params)
        for key, value in quad_params.items():
            if isinstance(key, str) and key.isidentifier():
                setattr(self, key, value)
        self._sim, self._centre, self._warned = None, None, False

    def simulator(self, position):
        """An aerobox.Simulator of this vehicle in an empty world around `position` [m]: the
        one made before while `position` is well inside its room."""
        position = np.asarray(position, dtype=float)
        if self._sim is None or np.max(np.abs(position - self._centre)) > _ROOM - 100.0:
            self._sim = _empty_world_simulator(self.quad_params, position, not self._warned)
            self._centre, self._warned = position, True
        return self._sim

    def step(self, state, cmd_rotor_speeds, t_step):
        """The state (x, v, q, w) after flying `cmd_rotor_speeds` [rad/s] for t_step [s] (a
        multiple of 1 ms) from `state`, as flightsim's Quadrotor.step."""
        sim = self.simulator(state["x"])
        # flightsim's rotors have no state: they spin at the command from the step's start
        sim.reset(state=dict(state, rotor_speeds=cmd_rotor_speeds))
        after = sim.step({"cmd_motor_speeds": cmd_rotor_speeds}, t_step, "cmd_motor_speeds")
        return {k: after[k] for k in ("x", "v", "q", "w")}


# far enough that no flight reaches the floor 500 m below its start
_ROOM = 500.0  # [m]


def _empty_world_simulator(quad_params, position, loud):
    import warnings

    from . import Simulator

    lo, hi = position - _ROOM, position + _ROOM
    world = {"bounds": {"extents": [lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]}, "blocks": []}
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "empty.json")
        with open(path, "w") as file:
            json.dump(_plain(world), file)
        with warnings.catch_warnings(record=True):  # said below, as flightsim means it
            warnings.simplefilter("always")
            sim = Simulator(path, vehicle=quad_params, start=position)
    # what aerobox adds to flightsim's dict is flightsim's meaning (no motor lag, its yaw signs,
    # rotors that may stop; a collision box, for a flight with no obstacles): only what changes
    # the flight is said
    flightsim = "rotor_pos" not in quad_params and "arm_length" in quad_params
    notes = [n for n in sim.vehicle_notes if not (flightsim and n.startswith("added "))]
    if loud and notes:
        warnings.warn("aerobox.flightsim: the vehicle dict, as aerobox flies it:\n  "
                      + "\n  ".join(notes), stacklevel=4)
    return sim


def _trajectory_end_exit(initial_state, trajectory):
    """flightsim's normal exit: at the trajectory's end (its update(inf)) within 2 cm, below
    3 cm/s and 0.02 rad of its yaw, and not before 1 s when the trajectory starts there."""
    end = trajectory.update(np.inf)
    xf = np.asarray(end["x"], dtype=float)
    yaw = float(end.get("yaw", 0.0))
    qf = np.array([0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)])
    min_time = 1.0 if np.array_equal(np.asarray(initial_state["x"], dtype=float), xf) else 0.0

    def exit_fn(t, state):
        if t < min_time or np.linalg.norm(state["x"] - xf) >= 0.02:
            return None
        if np.linalg.norm(state["v"]) > 0.03:
            return None
        q = np.asarray(state["q"], dtype=float)
        angle = 2 * math.acos(min(1.0, abs(float(q @ qf)) / np.linalg.norm(q)))
        return ExitStatus.COMPLETE if angle <= 0.02 else None

    return exit_fn


def _out_of_control(command, state, max_speed, statuses=ExitStatus):
    """The first of: an infinite or NaN command, a velocity component above max_speed [m/s], a
    body rate above 100 rad/s (flightsim's and RotorPy's checks), as a status of `statuses`."""
    command = np.asarray(command, dtype=float)
    if np.any(np.isinf(command)):
        return statuses.INF_VALUE
    if np.any(np.isnan(command)):
        return statuses.NAN_VALUE
    if np.any(np.abs(state["v"]) > max_speed):
        return statuses.OVER_SPEED
    if np.any(np.abs(state["w"]) > 100):
        return statuses.OVER_SPIN
    return None


def _safety_exit(state, flat, control):
    lost = _out_of_control(control["cmd_motor_speeds"], state, 100)
    if lost:
        return lost
    if np.any(np.abs(state["x"] - np.asarray(flat["x"], dtype=float)) > 20):
        return ExitStatus.FLY_AWAY
    return None


def _stack(dicts):
    return {key: np.array([d[key] for d in dicts]) for key in dicts[0]}


def simulate(initial_state, quadrotor, controller, trajectory, t_final, terminate=None):
    """Flies `controller` along `trajectory` from `initial_state` (x, v, q, w) as flightsim does
    (module doc) and returns (time (N,) [s], state {x, v, q, w}, control and flat (the dicts
    the controller and the trajectory returned, stacked), exit (an ExitStatus)).

    terminate: None ends the run at the trajectory's end (update(inf)) within 2 cm, 3 cm/s and
    0.02 rad; False never ends it before t_final (or a failure); a function f(t, state)
    returning a truthy ExitStatus ends it with that status.
    """
    if not isinstance(quadrotor, Quadrotor):
        raise TypeError("simulate: quadrotor: expected an aerobox.flightsim.Quadrotor")
    if not (t_final > 0):
        raise ValueError(f"simulate: t_final must be positive [s], got {t_final}")
    if terminate is None:
        normal_exit = _trajectory_end_exit(initial_state, trajectory)
    elif terminate is False:
        normal_exit = lambda t, s: None  # noqa: E731
    elif callable(terminate):
        normal_exit = terminate
    else:
        raise TypeError("simulate: terminate: expected None, False or a function f(t, state)")

    sim = quadrotor.simulator(initial_state["x"])
    start = sim.reset(state=initial_state)
    # the state as flightsim's: x, v, q, w
    state = [{k: np.array(start[k], dtype=float) for k in ("x", "v", "q", "w")}]
    time = [0.0]
    flat = [trajectory.update(0.0)]
    control = [controller.update(0.0, state[-1], flat[-1])]
    while True:
        exit_status = (_safety_exit(state[-1], flat[-1], control[-1])
                       or normal_exit(time[-1], state[-1])
                       or (ExitStatus.TIMEOUT if time[-1] >= t_final else None))
        if exit_status:
            break
        after = sim.step({"cmd_motor_speeds": control[-1]["cmd_motor_speeds"]}, T_STEP,
                         "cmd_motor_speeds")
        time.append(time[-1] + T_STEP)
        state.append({k: after[k] for k in ("x", "v", "q", "w")})
        flat.append(trajectory.update(time[-1]))
        control.append(controller.update(time[-1], state[-1], flat[-1]))
    return np.array(time), _stack(state), _stack(control), _stack(flat), exit_status
