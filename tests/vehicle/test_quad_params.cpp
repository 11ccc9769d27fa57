#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "vehicle/quad_params.h"

namespace aerobox {

TEST_CASE("default Tello parameters are valid and can hover with margin") {
  const QuadParams params;
  CHECK_NOTHROW(params.Validate());
  // thrust-to-weight about 2 (DESIGN.md): room to climb and to control attitude in a climb
  const double thrust_to_weight = 4 * params.max_rotor_thrust / (params.mass * kGravity);
  CHECK(thrust_to_weight == doctest::Approx(2.04).epsilon(0.01));
  CHECK(params.HoverThrustPerRotor() == doctest::Approx(0.1962));
}

TEST_CASE("allocation matrix: equal thrusts lift without moments and signs follow the layout") {
  const QuadParams params;
  const Mat4 a = AllocationMatrix(params);
  const Vec4 wrench = a * Vec4::Constant(0.2);
  CHECK(wrench[0] == doctest::Approx(0.8));
  CHECK(wrench.tail<3>().norm() < 1e-15);  // exact cancellation up to rounding

  // left rotors (0, 3) push +y side up: positive roll about +x
  CHECK((a * Vec4(1, 0, 0, 1))[1] > 0);
  // back rotors (2, 3) push the tail up: nose down, positive pitch about +y
  CHECK((a * Vec4(0, 0, 1, 1))[2] > 0);
  // clockwise rotors (0, 2) turn the body counter-clockwise: positive yaw
  CHECK((a * Vec4(1, 0, 1, 0))[3] == doctest::Approx(2 * params.yaw_moment_per_thrust));
  // the mixer needs the inverse: the matrix must be well conditioned
  CHECK(std::abs(a.determinant()) > 1e-8);
  for (int i = 0; i < kNumRotors; ++i) {
    CHECK(RotorPosition_B(params, i).head<2>().cwiseAbs().isApprox(
        Eigen::Vector2d::Constant(0.035)));  // the Tello's motor spacing
    // neighbours spin opposite ways
    CHECK(params.rotor_directions[i] == -params.rotor_directions[(i + 1) % kNumRotors]);
  }
}

TEST_CASE("Validate names the field and value that is not physical") {
  QuadParams params;
  params.mass = -1;
  CHECK_THROWS_WITH_AS(params.Validate(), "QuadParams.mass must be positive, got -1",
                       std::invalid_argument);
  params = QuadParams();
  params.max_rotor_thrust = 0.1;
  CHECK_THROWS_AS(params.Validate(), std::invalid_argument);
  params = QuadParams();
  params.inertia = Vec3(1e-5, 1e-5, 1e-4);
  CHECK_THROWS_AS(params.Validate(), std::invalid_argument);
}

TEST_CASE("the built-in vehicles: a Tello by default, a Crazyflie from published numbers") {
  CHECK(BuiltinVehicle("tello")->mass == QuadParams().mass);
  CHECK_FALSE(BuiltinVehicle("hummingbird"));
  const QuadParams cf = *BuiltinVehicle("crazyflie");
  CHECK_NOTHROW(cf.Validate());
  CHECK(cf.mass == 0.030);
  // RotorPy's inertia is not a rigid body's (1.43 + 1.43 < 2.89): refused, with the reason
  QuadParams rotorpy = cf;
  rotorpy.inertia = Vec3(1.43e-5, 1.43e-5, 2.89e-5);
  CHECK_THROWS_WITH_AS(rotorpy.Validate(), doctest::Contains("triangle inequality"),
                       std::invalid_argument);
  // RotorPy's k_eta and rotor_speed_max: 2.3e-8 x 2500^2 = 0.144 N a rotor, thrust/weight 1.95
  CHECK(cf.MaxRotorThrust() == doctest::Approx(0.14375));
  CHECK(4 * cf.MaxRotorThrust() / (cf.mass * kGravity) == doctest::Approx(1.95).epsilon(0.01));
  CHECK(cf.RotorSpeedFor(cf.MaxRotorThrust()) == doctest::Approx(2500));
  CHECK(cf.ArmLength() == doctest::Approx(0.043));
  // k_m / k_eta
  CHECK(cf.yaw_moment_per_thrust == doctest::Approx(7.8e-10 / 2.3e-8));
  const Mat4 a = AllocationMatrix(cf);
  // RotorPy's order: rotor 0 front-left and rotor 1 front-right; pushing the front up pitches
  // the nose up (negative pitch about +y in FLU)
  CHECK((a * Vec4(1, 1, 0, 0))[2] < 0);
  CHECK((a * Vec4(1, 0, 0, 1))[1] > 0);  // the left rotors (0 and 3) roll right side down
}

TEST_CASE("every built-in vehicle numbers its rotors as RotorPy: front-left, then clockwise") {
  // RotorPy's crazyflie_params: r1 (+x, +y), r2 (+x, -y), r3 (-x, -y), r4 (-x, +y) in FLU,
  // rotor_directions 1, -1, 1, -1; a motor-level controller written for it relies on both
  const double x_sign[kNumRotors] = {+1, +1, -1, -1};
  const double y_sign[kNumRotors] = {+1, -1, -1, +1};
  const int directions[kNumRotors] = {+1, -1, +1, -1};
  for (const std::string& kind : BuiltinVehicleNames()) {
    CAPTURE(kind);
    const QuadParams params = *BuiltinVehicle(kind);
    for (int i = 0; i < kNumRotors; ++i) {
      CAPTURE(i);
      const Vec3 r = RotorPosition_B(params, i);
      CHECK(r.x() * x_sign[i] > 0);
      CHECK(r.y() * y_sign[i] > 0);
      CHECK(params.rotor_directions[i] == directions[i]);
    }
  }
}

TEST_CASE("rotor layouts that cannot control every axis are refused") {
  QuadParams params;
  params.rotor_directions = {+1, +1, -1, -1};  // neighbours alike: yaw and roll mix
  CHECK_THROWS_WITH_AS(params.Validate(), doctest::Contains("allocation matrix is singular"),
                       std::invalid_argument);
  params = QuadParams();
  params.rotor_directions[2] = 0;
  CHECK_THROWS_WITH_AS(params.Validate(), doctest::Contains("rotor_directions[2]"),
                       std::invalid_argument);
  params = QuadParams();
  params.rotor_positions_B[1] = Vec3::Zero();
  CHECK_THROWS_WITH_AS(params.Validate(), doctest::Contains("rotor_positions[1]"),
                       std::invalid_argument);
}

}  // namespace aerobox
