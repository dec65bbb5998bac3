// Inputs found by the libFuzzer targets (fuzz/, docs/ARCHITECTURE.md "Fuzzing"), each minimised and
// kept here so that the normal suite (release and sanitize) replays it. fuzz_mass: mass properties must
// be finite numbers or a tumble::Error, never inf or NaN returned without a word.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "tumble/error.hpp"
#include "tumble/mass/mass_spec.hpp"
#include "tumble/mass/mesh_mass.hpp"

namespace tumble {
namespace {

/// A closed tetrahedron with corners 0, s·e_x, s·e_y, s·e_z (outward winding).
TriangleMesh tetrahedron(double s) {
  return {{{0, 0, 0}, {s, 0, 0}, {0, s, 0}, {0, 0, s}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
}

std::string message_of(auto&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// fuzz_mass, crash-57ffdd10: an inside-out tetrahedron with integer corners times 2^240 (1.8e72 m):
// finite coordinates, but the second moments (∝ s^5) overflowed and solid_mass_properties returned an
// infinite inertia. The same for the shell (area moments ∝ s^4, overflowing beyond about 1e77 m).
TEST(FuzzRegressions, MeshIntegralsThatOverflowAreRefused) {
  TriangleMesh huge = tetrahedron(std::ldexp(1.0, 240));
  huge.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};  // as found: inside-out
  const std::string solid =
      message_of([&] { (void)solid_mass_properties(huge, MassSpec::density(1.0), "huge.stl"); });
  EXPECT_NE(solid.find("huge.stl: the mesh's integrals overflow double"), std::string::npos) << solid;
  EXPECT_NE(solid.find("scale the mesh down"), std::string::npos) << solid;
  const TriangleMesh huger = tetrahedron(1e100);
  const std::string shell =
      message_of([&] { (void)shell_mass_properties(huger, 0.01, MassSpec::density(1.0), "huge.stl"); });
  EXPECT_NE(shell.find("the mesh's integrals overflow double"), std::string::npos) << shell;
  // Large but representable: still computed, and finite.
  const MeshMassResult big = solid_mass_properties(tetrahedron(1e50), MassSpec::density(1.0));
  EXPECT_TRUE(std::isfinite(big.properties.mass) && big.properties.inertia.allFinite());
}

// fuzz_mass: a density or mass that scales finite unit integrals beyond double (or to 0) gave inf or 0
// kg; MassSpec::apply now refuses it.
TEST(FuzzRegressions, MassSpecThatOverflowsOrUnderflowsIsRefused) {
  const TriangleMesh big = tetrahedron(1e20);  // volume 1.7e59 m^3
  EXPECT_THROW((void)solid_mass_properties(big, MassSpec::density(1e300)), InvalidArgument);
  const TriangleMesh small = tetrahedron(1e-60);  // volume 1.7e-181 m^3, second moments 1e-301
  EXPECT_THROW((void)solid_mass_properties(small, MassSpec::mass(1e300)), InvalidArgument);  // inertia ∞
  EXPECT_THROW((void)solid_mass_properties(small, MassSpec::density(1e-300)), InvalidArgument);  // 0 kg
  const std::string m = message_of([&] { (void)solid_mass_properties(big, MassSpec::density(1e300)); });
  EXPECT_NE(m.find("out of the range of double"), std::string::npos) << m;
  EXPECT_NO_THROW((void)solid_mass_properties(tetrahedron(1.0), MassSpec::density(1e300)));
}

// fuzz_mass, crash-30337a2d (as found): one triangle of coordinates k·2^-12 as a shell of thickness
// 6.66e-310 m (a subnormal double): mass 1.8e-318 kg and an inertia of subnormals without a digit
// left, which validated, and whose principal moments came out unordered.
TEST(FuzzRegressions, SubnormalMassPropertiesAreRefused) {
  const double s = std::ldexp(1.0, -12);
  const TriangleMesh sheet{{Vec3(63, 0, 1) * s, Vec3(83, 0, 0) * s, Vec3(0, 1, 0) * s, Vec3(1, 2, 0) * s},
                           {{3, 1, 0}}};
  const double thickness = 6.6646e-310;
  ASSERT_LT(thickness, std::numeric_limits<double>::min());
  const std::string m =
      message_of([&] { (void)shell_mass_properties(sheet, thickness, MassSpec::density(1.0)); });
  EXPECT_NE(m.find("mass properties out of the range of double"), std::string::npos) << m;
  const MeshMassResult ok = shell_mass_properties(sheet, 1e-3, MassSpec::density(1.0));
  const PrincipalAxes axes = ok.properties.validated_principal_axes();
  EXPECT_TRUE(axes.Lambda[0] <= axes.Lambda[1] && axes.Lambda[1] <= axes.Lambda[2]);
  EXPECT_THROW((void)solid_mass_properties(tetrahedron(1.0), MassSpec::mass(5e-324)), InvalidArgument);
}

// fuzz_mass, crash-4cceed37: a closed mesh as a shell of thickness 1.35e308 m and a total mass of
// 1.35e308 kg: mass and inertia finite, but the material volume (area · thickness) was inf m^3.
TEST(FuzzRegressions, ShellVolumeThatOverflowsIsRefused) {
  const std::string m = message_of(
      [&] { (void)shell_mass_properties(tetrahedron(1.0), 1.348e308, MassSpec::mass(1.348e308), "t"); });
  EXPECT_NE(m.find("t: shell thickness 1.348e+308 m times the surface area"), std::string::npos) << m;
  EXPECT_NE(m.find("overflows double"), std::string::npos) << m;
}

}  // namespace
}  // namespace tumble
