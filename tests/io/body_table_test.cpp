// [[body_tables]]: bodies from a CSV file, a row each. A row must give the same body and state as the
// [[bodies]] table it stands for, and every mistake in the file is one line at file:line:column.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../support/scene_files.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {
namespace {

const std::string kScene =
    "[simulation]\nduration = 0.5\ntimestep = 1e-3\n[world]\ngravity = [0, 0, -9.81]\n"
    "[[body_tables]]\nfile = \"boxes.csv\"\n";

/// The message of the SceneError that loading a scene with this CSV throws ("" if none).
std::string error_of(const std::string& csv, const std::string& scene = kScene) {
  test::TempDir dir("body_table_errors");
  dir.write("boxes.csv", csv);
  try {
    load_scene(dir.write("s.toml", scene));
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
    // Messages name the files as the scene reader found them, in this directory; keep their names only.
    std::string names_only;
    const std::string prefix = dir.path().string() + "/";
    for (size_t pos = 0, at; pos < m.size(); pos = at + prefix.size()) {
      at = std::min(m.find(prefix, pos), m.size());
      names_only += m.substr(pos, at - pos);
    }
    return names_only;
  }
  return "";
}

TEST(BodyTable, ARowIsTheBodyItsTomlTableDescribes) {
  // A 0.1 x 0.2 x 0.3 m box of 2700 kg/m^3: m = ρabc, I_x = m(b² + c²)/12 (tutorial §IV, a box about
  // its centre), written to 17 digits as a script would; the same box as a [[bodies]] table.
  const double m = 2700 * 0.1 * 0.2 * 0.3;
  const Vec3 I = m / 12 * Vec3(0.2 * 0.2 + 0.3 * 0.3, 0.1 * 0.1 + 0.3 * 0.3, 0.1 * 0.1 + 0.2 * 0.2);
  const std::string state = "1.5,-2,0.25, 0.5,0.5,0.5,0.5, 0.1,0.2,3, 0.3,10,-0.2";
  test::TempDir dir("body_table");
  dir.write("boxes.csv", fmt::format("# m, principal moments, then the state\n"
                                     "name,mass,I1,I2,I3,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n"
                                     "box,{:.17g},{:.17g},{:.17g},{:.17g},{}\n",
                                     m, I.x(), I.y(), I.z(), state));
  const Scene table = load_scene(dir.write("s.toml", kScene));
  const Scene toml =
      load_scene(dir.write("t.toml",
                           "[simulation]\nduration = 0.5\ntimestep = 1e-3\n[world]\ngravity = [0, 0, -9.81]\n"
                           "[[bodies]]\nname = \"box\"\nshape = { type = \"box\", size = [0.1, 0.2, 0.3] }\n"
                           "density = 2700\nposition = [1.5, -2, 0.25]\norientation = [0.5, 0.5, 0.5, 0.5]\n"
                           "velocity = [0.1, 0.2, 3]\nangular_velocity = [0.3, 10, -0.2]\n"));
  ASSERT_EQ(table.model.bodies.size(), 1u);
  const RigidBody &a = table.model.bodies[0], &b = toml.model.bodies[0];
  EXPECT_EQ(a.name(), "box");
  // The mesh-free closed form and the shape's own integral agree to rounding (a few ulps of m and I).
  EXPECT_NEAR(a.mass(), b.mass(), 4e-16 * b.mass());
  EXPECT_LT((a.Lambda() - b.Lambda()).norm(), 4e-16 * b.Lambda().norm());
  EXPECT_LT((a.U() - b.U()).norm(), 1e-15);
  const BodyState &sa = table.initial.bodies[0], &sb = toml.initial.bodies[0];
  EXPECT_LT((sa.o - sb.o).norm(), 1e-15 * 3);
  EXPECT_LT(std::abs(std::abs(sa.q.dot(sb.q)) - 1), 1e-15);
  EXPECT_LT((sa.v - sb.v).norm(), 1e-15 * 3);
  EXPECT_LT((sa.omega_w - sb.omega_w).norm(), 1e-15 * 10);
  EXPECT_TRUE(table.conserved.energy);
  // The table is one of the run's inputs, which no output may overwrite.
  ASSERT_EQ(table.input_files.size(), 2u);
  EXPECT_EQ(table.input_files[1], dir / "boxes.csv");

  // And it moves as that body does: 500 rk4 steps from states equal to rounding stay equal to within
  // the rounding amplified over the run (ω·t = 5 rad of tumbling; 1e-12 is ~10⁴ ulps).
  RunSettings settings = table.settings;
  const SystemState end_a = simulate(table.model, table.initial, settings);
  const SystemState end_b = simulate(toml.model, toml.initial, settings);
  EXPECT_LT((end_a.bodies[0].omega_w - end_b.bodies[0].omega_w).norm(), 1e-12 * 10);
  EXPECT_LT(std::abs(std::abs(end_a.bodies[0].q.dot(end_b.bodies[0].q)) - 1), 1e-12);
}

TEST(BodyTable, OptionalColumnsNamesAndFrames) {
  // Only mass and moments: at rest at the origin, named by the file's stem and the row from 0.
  test::TempDir dir("body_table_defaults");
  dir.write("boxes.csv", "mass,I3,I2,I1\n\n2, 3,2,2\n# a comment between rows\n1,1,1,1\n");
  const Scene s = load_scene(dir.write("s.toml", kScene));
  ASSERT_EQ(s.model.bodies.size(), 2u);
  EXPECT_EQ(s.model.bodies[0].name(), "boxes_0");
  EXPECT_EQ(s.model.bodies[1].name(), "boxes_1");
  EXPECT_EQ(s.model.bodies[0].Lambda(), Vec3(2, 2, 3));  // columns in any order
  EXPECT_EQ(s.initial.bodies[0].o, Vec3::Zero());
  EXPECT_EQ(s.initial.bodies[0].omega_w, Vec3::Zero());

  // name_prefix, and ω given in principal axes: ω_w = R ω_b with R the principal frame's rotation.
  dir.write("spin.csv", "mass,I1,I2,I3,qw,qx,qy,qz,wx,wy,wz\n1,3,1,2,0,0,0,1,1,2,3\n");
  const Scene p = load_scene(dir.write("p.toml",
                                       "[simulation]\nduration = 1\n[[body_tables]]\nfile = "
                                       "\"spin.csv\"\nname_prefix = \"debris.\"\n"
                                       "angular_velocity_frame = \"principal\"\n"));
  EXPECT_EQ(p.model.bodies[0].name(), "debris.0");
  EXPECT_LT((p.initial.bodies[0].omega_b() - Vec3(1, 2, 3)).norm(), 1e-15 * 4);
  EXPECT_LT((p.initial.bodies[0].omega_w - p.initial.bodies[0].q * Vec3(1, 2, 3)).norm(), 1e-15 * 4);
}

TEST(BodyTable, ForcesNameRowsAndNamesAreShared) {
  test::TempDir dir("body_table_names");
  dir.write("boxes.csv", "name,mass,I1,I2,I3\nhub,1,1,1,1\n");
  const Scene s = load_scene(
      dir.write("s.toml", kScene + "[[forces]]\ntype = \"damping\"\nbody = \"hub\"\nangular = 0.5\n"));
  EXPECT_EQ(s.model.bodies[0].name(), "hub");
  const std::string duplicate =
      error_of("name,mass,I1,I2,I3\nhub,1,1,1,1\n", kScene + "[[particles]]\nname = \"hub\"\nmass = 1\n");
  EXPECT_EQ(
      duplicate,
      "s.toml:9:8: [[particles]] #1: duplicate name \"hub\" (first defined at boxes.csv:2:1): give every "
      "body and particle its own name");
}

TEST(BodyTable, ATableLargerThanAPieceIsReadRowForRow) {
  // The file is read a megabyte at a time: 6000 rows of ~330 bytes straddle two piece boundaries, a
  // comment line of 3 MB is longer than a piece, and every row must still be the body it describes,
  // bit for bit (the same characters through the same std::from_chars).
  std::string csv = "name,mass,I1,I2,I3,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  const auto row = [](int i) {
    const double x = 0.1 * i + 1.0 / 3.0;
    return fmt::format("r{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},0,0,1,0,0,0,0,0,{:.17g},{:.17g},0,0\n", i,
                       1 + x, 1 + x / 7, 1.5 + x / 7, 2 + x / 7, x, -x, x / 3);
  };
  for (int i = 0; i < 3000; ++i) csv += row(i);
  csv += "# " + std::string(3 << 20, 'x') + "\n";
  for (int i = 3000; i < 6000; ++i) csv += row(i);
  test::TempDir dir("body_table_pieces");
  dir.write("boxes.csv", csv);
  const Scene s = load_scene(dir.write("s.toml", kScene));
  ASSERT_EQ(s.model.bodies.size(), 6000u);
  for (const int i : {0, 2999, 3000, 3172, 5999}) {
    const double x = 0.1 * i + 1.0 / 3.0;
    const auto number = [](double v) { return std::stod(fmt::format("{:.17g}", v)); };
    EXPECT_EQ(s.model.bodies[static_cast<size_t>(i)].name(), fmt::format("r{}", i));
    EXPECT_EQ(s.model.bodies[static_cast<size_t>(i)].mass(), number(1 + x)) << i;
    EXPECT_EQ(s.model.bodies[static_cast<size_t>(i)].Lambda().x(), number(1 + x / 7)) << i;
    EXPECT_EQ(s.initial.bodies[static_cast<size_t>(i)].o.x(), number(x)) << i;
    EXPECT_EQ(s.initial.bodies[static_cast<size_t>(i)].omega_w.x(), number(x / 3)) << i;
  }
  // Every row shares one description of where its mass came from.
  EXPECT_EQ(s.body_info.front().source, s.body_info.back().source);
  EXPECT_EQ(*s.body_info.front().source, "body table boxes.csv");

