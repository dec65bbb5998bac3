// The table of run settings (sim/run_settings.hpp) is what the scene reader, the command line, Python,
// checkpoints and the docs use: each of them is checked against it here, so that a setting added to
// the table and forgotten in one of them fails a test.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "../support/scene_files.hpp"
#include "tumble/error.hpp"
#include "tumble/io/checkpoint.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/sim/run_settings.hpp"

namespace tumble {
namespace {

std::string text_of(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A value of the setting other than its default, of the right kind.
SettingValue other_value(const RunSetting& s) {
  if (s.kind == RunSetting::Kind::name)
    return s.key == "integrator" ? std::string("splitting") : std::string("body");
  if (s.kind == RunSetting::Kind::count) return 2.0;
  return s.key == "duration" ? 3.5 : 0.25;
}

TEST(RunSettings, EveryKeyIsReadFromAScene) {
  std::string simulation = "[simulation]\n";
  for (const RunSetting& s : run_settings()) {
    if (!s.in_scene) continue;
    const SettingValue v = other_value(s);
    simulation += std::holds_alternative<std::string>(v)
                      ? fmt::format("{} = \"{}\"\n", s.key, std::get<std::string>(v))
                      : fmt::format("{} = {}\n", s.key, std::get<double>(v));
  }
  const Scene scene =
      parse_scene(simulation + "[[bodies]]\nname = \"b\"\nmass = 1.0\ninertia = [1.0, 2.0, 2.5]\n", "s.toml");
  for (const RunSetting& s : run_settings()) {
    if (s.in_scene) {
      EXPECT_EQ(s.get(scene.settings), other_value(s)) << s.key;
    }
  }
}

TEST(RunSettings, EveryOneIsSetByKindAndTheWrongKindIsNamed) {
  RunSettings r;
  for (const RunSetting& s : run_settings()) {
    set_run_setting(r, s, other_value(s), s.flag);
    EXPECT_EQ(s.get(r), other_value(s)) << s.key;
    EXPECT_EQ(find_run_setting(s.key), &s);
    EXPECT_EQ(find_run_setting(s.flag), &s);
  }
  EXPECT_NO_THROW(validate(r));
  try {
    set_run_setting(r, *find_run_setting("timestep"), std::string("fast"), "--timestep");
    FAIL() << "a name was taken for a number";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "--timestep takes a number, not a name");
  }
  try {
    set_run_setting(r, *find_run_setting("threads"), 1.5, "threads=");
    FAIL() << "1.5 threads were taken";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "threads= 1.5 is invalid: give a whole number");
  }
}

/// The least checkpoint that writes and reads back: a scene and an output in `dir`, one sample.
Checkpoint checkpoint_in(const std::filesystem::path& dir) {
  Checkpoint c;
  c.tumble_version = "test";
  c.scene_path = "s.toml";
  c.scene_absolute = (dir / "s.toml").string();
  c.output = (dir / "o.csv").string();
  c.writer_pid = 1;
  c.point.samples = 1;
  return c;
}

TEST(RunSettings, ACheckpointKeepsEverySetting) {
  const test::TempDir dir("run_settings_checkpoint");
  Checkpoint c = checkpoint_in(dir.path());
  for (const RunSetting& s : run_settings()) set_run_setting(c.settings, s, other_value(s), s.flag);
  write_checkpoint(dir / "c.ckpt", c);
  const Checkpoint back = read_checkpoint(dir / "c.ckpt");
  for (const RunSetting& s : run_settings()) EXPECT_EQ(s.get(back.settings), other_value(s)) << s.key;
}

// A checkpoint stores the settings by key: one this tumble does not know (a checkpoint of another
// version) is refused by name, not read into the wrong setting.
TEST(RunSettings, ACheckpointWithASettingThisTumbleLacksIsRefusedByName) {
  const test::TempDir dir("run_settings_checkpoint_key");
  write_checkpoint(dir / "c.ckpt", checkpoint_in(dir.path()));
  std::string bytes = text_of(dir / "c.ckpt");
  const size_t at = bytes.find("drift_threshold");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 15, "drift_ceiling_x");  // the same length, and the checksum made again
  const std::uint64_t sum = fnv1a64(std::string_view(bytes).substr(0, bytes.size() - 8));
  std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
  std::ofstream(dir / "c.ckpt", std::ios::binary) << bytes;
  try {
    read_checkpoint(dir / "c.ckpt");
    FAIL() << "an unknown setting was read";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("holds the setting 'drift_ceiling_x'"), std::string::npos)
        << e.what();
  }
}

// docs/scene-format.md's [simulation] table has a row per scene setting with its unit and default, and
// says which command-line options override them.
TEST(RunSettings, TheDocsListEverySettingWithItsUnitAndDefault) {
  const std::string docs = text_of(std::filesystem::path(TUMBLE_SOURCE_DIR) / "docs" / "scene-format.md");
  for (const RunSetting& s : run_settings()) {
    if (s.in_scene) {
      const std::string row = fmt::format(
          "| `{}` |{}| {} |", s.key, s.unit.empty() ? std::string(" ") : fmt::format(" {} ", s.unit),
          s.scene_default == "required" ? std::string("required") : fmt::format("`{}`", s.scene_default));
      EXPECT_NE(docs.find(row), std::string::npos) << "docs/scene-format.md has no row starting " << row;
    }
    EXPECT_NE(docs.find(fmt::format("`{}`", s.flag)), std::string::npos) << s.flag;
  }
}

}  // namespace
}  // namespace tumble
