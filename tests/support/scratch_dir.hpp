// A scratch directory of the running test's own. ctest runs each test in its own process, two at a
// time or more, so a directory shared by name between tests is a race (one test reading the file
// another is rewriting); this one is named after the suite and the test.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace tumble::test {

/// testing::TempDir()/area/Suite.Test, created if missing.
inline std::filesystem::path scratch_dir(const std::string& area) {
  const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / area /
                                    (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace tumble::test
