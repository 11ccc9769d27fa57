"""aerobox: fly your Python controllers, trajectories and planners in aerobox's MuJoCo physics.

Conventions (RotorPy's): world frame ENU with z up, body frame FLU (x forward, y left, z up),
SI units (m, s, N, rad), quaternions as [i, j, k, w] (body to world), body rates in the body
frame. Arrays are numpy float64.

    import aerobox
    world = aerobox.read_map("scenes/window/map.json")
    path = aerobox.plan(world, start, goal, seed=1)              # (N, 3) [m]
    trajectory = aerobox.min_snap(world, path, max_speed=3.0)    # .duration, .update(t)
    sim = aerobox.Simulator(world, vehicle="tello", start=path[0])
    result = sim.run(MyController(sim.quad_params), trajectory)  # RotorPy's result dict
    aerobox.write_outputs(result, "renders/mine")                # what `aerobox fly` writes
    result = aerobox.fly("scenes/maze_unknown/scenario.toml")    # a whole run, as the command

Scenario keys: every function that takes **keys takes the tables of a scenario.toml (README:
Scenarios): ``planner={...}``, ``trajectory={...}``, ``controller={...}``, ``flight={...}``,
``vehicle={...}``; plan() and min_snap() take their own table's keys directly.
"""

import math
import os
import warnings

from . import _aerobox

__version__ = _aerobox.__version__
__all__ = [
    "Map",
    "Scenario",
    "Simulator",
    "Swarm",
    "Trajectory",
    "builtin_controller",
    "fly",
    "load_scenario",
    "min_snap",
    "plan",
    "read_map",
    "trajectory",
    "write_outputs",
]

Trajectory = _aerobox.Trajectory
Trajectory.__doc__ = """An aerobox trajectory (min-snap or a baseline), flown exactly.

duration [s]; update(t) -> RotorPy's flat-output dict (x, x_dot, x_ddot, x_dddot, x_ddddot
[m, m/s, m/s^2, m/s^3, m/s^4], yaw [rad], yaw_dot [rad/s]); status, solved, message, method,
waypoints (N, 3) [m], solve_time [s], max_speed [m/s], max_accel [m/s^2]. Beyond its duration
the end point is held at rest."""


