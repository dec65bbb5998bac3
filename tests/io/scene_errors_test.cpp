// Bad scene files: each kind of mistake gets one line with file:line:column, what was expected, what
// was found and how to fix it. The full text is checked, so a change to a message is deliberate.
#include <gtest/gtest.h>

#include "../support/scene_files.hpp"
#include "tumble/io/scene.hpp"

namespace tumble {
namespace {

/// The message of the SceneError that parsing `text` as "bad.toml" throws ("" if none).
std::string error_of(const std::string& text, const std::filesystem::path& path = "bad.toml") {
  try {
    parse_scene(text, path);
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
    return m;
  }
  return "";
}

const std::string kSim = "[simulation]\nduration = 1.0\n";  // lines 1-2

TEST(SceneErrors, SyntaxError) {
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"a\"\ndensity = = 3\n"),
            "bad.toml:5:11: TOML syntax error: Error while parsing value: could not determine value type");
}

// Found by fuzz/fuzz_scene.cpp: malformed text reached undefined behaviour inside toml++ 3.3's parser
// (src/io/toml.hpp): a code point such as U+03C9 (ω) where the parser asks whether a character is
// whitespace reached a __builtin_unreachable (in every build), and a table header whose key starts
// with neither a bare-key character nor a quote broke a precondition (an assertion abort in a debug
// build, __builtin_assume under Clang). Each is now a syntax error like any other.
TEST(SceneErrors, TomlParserUndefinedBehaviour) {
  for (const char* text : {"[\n[bodies]]\n", "[[[1]]]", "[[[a]]]", "[[[]]", "[[=", "[&", "[[\n", "[ \t\n",
                           "a\xcf\x89 = 1\n", "a \xcf\x89= 1\n", "\xcc\xaa", "\xe2\xb4\x80 = 1"}) {
    const std::string m = error_of(text);
    EXPECT_EQ(m.rfind("bad.toml:", 0), 0u) << text << " -> " << m;
    EXPECT_NE(m.find("TOML syntax error"), std::string::npos) << text << " -> " << m;
  }
  // As found (crash-0cb0c2c1, shortened): a stray '[' line before [[bodies]].
  EXPECT_EQ(error_of("[simulation]\nduration = 1.0\n[\n[bodies]]\nname = \"cube\"\n"),
            "bad.toml:3:2: TOML syntax error: Error while parsing key: expected bare key starting character "
            "or string delimiter, saw '\\n'");
  // As found (crash-7c596a57, shortened): "ω" typed into a key.
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"top\"\n\xcf\x89 = [0.0, 0.0, 1.0]\n"),
            "bad.toml:5:1: TOML syntax error: Error while parsing root table: expected keys, tables, "
            "whitespace or comments, saw '\xcf\x89'");
  // Upstream's report (#190): valid TOML, read to the end; only the key is tumble's error.
  EXPECT_EQ(error_of("s = \"\"\"\\\n\xc2\xa7\"\"\"\n"),
            "bad.toml:1:1: scene: unknown key 's'; the keys here are: simulation, output, world, bodies, "
            "body_tables, particles, forces, rotors, events, ensemble");
}

TEST(SceneErrors, UnknownKeysSuggestTheClosest) {
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 1, 1] }\ndensty "
                            "= 1.0\n"),
            "bad.toml:6:1: body 'a': unknown key 'densty'; did you mean 'density'?");
  EXPECT_EQ(error_of("[simulaton]\nduration = 1.0\n"),
            "bad.toml:1:2: scene: unknown key 'simulaton'; did you mean 'simulation'?");
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"a\"\nshape = { type = \"sphere\", radius = 1, size = 2 "
                            "}\nmass = 1\n"),
            "bad.toml:5:40: body 'a' shape (sphere): unknown key 'size'; the keys here are: radius, type");
  // Nothing close: the valid keys are listed instead.
  EXPECT_EQ(
      error_of("[simulation]\nduration = 1.0\ncolour = \"red\"\n"),
      "bad.toml:3:1: [simulation]: unknown key 'colour'; the keys here are: duration, timestep, integrator, "
      "formulation, output_interval, rtol, atol, drift_threshold");
  EXPECT_EQ(error_of(kSim +
                     "[[bodies]]\nname = \"a\"\nshape = { type = \"bx\", size = [1, 1, 1] }\nmass = 1\n"),
            "bad.toml:5:18: body 'a' shape: unknown shape type \"bx\"; did you mean \"box\"?");
  EXPECT_EQ(error_of(
                "[simulation]\nduration = 1.0\nintegrator = \"rk5\"\n[[particles]]\nname = \"p\"\nmass = 1\n")
                .substr(0, 66),
            "bad.toml:3:14: [simulation]: unknown integrator \"rk5\"; did you mea");
}

