"""RotorPy's contract (rotorpy.environments.Environment), flown in aerobox's MuJoCo physics.

A RotorPy script runs with one import changed:

    from aerobox.rotorpy import Environment      # was: from rotorpy.environments import Environment
    from rotorpy.vehicles.multirotor import Multirotor
    from rotorpy.vehicles.crazyflie_params import quad_params
    from rotorpy.controllers.quadrotor_control import SE3Control
    from rotorpy.trajectories.hover_traj import HoverTraj
    from rotorpy.wind.default_winds import ConstantWind

    sim = Environment(vehicle=Multirotor(quad_params), controller=SE3Control(quad_params),
                      trajectory=HoverTraj(), wind_profile=ConstantWind(1, 0, 0), sim_rate=100)
    result = sim.run(t_final=5)          # result["exit"] is RotorPy's own ExitStatus

As RotorPy's simulate(): every 1/sim_rate [s] the controller is called with (t, state,
flat_output) (the mocap's measurement in place of the state when use_mocap), its command is flown
until the next call, and the IMU, the mocap and the estimator are asked for their readings; the
run ends on the first of: a safety failure (a speed component above 20 m/s, a body rate above
100 rad/s, the path within safety_margin of a block of the world), the normal exit
(`terminate`), t_final. The result is RotorPy's dict (time, state, control, flat,
imu_measurements, imu_gt, mocap_measurements, state_estimate, exit, camera_measurements).

What aerobox flies instead of RotorPy's Multirotor.step: MuJoCo at a 1 ms step, the vehicle's
quad_params read off the Multirotor (its mass, inertia, rotors, motor lag, motor noise and drag
terms; aerobox.Simulator's vehicle notes say what maps how), its control_abstraction through
aerobox's inner loops (cmd_vel and cmd_acc have none), its aero flag as aerobox's drag, the wind
profile asked every 1 ms, and the world's blocks as boxes MuJoCo collides with (no world: an
empty room around the start, as RotorPy's free space). The IMU reads the accelerations of the last physics
step (Simulator.statedot) where RotorPy computes its model's. The user's IMU, mocap, estimator,
camera and world are called as RotorPy calls them; the defaults (None) are RotorPy's own, made
as its Environment makes them, so RotorPy must be installed for them.
"""

import copy
import json
import os
import tempfile
import time as clock
import warnings

import numpy as np

from .flightsim import _out_of_control, _plain, _stack, _trajectory_end_exit

__all__ = ["Environment", "ExitStatus"]

try:  # RotorPy's own statuses, so that result["exit"] == rotorpy's ExitStatus.COMPLETE holds
    from rotorpy.simulate import ExitStatus
except ImportError:  # the same names and messages, for scripts without RotorPy: flightsim's and
    import enum      # RotorPy's collision

    from .flightsim import ExitStatus as _FlightsimStatus

    ExitStatus = enum.Enum("ExitStatus", [(s.name, s.value) for s in _FlightsimStatus] + [
        ("COLLISION", "Failure: Your quadrotor collided with an object.")])


# the command levels aerobox's inner loops take, by RotorPy's control_abstraction names
_ABSTRACTIONS = ("cmd_motor_speeds", "cmd_motor_thrusts", "cmd_ctbm", "cmd_ctbr", "cmd_ctatt")
# [m] half the side of the empty room flown in when no world is given (RotorPy's free space)
_ROOM = 500.0
# RotorPy's default motion capture (its Environment's, "made up based on qualitative comparison
# with real data from Vicon"): noise densities and artifacts
_MOCAP = {"pos_noise_density": 0.0005 * np.ones(3), "vel_noise_density": 0.0010 * np.ones(3),
          "att_noise_density": 0.0005 * np.ones(3), "rate_noise_density": 0.0005 * np.ones(3),
          "vel_artifact_max": 5, "vel_artifact_prob": 0.001, "rate_artifact_max": 1,
          "rate_artifact_prob": 0.0002}


def _need_rotorpy(what):
    try:
        import rotorpy  # noqa: F401
    except ImportError:
        raise ImportError(f"aerobox.rotorpy: {what} is RotorPy's own default: install RotorPy "
                          "(pip install rotorpy==3.0.0) or pass your own") from None


