// The SDFormat reader: link, inertial and geometry poses through SDFormat's frames (relative_to,
// attached_to, nested models), every primitive and meshes, joint origins from the links' poses, and
// errors that name the file and line. Each expected value is worked by hand in the comments.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

#include "tumble/error.hpp"
#include "tumble/robot/robot_model.hpp"

namespace tumble::robot {
namespace {

namespace fs = std::filesystem;

/// The files the tests wrote, removed when the program ends.
struct Written {
  std::vector<fs::path> paths;
  ~Written() {
    std::error_code ec;
    for (const fs::path& p : paths) fs::remove(p, ec);
  }
};

fs::path write_sdf(const std::string& name, const std::string& text) {
  static Written written;
  const fs::path p = fs::path(testing::TempDir()) /
                     ("tumble_read_sdf_" + std::to_string(::getpid()) + "_" + name + ".sdf");
  std::ofstream(p, std::ios::binary) << text;
  written.paths.push_back(p);
  return p;
}

RobotModel read(const std::string& name, const std::string& text) {
  return read_robot_model(write_sdf(name, text));
}

/// The message of the InvalidArgument that reading `text` throws ("" if none).
std::string error_of(const std::string& name, const std::string& text) {
  try {
    (void)read(name, text);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

/// The line (1-based) of the first occurrence of `needle`.
int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

/// "path:line:", as the messages of a file `name` start.
std::string where(const std::string& name, const std::string& text, const std::string& needle) {
  return write_sdf(name, text).string() + ":" + std::to_string(line_of(text, needle)) + ":";
}

const Link& link(const RobotModel& m, const std::string& name) {
  for (const Link& l : m.links)
    if (l.name == name) return l;
  throw std::runtime_error("no link " + name);
}

const Joint& joint(const RobotModel& m, const std::string& name) {
  for (const Joint& j : m.joints)
    if (j.name == name) return j;
  throw std::runtime_error("no joint " + name);
}

bool has_note(const RobotModel& m, const std::string& part) {
  return std::any_of(m.notes.begin(), m.notes.end(),
                     [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

/// A quarter turn about z, exactly.
Mat3 rz90() { return (Mat3() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished(); }

/// The largest entry of |A − B|.
double diff(const Mat3& A, const Mat3& B) { return (A - B).cwiseAbs().maxCoeff(); }

// cos(π/2) in double is 6.1e-17, not 0: a rotation by a yaw of 1.5707963267948966 is the exact quarter
// turn to within that, and products of such rotations to within a few times it. Hence the 1e-15
// tolerances below wherever such a rotation enters; everything else is exact.

TEST(ReadSdf, ThreeLinksPosedInTheModelFrameAndTheJointOriginsBetweenThem) {
  const std::string text = R"(<?xml version="1.0"?>
<sdf version="1.10">
  <model name="arm">
    <link name="base">
      <pose>0 0 0.1 0 0 0</pose>
    </link>
    <link name="upper">
      <pose>0 0 0.5 0 0 1.5707963267948966</pose>
    </link>
    <link name="fore">
      <pose relative_to="upper">0.3 0 0 0 0 0</pose>
    </link>
    <joint name="anchor" type="fixed">
      <parent>world</parent>
      <child>base</child>
    </joint>
    <joint name="shoulder" type="revolute">
      <pose>0 0 -0.2 0 0 0</pose>
      <parent>base</parent>
      <child>upper</child>
    </joint>
    <joint name="elbow" type="revolute">
      <parent>upper</parent>
      <child>fore</child>
    </joint>
  </model>
</sdf>
)";
  const RobotModel m = read("three_links", text);
  EXPECT_EQ(m.format, Format::sdf);
  EXPECT_EQ(m.name, "arm");
  ASSERT_EQ(m.links.size(), 3u);
  EXPECT_EQ(m.links[0].name, "base");
  EXPECT_EQ(m.links[1].name, "upper");
  EXPECT_EQ(m.links[2].name, "fore");
  EXPECT_EQ(m.links[2].line, line_of(text, "<link name=\"fore\">"));
  EXPECT_FALSE(m.links[0].inertial);
  ASSERT_EQ(m.joints.size(), 3u);

  // anchor: the world holds base at its model-frame pose, (0, 0, 0.1) unrotated — exact.
  const Joint& anchor = joint(m, "anchor");
  EXPECT_EQ(anchor.parent, "world");
  EXPECT_EQ(anchor.child, "base");
  EXPECT_EQ(anchor.type, "fixed");
  EXPECT_EQ(anchor.line, line_of(text, "<joint name=\"anchor\""));
  EXPECT_EQ(anchor.origin.p, Vec3(0, 0, 0.1));
  EXPECT_EQ(anchor.origin.R, Mat3::Identity());

  // shoulder: upper in base = base⁻¹ upper = (0, 0, 0.5 − 0.1) turned a quarter about z. The joint's own
  // pose (in upper's frame) moves no link and does not enter. 0.5 − 0.1 rounds once (1e-16).
  const Joint& shoulder = joint(m, "shoulder");
  EXPECT_EQ(shoulder.parent, "base");
  EXPECT_EQ(shoulder.child, "upper");
  EXPECT_LT((shoulder.origin.p - Vec3(0, 0, 0.4)).norm(), 1e-16);
  EXPECT_LT(diff(shoulder.origin.R, rz90()), 1e-15);

  // elbow: fore is written 0.3 along upper's x, so in upper's frame it is (0.3, 0, 0), unrotated; the
  // reader goes through the model frame (Rz · (0.3, 0, 0) and back by Rzᵀ): a few roundings, 1e-15.
  const Joint& elbow = joint(m, "elbow");
  EXPECT_LT((elbow.origin.p - Vec3(0.3, 0, 0)).norm(), 1e-15);
  EXPECT_LT(diff(elbow.origin.R, Mat3::Identity()), 1e-15);
}

TEST(ReadSdf, RotatedInertialGivesTheTensorInTheLinkAxesAndItsSpan) {
  const std::string text = R"(<sdf version="1.9">
  <model name="m">
    <link name="body">
      <inertial>
        <pose>0.1 0.2 0.3 0 0 1.5707963267948966</pose>
        <mass> 2.50 </mass>
        <inertia>
          <ixx>1</ixx>
          <ixy>0.5</ixy>
          <ixz>0</ixz>
          <iyy>2</iyy>
          <iyz>0</iyz>
          <izz>3</izz>
        </inertia>
      </inertial>
    </link>
  </model>
</sdf>
)";
  const RobotModel m = read("rotated_inertial", text);
  ASSERT_TRUE(link(m, "body").inertial);
  const Inertial& in = *link(m, "body").inertial;
  EXPECT_EQ(in.mass, 2.5);  // parsed, exact
  EXPECT_EQ(in.mass_text, "2.50");
  EXPECT_EQ(in.frame.p, Vec3(0.1, 0.2, 0.3));  // the same decimal text as these literals: exact
  EXPECT_TRUE(in.rotated);
  Mat3 written;
  written << 1, 0.5, 0, 0.5, 2, 0, 0, 0, 3;
  EXPECT_EQ(in.inertia_written, written);
  // R I Rᵀ with R the quarter turn about z: x → y, y → −x, so I'xx = Iyy = 2, I'yy = Ixx = 1,
  // I'xy = −Ixy = −0.5, I'zz = 3. Entries up to 3 times cos(π/2)'s 6e-17: 1e-15.
  Mat3 in_link;
  in_link << 2, -0.5, 0, -0.5, 1, 0, 0, 0, 3;
  EXPECT_LT(diff(in.inertia_link(), in_link), 1e-15);
  // The span is the whole element, for a fix that rewrites it alone.
  const std::string span = m.text.substr(in.span.begin, in.span.end - in.span.begin);
  EXPECT_EQ(span.rfind("<inertial>", 0), 0u) << span;
  EXPECT_EQ(span.substr(span.size() - 11), "</inertial>");
  EXPECT_EQ(in.span.line, line_of(text, "<inertial>"));
}

TEST(ReadSdf, InertialDefaultsAreSdformatsAndTheNotesSaySo) {
  const std::string text = R"(<sdf version="1.11">
  <model name="m">
    <static>true</static>
    <link name="bare">
      <inertial/>
    </link>
    <link name="partial">
      <inertial>
        <mass>3</mass>
        <inertia><ixx>0.2</ixx><iyy>0.3</iyy></inertia>
      </inertial>
    </link>
    <link name="computed">
      <inertial auto="true"><mass>4</mass></inertial>
    </link>
    <link name="computed_written">
      <inertial auto="true"><mass>4</mass><inertia><ixx>2</ixx><iyy>2</iyy><izz>2</izz></inertia></inertial>
    </link>
  </model>
</sdf>
)";
  const RobotModel m = read("inertial_defaults", text);
  // No <mass>: 1 kg, written back as "1"; no <inertia>: the identity (SDFormat's defaults).
  const Inertial& bare = *link(m, "bare").inertial;
  EXPECT_EQ(bare.mass, 1.0);
  EXPECT_EQ(bare.mass_text, "1");
  EXPECT_EQ(bare.inertia_written, Mat3::Identity());
  EXPECT_FALSE(bare.rotated);
  EXPECT_EQ(bare.frame.p, Vec3::Zero());
  // izz missing: 1; the products missing: 0.
  const Inertial& partial = *link(m, "partial").inertial;
  EXPECT_EQ(partial.inertia_written, Vec3(0.2, 0.3, 1.0).asDiagonal().toDenseMatrix());
  // auto="true" without <inertia>: the simulator computes it, nothing to audit; with one: read as written.
  EXPECT_FALSE(link(m, "computed").inertial);
  ASSERT_TRUE(link(m, "computed_written").inertial);
  EXPECT_EQ(link(m, "computed_written").inertial->inertia_written, 2 * Mat3::Identity());
  EXPECT_TRUE(has_note(m, "link 'bare': <inertial> at line 5 has no <mass>"));
  EXPECT_TRUE(has_note(m, "link 'bare': <inertial> at line 5 has no <inertia>"));
  EXPECT_TRUE(has_note(m, "lacks ixy, ixz, iyz, izz"));
  EXPECT_TRUE(has_note(m, "link 'computed': <inertial auto=\"true\">"));
  EXPECT_TRUE(has_note(m, "model 'm' is static"));
}

TEST(ReadSdf, EveryPrimitiveAndMeshesWithTheirScaleAndFiles) {
  const std::string text = R"(<sdf version="1.11">
  <model name="shapes">
    <link name="l">
      <pose>1 0 0 0 0 0</pose>
      <collision name="box"><geometry><box><size>0.1 0.2 0.3</size></box></geometry></collision>
      <collision name="sphere"><geometry><sphere><radius>0.05</radius></sphere></geometry></collision>
      <collision name="cylinder">
        <pose>0 0 0.5 0 0 0</pose>
        <geometry><cylinder><radius>0.04</radius><length>0.3</length></cylinder></geometry>
      </collision>
      <collision name="capsule"><geometry><capsule><radius>0.03</radius><length>0.2</length></capsule></geometry></collision>
      <collision name="ellipsoid"><geometry><ellipsoid><radii>0.1 0.2 0.3</radii></ellipsoid></geometry></collision>
      <collision name="cone"><geometry><cone><radius>0.1</radius><length>0.4</length></cone></geometry></collision>
      <collision name="in_model">
        <pose relative_to="__model__">0 0 2 0 0 0</pose>
        <geometry><sphere><radius>1</radius></sphere></geometry>
      </collision>
      <collision name="ground"><geometry><plane><normal>0 0 1</normal></plane></geometry></collision>
      <collision name="terrain"><geometry><heightmap><uri>h.png</uri></heightmap></geometry></collision>
      <collision name="outline"><geometry><polyline><height>1</height></polyline></geometry></collision>
      <visual name="part">
        <geometry><mesh><uri> meshes/part.stl </uri><scale>0.001 0.001 0.002</scale></mesh></geometry>
      </visual>
      <visual name="packaged"><geometry><mesh><uri>model://arm/meshes/link.dae</uri></mesh></geometry></visual>
      <visual name="absolute"><geometry><mesh><uri>file:///opt/meshes/part.obj</uri></mesh></geometry></visual>
    </link>
  </model>
</sdf>
)";
  const fs::path path = write_sdf("primitives", text);
  const RobotModel m = read_robot_model(path);
  const Link& l = link(m, "l");
  ASSERT_EQ(l.collision.size(), 7u);
  const auto shape = [&](std::size_t i) { return *l.collision[i].shape; };
  // Full edge lengths, radius, radius and full length, radius and cylindrical length, semi-axes: as written.
  EXPECT_EQ(std::get<Box>(shape(0)).size, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(std::get<Sphere>(shape(1)).radius, 0.05);
  EXPECT_EQ(std::get<Cylinder>(shape(2)).radius, 0.04);
  EXPECT_EQ(std::get<Cylinder>(shape(2)).length, 0.3);
  EXPECT_EQ(l.collision[2].pose.p, Vec3(0, 0, 0.5));
  EXPECT_EQ(l.collision[2].name, "cylinder");
  EXPECT_EQ(l.collision[2].element, "collision");
  EXPECT_EQ(l.collision[2].line, line_of(text, "<collision name=\"cylinder\">"));
  EXPECT_EQ(std::get<Capsule>(shape(3)).radius, 0.03);
  EXPECT_EQ(std::get<Capsule>(shape(3)).length, 0.2);
  EXPECT_EQ(std::get<Ellipsoid>(shape(4)).semi_axes, Vec3(0.1, 0.2, 0.3));
  // SDFormat's cone is centred on its bounding box, tumble's has its base at z = 0: half the length
  // (0.2, exact) lower.
  EXPECT_EQ(std::get<Cone>(shape(5)).radius, 0.1);
  EXPECT_EQ(std::get<Cone>(shape(5)).height, 0.4);
  EXPECT_EQ(l.collision[5].pose.p, Vec3(0, 0, -0.2));
  // relative_to the model frame: (0, 0, 2) in the model is (−1, 0, 2) in the link at (1, 0, 0) — exact.
  EXPECT_EQ(l.collision[6].pose.p, Vec3(-1, 0, 2));
  EXPECT_EQ(l.collision[6].pose.R, Mat3::Identity());
  // Plane, heightmap and polyline: skipped, each with its reason.
  ASSERT_EQ(l.skipped.size(), 3u);
  EXPECT_NE(l.skipped[0].find("<plane> has no volume"), std::string::npos) << l.skipped[0];
  EXPECT_NE(l.skipped[1].find("<heightmap> has no volume"), std::string::npos) << l.skipped[1];
  EXPECT_NE(l.skipped[2].find("polyline"), std::string::npos) << l.skipped[2];
  // Meshes: the URI trimmed; a relative path resolved against the file's directory, file:// taken as
  // is, model:// left to the package paths.
  ASSERT_EQ(l.visual.size(), 3u);
  EXPECT_FALSE(l.visual[0].shape);
  EXPECT_EQ(l.visual[0].element, "visual");
  EXPECT_EQ(l.visual[0].mesh_uri, "meshes/part.stl");
  EXPECT_EQ(l.visual[0].mesh_path, path.parent_path() / "meshes/part.stl");
  EXPECT_EQ(l.visual[0].scale, Vec3(0.001, 0.001, 0.002));
  EXPECT_EQ(l.visual[1].mesh_uri, "model://arm/meshes/link.dae");
  EXPECT_TRUE(l.visual[1].mesh_path.empty());
  EXPECT_EQ(l.visual[1].scale, Vec3::Ones());
  EXPECT_EQ(l.visual[2].mesh_path, fs::path("/opt/meshes/part.obj"));
}

TEST(ReadSdf, DegreesAndQuaternions) {
  const std::string text = R"(<sdf version="1.10">
  <model name="m">
    <link name="in_degrees"><pose degrees="true">1 2 3 0 0 90</pose></link>
    <link name="in_quaternion"><pose rotation_format="quat_xyzw">1 2 3 0 0 0.7071067811865476 0.7071067811865476</pose></link>
    <joint name="a" type="fixed"><parent>world</parent><child>in_degrees</child></joint>
    <joint name="b" type="fixed"><parent>world</parent><child>in_quaternion</child></joint>
  </model>
</sdf>
)";
  const RobotModel m = read("degrees_quat", text);
  // Both are the quarter turn about z at (1, 2, 3): the position exact, the rotation to 1e-15 (90·π/180
  // and the rounded √½ are each within an ulp of the exact values).
  for (const char* name : {"a", "b"}) {
    EXPECT_EQ(joint(m, name).origin.p, Vec3(1, 2, 3)) << name;
    EXPECT_LT(diff(joint(m, name).origin.R, rz90()), 1e-15) << name;
  }
  const std::string bad = R"(<sdf version="1.10">
  <model name="m">
    <link name="l"><pose rotation_format="quat_xyzw" degrees="true">0 0 0 0 0 0 1</pose></link>
  </model>
</sdf>
)";
  const std::string e = error_of("degrees_quat_bad", bad);
  EXPECT_EQ(e.rfind(where("degrees_quat_bad", bad, "<pose"), 0), 0u) << e;
  EXPECT_NE(e.find("degrees=\"true\" does not apply"), std::string::npos) << e;
}

TEST(ReadSdf, NestedModelsScopeTheirNamesAndComposeTheirPoses) {
  const std::string text = R"(<sdf version="1.8">
  <model name="outer">
    <link name="base"/>
    <model name="inner">
      <pose>1 0 0 0 0 1.5707963267948966</pose>
      <link name="l"><pose>2 0 0 0 0 0</pose></link>
      <joint name="j" type="fixed">
        <parent>l</parent>
        <child>deep::tip</child>
      </joint>
      <model name="deep">
        <pose relative_to="l">0 0 1 0 0 0</pose>
        <link name="tip"/>
      </model>
    </model>
    <joint name="mount" type="fixed">
      <parent>base</parent>
      <child>inner::l</child>
    </joint>
  </model>
</sdf>
)";
  const RobotModel m = read("nested", text);
  EXPECT_EQ(m.name, "outer");
  ASSERT_EQ(m.links.size(), 3u);
  EXPECT_EQ(m.links[0].name, "base");
  EXPECT_EQ(m.links[1].name, "inner::l");
  EXPECT_EQ(m.links[2].name, "inner::deep::tip");
  ASSERT_EQ(m.joints.size(), 2u);
  // inner::l in outer: inner's pose (1, 0, 0, quarter turn) applied to (2, 0, 0) gives (1, 2, 0), turned.
  const Joint& mount = joint(m, "mount");
  EXPECT_EQ(mount.parent, "base");
  EXPECT_EQ(mount.child, "inner::l");
  EXPECT_LT((mount.origin.p - Vec3(1, 2, 0)).norm(), 1e-15);
  EXPECT_LT(diff(mount.origin.R, rz90()), 1e-15);
  // deep is written 1 above l, so its tip is at (0, 0, 1) in l, unrotated (through outer's frame: 1e-15).
  const Joint& j = joint(m, "inner::j");
  EXPECT_EQ(j.parent, "inner::l");
  EXPECT_EQ(j.child, "inner::deep::tip");
  EXPECT_LT((j.origin.p - Vec3(0, 0, 1)).norm(), 1e-15);
  EXPECT_LT(diff(j.origin.R, Mat3::Identity()), 1e-15);
}

TEST(ReadSdf, ConvertedUrdfChainsLinksToJointsAndJointsToFrames) {
  // libsdformat writes a URDF as links relative_to their parent joint, joints relative_to their parent
  // link; a frame attached to a link can be a joint's parent (its link is meant).
  const std::string text = R"(<sdf version="1.9">
  <model name="conv">
    <link name="base"/>
    <joint name="j1" type="revolute">
      <pose relative_to="base">0 0 0.5 0 0 0</pose>
      <parent>base</parent>
      <child>l1</child>
    </joint>
    <link name="l1"><pose relative_to="j1"/></link>
    <frame name="tool" attached_to="l1"><pose>0 0 0.25 0 0 0</pose></frame>
    <link name="l2"><pose relative_to="tool">0 0 0 0 0 0</pose></link>
    <joint name="j2" type="fixed">
      <parent>tool</parent>
      <child>l2</child>
    </joint>
  </model>
</sdf>
)";
  const RobotModel m = read("converted", text);
  // l1 at j1 = (0, 0, 0.5); l2 at the tool, 0.25 above l1: both sums of dyadic numbers, exact.
  EXPECT_EQ(joint(m, "j1").origin.p, Vec3(0, 0, 0.5));
  EXPECT_EQ(joint(m, "j2").parent, "l1");
  EXPECT_EQ(joint(m, "j2").origin.p, Vec3(0, 0, 0.25));
  EXPECT_EQ(joint(m, "j2").origin.R, Mat3::Identity());
}

TEST(ReadSdf, PlacementFramesCanonicalLinksAndOlderNamingRules) {
  const std::string text = R"(<sdf version="1.8">
  <model name="m">
    <link name="base"/>
    <model name="tool" placement_frame="tip">
      <pose>0 0 1 0 0 0</pose>
      <link name="body"/>
      <frame name="tip" attached_to="body"><pose>0 0 0.25 0 0 0</pose></frame>
    </model>
    <joint name="mount" type="fixed">
      <parent>base</parent>
      <child>tool</child>
    </joint>
    <link name="b"><pose>0 0 0.5 0 0 0</pose></link>
    <joint name="b" type="revolute">
      <parent>base</parent>
      <child>b</child>
    </joint>
    <link name="arm::flat"><pose>0 2 0 0 0 0</pose></link>
    <joint name="arm::j" type="fixed">
      <parent>arm::flat</parent>
      <child>b</child>
    </joint>
  </model>
</sdf>
)";
  const RobotModel m = read("placement", text);
  // The pose places the tool's tip, 0.25 above its body, at (0, 0, 1): the body is at (0, 0, 0.75), and a
  // joint to the nested model means its canonical (first) link. 1 − 0.25: exact.
  EXPECT_EQ(joint(m, "mount").child, "tool::body");
  EXPECT_EQ(joint(m, "mount").origin.p, Vec3(0, 0, 0.75));
  // A link and a joint sharing a name (SDFormat 1.6 and earlier allow it): <child>b</child> is the link.
  EXPECT_EQ(joint(m, "b").child, "b");
  EXPECT_EQ(joint(m, "b").origin.p, Vec3(0, 0, 0.5));
  // A name flattened by SDFormat 1.7 ("arm::flat" as one link's name) is that link, not a nested model's.
  EXPECT_EQ(joint(m, "arm::j").parent, "arm::flat");
  EXPECT_EQ(joint(m, "arm::j").origin.p, Vec3(0, -2, 0.5));
}

