#pragma once
// Shared by the robot layer's tests: where the test models are, and lookups into audits and models.
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "tumble/robot/audit.hpp"

#include "../support/scratch_dir.hpp"

namespace tumble::robot::test {

/// tests/robot/models/ (make_models.py writes them).
inline const std::string kModels = std::string(TUMBLE_SOURCE_DIR) + "/tests/robot/models/";

/// The codes of a link's findings.
inline std::set<std::string> codes(const LinkAudit& l) {
  std::set<std::string> out;
  for (const Finding& f : l.findings) out.insert(f.code);
  return out;
}

/// A link of an audit, or of a model, by name.
inline const LinkAudit& link(const ModelAudit& a, const std::string& name) {
  for (const LinkAudit& l : a.links)
    if (l.name == name) return l;
  throw std::runtime_error("no link " + name);
}
inline const Link& link_of(const RobotModel& m, const std::string& name) {
  for (const Link& l : m.links)
    if (l.name == name) return l;
  throw std::runtime_error("no link " + name);
}

/// The largest entry of |A − B| over the largest of |B|.
inline double relative(const Mat3& A, const Mat3& B) {
  return (A - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff();
}

/// Writes `text` as `name` in the running test's scratch directory under `dir` beside a link to the
/// test models' meshes, which models name relative to themselves; returns its path.
inline std::string written_beside_meshes(const std::string& dir, const std::string& name,
                                         const std::string& text) {
  const std::filesystem::path d = tumble::test::scratch_dir(dir);
  std::error_code ec;
  std::filesystem::create_directory_symlink(kModels + "meshes", d / "meshes", ec);  // exists: fine
  std::ofstream(d / name, std::ios::binary) << text;
  return (d / name).string();
}

}  // namespace tumble::robot::test