TEST(SceneErrors, WrongTypesAndLengths) {
  EXPECT_EQ(
      error_of(kSim + "[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 1] }\ndensity = 1.0\n"),
      "bad.toml:5:32: body 'a' shape (box): size must be an array of 3 numbers (m), found an array of 2");
  EXPECT_EQ(error_of(kSim +
                     "[[bodies]]\nname = \"a\"\nmass = 1\ninertia = [1, 1, 1]\nposition = [0, \"0\", 0]\n"),
            "bad.toml:7:16: body 'a': position[1] must be a number (m), found the string \"0\"");
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 1, 1] }\ndensity "
                            "= \"heavy\"\n"),
            "bad.toml:6:11: body 'a': density must be a number (kg/m^3), found the string \"heavy\"");
  EXPECT_EQ(
      error_of(kSim + "[[bodies]]\nname = \"a\"\nmass = 1\ninertia = [1, 1, 1]\nangular_velocity_frame "
                      "= \"bdy\"\n"),
      "bad.toml:7:26: body 'a': angular_velocity_frame must be \"world\", \"reference\" (the body's own "
      "axes; \"body\" is the older name) or \"principal\" (its principal axes), found \"bdy\"");
}

TEST(SceneErrors, NonFiniteNumbers) {
  EXPECT_EQ(error_of(kSim +
                     "[[bodies]]\nname = \"a\"\nmass = 1\ninertia = [1, 1, 1]\nvelocity = [0.0, nan, 0.0]\n"),
            "bad.toml:7:18: body 'a': velocity[1] is nan: give a finite number (m/s)");
  EXPECT_EQ(error_of("[simulation]\nduration = inf\n"),
            "bad.toml:2:12: [simulation]: duration is inf: give a finite number (s)");
}

TEST(SceneErrors, NonPositiveMassDensityTimestep) {
  EXPECT_EQ(error_of(kSim +
                     "[[bodies]]\nname = \"a\"\nshape = { type = \"sphere\", radius = 1.0 }\nmass = -2.0\n"),
            "bad.toml:6:8: body 'a': mass is -2 kg: it must be positive");
  EXPECT_EQ(error_of(kSim +
                     "[[bodies]]\nname = \"a\"\nshape = { type = \"sphere\", radius = 1.0 }\ndensity = 0\n"),
            "bad.toml:6:11: body 'a': density is 0 kg/m^3: it must be positive");
  EXPECT_EQ(error_of("[simulation]\nduration = 1.0\ntimestep = 0.0\n"),
            "bad.toml:3:12: [simulation]: timestep is 0 s: it must be positive");
  EXPECT_EQ(error_of(kSim + "[[particles]]\nname = \"p\"\nmass = 0\n"),
            "bad.toml:5:8: particle 'p': mass is 0 kg: it must be positive");
  EXPECT_EQ(error_of(kSim +
                     "[[bodies]]\nname = \"a\"\nshape = { type = \"sphere\", radius = -1.0 }\ndensity = 1\n"),
            "bad.toml:5:37: body 'a' shape (sphere): radius is -1 m: it must be positive");
}