TEST(ReadSdf, WorldOfModelsPrefixesNamesAndNotesIncludes) {
  const std::string text = R"(<sdf version="1.10">
  <world name="w">
    <include><uri>model://ground_plane</uri></include>
    <model name="a">
      <pose>0 0 1 0 0 0</pose>
      <link name="base"/>
    </model>
    <model name="b">
      <link name="base"><pose>2 0 0 0 0 0</pose></link>
      <joint name="pin" type="fixed"><parent>world</parent><child>base</child></joint>
    </model>
    <joint name="weld" type="fixed"><parent>a::base</parent><child>b::base</child></joint>
  </world>
</sdf>
)";
  const RobotModel m = read("world", text);
  EXPECT_EQ(m.name, "a");
  ASSERT_EQ(m.links.size(), 2u);
  EXPECT_EQ(m.links[0].name, "a::base");
  EXPECT_EQ(m.links[1].name, "b::base");
  // In a world, "world" is the world frame: b is at its origin, so b's base at (2, 0, 0) — exact.
  EXPECT_EQ(joint(m, "b::pin").parent, "world");
  EXPECT_EQ(joint(m, "b::pin").origin.p, Vec3(2, 0, 0));
  // b::base in a::base: (2, 0, 0) − (0, 0, 1) — exact.
  EXPECT_EQ(joint(m, "weld").parent, "a::base");
  EXPECT_EQ(joint(m, "weld").child, "b::base");
  EXPECT_EQ(joint(m, "weld").origin.p, Vec3(2, 0, -1));
  EXPECT_TRUE(has_note(m, "<include> of \"model://ground_plane\" at line 3 is not read"));
}

