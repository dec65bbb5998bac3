// tumble model check on the models of tests/robot/models (make_models.py wrote them, every authored
// inertial from closed forms in exact rational arithmetic): the clean arm passes, each planted defect is
// found on its own link with its code, and the computed mass properties are the closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "tumble/error.hpp"
#include "tumble/robot/audit.hpp"

namespace tumble::robot {
namespace {

const std::string kModels = std::string(TUMBLE_SOURCE_DIR) + "/tests/robot/models/";

std::set<std::string> codes(const LinkAudit& l) {
  std::set<std::string> out;
  for (const Finding& f : l.findings) out.insert(f.code);
  return out;
}

const LinkAudit& link(const ModelAudit& a, const std::string& name) {
  for (const LinkAudit& l : a.links)
    if (l.name == name) return l;
  throw std::runtime_error("no link " + name);
}

/// The largest entry of |A − B| over the largest of |B|.
double relative(const Mat3& A, const Mat3& B) {
  return (A - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff();
}

TEST(ModelAudit, TheCleanArmHasNoFindingAndItsGeometryGivesTheClosedForms) {
  const ModelAudit a = audit_model(kModels + "arm.urdf");
  EXPECT_EQ(a.model.format, Format::urdf);
  EXPECT_EQ(a.model.name, "arm");
  ASSERT_EQ(a.links.size(), 4u);
  for (const LinkAudit& l : a.links) {
    EXPECT_TRUE(l.findings.empty()) << l.name << ": " << (l.findings.empty() ? "" : l.findings[0].message);
    ASSERT_TRUE(l.authored && l.computed) << l.name;
    // The geometry at the authored mass: the authored values were computed from the same closed forms
    // (make_models.py), written with 17 digits: rounding only (the mesh and the sphere sum in another
    // order), 1e-13 relative.
    const MassProperties& c = l.computed->properties;
    EXPECT_NEAR(c.mass, l.authored->mass, 1e-15 * l.authored->mass) << l.name;
    EXPECT_LT((c.center_of_mass - l.authored->frame.p).norm(), 1e-15) << l.name;
    EXPECT_LT(relative(c.inertia, l.authored->inertia_link()), 1e-13) << l.name;
  }
  // Volumes: a box, a cylinder (πr²L), the bar mesh and a sphere, a box.
  EXPECT_NEAR(link(a, "base").computed->properties.volume, 0.004, 1e-18);
  EXPECT_NEAR(link(a, "upper").computed->properties.volume, M_PI * 0.05 * 0.05 * 0.4, 1e-18);
  EXPECT_NEAR(link(a, "fore").computed->properties.volume,
              0.3 * 0.04 * 0.04 + 4 * M_PI * 0.03 * 0.03 * 0.03 / 3, 1e-18);
  EXPECT_EQ(link(a, "fore").computed->geometry, "collision 1 mesh, sphere");
  EXPECT_FALSE(a.has_errors());
}

TEST(ModelAudit, EachPlantedDefectIsFoundOnItsLinkWithItsCode) {
  const ModelAudit a = audit_model(kModels + "arm_flawed.urdf");
  const std::map<std::string, std::set<std::string>> expected = {
      {"clean", {}},
      {"not_positive_definite", {"not_positive_definite"}},
      {"triangle_inequality", {"triangle_inequality"}},
      {"zero_mass_with_geometry", {"zero_mass_with_geometry"}},
      {"implied_density", {"implied_density"}},
      {"mesh_scale", {"mesh_scale"}},
      {"tensor_about_origin", {"tensor_about_origin"}},
      {"com_outside_geometry", {"com_outside_geometry"}},
      {"tensor_mismatch", {"tensor_mismatch"}},
      {"inertial_rotation", {"inertial_rotation"}},
      {"product_sign", {"tensor_mismatch"}},
      {"missing_mesh", {"missing_mesh"}},
      {"open_mesh", {"open_mesh"}},
  };
  ASSERT_EQ(a.links.size(), expected.size());
  for (const LinkAudit& l : a.links) {
    std::string messages;
    for (const Finding& f : l.findings) messages += "\n  " + f.message;
    EXPECT_EQ(codes(l), expected.at(l.name)) << l.name << messages;
  }
  EXPECT_TRUE(a.has_errors());
  // Messages say what, where and how to fix it.
  const auto message = [&](const std::string& name) { return link(a, name).findings.at(0).message; };
  EXPECT_NE(message("mesh_scale").find("millimetres"), std::string::npos) << message("mesh_scale");
  EXPECT_NE(message("mesh_scale").find("scale=\"0.001 0.001 0.001\""), std::string::npos);
  EXPECT_NE(message("tensor_mismatch").find("permuted"), std::string::npos) << message("tensor_mismatch");
  EXPECT_NE(message("product_sign").find("ixy has the wrong sign"), std::string::npos)
      << message("product_sign");
  EXPECT_NE(message("com_outside_geometry").find("beyond its convex hull"), std::string::npos);
  EXPECT_NE(message("missing_mesh").find("no_such_mesh.stl"), std::string::npos);
  EXPECT_NE(message("open_mesh").find("boundary"), std::string::npos) << message("open_mesh");
  EXPECT_NE(message("not_positive_definite").find("arm_flawed.urdf:"), std::string::npos);
  // Severities: an implied density of 30 kg/m³ and a zero mass are warnings; the rest errors.
  for (const LinkAudit& l : a.links)
    for (const Finding& f : l.findings)
      EXPECT_EQ(f.severity,
                f.code == "implied_density" || f.code == "zero_mass_with_geometry" || f.code == "open_mesh"
                    ? Severity::warning
                    : Severity::error)
          << f.code;
}

TEST(ModelAudit, FixedJointsLumpIntoOneBodyExactly) {
  // fore + tool (a 0.05 m cube turned 0.5 rad about z, its centre 0.355 m along fore's x): the lumped
  // authored body is the composition of the two, and so is the computed one; they agree (the clean arm).
  AuditOptions o;
  o.lump_fixed = true;
  const ModelAudit a = audit_model(kModels + "arm.urdf", o);
  const LinkAudit& lumped = link(a, "fore (lumped)");
  EXPECT_EQ(lumped.parts, (std::vector<std::string>{"fore", "tool"}));
  EXPECT_TRUE(lumped.findings.empty());
  ASSERT_TRUE(lumped.authored && lumped.computed);
  const LinkAudit &fore = link(a, "fore"), &tool = link(a, "tool");
  const double m = fore.authored->mass + tool.authored->mass;
  EXPECT_NEAR(lumped.authored->mass, m, 1e-15 * m);
  // The COM by hand: the tool's centre is at (0.355, 0, 0) in fore's frame.
  const Vec3 c = (fore.authored->mass * fore.authored->frame.p + tool.authored->mass * Vec3(0.355, 0, 0)) / m;
  EXPECT_LT((lumped.authored->frame.p - c).norm(), 1e-15);
  // A cube's tensor is isotropic: turning it changes nothing; the parallel-axis terms by hand.
  const auto about = [](double mass, const Vec3& d) {
    return mass * (d.dot(d) * Mat3::Identity() - d * d.transpose());
  };
  const Mat3 I = fore.authored->inertia_link() + about(fore.authored->mass, fore.authored->frame.p - c) +
                 tool.authored->inertia_link() + about(tool.authored->mass, Vec3(0.355, 0, 0) - c);
  EXPECT_LT(relative(lumped.authored->inertia_written, I), 1e-14);
  EXPECT_LT(relative(lumped.computed->properties.inertia, I), 1e-13);
}

TEST(ModelAudit, BadInputIsACleanErrorWithTheLine) {
  const std::string dir = testing::TempDir();
  const auto refused = [&](const std::string& text, const std::string& says) {
    const std::string path = dir + "/bad_model.urdf";
    std::ofstream(path) << text;
    try {
      (void)audit_model(path);
      ADD_FAILURE() << "accepted: " << says;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused("<robot name='r'><link name='a'>\n<inertial><mass value='x'/></inertial></link></robot>",
          "bad_model.urdf:2: <mass>: value \"x\": \"x\" is not a finite number");
  refused("<robot name='r'><link name='a'></robot>", "bad_model.urdf:1:");
  refused("<!DOCTYPE r [<!ENTITY a 'aaaa'>]>\n<robot name='r'/>", "document type declaration");
  refused("<robot xmlns:xacro='http://www.ros.org/wiki/xacro' name='r'><xacro:macro name='m'/></robot>",
          "xacro template");
  refused("<world/>", "tumble reads URDF (<robot>), MJCF (<mujoco>) and SDF (<sdf>)");
  refused(
      "<robot name='r'><link name='a'>\n<inertial><mass value='1'/>\n<inertia ixx='1' "
      "iyy='1'/></inertial></link></robot>",
      "bad_model.urdf:3: <inertia>: needs izz");
}

}  // namespace
}  // namespace tumble::robot
