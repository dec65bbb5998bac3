// libFuzzer target: TOML text -> validated scene (tumble::parse_scene), and the study of an [ensemble]
// table (tumble::EnsembleStudy::parse, its first runs' scenes). A tumble::Error (SceneError,
// FileError, InvalidArgument, ...) is the expected way to refuse a scene; anything else is a finding.
// The scene is named fuzz.toml in a temporary directory (not the working directory, so that relative
// paths on the command line keep working) that holds small meshes (cube.obj, cube.off,
// cube.ply, cube.stl, and the examples' meshes/t_handle.stl, meshes/asteroid.obj, debris_field.csv), so
// that scenes naming them go through mesh loading and body tables too.
#include <stdlib.h>  // mkdtemp

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <system_error>

#include "fuzz_support.hpp"
#include "io/scene_sections.hpp"
#include "tumble/io/ensemble.hpp"
#include "tumble/io/scene.hpp"

namespace fs = std::filesystem;

namespace {

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

const char* const kCubeObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
const char* const kCubeOff =
    "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
const char* const kCubePly =
    "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 6\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
const char* const kTetraStl =
    "solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
    "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
    "facet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid "
    "t\n";

fs::path work_dir;  // removed at exit (left behind only when a finding aborts the process)

void remove_work_dir() {
  std::error_code ec;
  fs::remove_all(work_dir, ec);
}

void copy_if_there(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char pattern[] = "/tmp/tumble-fuzz-scene-XXXXXX";
  const char* dir = mkdtemp(pattern);
  if (dir == nullptr) std::abort();
  work_dir = dir;
  std::atexit(remove_work_dir);
  fs::create_directory(work_dir / "meshes");
  for (const fs::path& sub : {work_dir, work_dir / "meshes"}) {
    write(sub / "cube.obj", kCubeObj);
    write(sub / "cube.off", kCubeOff);
    write(sub / "cube.ply", kCubePly);
    write(sub / "cube.stl", kTetraStl);
  }
  const fs::path examples = TUMBLE_EXAMPLES_DIR;
  copy_if_there(examples / "meshes/t_handle.stl", work_dir / "meshes/t_handle.stl");
  copy_if_there(examples / "meshes/asteroid.obj", work_dir / "meshes/asteroid.obj");
  copy_if_there(examples / "debris_field.csv", work_dir / "debris_field.csv");
  return 0;
}

namespace {

/// The scene of `text` read from the tree of the whole document, with no [[bodies]] sections split off
/// (io/body_sections.hpp), or null where that refuses it.
std::optional<tumble::Scene> whole_tree(const std::string& text) {
  const fs::path path = work_dir / "fuzz.toml";
  try {
    namespace scene = tumble::scene;
    return scene::read_scene(scene::parse_toml(text, scene::TomlFile{path.string()}), text, path);
  } catch (const tumble::Error&) {
    return std::nullopt;
  }
}

bool same_bits(const double* a, const double* b, size_t n) {
  return std::memcmp(a, b, n * sizeof(double)) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // Differential: the [[bodies]] sections parsed apart give the whole tree's scene, or both refuse (with
  // more than one mistake in the text, not always the same one first).
  const std::optional<tumble::Scene> reference = whole_tree(text);
  bool accepted = false;
  tumble::fuzz::refused_or_ok([&] {
    const tumble::Scene scene = tumble::parse_scene(text, work_dir / "fuzz.toml");
    accepted = true;
    FUZZ_CHECK(reference && reference->model.bodies.size() == scene.model.bodies.size());
    for (size_t i = 0; i < scene.model.bodies.size(); ++i) {
      const tumble::RigidBody &a = scene.model.bodies[i], &b = reference->model.bodies[i];
      FUZZ_CHECK(a.name() == b.name() && same_bits(a.Lambda().data(), b.Lambda().data(), 3) &&
                 same_bits(a.U().data(), b.U().data(), 9) && a.mass() == b.mass());
      const tumble::BodyState &s = scene.initial.bodies[i], &t = reference->initial.bodies[i];
      FUZZ_CHECK(same_bits(s.o.data(), t.o.data(), 3) && same_bits(s.v.data(), t.v.data(), 3) &&
                 same_bits(s.omega_w.data(), t.omega_w.data(), 3));
    }
    FUZZ_CHECK(scene.model.forces.size() == reference->model.forces.size());
    FUZZ_CHECK(scene.events.size() == reference->events.size());
    FUZZ_CHECK(scene.body_info.size() == scene.model.bodies.size());
    FUZZ_CHECK(scene.initial.bodies.size() == scene.model.bodies.size());
    for (const auto& body : scene.model.bodies) {
      FUZZ_CHECK(std::isfinite(body.mass()) && body.mass() > 0.0);
      FUZZ_CHECK(body.center_of_mass().allFinite() && body.Lambda().allFinite() && body.U().allFinite());
    }
    for (const auto& b : scene.initial.bodies) {
      FUZZ_CHECK(b.o.allFinite() && b.q.coeffs().allFinite() && b.v.allFinite() && b.omega_w.allFinite());
    }
    FUZZ_CHECK(std::isfinite(scene.initial.t));
    FUZZ_CHECK(std::isfinite(scene.settings.duration) && std::isfinite(scene.settings.timestep));
  });
  FUZZ_CHECK(accepted == reference.has_value());
  // An [ensemble] table: the study is read as `tumble ensemble` reads it, and its first runs' scenes
  // are built from their draws (not simulated); each is a valid scene or a tumble::Error.
  if (text.find("ensemble") != std::string::npos) {
    tumble::fuzz::refused_or_ok([&] {
      const tumble::EnsembleStudy study = tumble::EnsembleStudy::parse(text, work_dir / "fuzz.toml");
      FUZZ_CHECK(study.runs() >= 1);
      for (long i = 0; i < std::min(study.runs(), 3L); ++i) {
        FUZZ_CHECK(study.draws(i).size() + 1 <= study.columns().size());
        (void)study.scene_of_run(i);
      }
    });
  }
  return 0;
}
