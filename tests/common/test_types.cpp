#include <doctest/doctest.h>

#include "common/state.h"
#include "common/types.h"

namespace aerobox {

TEST_CASE("Aabb containment and overlap treat touching faces as not overlapping") {
  const Aabb a{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  CHECK(a.Contains(Vec3(1, 0.5, 0)));  // on the surface counts as inside
  CHECK_FALSE(a.Contains(Vec3(1.0001, 0.5, 0.5)));
  CHECK_FALSE(a.Overlaps(Aabb{Vec3(1, 0, 0), Vec3(2, 1, 1)}));  // shares a face only
  CHECK(a.Overlaps(Aabb{Vec3(0.999, 0, 0), Vec3(2, 1, 1)}));
  CHECK(Aabb{Vec3(0.2, 0.2, 0.2), Vec3(0.8, 1, 0.8)}.IsInside(a));
  CHECK(a.Inflated(0.5).min.isApprox(Vec3::Constant(-0.5)));
  CHECK(a.HalfSize().isApprox(Vec3::Constant(0.5)));
}

TEST_CASE("quaternions convert to and from MuJoCo's (w, x, y, z) order") {
  const double wxyz[4] = {0.5, 0.5, -0.5, 0.5};
  const Quat q = QuatFromWxyz(wxyz);
  CHECK(q.w() == 0.5);
  CHECK(q.y() == -0.5);
  double back[4];
  QuatToWxyz(q, back);
  for (int i = 0; i < 4; ++i) CHECK(back[i] == wxyz[i]);
}

}  // namespace aerobox