def quad_params_of(vehicle):
    """The quad_params dict a RotorPy Multirotor was made from, read off its attributes (mass
    [kg], inertia [kg m^2], rotors [m], thrust and moment coefficients, speed limits [rad/s],
    motor lag tau_m [s], drag terms)."""
    missing = [k for k in ("mass", "Ixx", "Iyy", "Izz", "num_rotors", "rotor_pos", "k_eta",
                           "k_m", "rotor_speed_min", "rotor_speed_max", "tau_m")
               if not hasattr(vehicle, k)]
    if missing:
        raise TypeError("Environment: vehicle: expected a RotorPy Multirotor (it has no "
                        + ", ".join(missing) + ")")
    params = {k: getattr(vehicle, k) for k in
              ("mass", "Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz", "num_rotors", "rotor_pos",
               "rotor_speed_min", "rotor_speed_max", "k_eta", "k_m", "tau_m", "c_Dx", "c_Dy",
               "c_Dz", "k_d", "k_z", "k_h", "k_flap") if hasattr(vehicle, k)}
    if hasattr(vehicle, "rotor_dir"):
        params["rotor_directions"] = np.asarray(vehicle.rotor_dir)
    if hasattr(vehicle, "motor_noise"):
        params["motor_noise_std"] = vehicle.motor_noise
    return params


