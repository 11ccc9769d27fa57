// aerobox bench --sections python, rotorpy and rl's peers: benchmarks written in Python, run with the build's
// aerobox package, their tables copied to `out`.
#pragma once

#include <ostream>
#include <string>

#include "bench/benchmark_medians.h"

namespace aerobox {

// Throws std::runtime_error when python3 cannot be started or the script fails.
// A smoke run flies each controller once, at 100 Hz only.
// python: src/bench/python_control.py, with Debian's python3.
void RunPythonBenchmark(const std::string& window_scenario, std::ostream& out,
                        const BenchSize& size);

// rotorpy: src/bench/rotorpy_peer.py, with the project environment's python (.venv, where
// tools/setup.sh installs RotorPy): RotorPy's Environment against aerobox.rotorpy's on the same
// scripts. A smoke run flies one script for 1 s.
void RunRotorPyBenchmark(std::ostream& out, const BenchSize& size);

// rl, its peers: src/bench/rl_peers.py, with the project environment's python: RotorPy's
// batched learning environment against aerobox's vector environment. A smoke run: 4 worlds, 5
// steps.
void RunRlPeers(std::ostream& out, const BenchSize& size);

}  // namespace aerobox
