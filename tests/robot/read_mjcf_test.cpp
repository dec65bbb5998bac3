// The MJCF reader (src/robot/read_mjcf.cpp) on small models written here: links and joints from the
// body tree, poses by MuJoCo's orientation rules against hand-computed matrices, default classes,
// inertiagrouprange, half-sizes, mesh assets, inertials and their byte spans, notes, and errors that
// name the line.
//
// Tolerances: a pose whose numbers need no rounding (xyaxes of unit axes, sums of exact decimals) is
// compared exactly. A rotation through sines and cosines (euler, axisangle, zaxis, quat normalised) has
// entries of magnitude ≤ 1, each the product of correctly rounded sin and cos of half angles: a few ulps,
// a few 1e-16, so 1e-15 absolute (= relative to the unit scale of a rotation).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "tumble/error.hpp"
#include "tumble/robot/robot_model.hpp"

#include "../support/scratch_dir.hpp"

namespace tumble::robot {
namespace {

constexpr double kRotationTolerance = 1e-15;  // see the header comment

std::filesystem::path model_dir() { return tumble::test::scratch_dir("read_mjcf"); }

/// Writes `text` to `name` in a scratch directory and reads it.
RobotModel read(const std::string& name, const std::string& text) {
  const std::filesystem::path path = model_dir() / name;
  std::ofstream(path, std::ios::binary) << text;
  return read_robot_model(path);
}

/// The 1-based line of the first occurrence of `needle` in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

/// The message of the InvalidArgument that reading `text` throws ("" and a failure when none).
std::string error_of(const std::string& text) {
  try {
    (void)read("bad.xml", text);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

const Link& link(const RobotModel& m, const std::string& name) {
  for (const Link& l : m.links)
    if (l.name == name) return l;
  throw std::runtime_error("no link " + name);
}

const Geometry& geom(const Link& l, const std::string& name) {
  for (const Geometry& g : l.collision)
    if (g.name == name) return g;
  throw std::runtime_error("no geom " + name + " in " + l.name);
}

Mat3 rows(std::initializer_list<double> v) {
  Mat3 R;
  auto it = v.begin();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = *it++;
  return R;
}

void expect_near(const Mat3& actual, const Mat3& expected, double tolerance) {
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), tolerance) << "actual\n"
                                                                  << actual << "\nexpected\n"
                                                                  << expected;
}

Mat3 Rx(double a) { return Eigen::AngleAxisd(a, Vec3::UnitX()).toRotationMatrix(); }
Mat3 Ry(double a) { return Eigen::AngleAxisd(a, Vec3::UnitY()).toRotationMatrix(); }
Mat3 Rz(double a) { return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix(); }

bool contains(const std::vector<std::string>& lines, const std::string& fragment) {
  for (const std::string& s : lines)
    if (s.find(fragment) != std::string::npos) return true;
  return false;
}

const std::string kArm = R"(<mujoco model="arm">
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="base" pos="0 0 0.1" euler="0 0 90">
      <inertial pos="0 0 0.05" mass="3.7" diaginertia="0.1 0.2 0.3"/>
      <geom name="plinth" type="box" size="0.1 0.2 0.3"/>
      <body name="upper" pos="0 0 0.2" quat="2 2 0 0">
        <joint name="shoulder" axis="0 1 0"/>
        <geom name="bone" type="capsule" fromto="0 0 0 0.3 0 0.4" size="0.04"/>
        <body pos="0 0 0.4" xyaxes="0 1 0 -1 0 0">
          <joint name="wrist" type="ball"/>
          <geom name="can" type="cylinder" size="0.03 0.1" zaxis="1 0 0"/>
          <geom name="egg" type="ellipsoid" size="0.01 0.02 0.03" axisangle="0 0 1 90"/>
          <geom name="ball" size="0.05" pos="0.1 0.2 0.3"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
)";

TEST(ReadMjcf, TheArmsBodiesAreLinksJoinedAsMuJoCoJoinsThem) {
  const RobotModel m = read("arm.xml", kArm);
  EXPECT_EQ(m.format, Format::mjcf);
  EXPECT_EQ(m.name, "arm");
  ASSERT_EQ(m.links.size(), 3u);  // not the world body
  EXPECT_EQ(m.links[0].name, "base");
  EXPECT_EQ(m.links[1].name, "upper");
  EXPECT_EQ(m.links[2].name, "body#3");  // unnamed: its MuJoCo body id (the world is body 0)
  EXPECT_EQ(m.links[2].line, line_of(kArm, "<body pos=\"0 0 0.4\""));
  ASSERT_EQ(m.joints.size(), 3u);
  const auto expect_joint = [&](std::size_t i, const char* name, const char* type, const char* parent,
                                const char* child) {
    EXPECT_EQ(m.joints[i].name, name);
    EXPECT_EQ(m.joints[i].type, type);
    EXPECT_EQ(m.joints[i].parent, parent);
    EXPECT_EQ(m.joints[i].child, child);
    EXPECT_EQ(m.joints[i].line, m.links[i].line);
  };
  expect_joint(0, "", "fixed", "world", "base");          // no joint: welded
  expect_joint(1, "shoulder", "hinge", "base", "upper");  // MuJoCo's default joint type
  expect_joint(2, "wrist", "ball", "upper", "body#3");
  // The world's plane is scenery: no link, nothing skipped.
  for (const Link& l : m.links) EXPECT_TRUE(l.skipped.empty()) << l.name;
  for (const Link& l : m.links) EXPECT_TRUE(l.visual.empty()) << l.name;
}

TEST(ReadMjcf, BodyPosesFollowMuJoCosOrientationRules) {
  const RobotModel m = read("arm.xml", kArm);
  // euler="0 0 90" in degrees (MuJoCo's default unit): Rz(90°).
  EXPECT_EQ(m.joints[0].origin.p, Vec3(0, 0, 0.1));
  expect_near(m.joints[0].origin.R, rows({0, -1, 0, 1, 0, 0, 0, 0, 1}), kRotationTolerance);
  // quat="2 2 0 0" is normalised: Rx(90°).
  EXPECT_EQ(m.joints[1].origin.p, Vec3(0, 0, 0.2));
  expect_near(m.joints[1].origin.R, rows({1, 0, 0, 0, 0, -1, 0, 1, 0}), kRotationTolerance);
  // xyaxes="0 1 0 -1 0 0": the columns are x, y and x × y, exactly (unit axes, no rounding).
  EXPECT_EQ(m.joints[2].origin.R, rows({0, -1, 0, 1, 0, 0, 0, 0, 1}));
}

TEST(ReadMjcf, GeomShapesAreFullSizesFromMuJoCosHalfSizes) {
  const RobotModel m = read("arm.xml", kArm);
  const Geometry& plinth = geom(link(m, "base"), "plinth");
  EXPECT_EQ(plinth.element, "geom");
  EXPECT_EQ(plinth.line, line_of(kArm, "name=\"plinth\""));
  ASSERT_TRUE(plinth.shape && std::holds_alternative<Box>(*plinth.shape));
  EXPECT_EQ(std::get<Box>(*plinth.shape).size, Vec3(0.2, 0.4, 0.6));  // 2 × half-size: exact doubling
  EXPECT_FALSE(plinth.mass);
  EXPECT_EQ(plinth.density, 1000.0);  // MuJoCo's default density
  EXPECT_TRUE(plinth.mesh_uri.empty());

  const Link& last = link(m, "body#3");
  const Geometry& can = geom(last, "can");
  ASSERT_TRUE(can.shape && std::holds_alternative<Cylinder>(*can.shape));
  EXPECT_EQ(std::get<Cylinder>(*can.shape).radius, 0.03);
  EXPECT_EQ(std::get<Cylinder>(*can.shape).length, 0.2);
  // zaxis="1 0 0": the minimal rotation taking z to x, Ry(90°).
  expect_near(can.pose.R, rows({0, 0, 1, 0, 1, 0, -1, 0, 0}), kRotationTolerance);
  EXPECT_EQ(can.pose.p, Vec3::Zero());

  const Geometry& egg = geom(last, "egg");
  ASSERT_TRUE(egg.shape && std::holds_alternative<Ellipsoid>(*egg.shape));
  EXPECT_EQ(std::get<Ellipsoid>(*egg.shape).semi_axes, Vec3(0.01, 0.02, 0.03));
  expect_near(egg.pose.R, rows({0, -1, 0, 1, 0, 0, 0, 0, 1}), kRotationTolerance);  // axisangle z 90°

  const Geometry& ball = geom(last, "ball");  // type defaults to sphere
  ASSERT_TRUE(ball.shape && std::holds_alternative<Sphere>(*ball.shape));
  EXPECT_EQ(std::get<Sphere>(*ball.shape).radius, 0.05);
  EXPECT_EQ(ball.pose.p, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(ball.pose.R, Mat3::Identity());
}

TEST(ReadMjcf, AFromtoCapsuleIsCentredBetweenItsPointsAlongTheSegment) {
  const RobotModel m = read("arm.xml", kArm);
  const Geometry& bone = geom(link(m, "upper"), "bone");
  ASSERT_TRUE(bone.shape && std::holds_alternative<Capsule>(*bone.shape));
  EXPECT_EQ(std::get<Capsule>(*bone.shape).radius, 0.04);
  // The length of the cylindrical part is the distance, |(0.3, 0, 0.4)| = 0.5: one rounding in the sum
  // of squares and one in the root.
  EXPECT_NEAR(std::get<Capsule>(*bone.shape).length, 0.5, 1e-15 * 0.5);
  EXPECT_EQ(bone.pose.p, Vec3(0.3 / 2, 0, 0.4 / 2));  // the midpoint: halving is exact
  // z along the segment: MuJoCo's compiler turns it towards "from" − "to" (mjCGeom::Compile), the
  // opposite of its documentation's wording; a capsule is the same either way.
  const Vec3 z = bone.pose.R.col(2);
  EXPECT_LE((z - Vec3(-0.6, 0, -0.8)).cwiseAbs().maxCoeff(), kRotationTolerance) << z.transpose();
  EXPECT_LE((bone.pose.R.transpose() * bone.pose.R - Mat3::Identity()).cwiseAbs().maxCoeff(),
            kRotationTolerance);
}

TEST(ReadMjcf, FromtoGivesBoxesAndCylindersTheirLengthAlongTheSegment) {
  const RobotModel m = read("fromto.xml", R"(<mujoco><worldbody><body name="b">
    <geom name="rod" type="cylinder" fromto="0 0 -0.1 0 0 0.1" size="0.02 9"/>
    <geom name="bar" type="box" fromto="1 0 0 1 0 0.5" size="0.05"/>
    <geom name="cigar" type="ellipsoid" fromto="0 0 0 0 0 2" size="0.25"/>
  </body></worldbody></mujoco>)");
  const Link& b = link(m, "b");
  // fromto overrides the size's length number (9 here).
  EXPECT_EQ(std::get<Cylinder>(*geom(b, "rod").shape).length, 0.2);
  // MuJoCo's z is towards from − to = (0, 0, −0.2): along −z, the rotation by π about x.
  expect_near(geom(b, "rod").pose.R, rows({1, 0, 0, 0, -1, 0, 0, 0, -1}), kRotationTolerance);
  EXPECT_EQ(std::get<Box>(*geom(b, "bar").shape).size, Vec3(0.1, 0.1, 0.5));
  EXPECT_EQ(geom(b, "bar").pose.p, Vec3(1, 0, 0.25));
  EXPECT_EQ(std::get<Ellipsoid>(*geom(b, "cigar").shape).semi_axes, Vec3(0.25, 0.25, 1));
}

TEST(ReadMjcf, EulerAnglesAreDegreesUnlessTheCompilerSaysRadianAndFollowEulerseq) {
  const auto rotation = [](const std::string& compiler, const std::string& euler) {
    const RobotModel m = read("euler.xml", "<mujoco>" + compiler + "<worldbody><body name=\"b\" euler=\"" +
                                               euler + "\"/></worldbody></mujoco>");
    return m.joints.at(0).origin.R;
  };
  const double a = std::numbers::pi / 6, b = std::numbers::pi / 4, c = std::numbers::pi / 3;
  // Lowercase: rotating axes, x then the new y then the newer z: Rx Ry Rz.
  const Mat3 intrinsic = Rx(a) * Ry(b) * Rz(c);
  expect_near(rotation("", "30 45 60"), intrinsic, kRotationTolerance);
  expect_near(rotation("<compiler angle=\"degree\"/>", "30 45 60"), intrinsic, kRotationTolerance);
  expect_near(rotation("<compiler angle=\"radian\"/>",
                       "0.5235987755982988 0.7853981633974483 1.0471975511965976"),
              intrinsic, kRotationTolerance);
  // Uppercase: fixed axes, x then y then z about the parent's axes: Rz Ry Rx.
  expect_near(rotation("<compiler eulerseq=\"XYZ\"/>", "30 45 60"), Rz(c) * Ry(b) * Rx(a),
              kRotationTolerance);
  expect_near(rotation("<compiler eulerseq=\"zyx\"/>", "30 45 60"), Rz(a) * Ry(b) * Rx(c),
              kRotationTolerance);
  // axisangle takes the compiler's unit too.
  const RobotModel m = read("axisangle.xml", R"(<mujoco><compiler angle="radian"/><worldbody>
    <body name="b" axisangle="0 0 2 1.5707963267948966"/></worldbody></mujoco>)");
  expect_near(m.joints[0].origin.R, rows({0, -1, 0, 1, 0, 0, 0, 0, 1}), kRotationTolerance);
}

const std::string kDefaults = R"(<mujoco model="defaults">
  <default>
    <geom density="500" size="0.1"/>
    <joint type="slide"/>
    <default class="limb">
      <geom type="capsule" size="0.05 0.2" euler="0 90 0"/>
      <default class="heavy">
        <geom density="8000"/>
      </default>
      <default class="loose">
        <joint type="ball"/>
      </default>
    </default>
  </default>
  <worldbody>
    <body name="a">
      <joint/>
      <geom name="plain"/>
      <body name="b" childclass="limb">
        <joint class="loose"/>
        <joint type="slide"/>
        <geom name="limb"/>
        <geom name="dense" class="heavy" size="0.02"/>
        <geom name="own_euler" type="box" size="0.1 0.1 0.1" euler="0 0 0"/>
        <geom name="own_quat" type="box" size="0.1 0.1 0.1" quat="1 0 0 0"/>
        <geom name="from_main" class="main"/>
        <body name="c">
          <joint/>
          <geom name="inherited" mass="2"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
)";

TEST(ReadMjcf, GeomsAndJointsTakeTheirDefaultClassesAttributes) {
  const RobotModel m = read("defaults.xml", kDefaults);
  // a: the top-level class "main".
  EXPECT_EQ(m.joints[0].type, "slide");
  const Geometry& plain = geom(link(m, "a"), "plain");
  EXPECT_EQ(std::get<Sphere>(*plain.shape).radius, 0.1);
  EXPECT_EQ(plain.density, 500.0);
  // b: childclass "limb"; its first joint names class "loose" (ball); the second does not count.
  EXPECT_EQ(m.joints[1].type, "ball");
  const Link& b = link(m, "b");
  const Geometry& limb = geom(b, "limb");
  ASSERT_TRUE(std::holds_alternative<Capsule>(*limb.shape));
  EXPECT_EQ(std::get<Capsule>(*limb.shape).radius, 0.05);
  EXPECT_EQ(std::get<Capsule>(*limb.shape).length, 0.4);
  EXPECT_EQ(limb.density, 500.0);  // "limb" inherits main's density
  expect_near(limb.pose.R, rows({0, 0, 1, 0, 1, 0, -1, 0, 0}),
              kRotationTolerance);  // the class's euler: Ry(90°)
  // "heavy" nests in "limb": its capsule, its density; size="0.02" replaces the radius only (MuJoCo
  // reads a partial size over the class's).
  const Geometry& dense = geom(b, "dense");
  EXPECT_EQ(std::get<Capsule>(*dense.shape).radius, 0.02);
  EXPECT_EQ(std::get<Capsule>(*dense.shape).length, 0.4);
  EXPECT_EQ(dense.density, 8000.0);
  // The geom's own euler wins over the class's; its own quat does not (MuJoCo's rule), with a note.
  EXPECT_EQ(geom(b, "own_euler").pose.R, Mat3::Identity());
  expect_near(geom(b, "own_quat").pose.R, rows({0, 0, 1, 0, 1, 0, -1, 0, 0}), kRotationTolerance);
  EXPECT_TRUE(contains(m.notes, "quat is overridden")) << ::testing::PrintToString(m.notes);
  // class="main" leaves the childclass.
  const Geometry& from_main = geom(b, "from_main");
  EXPECT_TRUE(std::holds_alternative<Sphere>(*from_main.shape));
  EXPECT_EQ(from_main.pose.R, Mat3::Identity());
  // c inherits b's childclass: a capsule; its joint from "limb", which inherits main's slide.
  EXPECT_EQ(m.joints[2].type, "slide");
  const Geometry& inherited = geom(link(m, "c"), "inherited");
  EXPECT_TRUE(std::holds_alternative<Capsule>(*inherited.shape));
  ASSERT_TRUE(inherited.mass);
  EXPECT_EQ(*inherited.mass, 2.0);
}

TEST(ReadMjcf, OnlyGeomsInTheInertiaGroupRangeCarryMass) {
  const std::string text = R"(<mujoco>
  <compiler inertiagrouprange="0 2"/>
  <default><default class="visual"><geom group="3"/></default></default>
  <asset><hfield name="h" nrow="2" ncol="2" size="1 1 1 0.1"/></asset>
  <worldbody><body name="b">
    <geom name="g0" size="0.1"/>
    <geom name="g2" size="0.1" group="2"/>
    <geom name="g3" size="0.1" group="3"/>
    <geom name="by_class" class="visual" size="0.1"/>
    <geom name="ground" type="plane" size="1 1 1"/>
    <geom name="weightless" size="0.1" mass="0"/>
    <geom name="airy" size="0.1" density="0"/>
    <geom name="terrain" type="hfield" hfield="h"/>
  </body></worldbody>
</mujoco>)";
  const RobotModel m = read("groups.xml", text);
  const Link& b = link(m, "b");
  ASSERT_EQ(b.collision.size(), 2u);
  EXPECT_EQ(b.collision[0].name, "g0");
  EXPECT_EQ(b.collision[1].name, "g2");
  ASSERT_EQ(b.skipped.size(), 4u) << ::testing::PrintToString(b.skipped);
  EXPECT_EQ(b.skipped[0], fmt::format("geom 'ground' (plane) at line {}: MuJoCo gives planes no mass",
                                      line_of(text, "\"ground\"")));
  EXPECT_NE(b.skipped[1].find("'weightless'"), std::string::npos);
  EXPECT_NE(b.skipped[2].find("'airy'"), std::string::npos);
  EXPECT_NE(b.skipped[3].find("'terrain' (hfield)"), std::string::npos);
  // MuJoCo's default range is 0 to 5: group 3 counts, group 6 does not.
  const RobotModel d = read("groups_default.xml", R"(<mujoco><worldbody><body name="b">
    <geom name="g3" size="0.1" group="3"/><geom name="g6" size="0.1" group="6"/>
  </body></worldbody></mujoco>)");
  ASSERT_EQ(link(d, "b").collision.size(), 1u);
  EXPECT_EQ(link(d, "b").collision[0].name, "g3");
}