class Environment:
    """RotorPy's Environment (module doc): a vehicle, a controller and a trajectory, with a wind
    profile, an IMU, a mocap, an estimator, a world and a camera, each optional; sim_rate [Hz]
    of the controller and the sensors (it must divide aerobox's 1000 Hz physics);
    safety_margin [m] around the vehicle for collisions with the world's blocks."""

    def __init__(self, vehicle, controller, trajectory, wind_profile=None, imu=None, mocap=None,
                 world=None, estimator=None, camera=None, sim_rate=100, safety_margin=0.25):
        if not sim_rate > 0 or abs(1000.0 / sim_rate - round(1000.0 / sim_rate)) > 1e-9:
            raise ValueError(f"Environment: sim_rate {sim_rate} Hz must divide aerobox's "
                             "1000 Hz physics (1000, 500, 250, 200, 100, 50 ...)")
        abstraction = getattr(vehicle, "control_abstraction", "cmd_motor_speeds")
        if abstraction not in _ABSTRACTIONS:
            raise ValueError(f"Environment: the vehicle's control_abstraction '{abstraction}' "
                             "has no aerobox inner loop: use one of " + ", ".join(_ABSTRACTIONS))
        self.quad_params = quad_params_of(vehicle)
        self.vehicle, self.controller, self.trajectory = vehicle, controller, trajectory
        self.sim_rate, self.safety_margin = sim_rate, safety_margin
        self.wind_profile, self.camera = wind_profile, camera
        self.abstraction = abstraction
        self.world = world if world is not None else self._free_space()
        self.imu = imu if imu is not None else self._default_imu()
        self.mocap = mocap if mocap is not None else self._default_mocap()
        if estimator is None:
            _need_rotorpy("estimator=None (NullEstimator)")
            from rotorpy.estimators.nullestimator import NullEstimator
            estimator = NullEstimator()
        self.estimator = estimator
        self.result = None
        self._sim = self._simulator()

    def _free_space(self):
        """RotorPy's world for no world: free space (its World.empty of +-3 m; aerobox flies in
        a room _ROOM around the start, with no floor in reach)."""
        try:
            from rotorpy.world import World
        except ImportError:
            from .flightsim import World
        return World.empty((-3, 3, -3, 3, -3, 3))

    def _default_imu(self):
        _need_rotorpy("imu=None (an Imu at sim_rate)")
        from rotorpy.sensors.imu import Imu
        return Imu(p_BS=np.zeros(3), R_BS=np.eye(3), sampling_rate=self.sim_rate)

    def _default_mocap(self):
        _need_rotorpy("mocap=None (a MotionCapture at sim_rate)")
        from rotorpy.sensors.external_mocap import MotionCapture
        return MotionCapture(sampling_rate=self.sim_rate, mocap_params=copy.deepcopy(_MOCAP),
                             with_artifacts=False)

    def _simulator(self):
        """An aerobox.Simulator of the vehicle in the world (an empty room when none was given),
        the wind profile blowing, with drag when the Multirotor has aero on."""
        from . import Simulator

        start = np.asarray(self.vehicle.initial_state["x"], dtype=float)
        blocks = self.world.world.get("blocks", []) if hasattr(self.world, "world") else []
        if blocks:
            data = {"bounds": self.world.world["bounds"], "blocks": blocks}
        else:
            lo, hi = start - _ROOM, start + _ROOM
            data = {"bounds": {"extents": [lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]},
                    "blocks": []}
        keys = {"aero": {"drag": bool(getattr(self.vehicle, "aero", True))}}
        if self.wind_profile is not None:
            keys["wind"] = self.wind_profile
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "world.json")
            with open(path, "w") as file:
                json.dump(_plain(data), file)
            with warnings.catch_warnings(record=True):  # said once below, in RotorPy's terms
                warnings.simplefilter("always")
                sim = Simulator(path, vehicle=self.quad_params, start=start, **keys)
        # a Multirotor has no rotor radius; the one aerobox adds sizes only its collision box
        notes = [n for n in sim.vehicle_notes if not n.startswith("added rotor_radius")]
        if notes:
            warnings.warn("aerobox.rotorpy: the Multirotor, as aerobox flies it:\n  "
                          + "\n  ".join(notes), stacklevel=3)
        return sim

    def _normal_exit(self, terminate, initial_state):
        if terminate is None:
            complete = _trajectory_end_exit(initial_state, self.trajectory)
            return lambda t, s: ExitStatus.COMPLETE if complete(t, s) else None
        if terminate is False:
            return lambda t, s: None
        if callable(terminate):
            return terminate
        raise TypeError("Environment.run: terminate: expected None, False or a function "
                        "f(t, state) returning an ExitStatus or None")

    def _safety_exit(self, state, control):
        """RotorPy's safety checks, and a command that cannot be flown."""
        lost = _out_of_control(control.get(self.abstraction, 0.0), state, 20, ExitStatus)
        if lost:
            return lost
        blocks = self.world.world.get("blocks", []) if hasattr(self.world, "world") else []
        if blocks and self.world.path_collisions(state["x"], self.safety_margin).size > 0:
            return ExitStatus.COLLISION
        if any(c != "floor" for c in self._sim.contacts()):
            return ExitStatus.COLLISION
        return None

    def run(self, t_final=10, use_mocap=False, terminate=False, plot=False, plot_mocap=True,
            plot_estimator=True, plot_imu=True, plot_camera=True, animate_bool=False,
            animate_wind=False, verbose=False, fname=None):
        """Flies the run (module doc) until t_final [s] at the latest and returns RotorPy's
        result dict. terminate: False (RotorPy's Environment's default) never ends it early;
        None ends it at the trajectory's end (update(inf)) within 2 cm, 3 cm/s and 0.02 rad; a
        function f(t, state) ends it with the ExitStatus it returns. plot, animate_bool, fname
        and the other plot flags are RotorPy's, drawn by RotorPy's Plotter."""
        t_step = 1.0 / self.sim_rate
        initial = {k: np.array(v, dtype=float) for k, v in self.vehicle.initial_state.items()}
        normal_exit = self._normal_exit(terminate, initial)
        start = clock.time()
        sim, mocap, imu = self._sim, self.mocap, self.imu
        # aerobox's own noise (the rotors', with the Multirotor's motor_noise_std) is seeded from
        # numpy's global generator, which RotorPy draws all of its noise from: np.random.seed(k)
        # before a run repeats it, and each run draws anew
        seed = int(np.random.randint(1, 2**31 - 1))
        state = [sim.reset(seed=seed, state=initial)]  # x, v, q, w, wind, rotor_speeds
        time = [0.0]
        flat = [self.trajectory.update(0.0)]
        mocap_measurements = [mocap.measurement(state[-1], with_noise=True, with_artifacts=False)]
        control = [self.controller.update(0.0, mocap_measurements[-1] if use_mocap else state[-1],
                                          flat[-1])]
        imu_measurements = [imu.measurement(state[-1], sim.statedot, with_noise=True)]
        imu_gt = [imu.measurement(state[-1], sim.statedot, with_noise=False)]
        state_estimate = [self.estimator.step(state[0], control[0], imu_measurements[0],
                                              mocap_measurements[0])]
        camera = _CameraLog(self.camera, t_step, self.world) if self.camera is not None else None
        if camera:
            camera.capture(0.0, state[-1])
        while True:
            exit_status = (self._safety_exit(state[-1], control[-1])
                           or normal_exit(time[-1], state[-1])
                           or (ExitStatus.TIMEOUT if time[-1] >= t_final else None))
            if exit_status:
                break
            time.append(time[-1] + t_step)
            state.append(sim.step(control[-1], t_step, self.abstraction))
            flat.append(self.trajectory.update(time[-1]))
            mocap_measurements.append(mocap.measurement(state[-1], with_noise=True,
                                                        with_artifacts=mocap.with_artifacts))
            state_estimate.append(self.estimator.step(state[-1], control[-1],
                                                      imu_measurements[-1],
                                                      mocap_measurements[-1]))
            seen = mocap_measurements[-1] if use_mocap else state[-1]
            control.append(self.controller.update(time[-1], seen, flat[-1]))
            imu_measurements.append(imu.measurement(state[-1], sim.statedot, with_noise=True))
            imu_gt.append(imu.measurement(state[-1], sim.statedot, with_noise=False))
            if camera:
                camera.capture(time[-1], state[-1])
        if verbose:
            print("-------------------RESULTS-----------------------")
            print("SIM TIME -- %3.2f seconds | WALL TIME -- %3.2f seconds"
                  % (min(t_final, time[-1]), clock.time() - start))
            print("EXIT STATUS -- " + exit_status.value)
        self.result = dict(time=np.array(time, dtype=float), state=_stack(state),
                           control=_stack(control), flat=_stack(flat),
                           imu_measurements=_stack(imu_measurements), imu_gt=_stack(imu_gt),
                           mocap_measurements=_stack(mocap_measurements),
                           state_estimate=_stack(state_estimate), exit=exit_status,
                           camera_measurements=camera.merged() if camera else None)
        if plot or animate_bool:
            self._draw(plot, animate_bool, animate_wind, fname, plot_mocap, plot_estimator,
                       plot_imu, plot_camera)
        return self.result

    def _draw(self, plot, animate_bool, animate_wind, fname, *flags):
        _need_rotorpy("plotting")
        import matplotlib.pyplot as plt
        from rotorpy.utils.plotter import Plotter

        visualizer = Plotter(self.result, self.world, self.camera)
        if fname is not None:
            fname = fname.replace(".gif", "").replace(".mp4", "")
        if animate_bool:
            visualizer.animate_results(fname=fname, animate_wind=animate_wind)
        if plot:
            plot_mocap, plot_estimator, plot_imu, plot_camera = flags
            visualizer.plot_results(fname=fname, plot_mocap=plot_mocap,
                                    plot_estimator=plot_estimator, plot_imu=plot_imu,
                                    plot_camera=plot_camera)
            if not animate_bool:
                plt.show()

    def save_to_csv(self, savepath=None):
        """The run's result as RotorPy's CSV (its unpack_sim_data; the camera left out)."""
        if self.result is None:
            raise ValueError("Environment.save_to_csv: run() first: there is no result")
        _need_rotorpy("save_to_csv")
        from rotorpy.utils.postprocessing import unpack_sim_data

        savepath = savepath or "rotorpy_simulation_results.csv"
        if not savepath.endswith(".csv"):
            savepath += ".csv"
        unpack_sim_data(self.result).to_csv(savepath)
        return savepath


    def save_camera_data(self, savepath=None, save_pngs=False):
        """The run's camera frames as RotorPy's .npz archive (and each frame as a png with
        save_pngs), written by RotorPy's own Environment.save_camera_data."""
        if self.result is None or self.result.get("camera_measurements") is None:
            raise ValueError("Environment.save_camera_data: there are no camera frames: run() "
                             "with a camera first")
        _need_rotorpy("save_camera_data")
        from rotorpy.environments import Environment as RotorPyEnvironment

        savepath = savepath or "rotorpy_camera_results.npz"
        if not savepath.endswith(".npz"):
            savepath += ".npz"
        RotorPyEnvironment.save_camera_data(self, savepath, save_pngs)
        return savepath


class _CameraLog:
    """A camera's frames at its frame_rate [Hz] (every step without one), as RotorPy keeps them."""

    def __init__(self, camera, t_step, world):
        rate = getattr(camera, "frame_rate", None)
        self.camera, self.world, self.period = camera, world, 1.0 / rate if rate else t_step
        self.next, self.frames, self.times = -np.inf, [], []

    def capture(self, t, state):
        if t >= self.next - 1e-9:
            self.frames.append(self.camera.measurement(state, self.world))
            self.times.append(t)
            self.next = t + self.period

    def merged(self):
        from rotorpy.simulate import merge_camera_measurements

        return merge_camera_measurements(self.frames, self.times)
