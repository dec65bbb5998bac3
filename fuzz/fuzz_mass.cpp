// libFuzzer target: arbitrary triangle soups -> check_mesh, welding, solid and shell mass properties,
// validation and principal axes. Each either gives a result that keeps its contract (finite, validated
// principal axes: Λ ascending, U a rotation) or throws a tumble::Error; NaN or ∞ returned silently is a
// finding.
//
// Input layout (every byte optional; missing bytes read as 0):
//   byte 0      flags: bit 0 coordinates as raw doubles (8 bytes each) instead of small integers,
//               bit 1 welding first, bits 2-3 the mass spec (density 1, density d, mass d, density 1e3)
//   byte 1      vertex count n = 1 + byte % 64
//   byte 2      binary exponent e (signed): small-integer coordinates are k · 2^(4e)
//   bytes 3-10  d: a double for the mass spec and the shell thickness (|d|)
//   then        n vertices (3 coordinates), then triangles as 3 bytes each, index = byte % (n + 1)
//               (n itself is out of range)
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_support.hpp"
#include "tumble/mass/mass_spec.hpp"
#include "tumble/mass/mesh_check.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/mesh_weld.hpp"

namespace {

struct Reader {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t pos = 0;
  std::uint8_t byte() { return pos < size ? data[pos++] : 0; }
  double raw_double() {
    std::uint8_t b[8];
    for (auto& x : b) x = byte();
    double d;
    std::memcpy(&d, b, 8);
    return d;
  }
  bool done() const { return pos >= size; }
};

bool finite(const tumble::MassProperties& p) {
  return std::isfinite(p.mass) && p.center_of_mass.allFinite() && p.inertia.allFinite() &&
         std::isfinite(p.volume);
}

/// A result must be finite; if it validates, its principal axes must be a proper rotation with Λ
/// ascending. (Validation itself may refuse it: a self-intersecting closed mesh is not a body.)
void check_result(const tumble::MeshMassResult& r) {
  FUZZ_CHECK(finite(r.properties));
  FUZZ_CHECK(r.properties.mass > 0.0);
  FUZZ_CHECK(std::isfinite(r.surface_area) && r.surface_area >= 0.0);
  tumble::fuzz::refused_or_ok([&] {
    const tumble::PrincipalAxes axes = r.properties.validated_principal_axes();
    FUZZ_CHECK(axes.Lambda.allFinite() && axes.U.allFinite());
    FUZZ_CHECK(axes.Lambda[0] <= axes.Lambda[1] && axes.Lambda[1] <= axes.Lambda[2]);
    FUZZ_CHECK(axes.Lambda[0] > 0.0);
    const tumble::Mat3 should_be_identity = axes.U.transpose() * axes.U;
    FUZZ_CHECK((should_be_identity - tumble::Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-9);
    FUZZ_CHECK(std::abs(axes.U.determinant() - 1.0) < 1e-9);
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Reader in{data, size};
  const std::uint8_t flags = in.byte();
  const std::size_t n = 1 + in.byte() % 64;
  const int exponent = 4 * static_cast<std::int8_t>(in.byte());
  const double d = in.raw_double();

  tumble::TriangleMesh mesh;
  mesh.vertices.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    tumble::Vec3 v;
    for (int k = 0; k < 3; ++k) {
      v[k] = (flags & 1) ? in.raw_double()
                         : std::ldexp(static_cast<double>(static_cast<std::int8_t>(in.byte())), exponent);
    }
    mesh.vertices.push_back(v);
  }
  while (!in.done()) {
    std::array<std::uint32_t, 3> t{};
    for (auto& i : t) i = in.byte() % static_cast<std::uint32_t>(n + 1);
    mesh.triangles.push_back(t);
  }

  const tumble::MeshReport report = tumble::check_mesh(mesh);
  FUZZ_CHECK(report.vertex_count == mesh.vertices.size() && report.triangle_count == mesh.triangles.size());
  if ((flags & 2) && report.usable()) mesh = tumble::weld_identical_vertices(mesh);

  tumble::fuzz::refused_or_ok([&] {
    const tumble::MassSpec spec = [&] {
      switch ((flags >> 2) & 3) {
        case 1:
          return tumble::MassSpec::density(d);
        case 2:
          return tumble::MassSpec::mass(d);
        case 3:
          return tumble::MassSpec::density(1e3);
        default:
          return tumble::MassSpec::density(1.0);
      }
    }();
    tumble::fuzz::refused_or_ok([&] { check_result(tumble::solid_mass_properties(mesh, spec, "fuzz")); });
    tumble::fuzz::refused_or_ok(
        [&] { check_result(tumble::shell_mass_properties(mesh, std::abs(d), spec, "fuzz")); });
  });
  return 0;
}