  // A mistake far into the file is named at its line (the header is line 1, the comment line 3002).
  dir.write("boxes.csv", csv + "r6000,1,1,1,x,0,0,0,1,0,0,0,0,0,0,0,0,0\n");
  try {
    load_scene(dir / "s.toml");
    ADD_FAILURE() << "a bad number was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("boxes.csv:6003:13: column I3: expected a number, found \"x\""),
              std::string::npos)
        << e.what();
  }
}

TEST(BodyTable, TheFirstRepeatedNameInTheFileIsTheOneReported) {
  // Names are checked all at once after every body is read; the message is still the one a check in
  // file order gives: the earliest repeat, naming its first definition.
  EXPECT_EQ(error_of("name,mass,I1,I2,I3\nb,1,1,1,1\na,1,1,1,1\nb,1,1,1,1\na,1,1,1,1\n",
                     kScene + "[[particles]]\nname = \"a\"\nmass = 1\n"),
            "boxes.csv:4:1: row 3: duplicate name \"b\" (first defined at line 2, column 1): give every body "
            "and particle its own name");
  EXPECT_EQ(error_of("name,mass,I1,I2,I3\nc,1,1,1,1\n",
                     "[[bodies]]\nname = \"c\"\nmass = 1\ninertia = [1, 1, 1]\n" + kScene),
            "boxes.csv:2:1: row 1: duplicate name \"c\" (first defined at s.toml:2:8): give every body and "
            "particle its own name");
}

