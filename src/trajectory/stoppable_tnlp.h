// Private to this library's .cpp files (it includes Ipopt, whose types stay out of the public
// headers): an Ipopt problem that stops at its next iteration once a stop was asked for
// (common/stop.h), and the check that turns that stop into Interrupted after the solve.
#pragma once

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include "common/stop.h"

namespace aerobox {

class StoppableTnlp : public Ipopt::TNLP {
 public:
  // Called by Ipopt once an iteration: false ends the solve with User_Requested_Stop.
  bool intermediate_callback(Ipopt::AlgorithmMode, Ipopt::Index, Ipopt::Number, Ipopt::Number,
                             Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Number,
                             Ipopt::Number, Ipopt::Number, Ipopt::Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    return !StopRequested();
  }
};

// After OptimizeTNLP: a solve stopped on request is not a solver failure but the user's Ctrl-C.
inline void ThrowIfStoppedOnRequest(Ipopt::ApplicationReturnStatus status, const char* during) {
  if (status == Ipopt::User_Requested_Stop) ThrowIfStopRequested(during);
}

}  // namespace aerobox
