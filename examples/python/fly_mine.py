import sys

import numpy as np
import aerobox

class MyController:        # RotorPy's interface; a position PD asking for thrust and attitude
    def __init__(self, quad_params):
        self.mass = quad_params["mass"]

    def update(self, t, state, flat_output):
        a = (flat_output["x_ddot"] + 6.0 * (flat_output["x"] - state["x"])
             + 4.0 * (flat_output["x_dot"] - state["v"]) + [0.0, 0.0, 9.81])
        z = a / np.linalg.norm(a)                           # body z along the thrust
        w = np.sqrt((1.0 + z[2]) / 2.0)                     # and no yaw: [i, j, k, w]
        return {"cmd_thrust": self.mass * a @ z, "cmd_q": [-z[1] / (2 * w), z[0] / (2 * w), 0, w]}

if __name__ == "__main__":      # from the repository's top
    scenario = aerobox.load_scenario("scenes/window/scenario.toml")   # or aerobox.read_map(path)
    path = aerobox.plan(scenario, seed=1)              # (N, 3) [m]; [planner] keys as keywords
    trajectory = aerobox.min_snap(scenario, path, max_speed=2.0)     # .duration [s], .update(t)
    sim = aerobox.Simulator(scenario, vehicle="tello")  # "crazyflie", or RotorPy's quad_params
    result = sim.run(MyController(sim.quad_params), trajectory, control_rate=500)
    print(result["status"], result["tracking_rms"], result["min_clearance"])
    out = sys.argv[1] if len(sys.argv) > 1 else "renders/mine"
    aerobox.write_outputs(result, out)                 # what aerobox fly writes, video included
