#include "common/drag.h"

namespace aerobox {

Vec3 DragAcceleration(const DragModel& drag, const Vec3& air_W) {
  return -(drag.linear.cwiseProduct(air_W) + air_W.norm() * drag.quadratic.cwiseProduct(air_W));
}

Vec3 DragAccelerationRate(const DragModel& drag, const Vec3& air_W, const Vec3& a_W) {
  const double speed = air_W.norm();
  // d/dt (|v| v) = |v| a + (v . a / |v|) v
  const Vec3 quadratic =
      speed > 1e-9 ? Vec3(speed * a_W + air_W.dot(a_W) / speed * air_W) : Vec3::Zero();
  return -(drag.linear.cwiseProduct(a_W) + drag.quadratic.cwiseProduct(quadratic));
}

FlatOutput CompensateDrag(const FlatOutput& setpoint, const DragModel& drag, const Vec3& wind_W) {
  if (!drag.active()) return setpoint;
  FlatOutput out = setpoint;
  const Vec3 air = setpoint.v_W - wind_W;
  out.a_W = setpoint.a_W - DragAcceleration(drag, air);
  out.j_W = setpoint.j_W - DragAccelerationRate(drag, air, setpoint.a_W);
  return out;
}

}  // namespace aerobox
