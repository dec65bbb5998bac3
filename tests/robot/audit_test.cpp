// tumble model check on the models of tests/robot/models (make_models.py wrote them, every authored
// inertial from closed forms in exact rational arithmetic): the clean arm passes, each planted defect is
// found on its own link with its code, and the computed mass properties are the closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <map>
#include <set>
#include <string>

#include "tumble/error.hpp"
#include "tumble/robot/audit.hpp"

#include "robot_support.hpp"

namespace tumble::robot {
namespace {

using namespace test;

std::string model_file(const std::string& name, const std::string& text) {
  return written_beside_meshes("robot_audit", name, text);
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
  const auto about = [](double mass, const Vec3& d) -> Mat3 {
    return mass * (d.dot(d) * Mat3::Identity() - d * d.transpose());
  };
  const Mat3 I = fore.authored->inertia_link() + about(fore.authored->mass, fore.authored->frame.p - c) +
                 tool.authored->inertia_link() + about(tool.authored->mass, Vec3(0.355, 0, 0) - c);
  EXPECT_LT(relative(lumped.authored->inertia_written, I), 1e-14);
  EXPECT_LT(relative(lumped.computed->properties.inertia, I), 1e-13);
}

TEST(ModelAudit, ABodyWeldedThroughARotatedJointIsComposedExactly) {
  // A 0.4 x 0.1 x 0.1 box (4 kg) with a 0.1 x 0.3 x 0.1 box (3 kg) welded 0.25 m along x, turned 0.3 rad
  // about z: the lumped body by hand, I = Σ R_i I_i R_iᵀ + m_i((d·d)I₃ − d dᵀ), d from the joint COM.
  const auto box = [](double m, const Vec3& s) -> Mat3 {  // (a Mat3, not an Eigen expression of temporaries)
    return Vec3(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(), s.x() * s.x() + s.y() * s.y())
               .asDiagonal() *
           (m / 12);
  };
  const Mat3 Ia = box(4, Vec3(0.4, 0.1, 0.1)), Ib = box(3, Vec3(0.1, 0.3, 0.1));
  const auto urdf_inertia = [](const Mat3& I) {
    return fmt::format("ixx=\"{}\" ixy=\"0\" ixz=\"0\" iyy=\"{}\" iyz=\"0\" izz=\"{}\"", I(0, 0), I(1, 1),
                       I(2, 2));
  };
  const std::string text = fmt::format(
      "<robot name='w'>\n"
      "<link name='a'><inertial><mass value='4'/><inertia {}/></inertial>\n"
      "  <collision><geometry><box size='0.4 0.1 0.1'/></geometry></collision></link>\n"
      "<link name='b'><inertial><mass value='3'/><inertia {}/></inertial>\n"
      "  <collision><geometry><box size='0.1 0.3 0.1'/></geometry></collision></link>\n"
      "<joint name='weld' type='fixed'><parent link='a'/><child link='b'/><origin xyz='0.25 0 0' rpy='0 0 "
      "0.3'/></joint>\n"
      "</robot>\n",
      urdf_inertia(Ia), urdf_inertia(Ib));
  AuditOptions o;
  o.lump_fixed = true;
  const ModelAudit a = audit_model(model_file("welded.urdf", text), o);
  const LinkAudit& lumped = link(a, "a (lumped)");
  const Mat3 R = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 c = 3.0 * Vec3(0.25, 0, 0) / 7.0;
  const auto shift = [](double m, const Vec3& d) -> Mat3 {
    return m * (d.dot(d) * Mat3::Identity() - d * d.transpose());
  };
  const Mat3 I = Ia + shift(4, -c) + R * Ib * R.transpose() + shift(3, Vec3(0.25, 0, 0) - c);
  EXPECT_LT((lumped.authored->frame.p - c).norm(), 1e-16);
  // The authored values are written with 17 digits (fmt's shortest round trip): rounding only.
  EXPECT_LT(relative(lumped.authored->inertia_written, I), 1e-14);
  EXPECT_LT(relative(lumped.computed->properties.inertia, I), 1e-14);
  EXPECT_TRUE(lumped.findings.empty());
}

TEST(ModelAudit, ACollidaMeshInMillimetresIsReadAtItsUnit) {
  // cube_mm.dae: a 1000 x 1000 x 1000 cube with <unit meter="0.001">: 1 m³ (assimp applies the unit).
  const ModelAudit a = audit_model(model_file(
      "dae.urdf",
      "<robot name='d'><link name='c'><inertial><mass value='1000'/>"
      "<origin xyz='0.5 0.5 0.5'/><inertia ixx='166.66666666666666' iyy='166.66666666666666' "
      "izz='166.66666666666666'/></inertial><collision><geometry><mesh filename='meshes/cube_mm.dae'/>"
      "</geometry></collision></link></robot>"));
  ASSERT_TRUE(link(a, "c").computed);
  EXPECT_NEAR(link(a, "c").computed->properties.volume, 1.0, 1e-15);  // float32 corners 0 and 1000: exact
  EXPECT_TRUE(link(a, "c").findings.empty()) << link(a, "c").findings.at(0).message;
}

TEST(ModelAudit, BadInputIsACleanErrorWithTheLine) {
  const std::string dir = tumble::test::scratch_dir("audit").string();
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