def _toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        if isinstance(value, float) and not math.isfinite(value):
            return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
        return repr(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, os.PathLike):
        return _toml_value(os.fspath(value))
    if hasattr(value, "tolist"):  # numpy arrays and numbers
        return _toml_value(value.tolist())
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):  # a table, inline
        return "{" + ", ".join(f"{k} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"{type(value).__name__} is not a scenario value")


def _toml(document):
    """A scenario dict as TOML text: plain keys first, then one table per dict (nested dicts
    become [a.b] tables, lists of dicts [[a.b]] arrays of tables)."""
    lines = []

    def table(name, values):
        plain = {k: v for k, v in values.items() if not _is_table(v)}
        lines.append(f"[{name}]")
        lines.extend(f"{k} = {_toml_value(v)}" for k, v in plain.items())
        for k, v in values.items():
            if isinstance(v, dict):
                table(f"{name}.{k}", v)
            elif _is_table(v):
                for item in v:
                    lines.append(f"[[{name}.{k}]]")
                    lines.extend(f"{ik} = {_toml_value(iv)}" for ik, iv in item.items())

    for key, value in document.items():
        if not _is_table(value):
            lines.append(f"{key} = {_toml_value(value)}")
    for key, value in document.items():
        if isinstance(value, dict):
            table(key, value)
        elif _is_table(value):  # [[key]]: an array of tables
            for item in value:
                lines.append(f"[[{key}]]")
                lines.extend(f"{k} = {_toml_value(v)}" for k, v in item.items())
    return "\n".join(lines) + "\n"


def _is_table(value):
    """A dict, or a non-empty list of dicts (an array of tables)."""
    if isinstance(value, dict):
        return True
    return (isinstance(value, (list, tuple)) and len(value) > 0
            and all(isinstance(v, dict) for v in value))


class Map:
    """An obstacle map (TXT, JSON or CSV, README: Map formats).

    name, source (the file), bounds (2, 3) [m] (min row, max row), boxes (N, 6) [m] as
    [xmin, ymin, zmin, xmax, ymax, zmax], colors (N, 3) in [0, 1], start and goal [m] when the
    file gives them (else None); world() is flightsim's world dict (bounds.extents and blocks
    with extents [xmin, xmax, ymin, ymax, zmin, zmax] and color), what MEAM620 planners read;
    clearance(point) is the distance [m] from the vehicle's box at `point` to the nearest box.
    """

    def __init__(self, setup):
        self._setup = setup
        self.name = setup.name
        self.source = setup.map_path
        self.bounds = setup.bounds
        self.boxes = setup.boxes
        self.colors = setup.colors

    @property
    def start(self):
        return self._setup.start

    @property
    def goal(self):
        return self._setup.goal

    def world(self):
        return self._setup.world()

    def clearance(self, point):
        return self._setup.clearance(point)

    def __repr__(self):
        return f"aerobox.Map({self.source!r}: {len(self.boxes)} boxes)"


def read_map(path):
    """Reads a map file; ValueError names the file, line and field of a bad one."""
    return Map(_aerobox._load(os.fspath(path)))


class Scenario:
    """A scenario.toml: its keys (as a dict, `keys`), the map, start, goal and seed."""

    def __init__(self, path):
        import tomllib

        self.path = os.path.abspath(os.fspath(path))
        self._setup = _aerobox._load(self.path)
        with open(self.path, "rb") as file:
            self.keys = tomllib.load(file)
        map_path = self.keys.get("map", "")
        if not os.path.isabs(map_path):
            self.keys["map"] = os.path.join(os.path.dirname(self.path), map_path)
        self.keys.setdefault("name", self._setup.name)
        self.map = Map(self._setup)
        self.name = self._setup.name
        self.start = self._setup.start
        self.goal = self._setup.goal
        self.seed = self._setup.seed

    def __repr__(self):
        return f"aerobox.Scenario({self.path!r})"


def load_scenario(path):
    """Reads a scenario.toml (README: Scenarios); ValueError names the file, line and key."""
    return Scenario(path)


def _setup(where, start=None, goal=None, seed=None, caller="aerobox", own=None, extra=(),
           vehicles=None, **tables):
    """A set-up from a Map, a Scenario or a path, with scenario keys given as Python arguments
    set over it. Each is checked as `--set` checks a key, and a refused one is named as the
    caller's argument and the key: `wind['turbulence'] (wind.turbulence)`, with the bare keyword
    for the table `own` (the caller's own keywords: plan()'s are [planner] keys)."""
    if isinstance(where, (str, os.PathLike)):
        where = os.fspath(where)
        where = Scenario(where) if where.endswith(".toml") else read_map(where)
    if isinstance(where, Scenario):
        document = {k: (dict(v) if isinstance(v, dict) else v) for k, v in where.keys.items()}
    elif isinstance(where, Map):
        document = {"name": where.name, "map": os.path.abspath(where.source)}
    else:
        raise TypeError("expected a map or scenario path, an aerobox.Map or an aerobox.Scenario")
    if vehicles is not None:
        document["vehicles"] = vehicles
    settings = list(extra)
    for key, value in (("start", start), ("goal", goal), ("seed", seed)):
        if value is not None:
            settings.append((key, _toml_value(value), key))
    for table, keys in tables.items():
        if keys is None:
            continue
        if not isinstance(keys, dict):
            simulator = caller == "aerobox.Simulator"  # the one that takes a wind object
            also = " or an object with update(t, position)" if table == "wind" and simulator else ""
            raise TypeError(f"{caller}: {table}: expected a dict of [{table}] keys{also}")
        for key, value in keys.items():
            argument = key if table == own else f"{table}[{key!r}]"
            settings.append((f"{table}.{key}", _toml_value(value),
                             f"{argument} ({table}.{key})"))
    return _aerobox._from_toml(_toml(document), f"{caller} (its map or scenario)", settings,
                               caller)


def plan(map, start=None, goal=None, seed=1, **planner_keys):
    """A collision-free path from start to goal [m] as an (N, 3) array.

    map: an aerobox.Map, an aerobox.Scenario or a path; start, goal [m] (default: the map's or
    the scenario's). planner_keys are [planner] keys (README: Scenarios), e.g. kind="lattice",
    max_iterations=2000, clearance=0.1. Raises RuntimeError when there is no path (its status in
    the message) and ValueError for bad input.
    """
    setup = _setup(map, start, goal, seed, "aerobox.plan", "planner", planner=planner_keys)
    result = _aerobox._plan(setup)
    if result["status"] != "solved":
        raise RuntimeError(f"aerobox.plan: {result['status']}")
    return result["path"]


def trajectory(map, waypoints, method="minsnap", **trajectory_keys):
    """A trajectory through `waypoints` ((N, 3) [m], at rest at both ends) by `method`:
    minsnap (corridor-constrained minimum snap, Ipopt), or a baseline on its waypoints and
    times: quintic, cubic, septic-full. trajectory_keys are [trajectory] keys, e.g.
    max_speed=3.0 [m/s], max_accel=3.0 [m/s^2], clearance=0.05 [m]. Raises RuntimeError when no
    feasible trajectory is found.
    """
    keys = dict(trajectory_keys)
    keys["method"] = method
    setup = _setup(map, caller=f"aerobox.{method}", own="trajectory", trajectory=keys)
    result = _aerobox._trajectory(setup, waypoints)
    if not result.solved:
        raise RuntimeError(f"aerobox.{method}: {result.status} ({result.message})")
    return result


def min_snap(map, waypoints, **trajectory_keys):
    """The minimum-snap trajectory through `waypoints` (see trajectory())."""
    return trajectory(map, waypoints, "minsnap", **trajectory_keys)


def quintic(map, waypoints, **trajectory_keys):
    """Minimum-jerk quintic segments on min-snap's waypoints and times (see trajectory())."""
    return trajectory(map, waypoints, "quintic", **trajectory_keys)


def cubic(map, waypoints, **trajectory_keys):
    """Cubic segments on min-snap's waypoints and times (see trajectory())."""
    return trajectory(map, waypoints, "cubic", **trajectory_keys)


class Simulator:
    """A quadrotor in a map, simulated by MuJoCo at a 1 ms step.

    Simulator(map, vehicle="tello", start=None, seed=1, **scenario_keys)

    map: an aerobox.Map, an aerobox.Scenario or a path (map file or scenario.toml).
    vehicle: "tello" (80 g, the default), "crazyflie" (RotorPy's and Foerster's Crazyflie 2.0),
        or a quad_params dict as RotorPy ships it (or flightsim's). From the dict aerobox takes
        mass [kg], Ixx, Iyy, Izz [kg m^2], num_rotors (must be 4), rotor_pos (dict r1..r4 or an
        (4, 3) array, rotors in the order given) [m, body frame], rotor_directions (+1:
        positive yaw reaction, as RotorPy's: a rotor spinning clockwise seen from above), k_eta
        [N/(rad/s)^2], k_m [N m/(rad/s)^2], rotor_speed_min, rotor_speed_max [rad/s] (thrust
        limits k_eta w^2), tau_m [s] (one motor lag for all rotors: their mean), rotor_radius
        [m] (the collision box covers the rotor discs, 3 cm high), c_Dx, c_Dy, c_Dz (RotorPy's
        parasitic drag, aerobox's body drag term for term) and k_d, k_z (rotor drag, set equal
        at hover: RotorPy's grows with rotor speed, aerobox's with thrust); drag acts with
        aero={"drag": True}. flightsim's dict (arm_length, k_thrust, k_drag) is flightsim's
        vehicle: a "+" layout, its yaw signs, and no motor lag unless tau_m is given (the thrust
        follows the command after one 1 ms physics step).
        What aerobox adds (a key absent: a default motor lag, rotor_directions, rotor_radius),
        adjusts (principal moments MuJoCo would refuse by a rounding, as RotorPy's Crazyflie's
        Izz, are set to the sum; the rotor drag's mapping; motor_noise_std [rad/s], drawn once
        per control period as RotorPy draws it once per simulation step) or ignores
        (off-diagonal inertia, k_h, k_flap, unknown keys) is listed in
        `added_vehicle_keys`, `adjusted_vehicle_keys`, `ignored_vehicle_keys`, all of it with
        the reasons in `vehicle_notes` (also in run()'s result), and printed once as a warning.
    start: [m]; the vehicle rests there (on the floor when the start is at floor level,
        hovering otherwise). Default: the map's or scenario's start.
    scenario_keys: goal, and tables: controller={...}, flight={...} (settle_time,
        goal_tolerance, ...), planner and trajectory (for plans made from this simulator),
        wind={"mean": [3, 0, 0], "turbulence": "dryden", "intensity": 1.0, "gusts": [{...}]},
        aero={"drag": True}, sensors={"imu": True, "position": True} (or a dict of keys for
        either): the scenario's [wind], [aero] and [sensors] (README: Wind, drag and
        sensors). wind may also be an object with update(t, position) -> wind [m/s] (RotorPy's
        wind profiles), asked at each 1 ms physics step with the time [s] and the vehicle's
        position [m] in place of the scenario's wind; like it, it acts through the drag. They act in run() and step() alike: a loop of step() calls, each with the
        command of a controller given the state step() returned, flies as run() does, to the
        bit, with the same seed.

    Attributes: quad_params (the vehicle as RotorPy's dict; its rotor_pos r1..r4 and
    rotor_directions are in the order cmd_motor_thrusts and cmd_motor_speeds command the rotors:
    RotorPy's for "tello" and "crazyflie", r1 front-left, then clockwise seen from above; a
    dict's own as it was given), timestep [s], time [s], state (the true state as RotorPy's
    dict: x [m], v [m/s], q [i, j, k, w], w [rad/s], wind [m/s] at the vehicle, rotor_speeds
    [rad/s]), map (aerobox.Map).
    """

    def __init__(self, map, vehicle="tello", start=None, seed=1, **scenario_keys):
        tables = dict(scenario_keys)
        goal = tables.pop("goal", None)
        wind_object = None
        if not isinstance(tables.get("wind"), (dict, type(None))) and hasattr(tables["wind"],
                                                                             "update"):
            wind_object = tables.pop("wind")
        self.ignored_vehicle_keys = []
        self.adjusted_vehicle_keys = []
        self.added_vehicle_keys = []
        self.vehicle_notes = []
        if isinstance(vehicle, str):
            setup = _setup(map, start, goal, seed, "aerobox.Simulator",
                           extra=[("vehicle.kind", _toml_value(vehicle), "vehicle (vehicle.kind)")], **tables)
        elif isinstance(vehicle, dict):
            setup = _setup(map, start, goal, seed, "aerobox.Simulator", **tables)
            setup, ignored, self.adjusted_vehicle_keys, self.added_vehicle_keys = (
                setup.with_vehicle(vehicle))
            self.ignored_vehicle_keys = [key for key, _ in ignored]
            self.vehicle_notes = ([f"added {note}" for note in self.added_vehicle_keys]
                                  + [f"adjusted {note}" for note in self.adjusted_vehicle_keys]
                                  + [f"ignored {key}: {why}" for key, why in ignored])
            if self.vehicle_notes:
                warnings.warn("aerobox.Simulator: the vehicle dict, as aerobox flies it:\n  "
                              + "\n  ".join(self.vehicle_notes), stacklevel=2)
        else:
            raise TypeError("vehicle: expected 'tello', 'crazyflie' or a quad_params dict")
        self._core = _aerobox.SimulatorCore(setup)
        if wind_object is not None:
            self._core.set_wind(wind_object)
        self._seed = seed
        self.map = Map(setup)

    @property
    def quad_params(self):
        return self._core.vehicle

    @property
    def timestep(self):
        return self._core.timestep

    @property
    def time(self):
        return self._core.time

    @property
    def state(self):
        return self._core.state

    @property
    def start(self):
        return self._core.setup.start

    def reset(self, seed=None, state=None):
        """Back to the start at t = 0: at rest on the floor, or hovering level with the rotors at
        hover speed when the start is in the air (or to `state`, RotorPy's dict: x [m], v [m/s],
        q [i, j, k, w], w [rad/s], and rotor_speeds [rad/s], else the rotors at hover). `seed`
        seeds the turbulence, the sensors' and the rotors' noise (the same seed gives the same flight; the
        default is the Simulator's). The wind, the sensors and the estimator start anew.
        Returns the state a controller sees, as step() does."""
        if seed is not None:
            self._seed = seed
        self._core.reset(self._seed, state)
        return self._core.seen

    def step(self, command, dt, command_kind="auto"):
        """Applies a controller's command dict for dt [s] (a multiple of the 1 ms physics step)
        as run() applies it between two control steps: each physics step runs the inner loops
        below the command on what the vehicle senses, in the wind and drag, then the sensors and
        the estimator. Returns the state a controller sees, the dict run() gives
        controller.update: the estimate with sensors on (`state` stays the truth), else the
        true state, with wind [m/s] and rotor_speeds [rad/s]. Contacts do not stop it (see
        contacts()). command_kind: see run()."""
        return self._core.step(command, dt, command_kind)

    @property
    def statedot(self):
        """The last physics step's accelerations, as RotorPy's vehicle.statedot names them:
        vdot [m/s^2] (world frame) and wdot [rad/s^2] (body frame)."""
        return self._core.statedot

    def contacts(self):
        """The geoms the vehicle touches now (names; "floor" for the floor)."""
        return self._core.contacts()

    def run(self, controller, trajectory, t_final=0.0, control_rate=None, command="auto",
            reset=True, terminate=None):
        """Flies `trajectory` with `controller` and returns RotorPy's result dict.

        controller: any object with update(t, state, flat_output) -> dict, or a built-in by
            name ("cascade", "se3", "indi"). The dict holds cmd_motor_thrusts [N] (4), or
            cmd_motor_speeds [rad/s] (through k_eta), or cmd_thrust [N] with cmd_moment [N m]
            (body), cmd_w [rad/s] (body) or cmd_q ([i, j, k, w]; with it, aerobox's own
            cmd_w_ff [rad/s] adds body rates to the attitude loop's, a feed-forward); extra
            keys are ignored.
        command: which keys fly: "auto" (the first present of cmd_motor_thrusts,
            cmd_motor_speeds, cmd_moment, cmd_w, cmd_q), or RotorPy's control abstraction
            "cmd_motor_thrusts", "cmd_motor_speeds", "cmd_ctbm", "cmd_ctbr", "cmd_ctatt".
            aerobox runs the loops below it (attitude, rates, mixer) at 1 kHz.
        trajectory: an aerobox Trajectory, or any object with update(t) -> flat_output dict
            (x required; x_dot ... x_ddddot, yaw, yaw_dot default to 0) and a `duration` or
            `t_final` [s] attribute (otherwise t_final is required).
        t_final: [s] when the run ends at the latest; 0: the trajectory's duration plus the
            scenario's settle time (5 s). It ends earlier on completion (`terminate`) and on
            every failure: contact, fly-away (2 m off the setpoint), a non-finite state.
        terminate: None: complete ("reached goal") once the vehicle rests at the trajectory's
            end: within the scenario's goal_tolerance (0.10 m) below its goal_speed (0.10 m/s)
            after its duration, or, for an object without one, at its update(inf) within 2 cm
            below 3 cm/s, as flightsim and RotorPy find the end (from 1 s on when the
            trajectory starts there; status "timeout" when never reached by t_final); False: never, the run ends at t_final
            ("completed"); a function f(t, state) -> truthy ends it ("terminated"), called at
            each control step with the true state (x, v, q, w), as RotorPy's.
        control_rate: [Hz] of controller.update (must divide 1000); None: the scenario's
            [controller] rate, as `aerobox fly` uses it (250 Hz unless the scenario says).
        reset: start from the simulator's start (hovering at the trajectory's first point when
            the start is in the air), the wind and the sensors anew from the seed; False: from
            the current state, the wind, gusts and estimator going on from where step() or the
            last run left them (the result's time starts at 0 again).

        Returns: time (N,) [s]; state {x, v, q, w} (N, 3|4); control {cmd_motor_thrusts (N, 4)
        [N] as sent to the rotors, cmd_thrust (N,) [N], cmd_moment (N, 3) [N m]}; flat {x, x_dot,
        x_ddot, x_dddot, x_ddddot (N, 3), yaw, yaw_dot (N,)}; rotor_thrusts (N, 4) [N] produced;
        position_error, clearance (N,) [m]; status ("reached goal", "collision", "timeout",
        "fly-away", "non-finite state", "completed": run to t_final with no end to reach,
        "terminated": by `terminate`); reached_goal, collisions, collision_with, min_clearance [m], tracking_rms,
        tracking_max [m], flight_time [s], distance [m], top_speed [m/s], peak_rotor_fraction,
        rotor_saturated_time [s], wall_time [s], seed; wind (N, 3) [m/s] at the vehicle, drag
        (N, 3) [N], max_wind [m/s]. With sensors on, the controller flies on the estimate:
        estimate {x, v, q, w}, imu {gyro [rad/s], accel [m/s^2]} (N, 3|4), estimate_error (N,)
        [m], nees (N,), estimate_rms, estimate_max [m]. One row per control step.
        telemetry: telemetry.csv's columns by name (N,) each, in the CSV's order
        (pandas.DataFrame(result["telemetry"]) is the table; no obstacle in range: NaN).

        An exception in controller.update or trajectory.update ends the run with that exception
        (its notes name the time); a command with a missing key, a wrong shape or a non-finite
        value raises ValueError naming the key and the time.
        """
        if control_rate is None:
            control_rate = self._core.setup.control_rate
        result, record = self._core.run(controller, trajectory, float(t_final),
                                        float(control_rate), command, reset, terminate)
        result["vehicle_notes"] = list(self.vehicle_notes)
        result["_record"] = record
        return result


class Swarm:
    """Several vehicles in one map, simulated by MuJoCo in one world at a 1 ms step, each flown by
    its own controller (RotorPy's contract, per vehicle).

    Swarm(map, vehicles=None, seed=1, **scenario_keys)

    map: as Simulator's (a scenario with [[vehicles]] brings its own).
    vehicles: a list of dicts, one per vehicle: name, start [m], and optionally vehicle
        ("tello" or "crazyflie"; default the scenario's [vehicle]) and goal [m] (default the
        start); None: the scenario's [[vehicles]]. Each rests at its start, hovering when it is
        in the air. Names are unique; vehicles starting inside each other, or outside the map,
        raise ValueError naming the vehicle.
    scenario_keys: as Simulator's tables (flight, wind, aero, sensors, swarm={"downwash": True}).

    Attributes: names (the vehicles', in order), quad_params (one RotorPy dict per vehicle).
    """

    def __init__(self, map, vehicles=None, seed=1, **scenario_keys):
        entries = None
        if vehicles is not None:
            if not isinstance(vehicles, (list, tuple)) or not vehicles or not all(
                    isinstance(v, dict) for v in vehicles):
                raise TypeError("aerobox.Swarm: vehicles: expected a list of dicts (name, start, "
                                "vehicle, goal)")
            entries = []
            for v in vehicles:
                unknown = set(v) - {"name", "start", "goal", "vehicle"}
                if unknown:
                    raise TypeError(f"aerobox.Swarm: vehicles: unknown key {sorted(unknown)[0]!r} "
                                    "(keys: name, start, goal, vehicle)")
                entry = {"name": v.get("name"), "start": v.get("start"),
                         "goal": v.get("goal", v.get("start"))}
                if "vehicle" in v:
                    entry["kind"] = v["vehicle"]
                entries.append({k: val for k, val in entry.items() if val is not None})
        setup = _setup(map, None, None, seed, "aerobox.Swarm", vehicles=entries, **scenario_keys)
        self._core = _aerobox.SwarmSimulatorCore(setup)
        self.map = Map(setup)

    @property
    def names(self):
        return list(self._core.names)

    @property
    def quad_params(self):
        return list(self._core.vehicles)

    def run(self, controllers, trajectories, t_final=0.0, control_rate=None, command="auto"):
        """Flies every vehicle's trajectory with its controller, all at once, from their starts.

        controllers, trajectories: one per vehicle, as lists in the vehicles' order or dicts by
            name; each as Simulator.run takes it (a built-in's name or an object with
            update(t, state, flat_output); an aerobox Trajectory or an object with update(t)).
        t_final, control_rate, command: as Simulator.run's (control_rate None: 250 Hz, or the
            scenario's [controller] rate).

        Returns {"vehicles": {name: Simulator.run's result dict, with min_separation [m] (to
        the closest other vehicle)}, "all_reached", "min_separation" [m], "closest_pair",
        "flight_time" [s], "wall_time" [s]}. A vehicle that reaches its goal holds it while the
        others fly; a contact between two ends both flights as a collision naming the other
        (collision_with)."""
        controllers = self._in_order(controllers, "controllers")
        trajectories = self._in_order(trajectories, "trajectories")
        if control_rate is None:
            control_rate = 250.0
        return self._core.run(controllers, trajectories, float(t_final), float(control_rate),
                              command)

    def _in_order(self, given, what):
        names = self.names
        if isinstance(given, dict):
            missing = [n for n in names if n not in given]
            extra = [k for k in given if k not in names]
            if missing or extra:
                raise ValueError(f"aerobox.Swarm.run: {what}: "
                                 + (f"none for {missing[0]!r}" if missing
                                    else f"{extra[0]!r} is not a vehicle") + f" (vehicles: {names})")
            return [given[n] for n in names]
        if not isinstance(given, (list, tuple)) or len(given) != len(names):
            raise ValueError(f"aerobox.Swarm.run: {what}: expected one per vehicle ({len(names)}), "
                             "as a list or a dict by name")
        return list(given)


def fly(map, controller=None, start=None, goal=None, goals=None, unknown_fraction=None,
        seed=None, command="auto", **scenario_keys):
    """Flies a map or scenario as `aerobox fly` does: plans (RRT*, or the scenario's planner),
    solves the trajectory, flies it with the scenario's controller (or `controller`, any object
    with update(t, state, flat_output) -> dict, flown as in Simulator.run with `command`), and
    returns Simulator.run's dict (aerobox.write_outputs writes its files) with, besides:
    mission_status ("reached goal", "no path", "no feasible trajectory", "flight failed"),
    path (N, 3) [m] as planned, goal_times [s] (a mission's goals before the last, when each was
    reached), unknown_boxes and revealed_boxes (how many of the map's boxes the planner did
    not know, and how many the sensor revealed), revealed_at [s] per box (< 0: never, or known)
    and replans (a dict each: t [s], trigger (the box), outcome, planning_time, solve_time,
    latency [s], path_length [m], time_capped). A flight that could not start (no path, no
    trajectory) has status mission_status and empty arrays.

    start, goal [m]; goals: a mission's goals in order ([[x, y, z], ...], the last the goal);
    unknown_fraction: the share of the map's boxes the planner does not know before take-off
    (0..1, chosen by the seed); seed; scenario_keys: tables as Simulator's (planner,
    trajectory, controller, flight, wind, aero, sensors, sensing, replan, vehicle, ...), each
    checked as `--set` checks it."""
    extra = []
    for key, value in (("goals", goals), ("unknown_fraction", unknown_fraction)):
        if value is not None:
            extra.append((key, _toml_value(value), key))
    setup = _setup(map, start, goal, seed, "aerobox.fly", extra=extra, **scenario_keys)
    result, record = _aerobox._fly(setup, controller, command)
    result["_record"] = record
    return result


def write_outputs(result, out_dir, video=True, size=(640, 480), fps=30, camera="chase",
                  report=True):
    """Writes what `aerobox fly` writes for a run of Simulator.run into out_dir: path.csv,
    trajectory.csv, telemetry.csv, summary.json, overview.png, report.html (unless
    report=False: the run in 3-D and in charts, for a browser) and video.mp4 (H.264, unless
    video=False). size [pixels] (W, H), fps [frames/s], camera "chase", "overview" or "top".
    Returns the folder. Bad options raise ValueError; nothing partial is left."""
    if "_record" not in result:
        raise ValueError("write_outputs: expected the dict Simulator.run returned")
    width, height = size
    return _aerobox._write_outputs(result["_record"], os.fspath(out_dir), bool(video), int(width),
                                   int(height), int(fps), camera, bool(report))


def builtin_controller(sim, kind="cascade", rate=None):
    """A built-in controller ("cascade", "se3") as a Python object for `sim`'s vehicle:
    update(t, state, flat_output) -> dict with every command level at once: its own command
    (cmd_thrust [N], cmd_q [i, j, k, w], cmd_w_ff [rad/s]) and what aerobox's inner loops make
    of it below it,
    called at `rate` [Hz] (None: the scenario's controller rate, which run() also calls it at
    by default): cmd_w [rad/s], cmd_moment [N m], cmd_motor_thrusts [N],
    cmd_motor_speeds [rad/s]. For comparing, or wrapping, in Python. Not "indi" nor a
    controller with the disturbance observer: they measure the acceleration and the rotors'
    thrusts, which a state dict does not carry (fly them by name with Simulator.run); asking
    raises ValueError."""
    if rate is None:
        rate = sim._core.setup.control_rate
    return _aerobox.BuiltinController(sim._core.setup, kind, float(rate))
