// libFuzzer target: bytes -> a robot description (URDF, MJCF or SDF by its root element) audited
// (tumble::robot::audit_model) and fixed (fix_model). A tumble::Error is the expected way to refuse a
// file; anything else is a finding. The contract: every finding has a code and a message, and the fixed
// text reads back as a model with the same links. The file is fuzz.xml in a temporary directory that
// holds meshes/cube.obj, so that models naming it go through mesh loading.
#include <stdlib.h>  // mkdtemp

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_support.hpp"
#include "tumble/robot/audit.hpp"
#include "tumble/robot/fix.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path& directory() {
  static const fs::path dir = [] {
    std::string name = (fs::temp_directory_path() / "tumble_fuzz_robot_XXXXXX").string();
    const char* made = mkdtemp(name.data());
    const fs::path d = made ? fs::path(made) : fs::temp_directory_path();
    fs::create_directories(d / "meshes");
    std::ofstream(d / "meshes" / "cube.obj")
        << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
           "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path model = directory() / "fuzz.xml";
  std::ofstream(model, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  tumble::fuzz::refused_or_ok([&] {
    const tumble::robot::ModelAudit audit = tumble::robot::audit_model(model);
    for (const auto& link : audit.links)
      for (const auto& f : link.findings) FUZZ_CHECK(!f.code.empty() && !f.message.empty());
    const tumble::robot::FixResult fixed = tumble::robot::fix_model(audit, {}, {});
    const fs::path again = directory() / "fixed.xml";
    std::ofstream(again, std::ios::binary | std::ios::trunc) << fixed.text;
    const tumble::robot::RobotModel back = tumble::robot::read_robot_model(again);
    FUZZ_CHECK(back.links.size() == audit.model.links.size());
  });
  return 0;
}