TEST(SceneErrors, QuaternionsFarFromUnit) {
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"a\"\nmass = 1\ninertia = [1, 1, 1]\norientation = [0.7, "
                            "0.7, 0.0, 0.0]\n"),
            "bad.toml:7:15: body 'a': orientation has norm 0.989949, more than 0.001 from 1: give a unit "
            "quaternion [w, x, y, z] (w first); normalised it would be [0.707107, 0.707107, 0, 0]");
  EXPECT_EQ(
      error_of(kSim +
               "[[bodies]]\nname = \"a\"\nmass = 1\ninertia = [1, 1, 1]\norientation = [1.0, 0.0, 0.0]\n"),
      "bad.toml:7:15: body 'a': orientation must be a unit quaternion [w, x, y, z], found an array of 3");
}

TEST(SceneErrors, InertiaViolatingTheTriangleInequality) {
  const std::string m = error_of(kSim + "[[bodies]]\nname = \"a\"\nmass = 2.0\ninertia = [1.0, 1.0, 3.0]\n");
  EXPECT_EQ(m.substr(0, 80),
            "bad.toml:6:11: body 'a': inertia tensor violates the triangle inequality: the la");
  EXPECT_NE(m.find("3 exceeds the sum of the other two 1 + 1 = 2 kg*m^2"), std::string::npos) << m;
  EXPECT_EQ(error_of(kSim +
                     "[[bodies]]\nname = \"a\"\nmass = 2.0\ninertia = [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]\n"),
            "bad.toml:6:11: body 'a': inertia must be symmetric (inertia[i][j] = inertia[j][i]): check the "
            "products of inertia");
  EXPECT_EQ(
      error_of(kSim + "[[bodies]]\nname = \"a\"\ndensity = 2.0\ninertia = [1.0, 1.0, 1.0]\n"),
      "bad.toml:6:11: body 'a': inertia needs the total mass: give mass = M (kg) (density does not apply)");
}

TEST(SceneErrors, MissingOrBrokenMeshes) {
  test::TempDir dir("scene_errors_mesh");
  const auto scene = dir / "bad.toml";
  const std::string missing =
      error_of(kSim + "[[bodies]]\nname = \"a\"\nmesh = \"nope.stl\"\ndensity = 1.0\n", scene);
  const std::string missing_head = scene.string() + ":5:8: body 'a': cannot load mesh \"nope.stl\": " +
                                   (dir / "nope.stl").string() + ": no such file";
  EXPECT_EQ(missing.substr(0, missing_head.size()), missing_head);
  EXPECT_NE(missing.find("mesh paths are relative to the scene file's directory"), std::string::npos)
      << missing;

  dir.write("broken.stl", "solid x\n");
  const std::string broken =
      error_of(kSim + "[[bodies]]\nname = \"a\"\nmesh = \"broken.stl\"\ndensity = 1.0\n", scene);
  const std::string broken_head =
      scene.string() + ":5:8: body 'a': cannot load mesh \"broken.stl\": " + (dir / "broken.stl").string();
  EXPECT_EQ(broken.substr(0, broken_head.size()), broken_head);

  // An open mesh: one triangle bounds no solid; the mesh check's message, located at the key.
  dir.write("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string open =
      error_of(kSim + "[[bodies]]\nname = \"a\"\nmesh = \"open.obj\"\ndensity = 1.0\n", scene);
  EXPECT_EQ(open.substr(0, scene.string().size() + 20), scene.string() + ":5:8: body 'a': open");
  // The fix is said in the scene's terms (the key), not the command line's (--shell).
  EXPECT_NE(open.find("add thickness = T (m) to this body to make it a thin shell"), std::string::npos)
      << open;
  EXPECT_EQ(open.find("--shell"), std::string::npos) << open;
}

TEST(SceneErrors, DuplicateAndBadNames) {
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"a\"\nmass = 1\ninertia = [1, 1, 1]\n"
                            "[[particles]]\nname = \"a\"\nmass = 1\n"),
            "bad.toml:8:8: [[particles]] #1: duplicate name \"a\" (first defined at line 4, column 8): give "
            "every body and particle its own name");
  EXPECT_EQ(
      error_of(kSim + "[[bodies]]\nname = \"a,b\"\nmass = 1\ninertia = [1, 1, 1]\n"),
      "bad.toml:4:8: [[bodies]] #1: name \"a,b\" is not allowed: use letters, digits, '_', '-' and '.' only");
}

