// Exact polyhedral integration checked against closed forms (boxes, parallelepipeds), against the
// exact transformation law of mass properties under affine maps, and for the invariances it must have
// (far translation, inside-out meshes, triangle and vertex order).
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "../support/random.hpp"
#include "mesh_support.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/shapes.hpp"
#include "tumble/mass/tessellate.hpp"

namespace tumble {
namespace {

using test::expect_close;
using test::mapped;

// A dozen triangles, each term a product of five coordinates of size O(1..10) and a few additions:
// rounding leaves ~1e-15 relative; 1e-12 is a margin of 1000 for the conditioning of the shifted sums.
constexpr double kRounding = 1e-12;

Mat3 box_inertia(double m, const Vec3& s) {
  const Vec3 q = s.cwiseProduct(s);  // I_xx = m(b² + c²)/12
  return (m / 12.0 * Vec3(q.y() + q.z(), q.x() + q.z(), q.x() + q.y())).asDiagonal();
}

TEST(MeshIntegrals, UnitCubeTranslatedAndRotatedMatchesClosedForm) {
  test::Random rng(11);
  const TriangleMesh cube = tessellate(Box{Vec3(1, 1, 1)}, 4);
  for (int trial = 0; trial < 20; ++trial) {
    const Mat3 R = rng.rotation();
    const Vec3 t = rng.vec(-10, 10);
    const MassProperties mp = integrate_solid_mesh(mapped(cube, R, t));
    // V = 1, c = t, I = R (I₃/6) Rᵀ = I₃/6 (a cube's inertia is isotropic).
    expect_close(mp, MassProperties{1.0, t, Mat3::Identity() / 6.0, 1.0}, kRounding, 1.0);
    EXPECT_NEAR(mp.volume, 1.0, kRounding);
  }
}

TEST(MeshIntegrals, RotatedBoxMatchesClosedForm) {
  // Unequal sides make the tensor anisotropic, so the rotation is really tested: I = R I₀ Rᵀ.
  test::Random rng(12);
  const Vec3 size(0.3, 1.1, 2.5);
  const TriangleMesh box = tessellate(Box{size}, 4);
  for (int trial = 0; trial < 20; ++trial) {
    const Mat3 R = rng.rotation();
    const Vec3 t = rng.vec(-10, 10);
    const double V = size.prod();
    const MassProperties want{V, t, R * box_inertia(V, size) * R.transpose(), V};
    expect_close(integrate_solid_mesh(mapped(box, R, t)), want, kRounding, size.norm());
  }
}

/// A random map with det A > 0 (a negative determinant would turn the mesh inside out).
Mat3 random_affine(test::Random& rng) {
  Mat3 A;
  for (int i = 0; i < 9; ++i) A(i) = rng.uniform(-1.0, 1.0);
  A += 1.5 * Mat3::Identity();
  if (A.determinant() < 0) A.col(0) *= -1.0;
  return A;
}

TEST(MeshIntegrals, AffineImageOfCubeIsTheParallelepipedClosedForm) {
  // x' = A x + t maps the unit cube (V = 1, c = 0, C = I₃/12) to a parallelepiped with
  // V' = |det A|, c' = t, C' = |det A| A C Aᵀ; I' = tr(C') I₃ − C'.
  test::Random rng(13);
  const TriangleMesh cube = tessellate(Box{Vec3(1, 1, 1)}, 4);
  for (int trial = 0; trial < 50; ++trial) {
    const Mat3 A = random_affine(rng);
    const Vec3 t = rng.vec(-5, 5);
    const double det = A.determinant();
    const Mat3 C = det * A * (Mat3::Identity() / 12.0) * A.transpose();
    const MassProperties want{det, t, test::inertia_from_second_moment(C), det};
    expect_close(integrate_solid_mesh(mapped(cube, A, t)), want, kRounding, 1.0);
  }
}

TEST(MeshIntegrals, AffineMapsOfCurvedPolyhedraFollowTheTransformationLaw) {
  // The same law holds exactly for any polyhedron, e.g. tessellated (non-convex) tori and capsules:
  // the mapped mesh must give |det A| V, A c + t and |det A| A C Aᵀ of the original mesh. Thousands of
  // triangles and the rounding of the mapped vertices (1e-16 relative) stay far below 1e-12.
  test::Random rng(14);
  for (const Shape& shape : {Shape{Torus{1.0, 0.35}}, Shape{Capsule{0.4, 1.3}}, Shape{Cone{0.5, 1.2}}}) {
    const TriangleMesh mesh = tessellate(shape, 40);
    const MassProperties base = integrate_solid_mesh(mesh);
    for (int trial = 0; trial < 10; ++trial) {
      const Mat3 A = random_affine(rng);
      const Vec3 t = rng.vec(-5, 5);
      const double det = A.determinant();
      const Mat3 C = det * A * test::second_moment(base) * A.transpose();
      const MassProperties want{det * base.mass, A * base.center_of_mass + t,
                                test::inertia_from_second_moment(C), det * base.volume};
      expect_close(integrate_solid_mesh(mapped(mesh, A, t)), want, kRounding, 2.0, shape_name(shape));
    }
  }
}

/// The textbook evaluation about the origin (no reference point), to show what the test catches.
MassProperties integrate_about_origin(const TriangleMesh& mesh) {
  double V = 0;
  Vec3 first = Vec3::Zero();
  Mat3 C = Mat3::Zero();
  for (const auto& f : mesh.triangles) {
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    const double v = a.dot(b.cross(c)) / 6.0;
    const Vec3 s = a + b + c;
    V += v;
    first += v * s / 4.0;
    C += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  const Vec3 c = first / V;
  const Mat3 I_origin = C.trace() * Mat3::Identity() - C;
  return MassProperties{V, c, I_origin - parallel_axis_term(V, c), V};
}

TEST(MeshIntegrals, FarFromTheOriginTheReferencePointKeepsFullAccuracy) {
  // A body 1e5 m from the origin. Translating its vertices rounds them (half an ulp of 1e5 is 7e-12);
  // subtracting the offset again is exact (Sterbenz: x and 1e5 are within a factor of two), so
  // `near` and `far` describe exactly the same geometry and must agree to rounding of the integration
  // itself. Integrating about the origin instead loses ~10 digits (C ~ V·1e10 minus m c cᵀ).
  test::Random rng(15);
  const Vec3 offset(1e5, -1e5, 1e5);
  const TriangleMesh body = mapped(tessellate(Torus{0.8, 0.3}, 48), rng.rotation(), rng.vec(-1, 1));
  const TriangleMesh far = mapped(body, Mat3::Identity(), offset);
  const TriangleMesh near = mapped(far, Mat3::Identity(), -offset);
  const MassProperties n = integrate_solid_mesh(near);
  const MassProperties f = integrate_solid_mesh(far);
  EXPECT_NEAR(f.mass, n.mass, kRounding * n.mass);
  EXPECT_LT(test::rel_diff(f.inertia, n.inertia), kRounding);
  // The far centre of mass is a number near 1e5 and carries its half-ulp rounding (7.3e-12 m per
  // coordinate); allow two ulps per coordinate.
  const double ulp = std::nextafter(1e5, 2e5) - 1e5;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(f.center_of_mass(i) - offset(i), n.center_of_mass(i), 2 * ulp) << i;
  }

  const MassProperties naive = integrate_about_origin(far);
  EXPECT_GT((naive.inertia - n.inertia).cwiseAbs().maxCoeff(), 1e-8 * n.inertia.cwiseAbs().maxCoeff())
      << "the naive evaluation should lose accuracy here, or the test proves nothing";
}

TEST(MeshIntegrals, InsideOutMeshIsFlippedWithWarningAndIdenticalNumbers) {
  test::Random rng(16);
  const TriangleMesh mesh = mapped(tessellate(Capsule{0.3, 0.9}, 24), rng.rotation(), rng.vec(-3, 3));
  const auto spec = MassSpec::density(7850.0);
  const MeshMassResult right = solid_mass_properties(mesh, spec, "part.stl");
  const MeshMassResult wrong = solid_mass_properties(test::flipped(mesh), spec, "part.stl");
  EXPECT_FALSE(right.flipped);
  EXPECT_TRUE(right.warnings.empty());
  ASSERT_TRUE(wrong.flipped);
  ASSERT_EQ(wrong.warnings.size(), 1U);
  EXPECT_NE(wrong.warnings[0].find("part.stl"), std::string::npos) << wrong.warnings[0];
  EXPECT_NE(wrong.warnings[0].find("inside-out"), std::string::npos) << wrong.warnings[0];
  // Swapping b and c negates a·(b×c) exactly and only permutes the symmetric sums (see
  // mesh_integrals.cpp), so the numbers agree to the last bit; 4 ε allows a compiler that contracts
  // a·b − c·d into a fused multiply-add.
  expect_close(wrong.properties, right.properties, 4 * std::numeric_limits<double>::epsilon(), 1.0);
  EXPECT_EQ(wrong.properties.volume, right.properties.volume);
  EXPECT_EQ(wrong.surface_area, right.surface_area);
}

TEST(MeshIntegrals, TriangleAndVertexOrderDoNotMatter) {
  // Shuffling triangles, rotating each triangle's corners and renumbering the vertices changes only
  // the order of the sums: rounding.
  std::mt19937_64 engine(17);
  const TriangleMesh mesh = tessellate(Torus{1.0, 0.4}, 32);
  TriangleMesh shuffled = mesh;
  std::vector<std::uint32_t> perm(mesh.vertices.size());
  std::iota(perm.begin(), perm.end(), 0U);
  std::shuffle(perm.begin(), perm.end(), engine);
  for (std::size_t i = 0; i < perm.size(); ++i) shuffled.vertices[perm[i]] = mesh.vertices[i];
  for (auto& f : shuffled.triangles) {
    f = {perm[f[1]], perm[f[2]], perm[f[0]]};
  }
  std::shuffle(shuffled.triangles.begin(), shuffled.triangles.end(), engine);
  expect_close(integrate_solid_mesh(shuffled), integrate_solid_mesh(mesh), kRounding, 1.0);
}

TEST(MeshIntegrals, ScaleByDensityOrMass) {
  const TriangleMesh box = tessellate(Box{Vec3(0.1, 0.2, 0.4)}, 4);
  const double V = 0.1 * 0.2 * 0.4;
  const MeshMassResult steel = solid_mass_properties(box, MassSpec::density(7850.0));
  EXPECT_NEAR(steel.properties.mass, 7850.0 * V, kRounding * 7850.0 * V);
  EXPECT_NEAR(steel.properties.volume, V, kRounding * V);
  EXPECT_NEAR(steel.surface_area, 2 * (0.02 + 0.04 + 0.08), kRounding);
  const MeshMassResult two_kg = solid_mass_properties(box, MassSpec::mass(2.0));
  EXPECT_NEAR(two_kg.properties.mass, 2.0, kRounding);
  EXPECT_LT(test::rel_diff(two_kg.properties.inertia, box_inertia(2.0, Vec3(0.1, 0.2, 0.4))), kRounding);
}

TEST(MeshIntegrals, ShellOfABoxMatchesTheClosedForm) {
  // The box's six faces are flat: the triangulated surface integrals are exact.
  test::Random rng(18);
  const Vec3 size(0.4, 0.7, 1.3);
  const MassProperties closed = shell_mass_properties(Box{size}, 0.002, MassSpec::density(2700.0));
  for (int trial = 0; trial < 10; ++trial) {
    const Mat3 R = rng.rotation();
    const Vec3 t = rng.vec(-4, 4);
    const MeshMassResult r =
        shell_mass_properties(mapped(tessellate(Box{size}, 4), R, t), 0.002, MassSpec::density(2700.0));
    expect_close(r.properties, closed.transformed(R, t), kRounding, size.norm());
    EXPECT_NEAR(r.properties.volume, closed.volume, kRounding * closed.volume);
    EXPECT_NEAR(r.surface_area, surface_area(Box{size}), kRounding * r.surface_area);
  }
}

TEST(MeshIntegrals, OpenShellTriangleMatchesPointMassDefinition) {
  // A single right triangle (an open mesh) against the definition: ∫x dA = A(a+b+c)/3 and the
  // second moments of a triangle, I = A/12 (aaᵀ + bbᵀ + ccᵀ + ssᵀ) relative to the centroid, evaluated
  // independently by the 3-point edge-midpoint rule, exact for quadratics on a triangle.
  const Vec3 a(0.2, -0.1, 0.3), b(1.4, 0.3, -0.2), c(0.1, 0.9, 0.6);
  const TriangleMesh tri{{a, b, c}, {{0, 1, 2}}};
  const double A = 0.5 * (b - a).cross(c - a).norm();
  const Vec3 centroid = (a + b + c) / 3.0;
  Mat3 C = Mat3::Zero();
  for (const Vec3& m : {Vec3((a + b) / 2), Vec3((b + c) / 2), Vec3((c + a) / 2)}) {
    const Vec3 r = m - centroid;
    C += A / 3.0 * r * r.transpose();
  }
  const MeshMassResult r = shell_mass_properties(tri, 0.01, MassSpec::density(1.0 / 0.01));
  expect_close(r.properties, MassProperties{A, centroid, test::inertia_from_second_moment(C), 0.0}, kRounding,
               1.0);
  EXPECT_NEAR(r.properties.volume, A * 0.01, kRounding);
}

TEST(MeshIntegrals, ShellRejectsBadThickness) {
  const TriangleMesh box = tessellate(Box{Vec3(1, 1, 1)}, 4);
  for (double t : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW((void)shell_mass_properties(box, t, MassSpec::density(1.0)), InvalidArgument) << t;
  }
}

TEST(MeshIntegrals, BlockedSummationStaysAccurateForMillionsOfTriangles) {
  // Volume of a finely tessellated torus (≈ 2·10⁶ triangles) against an independent long-double sum
  // of the same tetrahedra: sequential double summation would drift by ~n ε ≈ 1e-10 worst case; the
  // blocked pairwise sum stays near log₂(n) ε. 1e-13 is well above that and well below n ε.
  const TriangleMesh mesh = tessellate(Torus{1.0, 0.3}, 1000);
  long double V = 0;
  const Vec3 ref(0, 0, 0);  // the torus' bounding box is centred on the origin: the same reference
  for (const auto& f : mesh.triangles) {
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    auto ld = [](double x) { return static_cast<long double>(x); };
    const long double ax = ld(a.x()), ay = ld(a.y()), az = ld(a.z()), bx = ld(b.x()), by = ld(b.y()),
                      bz = ld(b.z()), cx = ld(c.x()), cy = ld(c.y()), cz = ld(c.z());
    V += (ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx)) / 6;
  }
  const double got = integrate_solid_mesh(mesh).mass;
  EXPECT_NEAR(got, static_cast<double>(V), 1e-13 * got);
}

}  // namespace
}  // namespace tumble