TEST(ReadSdf, ALongChainOfRelativePosesIsResolvedWithoutRecursion) {
  // 20000 links each 1/1024 above the one before: a converted serial chain taken to the extreme.
  std::string text = "<sdf version=\"1.9\"><model name=\"snake\">\n<link name=\"l0\"/>\n";
  constexpr int n = 20000;
  for (int i = 1; i <= n; ++i) {
    text += "<link name=\"l" + std::to_string(i) + "\"><pose relative_to=\"l" + std::to_string(i - 1) +
            "\">0 0 0.0009765625 0 0 0</pose></link>\n";
  }
  text += "<joint name=\"j\" type=\"fixed\"><parent>l0</parent><child>l" + std::to_string(n) +
          "</child></joint>\n";
  text += "</model></sdf>\n";
  const RobotModel m = read("long_chain", text);
  ASSERT_EQ(m.links.size(), static_cast<std::size_t>(n + 1));
  // Multiples of 2⁻¹⁰ below 2⁴³: every partial sum exact.
  EXPECT_EQ(joint(m, "j").origin.p, Vec3(0, 0, n / 1024.0));
}

TEST(ReadSdf, BadValuesNameTheFileAndLine) {
  const std::string box = R"(<sdf version="1.10">
  <model name="m">
    <link name="l">
      <collision name="c">
        <geometry><box><size>0.1 0.2</size></box></geometry>
      </collision>
    </link>
  </model>
</sdf>
)";
  std::string e = error_of("bad_box", box);
  EXPECT_EQ(e.rfind(where("bad_box", box, "<size>"), 0), 0u) << e;
  EXPECT_NE(e.find("<size>: \"0.1 0.2\" has 2 numbers; it needs 3"), std::string::npos) << e;

  const std::string ghost = R"(<sdf version="1.10">
  <model name="m">
    <link name="l">
      <pose relative_to="ghost">0 0 1 0 0 0</pose>
    </link>
  </model>
