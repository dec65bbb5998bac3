// `tumble model check` on a large robot: 100 links, each with its own binary STL mesh of ~10⁵ triangles
// (ellipsoids of 100 different shapes, 5 MB each: 500 MB of meshes), a URDF that names them. Times the
// whole audit (read the URDF, read and weld every mesh, check its topology, integrate it, test the COM
// against it), in process, the files in the page cache (one run first, not timed).
//
//   build/release/bin/model_check_bench [LINKS [SEGMENTS [REPETITIONS]]]     (defaults 100 316 5)
//
// Prints the machine, the settings, and min/median of the repetitions. Target (issue 24): < 1 s.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "machine.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/tessellate.hpp"
#include "tumble/robot/audit.hpp"

int main(int argc, char** argv) {
  using namespace tumble;
  const int links = argc > 1 ? std::atoi(argv[1]) : 100;
  const int segments = argc > 2 ? std::atoi(argv[2]) : 316;
  const int repetitions = argc > 3 ? std::atoi(argv[3]) : 5;
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "tumble_model_check_bench";
  std::filesystem::create_directories(dir / "meshes");
  std::string urdf = "<?xml version=\"1.0\"?>\n<robot name=\"big\">\n";
  std::size_t triangles = 0;
  for (int i = 0; i < links; ++i) {
    const Ellipsoid shape{Vec3(0.05 + 0.001 * i, 0.04, 0.03)};
    const TriangleMesh mesh = tessellate(shape, segments);
    triangles = mesh.triangles.size();
    const std::string file = fmt::format("meshes/link{}.stl", i);
    if (!std::filesystem::exists(dir / file)) write_binary_stl(mesh, dir / file);
    // The authored inertial: the mesh's own at 2700 kg/m³ (the audit finds nothing to say).
    const MassProperties mp = solid_mass_properties(mesh, MassSpec::density(2700.0)).properties;
    const Mat3& I = mp.inertia;
    urdf += fmt::format(
        "  <link name=\"link{}\">\n    <inertial>\n      <origin xyz=\"{} {} {}\"/>\n      <mass "
        "value=\"{}\"/>\n"
        "      <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>\n    "
        "</inertial>\n"
        "    <collision><geometry><mesh filename=\"{}\"/></geometry></collision>\n  </link>\n",
        i, mp.center_of_mass.x(), mp.center_of_mass.y(), mp.center_of_mass.z(), mp.mass, I(0, 0), I(0, 1),
        I(0, 2), I(1, 1), I(1, 2), I(2, 2), file);
  }
  urdf += "</robot>\n";
  std::ofstream(dir / "big.urdf") << urdf;

  (void)robot::audit_model(dir / "big.urdf");  // the files into the page cache
  std::vector<double> seconds;
  std::size_t findings = 0;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const robot::ModelAudit audit = robot::audit_model(dir / "big.urdf");
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    findings = 0;
    for (const auto& l : audit.links) findings += l.findings.size();
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("machine: %s, %u hardware threads\n", bench::cpu_model().c_str(),
              std::thread::hardware_concurrency());
  std::printf(
      "model: %d links, each a binary STL of %zu triangles (%.0f MB of meshes in all), %zu findings\n", links,
      triangles, links * (84 + 50.0 * static_cast<double>(triangles)) / 1e6, findings);
  std::printf("audit_model: min %.3f s, median %.3f s over %d repetitions (target: < 1 s)\n", seconds.front(),
              seconds[seconds.size() / 2], repetitions);
  return 0;
}
