#!/usr/bin/python3
"""Plots the robustness benchmark's flights (aerobox bench --sections robustness
--robustness-csv FILE): tracking RMS against the mean wind per controller (per map when the file
has no controller column), each flight a dot (a cross when it failed), and the share that
reached the goal over every map, into one PNG.

Usage: tools/plot_robustness.py robustness.csv [robustness.png]
(default output: robustness.png beside the CSV). Needs Debian's python3-pandas and
python3-matplotlib (tools/setup.sh installs them).
"""
import sys

import matplotlib

matplotlib.use("Agg")  # headless
import matplotlib.pyplot as plt  # noqa: E402
from plot_input import read_input  # noqa: E402


def main(argv):
    data, target = read_input(argv, __doc__, "plot_robustness", "robustness.png",
                              ["map", "wind_mps", "seed", "status", "tracking_rms_m"],
                              "a robustness file")
    if data is None:
        return target

    figure, (rms_axis, rate_axis) = plt.subplots(1, 2, figsize=(12, 4.5))
    group = "controller" if "controller" in data.columns else "map"
    groups = list(dict.fromkeys(data[group]))
    winds = sorted(set(data["wind_mps"]))
    width = 0.8 / max(1, len(groups))
    for i, name in enumerate(groups):
        rows = data[data[group] == name]
        offset = (i - (len(groups) - 1) / 2) * width * 0.6
        ok = rows[rows["status"] == "reached goal"]
        bad = rows[rows["status"] != "reached goal"]
        colour = f"C{i}"
        rms_axis.scatter(ok["wind_mps"] + offset, ok["tracking_rms_m"] * 100, s=12,
                         color=colour, label=name)
        rms_axis.scatter(bad["wind_mps"] + offset, bad["tracking_rms_m"] * 100, s=40,
                         color=colour, marker="x")
        rate = [100 * (rows[rows["wind_mps"] == w]["status"] == "reached goal").mean()
                for w in winds]
        rate_axis.bar([w + offset for w in winds], rate, width=width * 0.6, color=colour,
                      label=name)
    rms_axis.set_xlabel("mean wind [m/s] (with Dryden turbulence)")
    rms_axis.set_ylabel("tracking RMS [cm]")
    rms_axis.set_title("tracking, each flight (x: failed)")
    rms_axis.legend()
    rms_axis.grid(alpha=0.3)
    rate_axis.set_xlabel("mean wind [m/s]")
    rate_axis.set_ylabel("reached the goal [%]")
    rate_axis.set_ylim(0, 105)
    rate_axis.set_title("success")
    rate_axis.grid(alpha=0.3, axis="y")
    figure.suptitle("aerobox: flights in wind, with drag, an IMU and motion capture")
    figure.tight_layout()
    figure.savefig(target, dpi=100)
    print(target)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
