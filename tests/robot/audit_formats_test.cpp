// tumble model check on the MJCF and SDF models of tests/robot/models (make_models.py wrote them beside
// the URDF ones, every authored inertial from the same closed forms): arm.xml and arm.sdf are arm.urdf's
// clean arm in each format's own terms (MJCF half-sizes, radians, meshdir, per-geom densities; SDF link
// poses in the model frame), and pass; arm_flawed.xml and arm_flawed.sdf plant the defects as each format
// writes them, each found on its own link with its code.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tumble/robot/audit.hpp"

#include "robot_support.hpp"

namespace tumble::robot {
namespace {

using namespace test;

/// Each link's frame in the frame of its tree's root (the link no joint of the model hangs from another
/// link), composed from the joints' origins.
std::map<std::string, Pose> link_poses(const RobotModel& m) {
  std::map<std::string, const Joint*> up;
  std::set<std::string> names;
  for (const Link& l : m.links) names.insert(l.name);
  for (const Joint& j : m.joints)
    if (names.count(j.parent)) up[j.child] = &j;
  std::map<std::string, Pose> out;
  for (const Link& l : m.links) {
    Pose pose;
    for (std::string at = l.name; up.count(at); at = up.at(at)->parent) {
      const Pose& o = up.at(at)->origin;
      pose = {o.R * pose.R, o.R * pose.p + o.p};
    }
    out[l.name] = pose;
  }
  return out;
}

struct Clean {
  const char* file;
  Format format;
  const char* fore_geometry;  ///< ComputedMass::geometry of the fore link
};
const std::vector<Clean> kClean = {{"arm.xml", Format::mjcf, "geom 1 mesh, sphere"},
                                   {"arm.sdf", Format::sdf, "collision 1 mesh, sphere"}};

TEST(ModelAuditFormats, TheCleanArmHasNoFindingInMjcfNorSdf) {
  const ModelAudit urdf = audit_model(kModels + "arm.urdf");
  const std::map<std::string, Pose> urdf_poses = link_poses(urdf.model);
  for (const Clean& clean : kClean) {
    SCOPED_TRACE(clean.file);
    const ModelAudit a = audit_model(kModels + clean.file);
    EXPECT_EQ(a.model.format, clean.format);
    EXPECT_EQ(a.model.name, "arm");
    ASSERT_EQ(a.links.size(), 4u);
    for (const LinkAudit& l : a.links) {
      EXPECT_TRUE(l.findings.empty()) << l.name << ": " << (l.findings.empty() ? "" : l.findings[0].message);
      ASSERT_TRUE(l.authored && l.computed) << l.name;
      // The same arm: the authored inertials are arm.urdf's, written with the same 17 digits and read
      // back to the same doubles (no rotation on any inertial: inertia_link() is the tensor as written).
      const Inertial& u = *link(urdf, l.name).authored;
      EXPECT_EQ(l.authored->mass, u.mass) << l.name;
      EXPECT_EQ(l.authored->frame.p, u.frame.p) << l.name;
      EXPECT_EQ(l.authored->inertia_link(), u.inertia_link()) << l.name;
      // The geometry gives the authored values. SDF: the authored mass spread over it, so the mass is
      // exact. MJCF: each geom's own density or mass (MuJoCo's rule), density × volume against the sum
      // make_models.py formed in another order: a few ulps, 2e-15 relative. COM and tensor: rounding only
      // (the mesh and the sphere sum in another order), 1e-15 m and 1e-13 relative, as for arm.urdf.
      const MassProperties& c = l.computed->properties;
      EXPECT_NEAR(c.mass, l.authored->mass, 2e-15 * l.authored->mass) << l.name;
      EXPECT_LT((c.center_of_mass - l.authored->frame.p).norm(), 1e-15) << l.name;
      EXPECT_LT(relative(c.inertia, l.authored->inertia_link()), 1e-13) << l.name;
    }
    // The same geometry: MJCF's half-sizes and SDF's full sizes give arm.urdf's volumes exactly (a box's
    // product of exact halves doubled, a cylinder πr²L, the bar mesh and a sphere).
    for (const char* name : {"base", "upper", "fore", "tool"}) {
      EXPECT_EQ(link(a, name).computed->properties.volume, link(urdf, name).computed->properties.volume)
          << name;
    }
    EXPECT_EQ(link(a, "fore").computed->geometry, clean.fore_geometry);
    // The same joints: each link's frame in the root link's, composed along the tree, is arm.urdf's.
    // MJCF nests bodies by the same origins (euler in radians); SDF poses each link in the model's frame
    // and the reader composes inverse(parent) ∘ child, so the rotations through sin and cos of π/2 and
    // 0.5 agree to a few ulps of the unit entries: 1e-15.
    const std::map<std::string, Pose> poses = link_poses(a.model);
    for (const auto& [name, pose] : urdf_poses) {
      EXPECT_LT((poses.at(name).R - pose.R).cwiseAbs().maxCoeff(), 1e-15) << name;
      EXPECT_LT((poses.at(name).p - pose.p).norm(), 1e-15) << name;
    }
    EXPECT_FALSE(a.has_errors());
  }
}

TEST(ModelAuditFormats, EachPlantedDefectIsFoundOnItsLinkWithItsCode) {
  // Both files plant the defects of arm_flawed.urdf on links named after them. MJCF plants no massless link
  // (MuJoCo refuses a moving body without mass); its inertial_rotation is a diaginertia,
  // already right in the body's axes, under an euler turn; its product_sign a fullinertia.
  std::map<std::string, std::set<std::string>> expected = {
      {"clean", {}},
      {"not_positive_definite", {"not_positive_definite"}},
      {"triangle_inequality", {"triangle_inequality"}},
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
  for (const auto& [file, format] :
       {std::pair{"arm_flawed.xml", Format::mjcf}, {"arm_flawed.sdf", Format::sdf}}) {
    SCOPED_TRACE(file);
    if (format == Format::sdf) expected["zero_mass_with_geometry"] = {"zero_mass_with_geometry"};
    const ModelAudit a = audit_model(kModels + file);
    EXPECT_EQ(a.model.format, format);
    ASSERT_EQ(a.links.size(), expected.size());
    for (const LinkAudit& l : a.links) {
      std::string messages;
      for (const Finding& f : l.findings) messages += "\n  " + f.message;
      ASSERT_TRUE(expected.count(l.name)) << l.name;
      EXPECT_EQ(codes(l), expected.at(l.name)) << l.name << messages;
      // A finding about the inertial names its file:line, the line of the element itself.
      for (const Finding& f : l.findings) {
        if (f.message.find("<inertial> at") == std::string::npos) continue;
        const SourceSpan& span = l.authored->span;
        EXPECT_NE(f.message.find(std::string(file) + ":" + std::to_string(span.line)), std::string::npos)
            << f.message;
        EXPECT_EQ(a.model.text.compare(span.begin, 9, "<inertial"), 0) << l.name;
      }
    }
    EXPECT_TRUE(a.has_errors());
    const auto message = [&](const std::string& name) { return link(a, name).findings.at(0).message; };
    EXPECT_NE(message("mesh_scale").find("millimetres"), std::string::npos) << message("mesh_scale");
    EXPECT_NE(message("tensor_mismatch").find("permuted"), std::string::npos) << message("tensor_mismatch");
    EXPECT_NE(message("product_sign").find("ixy has the wrong sign"), std::string::npos)
        << message("product_sign");
    EXPECT_NE(message("com_outside_geometry").find("beyond its convex hull"), std::string::npos);
    EXPECT_NE(message("open_mesh").find("boundary"), std::string::npos) << message("open_mesh");
    // The missing mesh where each format puts it: MJCF under <compiler meshdir>, SDF beside the file.
    EXPECT_NE(message("missing_mesh").find("meshes/no_such_mesh.stl"), std::string::npos)
        << message("missing_mesh");
    // Severities as for URDF: an implied density of 30 kg/m³, a zero mass and an open mesh are warnings.
    for (const LinkAudit& l : a.links)
      for (const Finding& f : l.findings)
        EXPECT_EQ(f.severity,
                  f.code == "implied_density" || f.code == "zero_mass_with_geometry" || f.code == "open_mesh"
                      ? Severity::warning
                      : Severity::error)
            << f.code;
  }
}

TEST(ModelAuditFormats, TheToolWeldedToForeLumpsIntoOneBody) {
  // MJCF welds a body without joints to its parent (tool to fore; base to the world, which is no link);
  // SDF has the fixed joint flange. Either way fore + tool is one body: a 0.05 m cube turned 0.5 rad
  // about z, its centre 0.355 m along fore's x; authored and computed compositions agree.
  AuditOptions o;
  o.lump_fixed = true;
  for (const Clean& clean : kClean) {
    SCOPED_TRACE(clean.file);
    const ModelAudit a = audit_model(kModels + clean.file, o);
    ASSERT_EQ(a.links.size(), 5u);  // the four links, then the one lumped body
    const LinkAudit& lumped = a.links.back();
    EXPECT_EQ(lumped.name, "fore (lumped)");
    EXPECT_EQ(lumped.parts, (std::vector<std::string>{"fore", "tool"}));
    EXPECT_TRUE(lumped.findings.empty()) << (lumped.findings.empty() ? "" : lumped.findings[0].message);
    ASSERT_TRUE(lumped.authored && lumped.computed);
    const LinkAudit &fore = link(a, "fore"), &tool = link(a, "tool");
    const double m = fore.authored->mass + tool.authored->mass;
    EXPECT_NEAR(lumped.authored->mass, m, 1e-15 * m);
    // The COM by hand. SDF's tool sits where inverse(fore pose) ∘ (tool pose) puts it: (0.355, 0, 0) up to
    // rounding of a few 1e-17 m, far within 1e-15.
    const Vec3 c = (fore.authored->mass * fore.authored->frame.p + tool.authored->mass * Vec3(0.355, 0, 0)) /
                   m;
    EXPECT_LT((lumped.authored->frame.p - c).norm(), 1e-15);
    const auto about = [](double mass, const Vec3& d) {
      return mass * (d.dot(d) * Mat3::Identity() - d * d.transpose());
    };
    // A cube's tensor is isotropic: its turn changes nothing; the parallel-axis terms by hand.
    const Mat3 I = fore.authored->inertia_link() + about(fore.authored->mass, fore.authored->frame.p - c) +
                   tool.authored->inertia_link() + about(tool.authored->mass, Vec3(0.355, 0, 0) - c);
    EXPECT_LT(relative(lumped.authored->inertia_written, I), 1e-14);
    // The computed body: MJCF's from the geoms' densities, whose masses agree with the authored to a few
    // ulps (above); the tensor to rounding, 1e-13 as for each link.
    EXPECT_NEAR(lumped.computed->properties.mass, m, 2e-15 * m);
    EXPECT_LT(relative(lumped.computed->properties.inertia, I), 1e-13);
  }
}

}  // namespace
}  // namespace tumble::robot