TEST(ReadMjcf, MeshGeomsNameTheirAssetsFileResolvedAgainstMeshdirWithItsScale) {
  const RobotModel m = read("meshes.xml", R"(<mujoco>
  <compiler meshdir="meshes"/>
  <default>
    <mesh scale="2 2 2"/>
    <default class="mm"><mesh scale="0.001 0.001 0.001"/></default>
  </default>
  <asset>
    <mesh name="shell" file="parts/shell.stl" class="mm"/>
    <mesh file="hand.obj"/>
    <mesh name="absolute" file="/opt/robot/x.stl" scale="1 2 3"/>
  </asset>
  <worldbody><body name="b">
    <geom name="s" type="mesh" mesh="shell" pos="0 0 1"/>
    <geom name="h" type="mesh" mesh="hand"/>
    <geom name="a" type="mesh" mesh="absolute" density="2700"/>
  </body></worldbody>
</mujoco>)");
  const Link& b = link(m, "b");
  const std::filesystem::path dir = model_dir();
  const Geometry& s = geom(b, "s");
  EXPECT_FALSE(s.shape);
  EXPECT_EQ(s.mesh_uri, "parts/shell.stl");
  EXPECT_EQ(s.mesh_path, dir / "meshes" / "parts" / "shell.stl");
  EXPECT_EQ(s.scale, Vec3::Constant(0.001));  // class "mm"
  EXPECT_EQ(s.pose.p, Vec3(0, 0, 1));
  const Geometry& h = geom(b, "h");  // an unnamed asset is named by its file's stem
  EXPECT_EQ(h.mesh_uri, "hand.obj");
  EXPECT_EQ(h.mesh_path, dir / "meshes" / "hand.obj");
  EXPECT_EQ(h.scale, Vec3::Constant(2));  // the top-level class
  const Geometry& a = geom(b, "a");
  EXPECT_EQ(a.mesh_path, std::filesystem::path("/opt/robot/x.stl"));
  EXPECT_EQ(a.scale, Vec3(1, 2, 3));
  EXPECT_EQ(a.density, 2700.0);
}