TEST(SceneErrors, MissingPiecesAndBadReferences) {
  EXPECT_EQ(error_of("[[particles]]\nname = \"p\"\nmass = 1\n"),
            "bad.toml:1:1: scene: missing [simulation]: give at least duration = T (s)");
  EXPECT_EQ(error_of(kSim),
            "bad.toml:1:1: scene: the scene has nothing to simulate: add [[bodies]], [[body_tables]] or "
            "[[particles]]");
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 1, 1] }\n"),
            "bad.toml:3:1: body 'a': missing the material: give density = RHO (kg/m^3) or mass = M (kg)");
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"handle\"\nmass = 1\ninertia = [1, 1, 1]\n"
                            "[[forces]]\ntype = \"torque\"\nbody = \"handel\"\ntorque = [1, 0, 0]\n"),
            "bad.toml:9:8: [[forces]] #1 (torque): no body named \"handel\"; did you mean \"handle\"?");
  EXPECT_EQ(error_of(kSim + "[[bodies]]\nname = \"a\"\nmass = 1\ninertia = [1, 1, 1]\n[[forces]]\ntype = "
                            "\"sprung\"\n"),
            "bad.toml:8:8: [[forces]] #1: unknown force type \"sprung\"; did you mean \"spring\"?");
}

/// How often `part` occurs in `text`.
size_t occurrences(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(SceneErrors, ACompositeErrorNamesTheBodyThePartAndTheLineOnce) {
  const std::string body = kSim +
                           "[[bodies]]\nname = \"c\"\ndensity = 1000\n[[bodies.parts]]\n"
                           "shape = { type = \"box\", size = [1, 1, 1] }\n";  // lines 3-7
  // A hole that sticks out of the part: the remainder has negative moments.
  const std::string rod =
      "[[bodies.parts]]\nshape = { type = \"box\", size = [10, 0.1, 0.1] }\nhole = true\n";
  std::string m = error_of(body + rod);
  EXPECT_EQ(m,
            "bad.toml:8:1: body 'c' part 2: this hole leaves the body with mass properties no body can have: "
            "inertia tensor is not positive definite: principal moments are -666.75, -666.75, 166.5 kg*m^2; "
            "every principal moment of a body must be positive; a hole must lie inside the parts it cuts: "
            "check its size and position");
  // Two holes: which one is wrong is not known, both are named.
  m = error_of(body + rod + rod);
  EXPECT_TRUE(
      m.starts_with("bad.toml:3:1: body 'c': the parts minus the holes (parts 2, 3) leave mass "
                    "properties no body can have: inertia tensor"))
      << m;
  EXPECT_EQ(occurrences(m, "body 'c'"), 1U) << m;

  // A mesh part with an error in the mesh file: the scene's line, the body and part, then the mesh's
  // own file:line:column, each once.
  test::TempDir dir("composite_errors");
  dir.write("bad.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 9\n");
  const auto scene = dir.write("c.toml", body + "[[bodies.parts]]\nmesh = \"bad.off\"\nhole = true\n");
  m = error_of(test::read_text(scene), scene);
  EXPECT_EQ(
      m,
      scene.string() + ":9:8: body 'c' part 2: cannot load mesh \"bad.off\": " + (dir / "bad.off").string() +
          ":10:7: vertex index 9 is out of range: the file has 4 vertices, numbered from 0; mesh paths are "
          "relative to the scene file's directory");
  EXPECT_EQ(occurrences(m, "body 'c'"), 1U) << m;
}

}  // namespace
}  // namespace tumble
