#!/usr/bin/python3
"""Plots an aerobox telemetry.csv: position against the setpoint per axis, tracking error,
speed, and rotor thrusts, into one PNG.

Usage: tools/plot_telemetry.py renders/window/telemetry.csv [plots.png]
(default output: plots.png beside the CSV). Needs Debian's python3-pandas and
python3-matplotlib (tools/setup.sh installs them).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")  # headless
import matplotlib.pyplot as plt  # noqa: E402
from plot_input import read_input  # noqa: E402


def main(argv):
    needed = ["t", "x", "y", "z", "x_des", "y_des", "z_des", "vx", "vy", "vz", "pos_err",
              "f1", "f2", "f3", "f4"]
    data, target = read_input(argv, __doc__, "plot_telemetry", "plots.png", needed,
                              "an aerobox telemetry file")
    if data is None:
        return target

    t = data["t"]
    figure, axes = plt.subplots(3, 2, figsize=(12, 9), sharex=True)
    for axis, name in zip(axes.flat[:3], ("x", "y", "z")):
        axis.plot(t, data[f"{name}_des"], "--", color="tab:gray", label="setpoint")
        axis.plot(t, data[name], color="tab:blue", label="flown")
        axis.set_ylabel(f"{name} [m]")
        axis.legend(loc="best", fontsize=8)
    axes.flat[3].plot(t, 100 * data["pos_err"], color="tab:red")
    axes.flat[3].set_ylabel("tracking error [cm]")
    speed = (data["vx"] ** 2 + data["vy"] ** 2 + data["vz"] ** 2) ** 0.5
    axes.flat[4].plot(t, speed, color="tab:green")
    axes.flat[4].set_ylabel("speed [m/s]")
    for i in range(1, 5):
        axes.flat[5].plot(t, data[f"f{i}"], linewidth=0.8, label=f"rotor {i}")
    axes.flat[5].set_ylabel("rotor thrust [N]")
    axes.flat[5].legend(loc="best", fontsize=8, ncol=2)
    for axis in axes[-1]:
        axis.set_xlabel("time [s]")
    rms = 100 * (data["pos_err"] ** 2).mean() ** 0.5
    figure.suptitle(f"{os.path.basename(os.path.dirname(os.path.abspath(argv[1])))}: "
                    f"tracking RMS {rms:.1f} cm, max {100 * data['pos_err'].max():.1f} cm")
    figure.tight_layout()
    partial = target + ".partial.png"
    figure.savefig(partial, dpi=100)
    os.replace(partial, target)  # complete or absent
    print(f"plots: {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
