#!/usr/bin/env bash
# Installs the Debian packages aerobox needs to build and test, and nothing when they are all
# there already. Runs apt-get as root, or through sudo otherwise.
# Usage: tools/setup.sh [--bench]   (--bench adds OMPL, L2F and crazyflow's own environment
# .venv-crazyflow: references of `aerobox bench`)
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake pkg-config git clang-format
  # src/common: vector math
  libeigen3-dev
  # src/sim (and every scene test): MuJoCo 2.2.2; its CMake config needs qhull's headers and
  # OpenGL (find_dependency), and mujoco-compile checks our scenes outside our code
  libmujoco-dev libqhull-dev libgl-dev libmujoco-samples
  # src/planning: nanoflann's k-d tree
  libnanoflann-dev
  # src/trajectory: Ipopt (with MUMPS) for the corridor-constrained minimum-snap QP; its
  # pkg-config links -llapack -lblas, whose .so links come only with these -dev packages
  coinor-libipopt-dev liblapack-dev libblas-dev
  # src/render: OSMesa (CPU OpenGL), libav (H.264 MP4 with libx264), libpng
  libosmesa6-dev libavcodec-dev libavformat-dev libavutil-dev libswscale-dev libpng-dev
  # src/app: command line, scenario files, aerobox bench
  libcli11-dev libtomlplusplus-dev libbenchmark-dev
  # aerobox bench's navigation section: OctoMap, the occupancy map's reference
  liboctomap-dev
  # src/telemetry: summary.json
  nlohmann-json3-dev
  # src/python: the aerobox package (pybind11, Debian's python3 with numpy)
  pybind11-dev python3-dev python3-numpy
  # `pip install .` (pyproject.toml) into a venv of Debian's python3, tested by tools/test.sh
  python3-venv python3-pip
  # tests/
  doctest-dev
  # report.html: three.js and Chart.js copied into the page; the page is tested in chromium
  libjs-three libjs-chart.js chromium
  # aerobox sweep slurm, tested on a single-node cluster on localhost (tools/slurm_local.sh)
  slurm-wlm munge
  # tools/plot_telemetry.py (run by tools/fly.sh, tested by tools/test.sh)
  python3-pandas python3-matplotlib
  # the project environment .venv (below): what RotorPy and Gymnasium need from Debian
  python3-scipy python3-yaml python3-tqdm python3-cvxopt python3-cloudpickle
  python3-typing-extensions
  # training a policy (examples/train_hover.py, tested): Debian's CPU torch 1.13, not PyPI's
  # multi-GB CUDA build; stable-baselines3 itself is pinned below. Torch (and numpy) call the
  # system's libblas.so.3: without OpenBLAS that is the reference BLAS, and training is 8 times
  # slower
  python3-torch libopenblas0-openmp
)
if [ "${1:-}" = "--bench" ]; then
  # OMPL 1.5.2 as the planners' reference; its CMake config links these Boost libraries
  packages+=(libompl-dev libboost-serialization-dev libboost-filesystem-dev libboost-system-dev)
fi

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null || true)
  [ "$status" = "installed" ] || missing+=("$package")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages are installed"
else
  sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo > /dev/null || { echo "setup: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
    sudo=(sudo)
  fi
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo[@]}" apt-get update -q
  "${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

top=$(cd "$(dirname "$0")/.." && pwd)
# --bench: crazyflow, the rl benchmark's peer, in its own environment (its JAX and numpy 2 would
# clash with the project environment's Debian packages)
if [ "${1:-}" = "--bench" ]; then
  peer=$top/.venv-crazyflow
  peer_pins=$(/usr/bin/python3 -c 'import sys, tomllib
with open(sys.argv[1], "rb") as file:
    print(" ".join(tomllib.load(file)["project"]["optional-dependencies"]["crazyflow-peer"]))' \
    "$top/pyproject.toml")
  if [ "$(cat "$peer/aerobox-pins" 2> /dev/null)" = "$peer_pins" ]; then
    echo "setup: crazyflow's environment .venv-crazyflow has its pinned packages"
  else
    echo "setup: crazyflow's environment .venv-crazyflow: installing $peer_pins"
    [ -x "$peer/bin/python" ] || /usr/bin/python3 -m venv "$peer"
    # shellcheck disable=SC2086 # one argument per pin
    "$peer/bin/python" -m pip install --quiet --disable-pip-version-check $peer_pins
    echo "$peer_pins" > "$peer/aerobox-pins"
  fi
fi

# The project environment .venv: Debian's python3, seeing Debian's numpy, scipy, matplotlib and
# pandas (--system-site-packages), with the packages our users take from PyPI: every one is
# pinned in pyproject.toml's "peers" extra and installed --no-deps, so nothing unpinned (PyPI's
# CUDA torch above all) comes in. The Python tests that fly RotorPy's own objects run in it.
venv=$top/.venv
# --bench adds the "bench-peers" extra (L2F, compiled here from its source package)
pins=$(/usr/bin/python3 -c 'import sys, tomllib
with open(sys.argv[1], "rb") as file:
    extras = tomllib.load(file)["project"]["optional-dependencies"]
print(" ".join(extras["peers"] + (extras["bench-peers"] if sys.argv[2] == "--bench" else [])))' \
  "$top/pyproject.toml" "${1:-}")
if [ "$(cat "$venv/aerobox-pins" 2> /dev/null)" = "$pins" ]; then
  echo "setup: the project environment .venv has its pinned packages"
  exit 0
fi
echo "setup: the project environment .venv: installing $pins"
[ -x "$venv/bin/python" ] || /usr/bin/python3 -m venv --system-site-packages "$venv"
# shellcheck disable=SC2086 # one argument per pin
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-deps $pins
# what the pinned packages need must be there (pip check also reports Debian's own packages'
# optional needs, which are not ours). Debian's torch calls itself 1.13.0a0, a pre-release that
# satisfies no torch>=1.13 although it is 1.13: that one line is not a missing need
names=$(for pin in $pins; do printf '%s|' "${pin%%==*}"; done)
if broken=$("$venv/bin/python" -m pip check --disable-pip-version-check |
  grep -iE "^(${names%|}) " | grep -vE "requirement torch>=1\.13, but you have torch 1\.13\.0a0"); then
  echo "setup: .venv: $broken" >&2
  exit 1
fi
echo "$pins" > "$venv/aerobox-pins"
