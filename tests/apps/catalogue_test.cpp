// The catalogue of broken inputs: scenes, meshes in every format, command-line values, output paths
// and signals, each run as a user would (a fresh directory, the program through the shell) and held
// to its exit status and the first line it prints after "tumble: ". One table, so that a change to
// any message is a deliberate change here, and a new kind of mistake is one row.
//
// Exit statuses: 0 done (possibly with a warning), 1 an input or value that cannot be used, 2 a
// command line that cannot be parsed, 128 + N stopped by signal N with its file kept.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../support/run.hpp"
#include "../support/scene_files.hpp"

#include <sys/wait.h>

namespace tumble {
namespace {

struct Case {
  const char* name;
  std::vector<std::pair<std::string, std::string>> files;  // written into the case's directory
  const char* command;                                     // {t} is the program
  int status;
  const char* first_line;  // the first line that starts with "tumble: " ("" if none); "…" ends a prefix
};

/// Runs `command` in `dir` through bash; returns the exit status and the first "tumble: " line.
std::pair<int, std::string> run_in(const std::filesystem::path& dir, std::string command) {
  for (size_t at = command.find("{t}"); at != std::string::npos; at = command.find("{t}")) {
    command.replace(at, 3, TUMBLE_CLI);
  }
  // Through a script file, so that the command needs no quoting.
  const std::filesystem::path script = dir / "case.sh";
  std::ofstream(script) << command << "\n";
  const auto [status, out] = test::run_shell_command("cd '" + dir.string() + "' && bash case.sh 2>&1");
  std::string first;
  for (size_t start = 0; start < out.size();) {
    const size_t end = std::min(out.find('\n', start), out.size());
    if (out.compare(start, 8, "tumble: ") == 0) {
      first = out.substr(start, end - start);
      break;
    }
    start = end + 1;
  }
  return {status, first};
}

/// A box at rest for 10 ms: the scene of the command-line rows.
const char* const kBoxScene =
    "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 2, 3] "
    "}\ndensity = 1000\n";
/// A box for 10⁴ s at steps of 0.1 ms: a run that is stopped (a signal, a limit) long before its end.
const char* const kLongBoxScene =
    "[simulation]\nduration = 1e4\ntimestep = 1e-4\noutput_interval = 1\n[[bodies]]\nname = \"a\"\nshape = "
    "{ type = \"box\", size = [1, 2, 3] }\ndensity = 1000\n";

/// A box tumbling about its intermediate axis for 3 s, sampled every 10 ms: its ω₂ changes sign once.
const char* const kEventScene =
    "[simulation]\nduration = 3.0\ntimestep = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = \"box\", "
    "size = [1, 2, 3] }\ndensity = 1000\nangular_velocity = [0.5, 5, 0.5]\n[[events]]\nname = \"flip\"\nbody "
    "= "
    "\"a\"\ncolumn = \"w2\"\n";

/// The unit cube as a glTF buffer: its 8 corners as float32, then 12 outward triangles as uint16.
std::string cube_gltf_bin() {
  std::string bytes;
  const auto put = [&](const void* p, size_t n) { bytes.append(static_cast<const char*>(p), n); };
  for (int i = 0; i < 8; ++i) {
    const float corner[3] = {static_cast<float>(i & 1), static_cast<float>((i >> 1) & 1),
                             static_cast<float>((i >> 2) & 1)};
    put(corner, sizeof corner);
  }
  const std::uint16_t triangles[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                          {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  put(triangles, sizeof triangles);
  return bytes;
}

/// A glTF document of that cube, its buffer in model/cube.bin.
const char* const kCubeGltf =
    R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
    R"("buffers":[{"byteLength":168,"uri":"cube.bin"}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96},)"
    R"({"buffer":0,"byteOffset":96,"byteLength":72}],"accessors":[{"bufferView":0,"componentType":5126,"count":8,)"
    R"("type":"VEC3","min":[0,0,0],"max":[1,1,1]},{"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}]})";

