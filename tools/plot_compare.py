#!/usr/bin/env python3
"""Plots the four trajectory generators on one path: position per axis and acceleration
magnitude against time, from a profiles CSV written by `aerobox compare`.

    tools/plot_compare.py renders/compare/window_profiles.csv compare.png

Exit codes: 0 written, 2 bad input (nothing written).
"""
import os
import sys

NAMES = {0: "minsnap (ours)", 1: "quintic", 2: "cubic", 3: "septic-full"}
STYLES = {0: "-", 1: "--", 2: ":", 3: "-."}


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    source, target = argv[1], argv[2]
    try:
        data = pd.read_csv(source)
    except (OSError, ValueError) as error:
        print(f"plot_compare: {source}: {error}", file=sys.stderr)
        return 2
    needed = {"t", "method", "x", "y", "z", "ax", "ay", "az"}
    if not needed.issubset(data.columns) or data.empty:
        print(f"plot_compare: {source}: not an aerobox compare profiles file", file=sys.stderr)
        return 2
    figure, axes = plt.subplots(4, 1, figsize=(9, 10), sharex=True)
    for code, group in data.groupby("method"):
        label = NAMES.get(int(code), str(code))
        style = STYLES.get(int(code), "-")
        for axis, column in zip(axes[:3], ["x", "y", "z"]):
            axis.plot(group["t"], group[column], style, label=label)
        accel = (group["ax"] ** 2 + group["ay"] ** 2 + group["az"] ** 2) ** 0.5
        axes[3].plot(group["t"], accel, style, label=label)
    for axis, name in zip(axes, ["x [m]", "y [m]", "z [m]", "|acceleration| [m/s^2]"]):
        axis.set_ylabel(name)
        axis.grid(alpha=0.3)
    axes[0].legend(loc="best")
    axes[3].set_xlabel("t [s]")
    axes[0].set_title(os.path.basename(source).replace("_profiles.csv", "") +
                      ": four generators on the same waypoints and times")
    figure.tight_layout()
    partial = target + ".partial.png"
    figure.savefig(partial, dpi=90)
    os.replace(partial, target)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
