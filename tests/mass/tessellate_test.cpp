// Tessellated primitives: closed, manifold, outward meshes whose exact polyhedral mass properties
// converge to the closed forms of shapes.hpp at second order, as an inscribed polyhedron must.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "mesh_support.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_check.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/tessellate.hpp"

namespace tumble {
namespace {

const std::vector<Shape>& curved_shapes() {
  static const std::vector<Shape> shapes = {Sphere{0.7},        Ellipsoid{Vec3(1.0, 0.6, 0.3)},
                                            Cylinder{0.5, 2.0}, Capsule{0.4, 1.0},
                                            Cone{0.5, 1.5},     Torus{1.0, 0.3}};
  return shapes;
}

TEST(Tessellate, EveryShapeIsAClosedManifoldOutwardMesh) {
  std::vector<Shape> shapes = curved_shapes();
  shapes.push_back(Box{Vec3(0.2, 0.5, 1.0)});
  for (const Shape& shape : shapes) {
    for (int segments : {3, 4, 5, 8, 17, 64}) {
      const TriangleMesh mesh = tessellate(shape, segments);
      const MeshReport r = check_mesh(mesh);
      EXPECT_TRUE(r.solid()) << shape_name(shape) << " " << segments << ": " << describe_solid_defects(r);
      // Consistent orientation plus positive signed volume means every triangle faces outward.
      EXPECT_GT(integrate_solid_mesh(mesh).mass, 0.0) << shape_name(shape) << " " << segments;
    }
  }
}

TEST(Tessellate, BoxIsExact) {
  const Box box{Vec3(0.2, 0.5, 1.0)};
  const MassProperties want = solid_mass_properties(box, MassSpec::density(3.0));
  const MeshMassResult got = solid_mass_properties(tessellate(box, 3), MassSpec::density(3.0));
  test::expect_close(got.properties, want, 1e-14, 1.0);  // 12 triangles: a few roundings
}

TEST(Tessellate, RejectsTooFewSegmentsAndInvalidShapes) {
  EXPECT_THROW(tessellate(Sphere{1.0}, 2), InvalidArgument);
  EXPECT_THROW(tessellate(Sphere{-1.0}, 16), InvalidArgument);
}

/// Signed relative errors of (V, I_xx, I_yy, I_zz) of the tessellation against the closed form.
/// Every shape here is symmetric about its own axes, so the closed-form tensor is diagonal.
Eigen::Vector4d errors(const MassProperties& got, const MassProperties& want) {
  return {(got.mass - want.mass) / want.mass, (got.inertia(0, 0) - want.inertia(0, 0)) / want.inertia(0, 0),
          (got.inertia(1, 1) - want.inertia(1, 1)) / want.inertia(1, 1),
          (got.inertia(2, 2) - want.inertia(2, 2)) / want.inertia(2, 2)};
}

/// Second-order convergence: an inscribed polygon's error is c₂/N² + c₄/N⁴ + …, so doubling N divides
/// it by 4(1 + O(N⁻²)): at N = 64 the ratio is within 3.9..4.1 (the O(N⁻²) correction is ~(π/N)²·c,
/// measured below 1%). Richardson's (4 X(2N) − X(N))/3 removes the N⁻² term and leaves O(N⁻⁴):
/// ~(error at N)² ≈ 2e-5 at N = 64; 1e-4 bounds it for all shapes. Finally the finest mesh is close.
void expect_second_order(const Shape& shape,
                         const std::function<MassProperties(const TriangleMesh&)>& of_mesh,
                         const MassProperties& exact) {
  const int N = 64;
  const MassProperties coarse = of_mesh(tessellate(shape, N));
  const MassProperties fine = of_mesh(tessellate(shape, 2 * N));
  const Eigen::Vector4d e1 = errors(coarse, exact), e2 = errors(fine, exact);
  for (int i = 0; i < 4; ++i) {
    const char* what[] = {"volume/area", "I_xx", "I_yy", "I_zz"};
    EXPECT_NEAR(e1(i) / e2(i), 4.0, 0.1) << shape_name(shape) << " " << what[i] << " errors " << e1(i)
                                         << " at N=" << N << ", " << e2(i) << " at 2N";
    EXPECT_LT(std::abs((4 * e2(i) - e1(i)) / 3), 1e-4) << shape_name(shape) << " " << what[i];
    EXPECT_LT(std::abs(e2(i)), 2.5e-3) << shape_name(shape) << " " << what[i];  // N = 128
  }
  // The centre of mass lies on the symmetry axis for every N; only its height converges.
  EXPECT_LT((fine.center_of_mass - exact.center_of_mass).norm(),
            4.0 * std::abs(e2(0)) * std::cbrt(std::abs(exact.mass)) + 1e-15)
      << shape_name(shape);
}

TEST(Tessellate, SolidsConvergeToTheClosedFormsAtSecondOrder) {
  const MassSpec spec = MassSpec::density(1.0);
  for (const Shape& shape : curved_shapes()) {
    expect_second_order(
        shape, [&](const TriangleMesh& m) { return solid_mass_properties(m, spec).properties; },
        solid_mass_properties(shape, spec));
  }
}

TEST(Tessellate, ShellsConvergeToTheClosedFormsAtSecondOrder) {
  const MassSpec spec = MassSpec::density(16.0);  // ρ·t = 16 · 0.0625 = 1 exactly
  for (const Shape& shape : curved_shapes()) {
    if (std::holds_alternative<Ellipsoid>(shape)) continue;  // no closed form (elliptic integrals)
    expect_second_order(
        shape, [&](const TriangleMesh& m) { return shell_mass_properties(m, 0.0625, spec).properties; },
        shell_mass_properties(shape, 0.0625, spec));
  }
}

TEST(Tessellate, EllipsoidShellAreaConvergesToLegendresFormula) {
  // The ellipsoid's shell has no closed-form inertia, but its area does (surface_area, Legendre).
  const Ellipsoid e{Vec3(1.0, 0.6, 0.3)};
  const double exact = surface_area(e);
  auto err = [&](int n) {
    return (shell_mass_properties(tessellate(e, n), 1.0, MassSpec::density(1.0)).surface_area - exact) /
           exact;
  };
  EXPECT_NEAR(err(64) / err(128), 4.0, 0.1);
  EXPECT_LT(std::abs(err(128)), 2.5e-3);
}

}  // namespace
}  // namespace tumble
