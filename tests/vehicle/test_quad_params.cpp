#include <doctest/doctest.h>

#include <stdexcept>

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

  // left rotors (0, 1) push +y side up: positive roll about +x
  CHECK((a * Vec4(1, 1, 0, 0))[1] > 0);
  // back rotors (1, 2) push the tail up: nose down, positive pitch about +y
  CHECK((a * Vec4(0, 1, 1, 0))[2] > 0);
  // clockwise rotors (0, 2) turn the body counter-clockwise: positive yaw
  CHECK((a * Vec4(1, 0, 1, 0))[3] == doctest::Approx(2 * params.yaw_moment_per_thrust));
  // the mixer needs the inverse: the matrix must be well conditioned
  CHECK(std::abs(a.determinant()) > 1e-8);
  for (int i = 0; i < kNumRotors; ++i) {
    CHECK(RotorPosition_B(params, i).head<2>().cwiseAbs().isApprox(
        Eigen::Vector2d::Constant(params.arm_offset)));
    CHECK(RotorSpin(i) == -RotorSpin((i + 1) % kNumRotors));  // neighbours spin opposite ways
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

}  // namespace aerobox
