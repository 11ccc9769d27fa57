#include "control/rate_control.h"

#include <algorithm>
#include <stdexcept>

namespace aerobox {

void RateControlParams::Validate() const {
  for (const Vec3* v : {&gain, &integral, &derivative, &integral_limit}) {
    if (!v->allFinite() || (v->array() < 0).any()) {
      throw std::invalid_argument("RateControlParams: gains and limits must be >= 0");
    }
  }
}

RateController::RateController(const RateControlParams& params, const Vec3& inertia)
    : params_(params), inertia_(inertia) {
  params_.Validate();
  if (!inertia.allFinite() || (inertia.array() <= 0).any()) {
    throw std::invalid_argument("RateController: inertia must be > 0");
  }
}

bool RateController::Update(const Vec3& rate_setpoint_B, const Vec3& w_B, double dt, bool saturated,
                            Vec3* torque_B) {
  if (!(dt > 0) || !rate_setpoint_B.allFinite() || !w_B.allFinite()) return false;
  const Vec3 error = rate_setpoint_B - w_B;
  const Vec3 w_dot = (w_B - previous_w_) / dt;
  previous_w_ = w_B;
  const Vec3 alpha =
      params_.gain.cwiseProduct(error) + integral_ - params_.derivative.cwiseProduct(w_dot);
  if (!saturated) {
    integral_ = (integral_ + params_.integral.cwiseProduct(error) * dt)
                    .cwiseMax(-params_.integral_limit)
                    .cwiseMin(params_.integral_limit);
  }
  const Vec3 jw = inertia_.cwiseProduct(w_B);
  *torque_B = inertia_.cwiseProduct(alpha) + w_B.cross(jw);
  return true;
}

}  // namespace aerobox
