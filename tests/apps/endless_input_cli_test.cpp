// Endless and oversized inputs, end to end: `tumble check /dev/zero`, `tumble inertia /dev/zero`, a
// scene that is a FIFO and a scene whose mesh is a FIFO or a device are refused at once with one line
// naming what the file is (no reading until std::bad_alloc, no waiting on a FIFO), and a file above
// TUMBLE_MAX_INPUT_BYTES names the limit and how to raise it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fmt/format.h>
#include <sys/stat.h>

#include "../support/run.hpp"
#include "../support/scene_files.hpp"

namespace tumble {
namespace {

using test::run_tumble;

void expect_one_line_error(const std::string& args, const std::string& expected) {
  const auto r = run_tumble(args);
  EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos)
      << args << "\n  got: " << r.output << "\n want: " << expected;
}

const std::string kDevice =
    "a character device (such as /dev/zero), which may never end, not a regular file; give a ";

TEST(EndlessInputCli, DevZeroAndFifosAreRefusedAtOnce) {
  expect_one_line_error("check /dev/zero", "tumble: error: cannot read scene file /dev/zero: " + kDevice +
                                               "scene file (tumble reads input from regular files only: "
                                               "save a stream to a file first)");
  expect_one_line_error("inertia /dev/zero", "tumble: error: /dev/zero: " + kDevice + "mesh file");
  expect_one_line_error("run /dev/zero", "cannot read scene file /dev/zero: " + kDevice + "scene file");

  test::TempDir dir("endless_input");
  ASSERT_EQ(::mkfifo((dir / "scene.toml").c_str(), 0600), 0);
  expect_one_line_error(
      "check " + (dir / "scene.toml").string(),
      "cannot read scene file " + (dir / "scene.toml").string() +
          ": a FIFO (named pipe) with nothing written into it, which may never end, not a regular file; give "
          "a scene file, or write the scene into the pipe as tumble reads it (e.g. tumble check <(cat "
          "s.toml))");
  expect_one_line_error("inertia " + (dir / "scene.toml").string(), "a FIFO (named pipe)");
  expect_one_line_error("check " + dir.path().string(), "cannot read scene file " + dir.path().string() +
                                                            ": a directory, not a regular file");

  // A scene whose mesh is a FIFO, or /dev/zero under a mesh's name.
  ASSERT_EQ(::mkfifo((dir / "pipe.obj").c_str(), 0600), 0);
  std::filesystem::create_symlink("/dev/zero", dir / "zero.stl");
  for (const char* mesh : {"pipe.obj", "zero.stl"}) {
    const auto scene = dir.write(std::string(mesh) + ".toml",
                                 fmt::format("[simulation]\nduration = 1\n[[bodies]]\nname = \"a\"\n"
                                             "mesh = \"{}\"\ndensity = 1000\n",
                                             mesh));
    expect_one_line_error("check " + scene.string(),
                          fmt::format("{}:5:8: body 'a': cannot load mesh \"{}\": {}: a ", scene.string(),
                                      mesh, (dir / mesh).string()));
  }
}

TEST(EndlessInputCli, TheInputLimitNamesItselfAndHowToRaiseIt) {
  const std::string scene = std::string(TUMBLE_SOURCE_DIR) + "/examples/t_handle.toml";
  const auto size = std::filesystem::file_size(scene);
  ::setenv("TUMBLE_MAX_INPUT_BYTES", "100", 1);
  expect_one_line_error(
      "check " + scene,
      fmt::format("cannot read scene file {}: the scene file is {} bytes ({:.3g} KiB), more "
                  "than tumble reads from one input file (100 bytes); to read it, raise the "
                  "limit with the environment variable TUMBLE_MAX_INPUT_BYTES, e.g. "
                  "TUMBLE_MAX_INPUT_BYTES=1G",
                  scene, size, static_cast<double>(size) / 1024.0));
  ::setenv("TUMBLE_MAX_INPUT_BYTES", "many", 1);
  expect_one_line_error("check " + scene,
                        "TUMBLE_MAX_INPUT_BYTES='many' is not a byte count: give a positive whole number of "
                        "bytes, optionally followed by k, M, G or T (powers of 1024), e.g. "
                        "TUMBLE_MAX_INPUT_BYTES=8G");
  ::setenv("TUMBLE_MAX_INPUT_BYTES", "1M", 1);
  EXPECT_EQ(run_tumble("check " + scene).status, 0);
  ::unsetenv("TUMBLE_MAX_INPUT_BYTES");
}

}  // namespace
}  // namespace tumble
