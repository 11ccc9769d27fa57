// References from functions of time, the circle and figure-8 the controller tests and the wind
// benchmark fly, and the empty room they are flown in.
#pragma once

#include <functional>

#include "map/map.h"
#include "mission/flight.h"
#include "sim/simulation.h"
#include "vehicle/quad_params.h"

namespace aerobox {

// A reference from a position function [m] of time [s], its derivatives by central
// differences. The step grows with the order so that rounding (1e-16 m / h^order) stays below
// the truncation error (h^2 times a higher derivative): 1e-4 s for velocity and acceleration
// (about 1e-8 of the derivative), 1e-3 s for jerk and 1e-2 s for snap (about 1e-4 of it, far
// below what a controller notices).
Reference FromFunction(double duration, std::function<Vec3(double)> position);

// A phase [rad] whose rate rises from 0 to `rate` [rad/s] over `ramp` [s] (a quintic
// smoothstep) and falls back to 0 over the last `ramp` before `duration` [s]: periodic
// references start and end at rest.
double RampedPhase(double t, double rate, double ramp, double duration);

// Two laps of a 1 m circle at 1 m/s (1 rad/s), with 2 s ramps at both ends, from and back to
// (0, 0, 1.5) m.
double CircleDuration();  // [s]
Vec3 Circle(double t);

// One loop of a figure-8, x = A sin(w t), y = A/2 sin(2 w t), at up to 2 m/s (A = 2 m), with 2 s
// ramps, at 1.5 m.
double EightRate();      // [rad/s]
double EightDuration();  // [s]
Vec3 Eight(double t);

// An empty 20 x 20 x 6 m room (and `extra`'s boxes) with `vehicle` at rest at `start` [m], its
// rotors at hover thrust.
Simulation RoomAt(const Vec3& start, const Map& extra = Map(),
                  const QuadParams& vehicle = QuadParams());

}  // namespace aerobox