const std::vector<Case>& catalogue() {
  static const std::vector<Case> cases = {
      {"scene: empty file",
       {{"s.toml", std::string()}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:1:1: scene: missing [simulation]: give at least duration = T (s)"},
      {"scene: TOML syntax error",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\ndensity = = 3\n",
                               123)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:11: TOML syntax error: Error while parsing key-value pair: cannot redefine "
       "existing integer 'density'"},
      {"scene: binary garbage",
       {{"s.toml", std::string("\x00\x01\x02garbage\xc3\xbf", 12)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:1:1: TOML syntax error: Error while parsing root table: expected keys, tables, "
       "whitespace or comments, saw '\\u0000'"},
      {"scene: UTF-16 text",
       {{"s.toml", std::string("\xff\xfe\xff\xfe[\x00s\x00i\x00m\x00u\x00l\x00"
                               "a\x00t\x00i\x00o\x00n\x00]\x00\n\x00"
                               "d\x00u\x00r\x00"
                               "a\x00t\x00i\x00o\x00n\x00 \x00=\x00 \x00"
                               "1\x00\n\x00",
                               56)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:1:1: TOML syntax error: Encountered invalid utf-8 sequence"},
      {"scene: missing file",
       {},
       "{t} check nothing.toml",
       1,
       "tumble: error: cannot read scene file nothing.toml: no such file; check the path and the working "
       "directory"},
      {"scene: a directory",
       {{"d/x", std::string()}},
       "{t} check d",
       1,
       "tumble: error: cannot read scene file d: a directory, not a regular file; give a scene file (tumble "
       "reads input from regular files only: save a stream to a file first)"},
      {"scene: /dev/zero",
       {},
       "{t} check /dev/zero",
       1,
       "tumble: error: cannot read scene file /dev/zero: a character device (such as /dev/zero), which may "
       "never end, not a regular file; give a scene file (tumble reads input from regular files only: save a "
       "stream to a file first)"},
      {"scene: no [simulation]",
       {{"s.toml", std::string("[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 2, 3] "
                               "}\ndensity = 1000\n",
                               80)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:1:1: scene: missing [simulation]: give at least duration = T (s)"},
      {"scene: misspelt section",
       {{"s.toml", std::string("[simulaton]\nduration = 1\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               105)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:1:2: scene: unknown key 'simulaton'; did you mean 'simulation'?"},
      {"scene: negative duration",
       {{"s.toml", std::string("[simulation]\nduration = -1\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               107)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:2:12: [simulation]: duration is -1 s: it must be zero or positive"},
      {"scene: duration is a string",
       {{"s.toml", std::string("[simulation]\nduration = \"ten\"\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               110)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:2:12: [simulation]: duration must be a number (s), found the string \"ten\""},
      {"scene: infinite duration",
       {{"s.toml", std::string("[simulation]\nduration = inf\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               108)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:2:12: [simulation]: duration is inf: give a finite number (s)"},
      {"scene: zero timestep",
       {{"s.toml", std::string("[simulation]\nduration = 1\ntimestep = 0\n[[bodies]]\nname = \"a\"\nshape = "
                               "{ type = \"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               119)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:3:12: [simulation]: timestep is 0 s: it must be positive"},
      {"scene: unknown integrator",
       {{"s.toml", std::string("[simulation]\nduration = 1\nintegrator = \"rk5\"\n[[bodies]]\nname = "
                               "\"a\"\nshape = { type = \"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               125)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:3:14: [simulation]: unknown integrator \"rk5\"; did you mean \"rk4\"? choose "
       "one of: dopri45, euler, exact, implicit_gyro, lie_rk4, midpoint, rk4, semi_implicit_euler, "
       "splitting, splitting4"},
      {"scene: unknown formulation",
       {{"s.toml", std::string("[simulation]\nduration = 1\nformulation = \"inertial\"\n[[bodies]]\nname = "
                               "\"a\"\nshape = { type = \"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               131)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:3:15: [simulation]: unknown formulation \"inertial\"; choose one of: world, "
       "mixed, body"},
      {"scene: negative rtol",
       {{"s.toml", std::string("[simulation]\nduration = 1\nrtol = -1\n[[bodies]]\nname = \"a\"\nshape = { "
                               "type = \"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               116)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:3:8: [simulation]: rtol is -1: it must be positive"},
      {"scene: negative output interval",
       {{"s.toml", std::string("[simulation]\nduration = 1\noutput_interval = -0.1\n[[bodies]]\nname = "
                               "\"a\"\nshape = { type = \"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               129)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:3:19: [simulation]: output_interval is -0.1 s: it must be zero or positive"},
      {"scene: duration 1e300 (run)",
       {{"s.toml", std::string("[simulation]\nduration = 1e300\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               110)}},
       "{t} run s.toml",
       1,
       "tumble: error: timestep 0.001 s is too small for duration 1e+300 s: 1e+303 steps, more than 2^53, "
       "where a step no longer advances the clock; give a larger timestep or a shorter duration"},
      {"scene: timestep 5e-324 (run)",
       {{"s.toml", std::string("[simulation]\nduration = 1\ntimestep = 5e-324\n[[bodies]]\nname = "
                               "\"a\"\nshape = { type = \"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               124)}},
       "{t} run s.toml",
       1,
       "tumble: error: timestep 5e-324 s is too small for duration 1 s: inf steps, more than 2^53, where a "
       "step no longer advances the clock; give a larger timestep or a shorter duration"},
      {"scene: nothing to simulate",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n", 29)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:1:1: scene: the scene has nothing to simulate: add [[bodies]], [[body_tables]] "
       "or [[particles]]"},
      {"scene: body without name",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nshape = { type = \"box\", size = "
                               "[1, 2, 3] }\ndensity = 1\n",
                               95)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:3:1: [[bodies]] #1: missing 'name': give the body a name, e.g. name = "
       "\"handle\""},
      {"scene: name with a space",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a b\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1\n",
                               108)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:4:8: [[bodies]] #1: name \"a b\" is not allowed: use letters, digits, '_', '-' "
       "and '.' only"},
      {"scene: duplicate names",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n[[bodies]]\nname = \"a\"\nshape "
                               "= { type = \"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               189)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:8:8: [[bodies]] #2: duplicate name \"a\" (first defined at line 4, column 8): "
       "give every body and particle its own name"},
      {"scene: unknown body key",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\ndensty = 3\n",
                               120)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:1: body 'a': unknown key 'densty'; did you mean 'density'?"},
      {"scene: no material",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\n",
                               94)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:3:1: body 'a': missing the material: give density = RHO (kg/m^3) or mass = M "
       "(kg)"},
      {"scene: unknown shape",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"cube\", size = [1, 2, 3] }\ndensity = 1\n",
                               107)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:5:18: body 'a' shape: unknown shape type \"cube\"; did you mean \"cone\"?"},
      {"scene: negative box size",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, -2, 3] }\ndensity = 1\n",
                               107)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:5:36: body 'a' shape (box): size[1] is -2 m: it must be positive"},
      {"scene: sphere radius nan",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"sphere\", radius = nan }\ndensity = 1\n",
                               105)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:5:37: body 'a' shape (sphere): radius is nan: give a finite number (m)"},
      {"scene: density and mass",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\nmass = 1\n",
                               118)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:8: body 'a': 'density' and 'mass' exclude each other: keep one"},
      {"scene: zero mass",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\nmass = 0\n",
                               103)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:6:8: body 'a': mass is 0 kg: it must be positive"},
      {"scene: negative density",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = -5\n",
                               107)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:6:11: body 'a': density is -5 kg/m^3: it must be positive"},
      {"scene: quaternion not unit",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\norientation = [1, 1, 0, 0]\n",
                               136)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:15: body 'a': orientation has norm 1.41421, more than 0.001 from 1: give a "
       "unit quaternion [w, x, y, z] (w first); normalised it would be [0.707107, 0.707107, 0, 0]"},
      {"scene: quaternion of 3",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\norientation = [1, 0, 0]\n",
                               133)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:15: body 'a': orientation must be a unit quaternion [w, x, y, z], found an "
       "array of 3"},
      {"scene: euler angles of 2",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\norientation = { euler_zyx = [1, "
                               "2] }\n",
                               146)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:29: body 'a' orientation: euler_zyx must be an array of 3 numbers (rad), "
       "found an array of 2"},
      {"scene: axis without angle",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\norientation = { axis = [0, 0, "
                               "1] }\n",
                               144)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:15: body 'a' orientation: missing 'angle': give a finite number (rad)"},
      {"scene: position of 2",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\nposition = [1, 2]\n",
                               127)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:12: body 'a': position must be an array of 3 numbers (m), found an array of "
       "2"},
      {"scene: velocity is a string",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\nvelocity = \"fast\"\n",
                               127)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:12: body 'a': velocity must be an array of 3 numbers (m/s), found the string "
       "\"fast\""},
      {"scene: unknown angular velocity frame",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\nangular_velocity_frame = "
                               "\"inertial\"\n",
                               145)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:26: body 'a': angular_velocity_frame must be \"world\", \"reference\" (the "
       "body's own axes; \"body\" is the older name) or \"principal\" (its principal axes), found "
       "\"inertial\""},
      {"scene: unknown velocity_of",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\nvelocity_of = \"centre\"\n",
                               132)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:15: body 'a': velocity_of must be \"origin\" (the reference frame's origin, "
       "the default) or \"com\" (the centre of mass), found \"centre\""},
      {"scene: missing mesh file",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nmesh = "
                               "\"nope.stl\"\ndensity = 1\n",
                               81)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:5:8: body 'a': cannot load mesh \"nope.stl\": nope.stl: no such file; check "
       "the path and the working directory; mesh paths are relative to the scene file's directory"},
      {"scene: mesh is a directory",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nmesh = "
                               "\"d\"\ndensity = 1\n",
                               74)},
        {"d/x", std::string()}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:5:8: body 'a': cannot load mesh \"d\": d: a directory, not a regular file; "
       "give a mesh file (tumble reads input from regular files only: save a stream to a file first); mesh "
       "paths are relative to the scene file's directory"},
      {"scene: inertia breaks the triangle inequality",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nmass = 1\ninertia = "
                               "[1, 1, 3]\n",
                               80)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:6:11: body 'a': inertia tensor violates the triangle inequality: the largest "
       "principal moment 3 exceeds the sum of the other two 1 + 1 = 2 kg*m^2 (by 1); no mass distribution "
       "has such moments \xe2\x80\x94 check signs of products of inertia and units"},
      {"scene: inertia not symmetric",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nmass = 1\ninertia = "
                               "[[1, 0.1, 0], [0, 1, 0], [0, 0, 1]]\n",
                               106)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:6:11: body 'a': inertia must be symmetric (inertia[i][j] = inertia[j][i]): "
       "check the products of inertia"},
      {"scene: inertia not positive definite",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nmass = 1\ninertia = "
                               "[-1, 1, 1]\n",
                               81)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:6:12: body 'a': inertia[0] is -1 kg*m^2: it must be positive"},
      {"scene: shell thicker than the body",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"sphere\", radius = 1 }\nthickness = 5\ndensity = 1\n",
                               117)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:5:9: body 'a': shell thickness 5 m does not fit inside the sphere: its walls "
       "can be at most 1 m thick (the radius of the largest sphere inside it); for a thick-walled body "
       "subtract an inner solid as a hole"},
      {"scene: ellipsoid shell",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"ellipsoid\", semi_axes = [1, 2, 3] }\nthickness = 0.01\ndensity = 1\n",
                               134)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:5:9: body 'a': a thin ellipsoidal shell has no closed form (its surface "
       "integrals are elliptic); tessellate the ellipsoid into a mesh and use shell mass properties of the "
       "mesh"},
      {"scene: torus tube too fat",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"torus\", major_radius = 1, minor_radius = 2 }\ndensity = 1\n",
                               126)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:5:9: body 'a': torus minor radius 2 m exceeds major radius 1 m: the tube would "
       "overlap itself; give minor radius <= major radius"},
      {"scene: hole larger than the body",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = "
                               "\"c\"\n[[bodies.parts]]\nshape = { type = \"box\", size = [1, 1, 1] "
                               "}\ndensity = 1\n[[bodies.parts]]\nshape = { type = \"box\", size = [2, 2, 2] "
                               "}\ndensity = 1\nhole = true\n",
                               207)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:8:1: body 'c' part 2: this hole would remove 8 kg from the 1 kg of the parts "
       "before it: a hole must lie inside the parts it cuts, listed after them"},
      {"scene: particle with zero mass",
       {{"s.toml",
         std::string("[simulation]\nduration = 0.01\n[[particles]]\nname = \"p\"\nmass = 0\n", 63)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:5:8: particle 'p': mass is 0 kg: it must be positive"},
      {"scene: event on an unknown body",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[[events]]\nname = \"e\"\nbody = \"c\"\ncolumn = \"w2\"\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:9:8: event 'e': no body or particle named \"c\"; did you mean \"b\"?"},
      {"scene: event on an unknown column",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[[events]]\nname = \"e\"\nbody = \"b\"\ncolumn = \"w4\"\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:10:10: event 'e': no output column \"w4\"; did you mean \"wx\"?"},
      {"scene: event that watches nothing",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[[events]]\nname = \"e\"\nbody = \"b\"\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:7:1: event 'e': say what to watch: column = \"w2\" (a column of the output "
       "table crossing `value`) or axis, toward and angle_deg (the angle between a body axis and a world "
       "direction)"},
      {"scene: event with a column and an axis",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[[events]]\nname = \"e\"\nbody = \"b\"\ncolumn = \"w2\"\naxis = [1, 0, 0]\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:11:8: event 'e': 'column' and 'axis' exclude each other: keep one"},
      {"scene: event angle beyond 180 degrees",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[[events]]\nname = \"e\"\nbody = \"b\"\naxis = [1, 0, 0]\ntoward = [0, 0, "
         "1]\nangle_deg = 200\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:12:13: event 'e': angle_deg = 200: an angle between two directions is 0 to "
       "180"},
      {"scene: event with an unknown direction",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[[events]]\nname = \"e\"\nbody = \"b\"\ncolumn = \"w2\"\ndirection = \"up\"\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:11:13: event 'e': unknown direction \"up\"; choose \"both\" (default), "
       "\"rising\" (g goes from below to above) or \"falling\""},
      {"scene: ensemble varies a body that is not there",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = "
         "1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.c.mass\"\ndistribution = "
         "\"uniform\"\nlow = "
         "1\nhigh = 2\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:10:8: [ensemble] vary #1: path bodies.c.mass: no element of bodies is named "
       "\"c\""},
      {"scene: unknown force type",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n[[forces]]\ntype = "
                               "\"gravity\"\n",
                               137)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:8:8: [[forces]] #1: unknown force type \"gravity\"; choose \"force\", "
       "\"torque\", \"damping\", \"drag\", \"spring\", \"gravity_gradient\""},
      {"scene: force on an unknown body",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n[[forces]]\ntype = "
                               "\"force\"\nbody = \"zz\"\nforce = [1, 0, 0]\n",
                               165)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:9:8: [[forces]] #1 (force): no body named \"zz\"; did you mean \"a\"?"},
      {"scene: negative damping",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n[[forces]]\ntype = "
                               "\"damping\"\nlinear = -1\n",
                               149)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:9:10: [[forces]] #1 (damping): linear is -1 N*s/m: it must be zero or "
       "positive"},
      {"scene: spring without stiffness",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n[[particles]]\nname = "
                               "\"p\"\nmass = 1\n[[forces]]\ntype = \"spring\"\na = { body = \"a\" }\nb = { "
                               "particle = \"p\" }\n",
                               212)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:10:1: [[forces]] #1 (spring): missing 'stiffness': give a positive number "
       "(N/m)"},
      {"scene: gravity of 2",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n[world]\ngravity = [0, -9.81]\n",
                               138)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:8:11: [world]: gravity must be an array of 3 numbers (m/s^2), found an array "
       "of 2"},
      {"scene: unknown output field",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n[output]\nfields = "
                               "[\"position\", \"spin\"]\n",
                               148)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:8:10: [output]: unknown output field 'spin': the fields are position, "
       "orientation, velocity, angular_velocity, com_position, com_velocity, angular_velocity_reference, "
       "angular_velocity_principal, orientation_principal, euler_zyx, euler_zxz, axis_angle, mrp, "
       "crp, euler_zyx_lvlh, mrp_lvlh, angular_velocity_lvlh"},
      {"scene: repeated output field",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n[output]\nfields = "
                               "[\"position\", \"position\"]\n",
                               152)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:8:10: [output]: output field 'position' is listed twice: give each field once"},
      {"scene: orbit-frame field without a central body",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n[output]\nfields = "
                               "[\"position\", \"euler_zyx_lvlh\"]\n")}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:8:10: [output]: output field 'euler_zyx_lvlh' is relative to the orbit frame "
       "(LVLH) of each body about its central body, and the system has none: add a gravity_gradient force "
       "(the central "
       "body's gravity), or "
       "choose a field in world axes"},
      {"scene: exact integrator with a torque (run)",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\nintegrator = \"exact\"\n[[bodies]]\nname = "
                               "\"a\"\nshape = { type = \"box\", size = [1, 2, 3] }\ndensity = "
                               "1000\n[[forces]]\ntype = \"torque\"\nbody = \"a\"\ntorque = [0, 0, 1]\n",
                               187)}},
       "{t} run s.toml",
       1,
       "tumble: error: integrator 'exact' solves torque-free motion only (no forces, or uniform gravity), "
       "but the scene has torque (0, 0, 1) N*m (world axes) on body 'a'; use 'splitting', which is exact for "
       "the free motion and second order in the forces (or 'splitting4' for fourth order)"},
      {"scene: body table missing",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[body_tables]]\nfile = \"b.csv\"\n", 60)}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:4:8: [[body_tables]] #1: cannot read body table b.csv: no such file; check the "
       "path and the working directory; the path is relative to the scene file's directory"},
      {"scene: body table unknown column",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[body_tables]]\nfile = \"b.csv\"\n", 60)},
        {"b.csv", std::string("mass,I1,I2,I3,spin\n1,1,1,1,0\n", 29)}},
       "{t} check s.toml",
       1,
       "tumble: error: b.csv:1:15: unknown column \"spin\"; the columns are: name, mass, I1, I2, I3, px, py, "
       "pz, qw, qx, qy, qz, vx, vy, vz, wx, wy, wz"},
      {"scene: body table bad number",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[body_tables]]\nfile = \"b.csv\"\n", 60)},
        {"b.csv", std::string("mass,I1,I2,I3\n1,1,one,1\n", 24)}},
       "{t} check s.toml",
       1,
       "tumble: error: b.csv:2:5: column I2: expected a number, found \"one\""},
      {"scene: body table short row",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[body_tables]]\nfile = \"b.csv\"\n", 60)},
        {"b.csv", std::string("mass,I1,I2,I3\n1,1,1\n", 20)}},
       "{t} check s.toml",
       1,
       "tumble: error: b.csv:2:1: row 1 has 3 fields, the header 4"},
      {"scene: body table negative mass",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[body_tables]]\nfile = \"b.csv\"\n", 60)},
        {"b.csv", std::string("mass,I1,I2,I3\n-1,1,1,1\n", 23)}},
       "{t} check s.toml",
       1,
       "tumble: error: b.csv:2:1: body 'b_0': mass is -1 kg but must be positive"},
      {"mesh: glTF buffer outside the mesh's directory (never read: it would leak into outputs)",
       {{"model/up.gltf",
         R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("buffers":[{"byteLength":96,"uri":"../secret.bin"}],"bufferViews":[{"buffer":0,"byteLength":96}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3"}]})"},
        {"secret.bin", std::string(96, '\0')}},
       "{t} inertia model/up.gltf --density 1",
       1,
       "tumble: error: model/up.gltf: the mesh refers to the file …"},
      {"run: -o naming a glTF's buffer file (an input as much as the mesh) is refused",
       {{"model/cube.gltf", kCubeGltf},
        {"model/cube.bin", cube_gltf_bin()},
        {"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"c\"\nmesh = \"model/cube.gltf\"\ndensity = "
         "1000\n"}},
       "{t} run s.toml -o model/cube.bin",
       1,
       "tumble: error: -o model/cube.bin is the file …"},
      {"mesh: two nested closed surfaces both facing outward (the material between counted twice)",
       {{"m.obj",
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nv 0.25 0.25 0.25\nv 0.75 "
         "0.25 0.25\nv 0.75 0.75 0.25\nv 0.25 0.75 0.25\nv 0.25 0.25 0.75\nv 0.75 0.25 0.75\nv 0.75 0.75 "
         "0.75\nv 0.25 0.75 0.75\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 1 5 8 4\nf 2 3 7 6\nf 9 12 "
         "11 "
         "10\nf 13 14 15 16\nf 9 10 14 13\nf 11 12 16 15\nf 9 13 16 12\nf 10 11 15 14\n"}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj: the closed surface of triangle 12 (12 triangles) lies inside the closed "
       "surface "
       "of triangle 0 (12 triangles), and both face outward: the material between them would be counted "
       "twice; if the inner surface bounds a cavity, reverse its triangles (its normals must point into the "
       "cavity); if it is a part of its own, give it as another part or body"},
      {"mesh: empty OBJ",
       {{"m.obj", std::string()}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj: the file holds no vertices and no faces (empty?); export the surface as "
       "triangles or polygons"},
      {"mesh: OBJ face index 0",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 0 4 "
                              "3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\nf 4 5 8\n",
                              160)}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj:9:3: vertex index 0: OBJ counts vertices from 1 (or from -1 backwards)"},
      {"mesh: OBJ face index past the end",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 4 "
                              "99\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\nf 4 5 8\n",
                              161)}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj:9:7: vertex index 99 is past the last vertex: the file has 8"},
      {"mesh: OBJ bad number",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 x 1\nv 0 1 1\nf 1 4 "
                              "3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\nf 4 5 8\n",
                              160)}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj:7:5: y coordinate 'x' is not a number"},
      {"mesh: OBJ nan coordinate",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 nan 1\nv 0 1 1\nf 1 "
                              "4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 "
                              "8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n",
                              162)}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj:7:5: y coordinate 'nan' is not finite; fix the file"},
      {"mesh: OBJ open (a face missing)",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 4 "
                              "3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\n",
                              152)}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj: cannot compute solid mass properties: the mesh has 3 boundary edges (an open "
       "surface), first: edge (7,4) of triangle 3, edge (3,7) of triangle 8, edge (4,3) of triangle 10; "
       "close the holes in a mesh editor, or treat it as a thin-walled part (shell mass properties): add "
       "--shell (with --thickness T and --density, or with --mass)"},
      {"mesh: OBJ inconsistently wound",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 3 "
                              "4\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\nf 4 5 8\n",
                              160)}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj: cannot compute solid mass properties: the mesh is inconsistently oriented: 3 "
       "edges are traversed in the same direction by both of their triangles, first: edge (0,2) in triangles "
       "0 and 1, edge (3,0) in triangles 0 and 10, edge (2,3) in triangles 0 and 8; flip one triangle of "
       "each pair so that all wind counter-clockwise seen from outside (e.g. MeshLab: Re-Orient all faces "
       "coherently)"},
      {"mesh: OBJ inside out (warns)",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 3 4 "
                              "1\nf 2 3 1\nf 7 6 5\nf 8 7 5\nf 6 2 1\nf 5 6 1\nf 7 3 2\nf 6 7 2\nf 8 4 3\nf "
                              "7 8 3\nf 5 1 4\nf 8 5 4\n",
                              160)}},
       "{t} inertia m.obj --density 1",
       0,
       "tumble: warning: m.obj: the mesh is inside-out (signed volume -1 m^3: its triangles wind clockwise "
       "seen from outside); it was integrated with the orientation flipped. Flip the normals in a mesh "
       "editor to silence this warning"},
      {"mesh: OBJ degenerate triangle, the surface closed without it: left out with a notice",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 4 "
                              "3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\nf 4 5 8\nf 1 1 2\n",
                              168)}},
       "{t} inertia m.obj --density 1",
       0,
       "tumble: warning: m.obj: left out 1 degenerate (zero-area) triangle (12), which add nothing to the "
       "solid: the surface without it is closed. Remove it in a mesh editor to silence this notice"},
      {"mesh: OBJ zero-area sliver closing a T-junction (the surface without it is open)",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nv 0.5 "
                              "0 0\nf 1 4 3\nf 1 3 9\nf 9 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 "
                              "7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\nf 1 9 2\n",
                              186)}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj: cannot compute solid mass properties: the mesh has 1 degenerate triangle (a "
       "repeated vertex or zero area), first: triangle 13 (vertices 0, 8, 1); remove them (e.g. MeshLab: "
       "Remove Duplicate Faces / Remove Zero Area Faces) or re-export the mesh"},
      {"units: a density in g/cm^3 typed as kg/m^3 (warned, with the number meant)",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 2.7\n",
                               108)}},
       "{t} check s.toml",
       0,
       "tumble: warning: s.toml:6:11: density 2.7 kg/m^3 is lighter than any solid (air is 1.2 kg/m^3): if "
       "it "
       "is in g/cm^3, write density = 2700 (kg/m^3)"},
      {"units: Euler angles in degrees (warned, with the radians)",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\norientation = { euler_zyx = [0, "
                               "90, 0] }\n",
                               150)}},
       "{t} check s.toml",
       0,
       "tumble: warning: s.toml:7:29: euler_zyx[1] = 90 rad is more than a full turn: angles are in radians; "
       "if these are degrees, write euler_zyx = [0, 1.5708, 0]"},
      {"units: a quaternion written (x, y, z, w) (a note on the order)",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\norientation = [0, 0, 0, 1]\n",
                               136)}},
       "{t} check s.toml",
       0,
       "tumble: warning: s.toml:7:15: orientation = [0, 0, 0, 1] is read as [w, x, y, z] (w first): a "
       "half-turn about an axis. If it was written [x, y, z, w], reorder it to [1, 0, 0, 0]"},
      {"units: a mesh drawn in millimetres read without scale (warned; scale = 1.0 says it is metres)",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"part\"\nmesh = "
                               "\"part.obj\"\ndensity = 2700\n",
                               87)},
        {"part.obj", std::string("v 0 0 0\nv 300 0 0\nv 300 200 0\nv 0 200 0\nv 0 0 100\nv 300 0 100\nv 300 "
                                 "200 100\nv 0 200 100\nf 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 "
                                 "5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n",
                                 184)}},
       "{t} check s.toml",
       0,
       "tumble: warning: s.toml:5:8: part.obj: the mesh is 374.2 m across as its coordinates are read "
       "(metres): if its file is in millimetres, add scale = 0.001 (inches: 0.0254); if it really is that "
       "large, say scale = 1.0"},
      {"units: --strict makes a scene's warnings errors (the error follows the warnings)",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 2.7\n",
                               108)}},
       "set -o pipefail; {t} run s.toml -o o.csv --strict 2>&1 | grep -v '^tumble: warning'",
       1,
       "tumble: error: 1 warning about the scene, and --strict makes them errors: fix the scene (each "
       "warning says how) or drop --strict"},
      {"mesh: OBJ points only",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\n", 24)}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj: the file has 3 vertices but no faces: a point cloud has no volume; tumble "
       "needs the closed surface as triangles or polygons (reconstruct a surface from the points first, then "
       "export it)"},
      {"mesh: OBJ in UTF-16",
       {{"m.obj", std::string("\xff\xfev\x00 \x00"
                              "0\x00 \x00"
                              "0\x00 \x00"
                              "0\x00\n\x00v\x00 \x00"
                              "1\x00 \x00"
                              "0\x00 \x00"
                              "0\x00\n\x00v\x00 \x00"
                              "1\x00 \x00"
                              "1\x00 \x00"
                              "0\x00\n\x00v\x00 \x00"
                              "0\x00 \x00"
                              "1\x00 \x00"
                              "0\x00\n\x00v\x00 \x00"
                              "0\x00 \x00"
                              "0\x00 \x00"
                              "1\x00\n\x00v\x00 \x00"
                              "1\x00 \x00"
                              "0\x00 \x00"
                              "1\x00\n\x00v\x00 \x00"
                              "1\x00 \x00"
                              "1\x00 \x00"
                              "1\x00\n\x00v\x00 \x00"
                              "0\x00 \x00"
                              "1\x00 \x00"
                              "1\x00\n\x00"
                              "f\x00 \x00"
                              "1\x00 \x00"
                              "4\x00 \x00"
                              "3\x00\n\x00"
                              "f\x00 \x00"
                              "1\x00 \x00"
                              "3\x00 \x00"
                              "2\x00\n\x00"
                              "f\x00 \x00"
                              "5\x00 \x00"
                              "6\x00 \x00"
                              "7\x00\n\x00"
                              "f\x00 \x00"
                              "5\x00 \x00"
                              "7\x00 \x00"
                              "8\x00\n\x00"
                              "f\x00 \x00"
                              "1\x00 \x00"
                              "2\x00 \x00"
                              "6\x00\n\x00"
                              "f\x00 \x00"
                              "1\x00 \x00"
                              "6\x00 \x00"
                              "5\x00\n\x00"
                              "f\x00 \x00"
                              "2\x00 \x00"
                              "3\x00 \x00"
                              "7\x00\n\x00"
                              "f\x00 \x00"
                              "2\x00 \x00"
                              "7\x00 \x00"
                              "6\x00\n\x00"
                              "f\x00 \x00"
                              "3\x00 \x00"
                              "4\x00 \x00"
                              "8\x00\n\x00"
                              "f\x00 \x00"
                              "3\x00 \x00"
                              "8\x00 \x00"
                              "7\x00\n\x00"
                              "f\x00 \x00"
                              "4\x00 \x00"
                              "1\x00 \x00"
                              "5\x00\n\x00"
                              "f\x00 \x00"
                              "4\x00 \x00"
                              "5\x00 \x00"
                              "8\x00\n\x00",
                              322)}},
       "{t} inertia m.obj --density 1",
       1,
       "tumble: error: m.obj: the file is UTF-16 text (byte-order mark FF FE, little-endian); tumble reads "
       "mesh text as ASCII or UTF-8: convert it, e.g. iconv -f UTF-16 -t UTF-8 'm.obj' > 'm-utf8.obj'"},
      {"mesh: OBJ --part out of range",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 4 "
                              "3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\nf 4 5 8\n",
                              160)}},
       "{t} inertia m.obj --density 1 --part 5",
       1,
       "tumble: error: m.obj: part 5 does not exist: the file has 1 group ('(unnamed)'); give 1 to 1"},
      {"mesh: OFF wrong header",
       {{"m.off",
         std::string("OFX\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n", 66)}},
       "{t} inertia m.off --density 1",
       1,
       "tumble: error: m.off:1:1: 'OFX' is not an OFF header: expected OFF (or COFF, NOFF, STOFF...) "
       "followed by the vertex and face counts"},
      {"mesh: OFF counts larger than the file",
       {{"m.off", std::string("OFF\n1000000000 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 "
                              "1 2 3\n",
                              75)}},
       "{t} inertia m.off --density 1",
       1,
       "tumble: error: m.off:2:1: the header declares 1000000000 vertices and 4 faces, which need at least "
       "6000000032 bytes (6 a vertex, 8 a face), but only 56 follow: the counts are wrong or the file is "
       "truncated"},
      {"mesh: OFF truncated",
       {{"m.off", std::string("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 ", 56)}},
       "{t} inertia m.off --density 1",
       1,
       "tumble: error: m.off:2:1: the header declares 4 vertices and 4 faces, which need at least 56 bytes "
       "(6 a vertex, 8 a face), but only 46 follow: the counts are wrong or the file is truncated"},
      {"mesh: OFF polygon of 2",
       {{"m.off",
         std::string("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n2 1 2\n", 64)}},
       "{t} inertia m.off --density 1",
       1,
       "tumble: error: m.off:2:1: the header declares 4 vertices and 4 faces, which need at least 56 bytes "
       "(6 a vertex, 8 a face), but only 54 follow: the counts are wrong or the file is truncated"},
      {"mesh: PLY without header end",
       {{"m.ply", std::string("ply\nformat ascii 1.0\nelement vertex 3\n", 38)}},
       "{t} inertia m.ply --density 1",
       1,
       "tumble: error: m.ply:4:1: the PLY header has no 'end_header' line"},
      {"mesh: PLY unknown format",
       {{"m.ply", std::string("ply\nformat ebcdic 1.0\nend_header\n", 33)}},
       "{t} inertia m.ply --density 1",
       1,
       "tumble: error: m.ply:2:8: unknown PLY format 'ebcdic': expected ascii, binary_little_endian or "
       "binary_big_endian"},
      {"mesh: binary PLY truncated",
       {{"m.ply", std::string("ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float "
                              "x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar "
                              "int "
                              "vertex_indices\nend_"
                              "header\n\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00"
                              "\x00\x00\x00",
                              189)}},
       "{t} inertia m.ply --density 1",
       1,
       "tumble: error: m.ply:3:1: 'element vertex 4' needs at least 48 bytes (12 per vertex), but only 20 "
       "follow the header: the count is wrong or the file is truncated"},
      {"mesh: PLY counts wrong",
       {{"m.ply", std::string("ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float "
                              "y\nproperty float z\nelement face 4\nproperty list uchar int "
                              "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 "
                              "3 2\n3 1 2 3\n",
                              210)}},
       "{t} inertia m.ply --density 1",
       1,
       "tumble: error: m.ply:14:7: face 0 has 1 corners; a face needs at least 3 (or the header's counts are "
       "wrong)"},
      {"mesh: binary STL truncated",
       {{"m.stl", std::string(80, static_cast<char>(0)) + std::string("\x0c", 1) +
                      std::string(519, static_cast<char>(0))}},
       "{t} inertia m.stl --density 1",
       1,
       "tumble: error: m.stl: truncated binary STL: the header says 12 triangles (84 + 50 x 12 = 684 bytes), "
       "the file size (600 bytes) allows 10"},
      {"mesh: binary STL with no triangles",
       {{"m.stl", std::string(84, static_cast<char>(0))}},
       "{t} inertia m.stl --density 1",
       1,
       "tumble: error: m.stl: a binary STL of 0 triangles (its 84-byte header only): no surface"},
      {"mesh: ASCII STL bad number",
       {{"m.stl", std::string("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\nvertex 1 0 "
                              "0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n",
                              108)}},
       "{t} inertia m.stl --density 1",
       1,
       "tumble: error: m.stl:4:12: z coordinate 'zero' is not a number"},
      {"mesh: ASCII STL with a 100 kB number",
       {{"m.stl", std::string("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 ", 49) +
                      std::string(100000, static_cast<char>(57)) +
                      std::string("x\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n", 56)}},
       "{t} inertia m.stl --density 1",
       1,
       "tumble: error: m.stl:4:12: z coordinate '9999999999999999999999999999999999999999...' is not a "
       "number"},
      {"mesh: unknown extension",
       {{"m.xyz", std::string("1 2 3\n", 6)}},
       "{t} inertia m.xyz --density 1",
       1,
       "tumble: error: m.xyz: cannot read the mesh: No suitable reader found for the file format of file "
       "\"m.xyz\"."},
      {"mesh: a FIFO",
       {},
       "mkfifo f.obj && {t} inertia f.obj --density 1",
       1,
       "tumble: error: f.obj: a FIFO (named pipe), which may never end, not a regular file; give a mesh file "
       "(tumble reads input from regular files only: save a stream to a file first)"},
      {"mesh: /dev/zero",
       {},
       "{t} inertia /dev/zero --density 1",
       1,
       "tumble: error: /dev/zero: a character device (such as /dev/zero), which may never end, not a regular "
       "file; give a mesh file (tumble reads input from regular files only: save a stream to a file first)"},
      {"mesh: shell thicker than the shortest edge (warns)",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 4 "
                              "3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\nf 4 5 8\n",
                              160)}},
       "{t} inertia m.obj --shell --thickness 2 --density 1",
       0,
       "tumble: warning: m.obj: shell thickness 2 m is at least the mesh's shortest edge, 1 m (triangle 0): "
       "the thin-wall model needs the wall thin against every feature of the surface; for a thick wall "
       "subtract an inner solid as a hole"},
      {"ensemble: -o whose summary would replace the study's own scene",
       {{"t.summary.csv",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} ensemble t.summary.csv -o t.csv",
       1,
       "tumble: error: -o t.csv would overwrite the study's input t.summary.csv (a study writes OUT, …"},
      {"ensemble: -o whose chosen run's run.json would replace an input",
       {{"t.run-2.run.json",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} ensemble t.run-2.run.json -o t.h5",
       1,
       "tumble: error: -o t.h5 would overwrite the study's input t.run-2.run.json (a study writes OUT, …"},
      {"ensemble: -o - (a study is files, not a stream)",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} ensemble s.toml -o -",
       1,
       "tumble: error: -o -: a study writes a table and files beside it (OUT.summary.csv, OUT.run-I.csv, "
       "OUT.partial-RANK), not a stream: give a file name, e.g. -o s_ensemble.csv"},
      {"ensemble: -o a device (no companions beside /dev/null)",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} ensemble s.toml -o /dev/null",
       1,
       "tumble: error: -o /dev/null is not a regular file (a device, FIFO or socket): a study writes files "
       "beside its table, which must not go beside it; give a file name, e.g. -o s_ensemble.csv"},
      {"ensemble: -o a directory",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"},
        {"out/keep", "x"}},
       "{t} ensemble s.toml -o out",
       1,
       "tumble: error: -o out is a directory: give a file name, e.g. -o out/s_ensemble.csv"},
      {"cli: an empty value ('') is not the default",
       {},
       "{t} inertia --shape sphere --radius 1 --density ''",
       2,
       "tumble: error: --density was given an empty value (''): give one, or leave the option out; see "
       "tumble inertia --help"},
      {"cli: an empty value after '='",
       {{"s.toml", kBoxScene}},
       "{t} run s.toml --timestep=",
       2,
       "tumble: error: --timestep was given an empty value: give one after the '=', or leave the option "
       "out; see tumble run --help"},
      {"cli: output with an unknown extension (not silently CSV)",
       {{"s.toml", kBoxScene}},
       "{t} run s.toml -o out.xyz",
       1,
       "tumble: error: -o out.xyz: unknown extension .xyz; tumble writes CSV (.csv), HDF5 (.h5, .hdf5) or "
       "CCSDS attitude messages (.aem): name the file so, or give --format csv, hdf5 or aem"},
      {"cli: an attitude message with chosen fields",
       {{"s.toml", kBoxScene}},
       "{t} run s.toml -o out.aem --fields position",
       1,
       "tumble: error: an attitude message (.aem) holds each body's quaternion and body rates, whatever the "
       "fields: drop --fields, or write CSV or HDF5"},
      {"cli: an attitude message with a malformed epoch",
       {{"s.toml", kBoxScene}},
       "{t} run s.toml -o out.aem --epoch 2026-02-30T00:00:00",
       1,
       "tumble: error: --epoch 2026-02-30T00:00:00: no such day; give a date as YYYY-MM-DDThh:mm:ss[.fff], "
       "e.g. "
       "2026-12-03T15:00:00.000 (UTC)"},
      {"cli: an epoch without an attitude message",
       {{"s.toml", kBoxScene}},
       "{t} run s.toml -o out.csv --epoch 2026-12-03T00:00:00",
       1,
       "tumble: error: --epoch dates and frames an attitude message: give an .aem output (-o s.aem)"},
      {"cli: output extension in capitals is HDF5",
       {{"s.toml", kBoxScene}},
       "{t} run s.toml -o OUT.H5 -q && head -c 8 OUT.H5 | od -c | grep -q 'H   D   F'",
       0,
       ""},
      {"cli: checkpoint into a directory that does not exist yet (created before the run)",
       {{"s.toml", kBoxScene}},
       "{t} run s.toml -o r.csv --checkpoint later/r.ckpt -q && test -d later",
       0,
       ""},
      {"cli: checkpoint that cannot be written (refused before the run)",
       {{"s.toml", kBoxScene}},
       "{t} run s.toml -o r.csv --checkpoint /proc/r.ckpt",
       1,
       "tumble: error: cannot write the checkpoint /proc/r.ckpt: …"},
      {"cli: checkpoint onto a device",
       {{"s.toml", kBoxScene}},
       "{t} run s.toml -o r.csv --checkpoint /dev/null",
       1,
       "tumble: error: --checkpoint /dev/null is not a regular file: give a file name, e.g. --checkpoint "
       "run.checkpoint"},
      {"ensemble: too many threads",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} ensemble s.toml -o t.csv --threads 100000",
       1,
       "tumble: error: threads = 100000 is invalid: give a count from 1 to 4096, or 0 for one per core"},
      {"ensemble: trajectories every = 0.5 (not a whole number)",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n[ensemble.outputs]\ntrajectories = { every = 0.5 }\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:15:26: [ensemble] outputs trajectories: every = 0.5 must be a whole number "
       "from 1 to 2^40 (every = N writes the trajectories of runs 0, N, 2N, …); leave it out for none"},
      {"ensemble: trajectories every = 1e30 (past any count)",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n[ensemble.outputs]\ntrajectories = { every = 1e30 }\n"}},
       "{t} ensemble s.toml -o t.csv",
       1,
       "tumble: error: s.toml:15:26: [ensemble] outputs trajectories: every = 1e+30 must be a whole number "
       "…"},
      {"ensemble: trajectories worst = 2.5",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n[ensemble.outputs]\ntrajectories = { worst = 2.5, by = "
         "\"energy_drift_max\" }\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:15:26: [ensemble] outputs trajectories: worst = 2.5 must be a whole number …"},
      {"ensemble: a path into [ensemble] itself",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"ensemble.runs\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:10:8: [ensemble] vary #1: path ensemble.runs: a study cannot vary its own "
       "[ensemble] table; vary a value of the scene (simulation, bodies, forces, …)"},
      {"ensemble: runs = 2^40 (a table no machine holds): check says so",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 1099511627776\n[[ensemble.vary]]\npath = "
         "\"bodies.b.mass\"\ndistribution = \"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: runs = 1099511627776: the table is gathered in memory to be written, about 8.03e+04 "
       "GB, more than this machine's …"},
      {"ensemble: runs = 2^40: ensemble refuses before any run",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 1099511627776\n[[ensemble.vary]]\npath = "
         "\"bodies.b.mass\"\ndistribution = \"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} ensemble s.toml -o t.csv; s=$?; ! ls t.csv* && exit $s",
       1,
       "tumble: error: runs = 1099511627776: the table is gathered in memory to be written, about 8.03e+04 "
       "GB, more than this machine's …"},
      {"check: a duration run refuses (the clock would not advance) is refused by check too",
       {{"s.toml",
         "[simulation]\nduration = 1e300\n[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 2, "
         "3] }\ndensity = 1000\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: timestep 0.001 s is too small for duration 1e+300 s: 1e+303 steps, more than 2^53, "
       "where a step no longer advances the clock; give a larger timestep or a shorter duration"},
      {"check: a run that run refuses without --force (days) is a warning",
       {{"s.toml",
         "[simulation]\nduration = 1e6\ntimestep = 1e-6\n[[bodies]]\nname = \"a\"\nshape = { type = \"box\", "
         "size = [1, 2, 3] }\ndensity = 1000\n"}},
       "{t} check s.toml",
       0,
       "tumble: warning: tumble run would refuse it: this run would take about …"},
      {"scene: a spring from a body to itself",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 2, "
         "3] }\ndensity = 1000\n[[bodies]]\nname = \"c\"\nshape = { type = \"box\", size = [1, 2, 3] "
         "}\ndensity = 1000\n[[forces]]\ntype = \"spring\"\na = { body = \"a\", point = [0.5, 0, 0] }\nb = { "
         "body = \"a\" }\nstiffness = 10\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:14:5: [[forces]] #1 (spring): both ends are on body 'a': within one rigid body "
       "the spring's forces cancel and it does nothing; attach b to another body, a particle or an anchor"},
      {"scene: a spring of non-zero rest length between coincident points",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 2, "
         "3] }\ndensity = 1000\n[[bodies]]\nname = \"c\"\nshape = { type = \"box\", size = [1, 2, 3] "
         "}\ndensity = 1000\n[[forces]]\ntype = \"spring\"\na = { body = \"a\" }\nb = { body = \"c\" "
         "}\nrest_length = 0.2\nstiffness = 10\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:15:15: [[forces]] #1 (spring): the ends coincide at the start (both at (0, 0, "
       "0) m) while the rest length is 0.2 m: the spring has no direction to push in; move an end apart or "
       "give rest_length = 0"},
      {"ensemble: truncated_normal beyond 150 standard deviations",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"truncated_normal\"\nmean = 1\nstd = 0.001\nlow = 2\nhigh = 3\n"}},
       "{t} check s.toml",
       1,
       "tumble: error: s.toml:14:7: [ensemble] vary #1: [low, high] = [2, 3] lies 1000 standard deviations "
       "from the mean 1: too far in the tail to draw from (at most 150); move the mean or the bounds"},
      // The limits leave 10 and 20 MB above what the program maps to start (about 70 MB since tumble_fit
      // links Ceres and its LAPACK, SuiteSparse and glog: 20 MB more), so that the run itself runs out.
      {"limit: ulimit -v during run (10^5 bodies): one line, no file",
       {{"s.toml", "[simulation]\nduration = 0.01\n[[body_tables]]\nfile = \"t.csv\"\n"}},
       "awk 'BEGIN{print \"name,mass,I1,I2,I3,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\"; "
       "for(i=0;i<100000;i++) printf \"b%d,1,1,2,3,%d,0,0,1,0,0,0,0,0,0,1,2,3\\n\", i, i}' > t.csv; (ulimit "
       "-v 80000; {t} run s.toml -o o.csv -q); s=$?; ! ls o.csv* && exit $s",
       1,
       "tumble: error: out of memory: the command needs more memory than this process may use (the "
       "machine's, or a limit such as ulimit -v); nothing was kept under the output names: free memory, "
       "raise the limit, or give a smaller problem"},
      {"limit: ulimit -v during report (10^5 bodies): one line, no crash, no file",
       {{"s.toml", "[simulation]\nduration = 0.01\n[[body_tables]]\nfile = \"t.csv\"\n"}},
       "awk 'BEGIN{print \"name,mass,I1,I2,I3,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\"; "
       "for(i=0;i<100000;i++) printf \"b%d,1,1,2,3,%d,0,0,1,0,0,0,0,0,0,1,2,3\\n\", i, i}' > t.csv && {t} "
       "run s.toml -o o.csv -q && (ulimit -v 90000; {t} report o.csv -o o.html); s=$?; ! ls o.html* && exit "
       "$s",
       1,
       "tumble: error: out of memory: the command needs more memory than this process may use (the "
       "machine's, or a limit such as ulimit -v); nothing was kept under the output names: free memory, "
       "raise the limit, or give a smaller problem"},
      {"report: an ensemble's table (csv) is not a trajectory",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} ensemble s.toml -o e.csv -q && {t} report e.csv",
       1,
       "tumble: error: e.csv is the table of a tumble ensemble study (a row per run), not a trajectory: "
       "report one of its runs' trajectories, e.g. e.run-0.csv (written for the runs that [ensemble.outputs] "
       "trajectories chooses: every = N, worst = N)"},
      {"report: an ensemble's table (h5) is not a trajectory",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"}},
       "{t} ensemble s.toml -o e.h5 -q && {t} report e.h5",
       1,
       "tumble: error: e.h5 is the table of a tumble ensemble study (a row per run), not a trajectory: "
       "report one of its runs' trajectories, e.g. e.run-0.h5 (written for the runs that [ensemble.outputs] "
       "trajectories chooses: every = N, worst = N)"},
      {"report: a trajectory whose times decrease (edited)",
       {{"s.toml", kEventScene}},
       "{t} run s.toml -o o.csv -q && sed -i '3s/^0.01,/0.2,/' o.csv && {t} report o.csv",
       1,
       "tumble: error: o.csv:4: t = 0.02 comes after t = 0.2, but times never decrease: the file is damaged "
       "or "
       "was edited; run the scene again"},
      {"report: a trajectory with a time that is not a number",
       {{"s.toml", kEventScene}},
       "{t} run s.toml -o o.csv -q && sed -i '3s/^0.01,/nan,/' o.csv && {t} report o.csv",
       1,
       "tumble: error: o.csv:3: t = nan is not a time: the file is damaged or was edited; run the scene "
       "again"},
      {"report: an event at a body the trajectory does not have",
       {{"s.toml", kEventScene}},
       "{t} run s.toml -o o.csv -q && sed -i '2s/,a$/,ghost/' o.events.csv && {t} report o.csv",
       1,
       "tumble: error: o.events.csv:2: body 'ghost' is not in o.csv: the file is damaged or was edited; run "
       "the scene again"},
      {"scene: through a pipe (process substitution) is read as a stream",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 2, "
         "3] }\ndensity = 1000\n"}},
       "{t} check <(cat s.toml) > /dev/null",
       0,
       ""},
      {"ensemble: a draw that makes the scene invalid names the run, its values and the drawn value",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 30\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"normal\"\nmean = 0\nstd = 1\n"}},
       "{t} ensemble s.toml -o t.csv",
       1,
       "tumble: error: run 1 (bodies.b.mass = -0.60834419961370922): s.toml, the drawn value: body 'b': mass "
       "is -0.6083441996137092 kg: it must be positive"},
      {"model: a xacro template (Debian has no xacro: expanded first)",
       {{"arm.urdf.xacro",
         "<robot name=\"arm\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
         "  <xacro:property name=\"l\" value=\"0.3\"/>\n</robot>\n"}},
       "{t} model check arm.urdf.xacro",
       1,
       "tumble: error: arm.urdf.xacro:1: <robot>: this is a xacro template, not yet a robot description: "
       "expand "
       "it first, e.g. `xacro arm.urdf.xacro > arm.urdf` (ROS) or `python3 -m xacro arm.urdf.xacro -o "
       "arm.urdf`, "
       "and give tumble arm.urdf"},
      {"model: a document type declaration (entities could expand without bound)",
       {{"r.urdf",
         "<?xml version=\"1.0\"?>\n<!DOCTYPE r [<!ENTITY a \"aaaaaaaa\">]>\n<robot "
         "name=\"r\"/>\n"}},
       "{t} model check r.urdf",
       1,
       "tumble: error: r.urdf:2:1: a document type declaration (<!DOCTYPE ...>) is refused: its entities "
       "could "
       "expand without bound; remove it (robot descriptions need none)"},
      {"model: XML that is not well-formed",
       {{"r.urdf", "<robot name=\"r\">\n  <link name=\"a\">\n</robot>\n"}},
       "{t} model check r.urdf",
       1,
       "tumble: error: r.urdf:3:3: not well-formed XML: Start-end tags mismatch"},
      {"model: a file whose root is not a robot",
       {{"r.xml", "<scene/>\n"}},
       "{t} model check r.xml",
       1,
       "tumble: error: r.xml:1: <scene>: is not a robot description's root: tumble reads URDF (<robot>), "
       "MJCF "
       "(<mujoco>) and SDF (<sdf>)"},
      {"model fix: the output is the input",
       {{"r.urdf", "<robot name=\"r\"><link name=\"a\"/></robot>\n"}},
       "{t} model fix r.urdf -o ./r.urdf",
       1,
       "tumble: error: the fixed model ./r.urdf is the input r.urdf: tumble never overwrites an input; give "
       "another output file"},
      {"scene: arrays nested 40 deep under a small stack (refused before the parser recurses)",
       {{"s.toml", "a = [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]\n"}},
       "ulimit -s 256; {t} check s.toml",
       1,
       "tumble: error: s.toml:1:37: arrays and inline tables nested more than 32 deep: a scene needs a few "
       "levels; flatten the value"},
      {"cli: unknown command",
       {},
       "{t} simulate x.toml",
       2,
       "tumble: error: unknown command 'simulate': the commands are run, resume, check, inertia, report, "
       "ensemble, model, fit; see tumble --help"},
      {"cli: unknown option",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --speed 2",
       2,
       "tumble: error: The following arguments were not expected: 2 --speed; see tumble run --help"},
      {"cli: negative timestep",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --timestep -1",
       1,
       "tumble: error: timestep -1 s is invalid: give a positive step, e.g. 1e-3"},
      {"cli: timestep not a number",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --timestep fast",
       2,
       "tumble: error: Could not convert: --timestep = fast; see tumble run --help"},
      {"cli: unknown integrator",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --integrator rk5",
       1,
       "tumble: error: unknown integrator 'rk5'; choose one of: dopri45, euler, exact, implicit_gyro, "
       "lie_rk4, midpoint, rk4, semi_implicit_euler, splitting, splitting4"},
      {"cli: unknown formulation",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --formulation inertial",
       1,
       "tumble: error: unknown formulation 'inertial'; choose world, mixed or body"},
      {"cli: negative threads",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --threads -1",
       1,
       "tumble: error: threads = -1 is invalid: give a count from 1 to 4096, or 0 for one per core"},
      {"cli: unknown field",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --fields position,spin",
       1,
       "tumble: error: unknown output field 'spin': the fields are position, orientation, velocity, "
       "angular_velocity, com_position, com_velocity, angular_velocity_reference, "
       "angular_velocity_principal, orientation_principal, euler_zyx, euler_zxz, axis_angle, mrp, "
       "crp, euler_zyx_lvlh, mrp_lvlh, angular_velocity_lvlh"},
      {"cli: orbit-frame field without a central body",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n")}},
       "{t} run s.toml --fields position,mrp_lvlh",
       1,
       "tumble: error: output field 'mrp_lvlh' is relative to the orbit frame (LVLH) of each body about its "
       "central body, and the system has none: add a gravity_gradient force (the central body's gravity), or "
       "choose a field in world axes"},
      {"cli: crp at a half turn",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\norientation = [0, 0, 1, 0]\n")}},
       "{t} run s.toml --fields crp -o out.csv",
       1,
       "tumble: error: 'a' at t = 0 s: output field 'crp': the attitude is a half turn, where the classical "
       "Rodrigues parameters are infinite; ask for 'mrp' (which switches to its shadow set there) or "
       "'axis_angle'"},
      {"cli: negative drift threshold",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --drift-threshold -1",
       1,
       "tumble: error: drift threshold -1 is invalid: give a number >= 0 (0 turns the warning off)"},
      {"cli: unknown format",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --format xml",
       2,
       "tumble: error: --format: xml not in {csv,hdf5,aem}; see tumble run --help"},
      {"cli: output interval 1e-300",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --output-interval 1e-300",
       1,
       "tumble: error: output interval 1e-300 s is too small for duration 0.01 s: 1e+298 samples, more than "
       "2^53; give a larger output interval (0 = every step)"},
      {"cli: a run of weeks",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --duration 1e9 --output-interval 1e7",
       1,
       "tumble: error: this run would take about …"},
      {"cli: terabytes of output",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml --duration 1e5 --timestep 0.1 --output-interval 1e-4",
       1,
       "tumble: error: this run would write up to 680 GB (1000000000 steps, 1000000001 samples): enlarge "
       "--output-interval, choose fewer --fields, or give --force to write it anyway"},
      {"cli: inertia unknown shape",
       {},
       "{t} inertia --shape blob --size 1 --density 1",
       1,
       "tumble: error: unknown shape 'blob': choose box, sphere, ellipsoid, cylinder, capsule, cone or "
       "torus"},
      {"cli: inertia box of 2 sizes",
       {},
       "{t} inertia --shape box --size 1,2 --density 1",
       1,
       "tumble: error: --shape box takes --size with 3 number(s) (x,y,z edge lengths), got 2"},
      {"cli: inertia negative density",
       {},
       "{t} inertia --shape sphere --size 1 --density -1",
       1,
       "tumble: error: density -1 kg/m^3 is invalid: give a positive number"},
      {"cli: inertia zero mass",
       {},
       "{t} inertia --shape sphere --size 1 --mass 0",
       1,
       "tumble: error: mass 0 kg is invalid: give a positive number"},
      {"cli: inertia zero axis",
       {},
       "{t} inertia --shape sphere --size 1 --density 1 --axis 0,0,0",
       1,
       "tumble: error: axis direction (0, 0, 0) has no direction: give a non-zero, finite vector"},
      {"cli: inertia shell with density but no thickness",
       {},
       "{t} inertia --shape sphere --size 1 --shell --density 1",
       1,
       "tumble: error: --shell with --density needs the wall thickness: add --thickness T (m), or give "
       "--mass"},
      {"cli: inertia shell thicker than the sphere",
       {},
       "{t} inertia --shape sphere --size 1 --shell --thickness 5 --density 1",
       1,
       "tumble: error: shell thickness 5 m does not fit inside the sphere: its walls can be at most 1 m "
       "thick (the radius of the largest sphere inside it); for a thick-walled body subtract an inner solid "
       "as a hole"},
      {"cli: inertia zero scale",
       {{"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 4 "
                              "3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\nf 4 5 8\n",
                              160)}},
       "{t} inertia m.obj --density 1 --scale 0",
       1,
       "tumble: error: m.obj: mesh scale 0 is invalid: give a positive factor (e.g. 0.001 for millimetres)"},
      {"cli: inertia --json to a full device",
       {},
       "{t} inertia --shape sphere --size 1 --density 1 --json > /dev/full",
       1,
       "tumble: error: writing to standard output failed: No space left on device; what was printed is "
       "incomplete"},
      {"output: -o is the scene",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml -o s.toml",
       1,
       "tumble: error: -o s.toml is the scene file s.toml: writing it would destroy the run's input; give "
       "another output name, e.g. -o s.csv"},
      {"output: -o is a directory",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)},
        {"d/x", std::string()}},
       "{t} run s.toml -o d",
       1,
       "tumble: error: -o d is a directory: give a file name, e.g. d/s.csv"},
      {"output: -o is the mesh",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nmesh = "
                               "\"m.obj\"\ndensity = 1\n",
                               78)},
        {"m.obj", std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 4 "
                              "3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf "
                              "3 8 7\nf 4 1 5\nf 4 5 8\n",
                              160)}},
       "{t} run s.toml -o m.obj",
       1,
       "tumble: error: -o m.obj is the file m.obj that the scene reads (a mesh or a body table): writing it "
       "would destroy the run's input; give another output name, e.g. -o s.csv"},
      {"output: -o is the body table",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[body_tables]]\nfile = \"b.csv\"\n", 60)},
        {"b.csv", std::string("mass,I1,I2,I3\n1,1,1,1\n", 22)}},
       "{t} run s.toml -o b.csv",
       1,
       "tumble: error: -o b.csv is the file b.csv that the scene reads (a mesh or a body table): writing it "
       "would destroy the run's input; give another output name, e.g. -o s.csv"},
      {"output: --diagnostics is the scene",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml -o x.csv --diagnostics s.toml",
       1,
       "tumble: error: --diagnostics s.toml is the scene file s.toml: writing it would destroy the run's "
       "input; give another file, e.g. --diagnostics s.diagnostics.csv"},
      {"output: trajectory and diagnostics one file",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml -o x.csv --diagnostics x.csv",
       1,
       "tumble: error: the trajectory x.csv and the diagnostics x.csv are the same file: give different "
       "files"},
      {"output: HDF5 with --diagnostics",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml -o x.h5 --diagnostics d.csv",
       1,
       "tumble: error: --diagnostics names a CSV file; HDF5 output keeps the diagnostics in its "
       "'diagnostics' group: drop --diagnostics or use --format csv"},
      {"output: HDF5 to standard output",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml -o - --format hdf5",
       1,
       "tumble: error: HDF5 cannot be written to standard output (the library seeks in its file): give a "
       "file name, or write CSV"},
      {"output: to a full device",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml -o - > /dev/full",
       1,
       "tumble: error: writing the trajectory to standard output failed: No space left on device"},
      {"output: -o /dev/null discards (ok)",
       {{"s.toml", std::string("[simulation]\nduration = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                               "\"box\", size = [1, 2, 3] }\ndensity = 1000\n",
                               109)}},
       "{t} run s.toml -o /dev/null --quiet && test -c /dev/null",
       0,
       ""},
      {"signal: SIGINT mid-run keeps a valid file",
       {{"s.toml", kLongBoxScene}},
       "set -m; {t} run s.toml -o x.csv --quiet & sleep 1; kill -INT $!; wait $!; s=$?; test -s x.csv && ! "
       "ls x.csv.tmp-* && exit $s",
       130,
       "tumble: interrupted at t = …"},
      {"signal: SIGTERM mid-run keeps a valid file",
       {{"s.toml", kLongBoxScene}},
       "set -m; {t} run s.toml -o x.csv --quiet & sleep 1; kill -TERM $!; wait $!; s=$?; test -s x.csv && ! "
       "ls x.csv.tmp-* && exit $s",
       143,
       "tumble: interrupted at t = …"},
      {"signal: SIGHUP mid-run keeps a valid file",
       {{"s.toml", kLongBoxScene}},
       "set -m; {t} run s.toml -o x.csv --quiet & sleep 1; kill -HUP $!; wait $!; s=$?; test -s x.csv && ! "
       "ls x.csv.tmp-* && exit $s",
       129,
       "tumble: interrupted at t = …"},
      {"signal: SIGXCPU (a batch system's CPU-time warning) mid-run keeps a valid file",
       {{"s.toml", kLongBoxScene}},
       "set -m; {t} run s.toml -o x.csv --quiet & sleep 1; kill -XCPU $!; wait $!; s=$?; test -s x.csv && ! "
       "ls x.csv.tmp-* && exit $s",
       152,
       "tumble: interrupted at t = …"},
      {"limit: ulimit -t (a CPU-time limit: SIGXCPU at the soft one) keeps a valid file and a checkpoint",
       {{"s.toml", kLongBoxScene}},
       "ulimit -S -t 1; {t} run s.toml -o x.csv --quiet --checkpoint c.ckpt; s=$?; test -s x.csv && test -s "
       "c.ckpt && ! ls x.csv.tmp-* && exit $s",
       152,
       "tumble: interrupted at t = …"},
      {"resume: a stale checkpoint (another, complete run wrote the same -o since) is refused, not cut back",
       {{"s.toml", kLongBoxScene}},
       "(ulimit -S -t 1; {t} run s.toml -o o.csv -q --checkpoint c.ckpt 2> /dev/null); {t} run s.toml -o "
       "o.csv "
       "-q --duration 2 && cp o.csv kept.csv && {t} resume c.ckpt; s=$?; cmp -s o.csv kept.csv && exit $s",
       1,
       "tumble: error: checkpoint c.ckpt is stale: …"},
      {"limit: ulimit -f during run (SIGXFSZ as the shell leaves it): one line, no file",
       {{"s.toml", std::string("[simulation]\nduration = 100\ntimestep = 1e-3\noutput_interval = "
                               "0.01\n[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 2, 3] "
                               "}\ndensity = 1000\n")}},
       "ulimit -f 20; {t} run s.toml -o x.csv; s=$?; ! ls x.csv* && exit $s",
       1,
       "tumble: error: writing the trajectory to x.csv failed: File too large; nothing was kept under that "
       "name: free some space or write elsewhere"},
      {"limit: ulimit -f during report: one line, no file",
       {{"s.toml", std::string("[simulation]\nduration = 100\ntimestep = 1e-3\noutput_interval = "
                               "0.01\n[[bodies]]\nname = \"a\"\nshape = { type = \"box\", size = [1, 2, 3] "
                               "}\ndensity = 1000\n")}},
       "{t} run s.toml -o x.csv -q --duration 1 && (ulimit -f 4; {t} report x.csv -o x.html); s=$?; ! ls "
       "x.html* && exit $s",
       1,
       "tumble: error: writing the report x.html failed: File too large; nothing was kept under that name"},
      {"limit: ulimit -f during ensemble: the rows done are kept for the rerun",
       {{"s.toml",
         "[simulation]\nduration = 0.01\n[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 0.1 "
         "}\nmass = 1\n[ensemble]\nruns = 3000\n[[ensemble.vary]]\npath = \"bodies.b.mass\"\ndistribution = "
         "\"uniform\"\nlow = 1\nhigh = 2\n"}},
       "(ulimit -f 20; {t} ensemble s.toml -o e.csv -q); s=$?; {t} ensemble s.toml -o e.csv | grep -q "
       "'resuming: 5' && exit $s",
       1,
       "tumble: error: writing the finished rows to e.csv.partial-0 failed: File too large; the rows written "
       "before are kept there: free some space (or raise the file size limit) and run the same command again "
       "to go on"},
      {"fit: times out of order name both lines",
       {{"g.csv", "t,wx,wy,wz\n0,1,2,3\n0.2,1,2,3\n0.1,1,2,3\n"}},
       "{t} fit g.csv --sigma 1e-3",
       1,
       "tumble: error: g.csv:4: t = 0.1 is before the previous sample's t = 0.2 (g.csv:3): the samples must "
       "be "
       "in time order, without repeated times"},
      {"fit: a NaN sample names line and column",
       {{"g.csv", "t,wx,wy,wz\n0,1,2,3\n0.1,1,NaN,3\n"}},
       "{t} fit g.csv --sigma 1e-3",
       1,
       "tumble: error: g.csv:3:7: 'NaN' in column 'wy' is not finite: every value must be a finite number "
       "(drop "
       "the sample instead)"},
      {"fit: an unknown column in the header",
       {{"g.csv", "time,wx,wy,wz\n0,1,2,3\n"}},
       "{t} fit g.csv --sigma 1e-3",
       1,
       "tumble: error: g.csv:1:1: unknown column 'time' in the header; the columns are t (s), wx, wy, wz "
       "(the "
       "gyro's angular velocity, rad/s) and optionally tau_x, tau_y, tau_z (a known applied torque, N m) and "
       "h_x, h_y, h_z (a known wheel angular momentum, N m s), all in sensor axes"},
      {"fit: too few samples",
       {{"g.csv", "t,wx,wy,wz\n0,1,2,3\n0.1,1,2,3\n"}},
       "{t} fit g.csv --sigma 1e-3",
       1,
       "tumble: error: g.csv:3: 2 samples (lines 2 to 3): the fit needs at least 10 (3 components each, "
       "against up to 12 unknowns, with residuals to spare)"},
      {"fit: --sigma 0",
       {{"g.csv",
         "t,wx,wy,wz\n0,1,2,3\n1,1,2,3\n2,1,2,3\n3,1,2,3\n4,1,2,3\n5,1,2,3\n6,1,2,3\n7,1,2,3\n8,1,"
         "2,3\n9,1,2,3\n"}},
       "{t} fit g.csv --sigma 0",
       1,
       "tumble: error: sigma = 0: give the gyro's noise, the standard deviation of each component (rad/s), a "
       "finite number > 0"},
      {"fit: --out the telemetry itself",
       {{"g.csv",
         "t,wx,wy,wz\n0,1,2,3\n1,1,2,3\n2,1,2,3\n3,1,2,3\n4,1,2,3\n5,1,2,3\n6,1,2,3\n7,1,2,3\n8,1,"
         "2,3\n9,1,2,3\n"}},
       "{t} fit g.csv --sigma 1e-3 --out g.csv",
       1,
       "tumble: error: the fit's result g.csv is the input g.csv: tumble never overwrites an input; give "
       "another "
       "output file"},
      {"run --sensitivities: CSV cannot hold them, nothing written",
       {{"s.toml",
         "[simulation]\nduration = 0.1\n[[bodies]]\nname = \"b\"\nshape = { type = \"box\", size = [1, 2, "
         "3] }\nmass = 1.0\nangular_velocity = [1, 2, 3]\n"}},
       "{t} run s.toml -o o.csv --sensitivities; s=$?; ! ls o.* && exit $s",
       1,
       "tumble: error: --sensitivities writes matrices (datasets stm and parameter_sensitivity) that CSV "
       "cannot "
       "hold: give an HDF5 output, e.g. -o s.h5"},
      {"run --sensitivities: a scene with a particle, nothing written",
       {{"s.toml",
         "[simulation]\nduration = 0.1\n[[bodies]]\nname = \"b\"\nshape = { type = \"box\", size = [1, 2, "
         "3] }\nmass = 1.0\nangular_velocity = [1, 2, 3]\n[[particles]]\nname = \"p\"\nmass = 1.0\n"}},
       "{t} run s.toml -o o.h5 --sensitivities; s=$?; ! ls o.* && exit $s",
       1,
       "tumble: error: sensitivities are of rigid bodies: the system has 1 particle (model them as small "
       "bodies)"},
      {"run --sensitivity-parameters forces: a scene without forces, nothing written",
       {{"s.toml",
         "[simulation]\nduration = 0.1\n[[bodies]]\nname = \"b\"\nshape = { type = \"box\", size = [1, 2, "
         "3] }\nmass = 1.0\nangular_velocity = [1, 2, 3]\n"}},
       "{t} run s.toml -o o.h5 --sensitivities --sensitivity-parameters forces; s=$?; ! ls o.* && exit $s",
       1,
       "tumble: error: sensitivities with respect to the force models' parameters: the system has no force "
       "model with parameters (a built-in model: gravity, a point force or torque, damping, drag, a spring, "
       "central gravity); choose inertia or mass"},
      {"run --sensitivities: a scene with events",
       {{"s.toml",
         "[simulation]\nduration = 0.1\n[[bodies]]\nname = \"b\"\nshape = { type = \"box\", size = [1, 2, "
         "3] }\nmass = 1.0\nangular_velocity = [1, 2, 3]\n[[events]]\nname = \"e\"\nbody = \"b\"\ncolumn = "
         "\"w2\"\n"}},
       "{t} run s.toml -o o.h5 --sensitivities",
       1,
       "tumble: error: --sensitivities runs its own loop, which watches no events yet: remove the scene's "
       "[[events]] for this run"},
      {"fit: no --sigma",
       {{"g.csv", "t,wx,wy,wz\n0,1,2,3\n"}},
       "{t} fit g.csv",
       2,
       "tumble: error: --sigma is required; see tumble fit --help"},
  };
  return cases;
}

