// The winding number of a closed mesh: 1 inside an outward surface, 0 outside, −1 inside an inward one,
// whatever the shape (a torus's hole is outside), and an octant's solid angle for a corner (π/2 sr).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tumble/mass/tessellate.hpp"
#include "tumble/mass/winding_number.hpp"

namespace tumble {
namespace {

TEST(WindingNumber, IsOneInsideZeroOutsideAndMinusOneInsideAnInwardSurface) {
  // Sums of atan2 over a few thousand triangles: whole numbers to 1e-12 (rounding).
  const TriangleMesh torus = tessellate(Torus{1.0, 0.3}, 48);
  EXPECT_NEAR(winding_number(torus, Vec3(1.0, 0.0, 0.0)), 1.0, 1e-12);  // in the tube
  EXPECT_NEAR(winding_number(torus, Vec3(0.0, 0.0, 0.0)), 0.0, 1e-12);  // in the hole
  EXPECT_NEAR(winding_number(torus, Vec3(3.0, 1.0, 2.0)), 0.0, 1e-12);  // far away
  TriangleMesh inward = torus;
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  EXPECT_NEAR(winding_number(inward, Vec3(1.0, 0.0, 0.0)), -1.0, 1e-12);
}

TEST(WindingNumber, ATriangleOfTheUnitAxesSubtendsAnEighthOfTheSphere) {
  // The triangle (1,0,0), (0,1,0), (0,0,1) seen from the origin covers one octant: 4π/8 = π/2 sr.
  EXPECT_NEAR(triangle_solid_angle(Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()), std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR(triangle_solid_angle(Vec3::UnitX(), Vec3::UnitZ(), Vec3::UnitY()), -std::numbers::pi / 2,
              1e-15);
}

}  // namespace
}  // namespace tumble
