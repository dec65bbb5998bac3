#pragma once
// Helpers for the mesh tests: moving meshes around and comparing mass properties.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "tumble/error.hpp"
#include "tumble/mass/mass_properties.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/triangle_mesh.hpp"

namespace tumble::test {

/// x ↦ A x + t for every vertex.
inline TriangleMesh mapped(TriangleMesh mesh, const Mat3& A, const Vec3& t) {
  for (Vec3& v : mesh.vertices) v = A * v + t;
  return mesh;
}

/// Every triangle's winding reversed (an inside-out mesh).
inline TriangleMesh flipped(TriangleMesh mesh) {
  for (auto& f : mesh.triangles) std::swap(f[1], f[2]);
  return mesh;
}

/// Second-moment matrix about the centre of mass, C = ½ tr(I) I₃ − I (inverse of I = tr(C) I₃ − C).
inline Mat3 second_moment(const MassProperties& mp) {
  return 0.5 * mp.inertia.trace() * Mat3::Identity() - mp.inertia;
}
/// Inertia from the second-moment matrix: I = tr(C) I₃ − C.
inline Mat3 inertia_from_second_moment(const Mat3& C) { return C.trace() * Mat3::Identity() - C; }

/// Mass, centre (relative to `length`) and inertia (relative to its largest entry) agree to `tol`.
inline void expect_close(const MassProperties& got, const MassProperties& want, double tol, double length,
                         const std::string& what = "") {
  EXPECT_NEAR(got.mass, want.mass, tol * std::abs(want.mass)) << what;
  EXPECT_LT((got.center_of_mass - want.center_of_mass).norm(), tol * length)
      << what << "\n got c = " << got.center_of_mass.transpose()
      << "\nwant c = " << want.center_of_mass.transpose();
  EXPECT_LT((got.inertia - want.inertia).cwiseAbs().maxCoeff(), tol * want.inertia.cwiseAbs().maxCoeff())
      << what << "\n got I =\n"
      << got.inertia << "\nwant I =\n"
      << want.inertia;
}

/// Writes `bytes` to `path` as they are (binary).
inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

/// The message of the FileError that loading `path` throws (a test failure if none is thrown).
inline std::string load_error(const std::filesystem::path& path) {
  try {
    (void)load_mesh(path);
  } catch (const FileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FileError for " << path;
  return "";
}

/// A fresh directory named after the running test, under the system's temporary directory, removed with
/// the object. (Not tests/support/scene_files.hpp's TempDir, which takes a name: one name, one class.)
class TestDir {
 public:
  TestDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() / (std::string("tumble_") + info->test_suite_name() + "_" +
                                                      info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path_);
  }
  ~TestDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TestDir(const TestDir&) = delete;
  TestDir& operator=(const TestDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace tumble::test