TEST(ReadMjcf, AssetdirAndStrippathPlaceMeshFilesAsMuJoCoDoes) {
  const RobotModel m = read("assetdir.xml", R"(<mujoco>
  <compiler assetdir="assets" strippath="true"/>
  <asset><mesh name="m" file="deep/er/part.stl" refpos="0 0 1"/></asset>
  <worldbody><body name="b"><geom name="g" type="mesh" mesh="m"/></body></worldbody>
</mujoco>)");
  const Geometry& g = geom(link(m, "b"), "g");
  EXPECT_EQ(g.mesh_uri, "deep/er/part.stl");
  EXPECT_EQ(g.mesh_path, model_dir() / "assets" / "part.stl");
  // refpos: MuJoCo subtracts it from the vertices, so the mesh sits 1 lower in the geom's frame.
  EXPECT_EQ(g.pose.p, Vec3(0, 0, -1));
}

TEST(ReadMjcf, FramesPlaceTheGeomsAndBodiesInsideThem) {
  const RobotModel m = read("frames.xml", R"(<mujoco><worldbody>
  <frame pos="0 0 1"><body name="a">
    <freejoint name="float"/>
    <frame pos="1 0 0" xyaxes="0 1 0 -1 0 0">
      <geom name="g" size="0.1" pos="1 0 0"/>
      <body name="b" pos="0 1 0"/>
    </frame>
  </body></frame>
</worldbody></mujoco>)");
  EXPECT_EQ(m.joints[0].origin.p, Vec3(0, 0, 1));
  EXPECT_EQ(m.joints[0].type, "free");
  EXPECT_EQ(m.joints[0].name, "float");
  EXPECT_EQ(m.joints[1].type, "fixed");
  // The frame turns x into y and y into −x: exact (unit axes).
  EXPECT_EQ(geom(link(m, "a"), "g").pose.p, Vec3(1, 1, 0));
  EXPECT_EQ(m.joints[1].parent, "a");
  EXPECT_EQ(m.joints[1].origin.p, Vec3(0, 0, 0));
  EXPECT_EQ(m.joints[1].origin.R, rows({0, -1, 0, 1, 0, 0, 0, 0, 1}));
}