</sdf>
)";
  e = error_of("bad_relative_to", ghost);
  EXPECT_EQ(e.rfind(where("bad_relative_to", ghost, "<pose"), 0), 0u) << e;
  EXPECT_NE(e.find(
                "relative_to=\"ghost\": model 'm' has no link, joint, frame or nested model named 'ghost'"),
            std::string::npos)
      << e;

  const std::string loop = R"(<sdf version="1.10">
  <model name="m">
    <link name="a"><pose relative_to="b">0 0 1 0 0 0</pose></link>
    <link name="b"><pose relative_to="a">0 0 1 0 0 0</pose></link>
    <joint name="j" type="fixed"><parent>a</parent><child>b</child></joint>
  </model>
</sdf>
)";
  e = error_of("loop", loop);
  EXPECT_NE(e.find("refer to one another in a loop"), std::string::npos) << e;

  const std::string no_child = R"(<sdf version="1.10">
  <model name="m">
    <link name="a"/>
    <joint name="j" type="fixed"><parent>a</parent></joint>
  </model>
</sdf>
)";
  e = error_of("no_child", no_child);
  EXPECT_EQ(e.rfind(where("no_child", no_child, "<joint"), 0), 0u) << e;
  EXPECT_NE(e.find("<joint>: needs <child>...</child>"), std::string::npos) << e;

  const std::string nan_mass = R"(<sdf version="1.10">
  <model name="m">
    <link name="a"><inertial><mass>heavy</mass></inertial></link>
  </model>
</sdf>
)";
  e = error_of("nan_mass", nan_mass);
  EXPECT_EQ(e.rfind(where("nan_mass", nan_mass, "<mass>"), 0), 0u) << e;
  EXPECT_NE(e.find("\"heavy\" is not a finite number"), std::string::npos) << e;

  EXPECT_NE(error_of("no_model", "<sdf version=\"1.10\"><world name=\"w\"/></sdf>").find("holds no <model>"),
            std::string::npos);
}

TEST(ReadSdf, DeeplyNestedModelsAreRefusedWithAClearError) {
  std::string text = "<sdf version=\"1.10\">\n";
  for (int i = 0; i < 40; ++i) text += "<model name=\"m" + std::to_string(i) + "\">\n";
  text += "<link name=\"l\"/>\n";
  for (int i = 0; i < 40; ++i) text += "</model>\n";
  text += "</sdf>\n";
  const std::string e = error_of("deep", text);
  EXPECT_EQ(e.rfind(where("deep", text, "<model name=\"m33\""), 0), 0u) << e;
  EXPECT_NE(e.find("nested more than 32 deep"), std::string::npos) << e;
}

}  // namespace
}  // namespace tumble::robot
