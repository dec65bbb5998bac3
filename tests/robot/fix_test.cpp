// tumble model fix: the inertials recomputed, the mass kept exactly as written, and every byte outside
// the rewritten elements as it was (checked against spans found by parsing the fixed file afresh).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>

#include "tumble/error.hpp"
#include "tumble/robot/fix.hpp"

#include "robot_support.hpp"

namespace tumble::robot {
namespace {

using namespace test;

std::string written(const std::string& name, const std::string& text) {
  return written_beside_meshes("robot_fix", name, text);
}

/// The text with every inertial element taken out.
std::string outside_inertials(const RobotModel& m) {
  std::string out;
  std::size_t at = 0;
  for (const Link& l : m.links) {
    if (!l.inertial) continue;
    out.append(m.text, at, l.inertial->span.begin - at);
    at = l.inertial->span.end;
  }
  return out + m.text.substr(at);
}

TEST(ModelFix, ChangesOnlyTheInertialsAndKeepsTheMassAsWritten) {
  const ModelAudit before = audit_model(kModels + "arm_flawed.urdf");
  const FixResult fixed = fix_model(before, {}, {});
  const std::string path = written("fixed.tmp.urdf", fixed.text);
  const ModelAudit after = audit_model(path);
  std::remove(path.c_str());
  // Every byte outside the inertials (found by parsing each file on its own) as it was.
  EXPECT_EQ(outside_inertials(after.model), outside_inertials(before.model));
  ASSERT_EQ(after.model.links.size(), before.model.links.size());
  // The links whose geometry is usable and whose mass is real are rewritten; their findings are gone
  // but those about the mass itself (a density of 30 kg/m³ is still one).
  std::map<std::string, std::string> reasons;
  for (const LinkFix& l : fixed.links)
    if (!l.changed) reasons[l.name] = l.reason;
  EXPECT_EQ(reasons.size(),
            6u);  // clean, a density (mass kept), zero mass, mesh in mm, missing and open meshes
  EXPECT_NE(reasons["clean"].find("no finding"), std::string::npos);
  EXPECT_NE(reasons["implied_density"].find("about its mass, which is kept"), std::string::npos);
  EXPECT_NE(reasons["mesh_scale"].find("scale"), std::string::npos);
  EXPECT_NE(reasons["missing_mesh"].find("could not be used"), std::string::npos);
  EXPECT_NE(reasons["zero_mass_with_geometry"].find("mass is 0"), std::string::npos);
  for (const LinkAudit& l : after.links) {
    if (reasons.count(l.name)) continue;
    for (const Finding& f : l.findings) EXPECT_EQ(f.code, "implied_density") << l.name << ": " << f.message;
  }
  // The masses exactly as written; the tensors those of the closed forms (make_models.py): a box
  // 0.3 x 0.1 x 0.1 of 1.8 kg turned 0.5 rad about z, and one not turned. Rounding only: 1e-13.
  const Link& turned = link_of(after.model, "inertial_rotation");
  EXPECT_EQ(turned.inertial->mass_text, "1.8");
  const double a = 0.3, b = 0.1, m = 1.8;
  const Mat3 box =
      Vec3(m * (b * b + b * b) / 12, m * (a * a + b * b) / 12, m * (a * a + b * b) / 12).asDiagonal();
  const Mat3 R = Eigen::AngleAxisd(0.5, Vec3::UnitZ()).toRotationMatrix();
  EXPECT_LT(relative(turned.inertial->inertia_link(), R * box * R.transpose()), 1e-13);
  EXPECT_FALSE(turned.inertial->rotated);
  EXPECT_LT(relative(link_of(after.model, "tensor_mismatch").inertial->inertia_link(), box), 1e-13);
  const Link& shifted = link_of(after.model, "tensor_about_origin");
  EXPECT_LT((shifted.inertial->frame.p - Vec3(0, 0, 0.2)).norm(), 1e-15);
  // Each rewritten element says what it is.
  EXPECT_NE(fixed.text.find(
                "<!-- inertial computed by tumble from the link's collision box (mass as written"),
            std::string::npos);
}

TEST(ModelFix, KeepsTheAuthoredComWhenAskedAndComputesTheMassFromADensity) {
  const ModelAudit before = audit_model(kModels + "arm_flawed.urdf");
  FixOptions keep_com{Keep::mass_and_com, {"com_outside_geometry"}};
  const FixResult fixed = fix_model(before, keep_com, {});
  ASSERT_EQ(fixed.links.size(), 1u);
  const std::string path = written("fixed.tmp.urdf", fixed.text);
  const RobotModel after = read_robot_model(path);
  std::remove(path.c_str());
  // The 2 kg cube of side 0.1 about a point 1 m off its centre along x: I_c + m((d·d)I − d dᵀ).
  const Link& l = link_of(after, "com_outside_geometry");
  const Vec3 d(1, 0, 0);
  const Mat3 expected = Mat3::Identity() * (2 * 0.02 / 12) +
                        2 * (d.dot(d) * Mat3::Identity() - d * d.transpose());
  EXPECT_LT(relative(l.inertial->inertia_link(), expected), 1e-13);
  EXPECT_EQ(l.inertial->frame.p, d);
  // --keep none: the mass from the density, 2700 kg/m³ x 0.001 m³.
  AuditOptions density;
  density.density = 2700;
  const ModelAudit at_density = audit_model(kModels + "arm_flawed.urdf", density);
  const FixResult none = fix_model(at_density, {Keep::none, {"clean"}}, density);
  const std::string path2 = written("fixed2.tmp.urdf", none.text);
  const RobotModel after2 = read_robot_model(path2);
  std::remove(path2.c_str());
  EXPECT_NEAR(link_of(after2, "clean").inertial->mass, 2.7, 1e-15);
}

TEST(ModelFix, RefusesWhatItCannotDo) {
  const ModelAudit a = audit_model(kModels + "arm.urdf");
  EXPECT_THROW((void)fix_model(a, {Keep::mass, {"no_such_link"}}, {}), InvalidArgument);
  EXPECT_THROW((void)fix_model(a, {Keep::none, {}}, {}), InvalidArgument);  // no density
  // A clean model fixed is the same file, byte for byte; with --all, values rewritten to the same numbers.
  EXPECT_EQ(fix_model(a, {}, {}).text, a.model.text);
  const FixResult same = fix_model(a, {Keep::mass, {}, true}, {});
  EXPECT_EQ(std::count_if(same.links.begin(), same.links.end(), [](const LinkFix& l) { return l.changed; }),
            4);
  const std::string path = written("fixed3.tmp.urdf", same.text);
  const ModelAudit again = audit_model(path);
  std::remove(path.c_str());
  for (const LinkAudit& l : again.links) EXPECT_TRUE(l.findings.empty()) << l.name;
}

}  // namespace
}  // namespace tumble::robot
