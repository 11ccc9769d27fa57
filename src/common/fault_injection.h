// Faults injected on purpose, for the reliability tests (docs/reliability.md): the environment
// variable AEROBOX_FAULT holds comma-separated faults, each "kind" or "kind:argument":
//   write:NAME     writing the output file NAME (e.g. telemetry.csv) fails as on a full disk
//   nonfinite:T    the controller's position setpoint becomes NaN at T seconds of flight
//   ipopt          Ipopt may not take a single iteration, so it stops with its own failure
//                  (passed down as IpoptSettings::injected_failure; domain code reads no
//                  environment)
// Unset (the normal case), nothing is injected.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace aerobox {

// The argument of the injected fault of this kind ("" when it has none), or nothing.
std::optional<std::string> InjectedFault(std::string_view kind);

}  // namespace aerobox