const std::string kInertials = R"(<mujoco>
  <worldbody>
    <body name="diagonal">
      <inertial pos="0.1 0.2 0.3" mass="3.70" diaginertia="0.1 0.2 0.3"/>
    </body>
    <body name="full">
      <inertial pos="0 0 0" mass="1" fullinertia="0.4 0.5 0.6 -0.01 -0.02 -0.03"/>
    </body>
    <body name="turned">
      <inertial mass="2" pos="0 0 0" euler="0 0 90" diaginertia="1 2 3"></inertial>
    </body>
    <body name="identity">
      <inertial pos="0 0 0" mass="2" quat="1 0 0 0" diaginertia="1 2 3"/>
    </body>
    <body name="none"><geom size="0.1"/></body>
  </worldbody>
</mujoco>
)";

TEST(ReadMjcf, InertialsAreReadWithTheirFrameTensorAndSpan) {
  const RobotModel m = read("inertials.xml", kInertials);
  const Inertial& d = *link(m, "diagonal").inertial;
  EXPECT_EQ(d.mass, 3.7);
  EXPECT_EQ(d.mass_text, "3.70");
  EXPECT_EQ(d.frame.p, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(d.frame.R, Mat3::Identity());
  EXPECT_FALSE(d.rotated);
  EXPECT_EQ(d.inertia_written, Mat3(Vec3(0.1, 0.2, 0.3).asDiagonal()));
  const std::string element = m.text.substr(d.span.begin, d.span.end - d.span.begin);
  EXPECT_EQ(element, "<inertial pos=\"0.1 0.2 0.3\" mass=\"3.70\" diaginertia=\"0.1 0.2 0.3\"/>");
  EXPECT_EQ(d.span.line, line_of(kInertials, "<inertial pos=\"0.1"));

  // fullinertia="ixx iyy izz ixy ixz iyz", symmetric, in the body's axes.
  const Inertial& f = *link(m, "full").inertial;
  EXPECT_EQ(f.inertia_written, rows({0.4, -0.01, -0.02, -0.01, 0.5, -0.03, -0.02, -0.03, 0.6}));
  EXPECT_FALSE(f.rotated);
  const std::string full = m.text.substr(f.span.begin, f.span.end - f.span.begin);
  EXPECT_EQ(full.rfind("<inertial", 0), 0u);
  EXPECT_EQ(full.substr(full.size() - 2), "/>");

  const Inertial& t = *link(m, "turned").inertial;
  EXPECT_TRUE(t.rotated);
  expect_near(t.frame.R, rows({0, -1, 0, 1, 0, 0, 0, 0, 1}), kRotationTolerance);
  const std::string turned = m.text.substr(t.span.begin, t.span.end - t.span.begin);
  EXPECT_EQ(turned, "<inertial mass=\"2\" pos=\"0 0 0\" euler=\"0 0 90\" diaginertia=\"1 2 3\"></inertial>");

  EXPECT_FALSE(link(m, "identity").inertial->rotated);  // an orientation, but the identity
  EXPECT_FALSE(link(m, "none").inertial);               // MuJoCo infers it from the geoms
}

TEST(ReadMjcf, NotesSayWhatTheReaderLeavesToMuJoCo) {
  const RobotModel m = read("notes.xml", R"(<mujoco>
  <include file="more.xml"/>
  <compiler inertiafromgeom="true"/>
  <worldbody>
    <body name="b"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/>
      <replicate count="3" offset="0 0 1"><geom size="0.1"/></replicate>
    </body>
  </worldbody>
</mujoco>)");
  ASSERT_EQ(m.notes.size(), 3u) << ::testing::PrintToString(m.notes);
  EXPECT_NE(m.notes[0].find("notes.xml:2: <include file=\"more.xml\"> is not followed"), std::string::npos);
  EXPECT_NE(m.notes[1].find("inertiafromgeom=\"true\""), std::string::npos);
  EXPECT_NE(m.notes[2].find("<replicate> is not expanded"), std::string::npos);
  EXPECT_TRUE(link(m, "b").collision.empty());
}

TEST(ReadMjcf, BadValuesAreRefusedWithTheLineAndWhatIsExpected) {
  const auto refused = [](const std::string& text, const std::string& fragment) {
    const std::string message = error_of(text);
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  };
  refused("<mujoco><worldbody><body name='b'>\n<geom type='mesh' mesh='nosuch'/></body></worldbody></mujoco>",
          "bad.xml:2: <geom>: mesh=\"nosuch\" names no <asset><mesh>");
  refused(
      "<mujoco><worldbody><body name='b'>\n"
      "<inertial pos='0 0 0' mass='1' fullinertia='1 1 1 0 0'/></body></worldbody></mujoco>",
      "bad.xml:2: <inertial>: fullinertia=\"1 1 1 0 0\" has 5 numbers; it needs 6");
  refused(
      "<mujoco><worldbody><body name='b'>\n<inertial pos='0 0 0' diaginertia='1 1 "
      "1'/></body></worldbody></mujoco>",
      "bad.xml:2: <inertial>: needs mass");
  refused("<mujoco><worldbody><body name='b'>\n<inertial pos='0 0 0' mass='1'/></body></worldbody></mujoco>",
          "bad.xml:2: <inertial>: needs diaginertia");
  refused(
      "<mujoco><worldbody><body name='b'>\n"
      "<inertial pos='0 0 0' mass='1' diaginertia='1 1 1' fullinertia='1 1 1 0 0 "
      "0'/></body></worldbody></mujoco>",
      "bad.xml:2: <inertial>: has both diaginertia and fullinertia");
  refused(
      "<mujoco><worldbody><body name='b'>\n<inertial mass='1' diaginertia='1 1 "
      "1'/></body></worldbody></mujoco>",
      "bad.xml:2: <inertial>: needs pos");
  refused("<mujoco><worldbody>\n<body name='b' quat='1 0 0 0' euler='0 0 0'/></worldbody></mujoco>",
          "bad.xml:2: <body>: has both quat and euler");
  refused("<mujoco><worldbody>\n<body name='b' quat='0 0 0 0'/></worldbody></mujoco>",
          "bad.xml:2: <body>: quat=");
  refused("<mujoco><worldbody><body name='b'>\n<geom class='nosuch' size='1'/></body></worldbody></mujoco>",
          "bad.xml:2: <geom>: class=\"nosuch\" names no <default> class");
  refused("<mujoco><worldbody><body name='b'>\n<geom type='capsule' size='0.1'/></body></worldbody></mujoco>",
          "bad.xml:2: <geom>: a capsule needs size=");
  refused(
      "<mujoco><worldbody><body name='b'>\n<geom type='box' size='0.1 0 0.1'/></body></worldbody></mujoco>",
      "bad.xml:2: <geom>: size number 2 of the box is 0");
  refused(
      "<mujoco><worldbody><body name='b'>\n<geom type='sphere' fromto='0 0 0 0 0 1' size='1'/>"
      "</body></worldbody></mujoco>",
      "bad.xml:2: <geom>: fromto is for capsule");
  refused(
      "<mujoco><default><geom pos='0 0 1'/></default><worldbody><body name='b'>\n"
      "<geom type='capsule' fromto='0 0 0 0 0 1' size='0.1'/></body></worldbody></mujoco>",
      "bad.xml:2: <geom>: has both pos (from its default class, line 1) and fromto");
  refused("<mujoco><worldbody><body name='b'>\n<geom size='0.1' mass='-1'/></body></worldbody></mujoco>",
          "bad.xml:2: <geom>: mass=\"-1\" is negative");
  refused("<mujoco><worldbody><body name='b' childclass='nosuch'/></worldbody></mujoco>",
          "bad.xml:1: <body>: childclass=\"nosuch\" names no <default> class");
  refused("<mujoco><worldbody><body name='b'/>\n<body name='b'/></worldbody></mujoco>",
          "bad.xml:2: <body>: repeated body name \"b\" (also at line 1)");
  refused("<mujoco><compiler angle='grad'/></mujoco>", "angle=\"grad\" must be \"degree\" or \"radian\"");
  refused("<mujoco><compiler eulerseq='xyw'/></mujoco>", "eulerseq=\"xyw\" must be three letters");
  refused("<mujoco><worldbody><body name='b'>\n<joint type='hinged'/></body></worldbody></mujoco>",
          "bad.xml:2: <joint>: type=\"hinged\" is not a MuJoCo joint type");
}

TEST(ReadMjcf, DeeplyNestedBodiesAreRefusedNotOverflowed) {
  std::string deep = "<mujoco><worldbody>";
  for (int i = 0; i < 1001; ++i) deep += "<body>";
  for (int i = 0; i < 1001; ++i) deep += "</body>";
  deep += "</worldbody></mujoco>";
  EXPECT_NE(error_of(deep).find("nest deeper than 1000 levels"), std::string::npos);
  // 1000 levels are read.
  std::string ok = "<mujoco><worldbody>";
  for (int i = 0; i < 1000; ++i) ok += "<body>";
  for (int i = 0; i < 1000; ++i) ok += "</body>";
  ok += "</worldbody></mujoco>";
  const RobotModel m = read("deep.xml", ok);
  ASSERT_EQ(m.links.size(), 1000u);
  EXPECT_EQ(m.joints.back().parent, "body#999");
  EXPECT_EQ(m.joints.back().child, "body#1000");
}

}  // namespace
}  // namespace tumble::robot