TEST(BodyTable, MistakesAreOneLineAtTheirPlace) {
  EXPECT_EQ(
      error_of("name,mass,I1,I2,I3,omega\n"),
      "boxes.csv:1:20: unknown column \"omega\"; the columns are: name, mass, I1, I2, I3, px, py, pz, qw, "
      "qx, qy, qz, vx, vy, vz, wx, wy, wz");
  EXPECT_EQ(error_of("mass,I1,I2,I3,mas\n"),
            "boxes.csv:1:15: unknown column \"mas\"; did you mean \"mass\"? the columns are: name, mass, I1, "
            "I2, I3, px, py, pz, qw, qx, qy, qz, vx, vy, vz, wx, wy, wz");
  EXPECT_EQ(error_of("mass,I1,I2,I3,I1\n"), "boxes.csv:1:15: column \"I1\" appears twice in the header");
  EXPECT_EQ(
      error_of("mass,I1,I2,I3,wx,wy\n1,1,1,1,0,0\n"),
      "boxes.csv:1:1: the header has only part of the angular velocity (rad/s): give the columns wx, wy, "
      "wz");
  EXPECT_EQ(error_of("I1,I2,I3\n"), "boxes.csv:1:1: the header lacks the mass (kg): give the column mass");
  EXPECT_EQ(error_of("mass,I1,I2,I3\n1,1,1\n"), "boxes.csv:2:1: row 1 has 3 fields, the header 4");
  EXPECT_EQ(error_of("mass,I1,I2,I3\n1,1,1,1\n2,1,1e999,1\n"),
            "boxes.csv:3:5: column I2: 1e999 is not a finite double");
  EXPECT_EQ(error_of("mass,I1,I2,I3\n1, 1 ,x1,1\n"),
            "boxes.csv:2:7: column I2: expected a number, found \"x1\"");
  EXPECT_EQ(error_of("mass,I1,I2,I3\n1,1,1,3\n"),
            "boxes.csv:2:1: body 'boxes_0': inertia tensor violates the triangle inequality: the largest "
            "principal moment 3 exceeds the sum of the other two 1 + 1 = 2 kg*m^2 (by 1); no mass "
            "distribution has such moments — check signs of products of inertia and units");
  EXPECT_EQ(error_of("mass,I1,I2,I3,qw,qx,qy,qz\n1,1,1,1,1,1,0,0\n"),
            "boxes.csv:2:9: body 'boxes_0': the orientation has norm 1.41421, more than 0.001 from 1: give a "
            "unit quaternion (qw, qx, qy, qz; w first)");
  EXPECT_EQ(error_of("name,mass,I1,I2,I3\na b,1,1,1,1\n"),
            "boxes.csv:2:1: name \"a b\" is not allowed: use letters, digits, '_', '-' and '.' only");
  EXPECT_EQ(error_of("name,mass,I1,I2,I3\na,1,1,1,1\na,1,1,1,1\n"),
            "boxes.csv:3:1: row 2: duplicate name \"a\" (first defined at line 2, column 1): give every body "
            "and particle its own name");
  EXPECT_EQ(error_of("mass,I1,I2,I3\n# no rows\n"),
            "s.toml:7:8: [[body_tables]] #1: boxes.csv has a header but no rows: add a row per body");
}

}  // namespace
}  // namespace tumble