/// AddressSanitizer maps terabytes of shadow memory at start and makes stack frames larger: under a
/// limit on address space (ulimit -v) a sanitized program cannot even start, and a small stack (ulimit
/// -s) measures ASan's frames rather than tumble's, so those cases run in the release build only.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

TEST(Catalogue, EveryBrokenInputGetsItsMessageAndStatus) {
  EXPECT_GE(catalogue().size(), 100u);
  for (const Case& c : catalogue()) {
    SCOPED_TRACE(c.name);
    const std::string_view command = c.command;
    if (kAddressSanitizer &&
        (command.find("ulimit -v") != command.npos || command.find("ulimit -s") != command.npos))
      continue;
    test::TempDir dir("catalogue");
    for (const auto& [name, bytes] : c.files) dir.write(name, bytes);
    const auto [status, first] = run_in(dir.path(), c.command);
    EXPECT_EQ(status, c.status) << first;
    // A message whose end depends on the machine or the moment (a time estimate, the time a signal
    // came) is held to its beginning, written with "…" at the end.
    const std::string expected = c.first_line, ellipsis = "…";
    if (expected.ends_with(ellipsis)) {
      EXPECT_EQ(first.rfind(expected.substr(0, expected.size() - ellipsis.size()), 0), 0u) << first;
    } else {
      EXPECT_EQ(first, expected);
    }
  }
}

}  // namespace
}  // namespace tumble
