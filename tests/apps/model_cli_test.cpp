// `tumble model check` and `tumble model fix` as a user runs them: exit statuses for CI, the table and
// the JSON, the fix written beside (never over) its input, and usage errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../support/run.hpp"
#include "../support/scratch_dir.hpp"

namespace tumble {
namespace {

const std::string kModels = std::string(TUMBLE_SOURCE_DIR) + "/tests/robot/models/";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ModelCli, CheckExitsZeroOnACleanModelAndOneOnErrors) {
  const test::CommandResult clean = test::run_tumble("model check " + kModels + "arm.urdf");
  EXPECT_EQ(clean.status, 0) << clean.output;
  EXPECT_NE(clean.output.find("0 errors, 0 warnings"), std::string::npos) << clean.output;
  const test::CommandResult flawed = test::run_tumble("model check " + kModels + "arm_flawed.urdf");
  EXPECT_EQ(flawed.status, 1) << flawed.output;
  EXPECT_NE(flawed.output.find("error [mesh_scale] link 'mesh_scale'"), std::string::npos) << flawed.output;
  EXPECT_NE(flawed.output.find("9 errors, 3 warnings"), std::string::npos) << flawed.output;
  // --json: one object, the same counts.
  const test::CommandResult json =
      test::run_shell_command(std::string(TUMBLE_CLI) + " model check --json " + kModels + "arm_flawed.urdf");
  EXPECT_EQ(json.status, 1);
  const nlohmann::json j = nlohmann::json::parse(json.output);
  EXPECT_EQ(j["format"], "urdf");
  EXPECT_EQ(j["errors"], 9);
  EXPECT_EQ(j["links"].size(), 13u);
}

TEST(ModelCli, FixWritesANewFileAndNeverTheInput) {
  const std::string dir = test::scratch_dir("model_cli").string();
  const std::string input = dir + "/arm.urdf";
  std::filesystem::copy_file(kModels + "arm_flawed.urdf", input,
                             std::filesystem::copy_options::overwrite_existing);
  std::error_code ec;
  std::filesystem::create_directory_symlink(kModels + "meshes", dir + "/meshes", ec);
  const std::string before = slurp(input);
  const test::CommandResult same = test::run_tumble("model fix " + input + " -o " + input);
  EXPECT_EQ(same.status, 1);
  EXPECT_NE(same.output.find("never overwrites an input"), std::string::npos) << same.output;
  EXPECT_EQ(slurp(input), before);
  const test::CommandResult fixed = test::run_tumble("model fix " + input + " -o " + dir + "/fixed.urdf");
  EXPECT_EQ(fixed.status, 0) << fixed.output;
  EXPECT_NE(fixed.output.find("7 inertials rewritten, nothing else changed"), std::string::npos)
      << fixed.output;
  EXPECT_EQ(fixed.output.find("note:"), std::string::npos)
      << fixed.output;  // beside the input: meshes resolve
  EXPECT_NE(fixed.output.find("link 'open_mesh' (line 160): left as it was"), std::string::npos)
      << fixed.output;
  EXPECT_EQ(slurp(input), before);
  // What is left after the fix: the mass-related findings and the meshes to mend.
  const test::CommandResult again = test::run_tumble("model check --json " + dir + "/fixed.urdf");
  const nlohmann::json j = nlohmann::json::parse(again.output.substr(again.output.find('{')));
  for (const auto& link : j["links"]) {
    for (const auto& f : link["findings"]) {
      const std::string code = f["code"];
      EXPECT_TRUE(code == "implied_density" || code == "zero_mass_with_geometry" || code == "mesh_scale" ||
                  code == "missing_mesh" || code == "open_mesh")
          << link["name"] << ": " << f["message"];
    }
  }
}

TEST(ModelCli, FixSaysWhenTheMeshesNoLongerResolveFromTheOutput) {
  const std::string dir = test::scratch_dir("model_cli_elsewhere").string();
  const test::CommandResult fixed =
      test::run_tumble("model fix " + kModels + "arm_flawed.urdf -o " + dir + "/fixed.urdf");
  EXPECT_EQ(fixed.status, 0) << fixed.output;
  EXPECT_NE(fixed.output.find(
                "names its meshes relative to its directory (\"meshes/bar_mm.obj\", link 'mesh_scale')"),
            std::string::npos)
      << fixed.output;
}

TEST(ModelCli, UsageErrorsExitTwo) {
  EXPECT_EQ(test::run_tumble("model").status, 2);
  EXPECT_EQ(test::run_tumble("model check").status, 2);
  EXPECT_EQ(test::run_tumble("model check " + kModels + "arm.urdf --geometry both").status, 2);
  EXPECT_EQ(test::run_tumble("model fix " + kModels + "arm.urdf").status, 2);  // no -o
  const test::CommandResult help = test::run_tumble("model check --help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.output.find("--package-path"), std::string::npos);
}

}  // namespace
}  // namespace tumble
