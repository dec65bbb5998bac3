// tumble model fix on MJCF and SDF (arm_flawed.xml, arm_flawed.sdf, written by make_models.py): the
// inertials recomputed in each format's own element — MJCF an <inertial pos mass fullinertia/> after a
// comment line, SDF a whole <inertial> with the comment inside — the masses kept as written, the tensors
// those of the closed forms, and every byte outside the rewritten text as it was (checked against spans
// found by parsing the fixed file afresh).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tumble/robot/fix.hpp"

#include "robot_support.hpp"

namespace tumble::robot {
namespace {

using namespace test;

std::string written(const std::string& name, const std::string& text) {
  return written_beside_meshes("robot_fix_formats", name, text);
}

/// The text with every inertial element taken out and, before each, the text `lead` names for its link:
/// what the fix wrote ahead of the element (MJCF's comment, its line end and the indentation; nothing in
/// SDF, whose comment is inside <inertial>). That text is checked to be there.
std::string outside_inertials(const RobotModel& m, const std::map<std::string, std::string>& lead = {}) {
  std::string out;
  std::size_t at = 0;
  for (const Link& l : m.links) {
    if (!l.inertial) continue;
    const SourceSpan& s = l.inertial->span;
    const auto it = lead.find(l.name);
    const std::size_t n = it == lead.end() ? 0 : it->second.size();
    if (n > 0) {
      EXPECT_GE(s.begin, at + n) << l.name;
      EXPECT_EQ(m.text.substr(s.begin - n, n), it->second) << l.name;
    }
    out.append(m.text, at, s.begin - n - at);
    at = s.end;
  }
  return out + m.text.substr(at);
}

/// Every link's name: FixOptions::only, so that each link is rewritten whatever its findings (a clean
/// one too) unless its geometry or its mass forbids it.
std::vector<std::string> every_link(const RobotModel& m) {
  std::vector<std::string> out;
  for (const Link& l : m.links) out.push_back(l.name);
  return out;
}

/// The closed forms make_models.py wrote the clean inertials from: a box a x b x c of mass m about its
/// centre, in its own axes.
Mat3 box(double m, double a, double b, double c) {
  return Vec3(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12).asDiagonal();
}

struct Expected {
  Vec3 com;
  Mat3 inertia;  ///< about the COM, in the link's axes
};

/// What each rewritten link of arm_flawed.{xml,sdf} must get: its geometry's own mass properties at the
/// authored mass. The 0.1 m cube (2 kg, or 0.03 kg for implied_density), at the origin or 0.2 m up z; the
/// 0.3 x 0.1 x 0.1 box of 1.8 kg, in the link's axes or turned 0.5 rad about z. In MJCF the
/// inertial_rotation link's box is not turned (the inertial's euler was the defect); in SDF it is (the
/// rotation applied twice was).
std::map<std::string, Expected> closed_forms(Format format) {
  const Mat3 cube = box(2, 0.1, 0.1, 0.1), bar = box(1.8, 0.3, 0.1, 0.1);
  const Mat3 R = Eigen::AngleAxisd(0.5, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 o = Vec3::Zero();
  return {
      {"clean", {o, cube}},
      {"not_positive_definite", {o, cube}},
      {"triangle_inequality", {o, cube}},
      {"implied_density", {o, box(0.03, 0.1, 0.1, 0.1)}},
      {"tensor_about_origin", {Vec3(0, 0, 0.2), cube}},
      {"com_outside_geometry", {o, cube}},
      {"tensor_mismatch", {o, bar}},
      {"inertial_rotation", {o, format == Format::mjcf ? bar : Mat3(R * bar * R.transpose())}},
      {"product_sign", {o, R * bar * R.transpose()}},
  };
}

/// Fixes `file` keeping the masses, writes it beside the meshes, and checks what the fix may change and
/// what it may not. `unchanged`: the links it must leave as they were.
void check_fix(const std::string& file, Format format, const std::set<std::string>& unchanged) {
  SCOPED_TRACE(file);
  const ModelAudit before = audit_model(kModels + file);
  ASSERT_EQ(before.model.format, format);
  const FixResult fixed = fix_model(before, {Keep::mass, every_link(before.model)}, {});
  const std::string path = written("fixed." + file, fixed.text);
  const ModelAudit after = audit_model(path);
  std::remove(path.c_str());
  ASSERT_EQ(after.model.links.size(), before.model.links.size());

  // Which links were rewritten, and how each rewritten element starts.
  std::set<std::string> left;
  std::map<std::string, std::string> lead;
  for (const LinkFix& l : fixed.links) {
    if (!l.changed) {
      left.insert(l.name);
      continue;
    }
    const std::size_t element = l.after.find("<inertial");
    ASSERT_NE(element, std::string::npos) << l.name;
    lead[l.name] = l.after.substr(0, element);
    if (format == Format::mjcf) {
      // A comment line, then the element in the body's axes: fullinertia, no orientation.
      EXPECT_EQ(
          l.after.rfind("<!-- inertial computed by tumble from the link's geom box (mass as written", 0), 0u)
          << l.after;
      EXPECT_NE(l.after.find("fullinertia=\""), std::string::npos) << l.after;
    } else {
      EXPECT_EQ(element, 0u) << l.after;
      EXPECT_NE(l.after.find(
                    "<!-- inertial computed by tumble from the link's collision box (mass as written"),
                std::string::npos)
          << l.after;
    }
  }
  EXPECT_EQ(left, unchanged);

  // (1) Every byte outside the rewritten text, as found by parsing each file on its own, as it was.
  EXPECT_EQ(outside_inertials(after.model, lead), outside_inertials(before.model));

  // (2) The masses exactly as written, on every link.
  for (const Link& l : before.model.links) {
    ASSERT_TRUE(l.inertial) << l.name;
    EXPECT_EQ(link_of(after.model, l.name).inertial->mass_text, l.inertial->mass_text) << l.name;
  }

  // (3) The rewritten COMs and tensors are the closed forms. Rounding only: the fix prints the shortest
  // text that reads back as the same double, and the geometry's values differ from the closed forms by
  // the rounding of their own arithmetic (a few ulps): 1e-13 relative to the tensor's largest entry, and
  // 1e-13 of the boxes' 0.3 m size for the COM.
  const std::map<std::string, Expected> expected = closed_forms(format);
  std::size_t checked = 0;
  for (const Link& l : after.model.links) {
    if (unchanged.count(l.name)) continue;
    SCOPED_TRACE(l.name);
    ASSERT_TRUE(expected.count(l.name));
    const Expected& e = expected.at(l.name);
    EXPECT_FALSE(l.inertial->rotated);
    EXPECT_LT((l.inertial->frame.p - e.com).norm(), 1e-13 * 0.3);
    EXPECT_LT(relative(l.inertial->inertia_link(), e.inertia), 1e-13);
    ++checked;
  }
  EXPECT_EQ(checked, expected.size());

  // (4) What is left after the fix is what the fix cannot mend: the masses themselves and the meshes.
  const std::set<std::string> unfixable = {"implied_density", "zero_mass_with_geometry", "mesh_scale",
                                           "missing_mesh", "open_mesh"};
  for (const LinkAudit& l : after.links)
    for (const Finding& f : l.findings) EXPECT_TRUE(unfixable.count(f.code)) << l.name << ": " << f.message;
  // ... and those findings are still there: the fix hid nothing.
  for (const char* name : {"implied_density", "mesh_scale", "missing_mesh", "open_mesh"}) {
    bool found = false;
    for (const LinkAudit& l : after.links)
      if (l.name == name) found = !l.findings.empty() && l.findings[0].code == name;
    EXPECT_TRUE(found) << name;
  }
}

TEST(ModelFixFormats, MjcfChangesOnlyTheInertialsAndKeepsTheMassAsWritten) {
  check_fix("arm_flawed.xml", Format::mjcf, {"mesh_scale", "missing_mesh", "open_mesh"});
}

TEST(ModelFixFormats, SdfChangesOnlyTheInertialsAndKeepsTheMassAsWritten) {
  // SDF also has the massless link, which the fix keeps under Keep::mass.
  check_fix("arm_flawed.sdf", Format::sdf,
            {"zero_mass_with_geometry", "mesh_scale", "missing_mesh", "open_mesh"});
}

TEST(ModelFixFormats, TheCleanArmFixedIsTheSameArm) {
  // Every inertial of arm.xml and arm.sdf rewritten from its geometry gives back the authored values
  // (make_models.py's closed forms): the fore link's mesh and sphere summed (MJCF: each at its geom's
  // density, then scaled to the authored mass) within the rounding of 1e-13 relative; the COM to 1e-15 m.
  for (const std::string file : {"arm.xml", "arm.sdf"}) {
    SCOPED_TRACE(file);
    const ModelAudit before = audit_model(kModels + file);
    const FixResult fixed = fix_model(before, {Keep::mass, every_link(before.model)}, {});
    for (const LinkFix& l : fixed.links) EXPECT_TRUE(l.changed) << l.name << ": " << l.reason;
    const std::string path = written("fixed." + file, fixed.text);
    const ModelAudit again = audit_model(path);
    std::remove(path.c_str());
    for (const LinkAudit& l : again.links) {
      EXPECT_TRUE(l.findings.empty()) << l.name << ": " << (l.findings.empty() ? "" : l.findings[0].message);
      const Inertial& was = *link_of(before.model, l.name).inertial;
      EXPECT_EQ(l.authored->mass_text, was.mass_text) << l.name;
      EXPECT_LT((l.authored->frame.p - was.frame.p).norm(), 1e-15) << l.name;
      EXPECT_LT(relative(l.authored->inertia_link(), was.inertia_link()), 1e-13) << l.name;
    }
  }
}

}  // namespace
}  // namespace tumble::robot
