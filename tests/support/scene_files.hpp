#pragma once
// Scene files written by tests into a fresh temporary directory, removed afterwards.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace tumble::test {

class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("tumble_test_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  /// Writes `text` to the file `name` in this directory and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto p = path_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

 private:
  std::filesystem::path path_;
};

inline std::string read_text(const std::filesystem::path& p) {
  std::string text;
  if (std::FILE* f = std::fopen(p.c_str(), "rb")) {
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
    std::fclose(f);
  }
  return text;
}

/// A free box spun near its intermediate axis, ω₂ at its extreme (ω₃ = 0), with an event at every flip
/// (ω₂ changing sign): the scene the ensemble tests vary.
inline std::string racket_scene(double duration) {
  return "[simulation]\nduration = " + std::to_string(duration) +
         "\ntimestep = 1e-3\noutput_interval = 0.05\n"
         "[[bodies]]\nname = \"racket\"\nshape = { type = \"box\", size = [0.1, 0.2, 0.3] }\nmass = 1.0\n"
         "orientation = [1.0, 0.0, 0.0, 0.0]\nangular_velocity = [0.05, 10.0, 0.0]\n"
         "angular_velocity_frame = \"principal\"\n"
         "[[events]]\nname = \"flip\"\nbody = \"racket\"\ncolumn = \"w2\"\n";
}

}  // namespace tumble::test
