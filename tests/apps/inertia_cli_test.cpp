// `tumble inertia` end to end: the numbers it prints are the library's closed forms, and bad input
// gets one clear line and a non-zero exit status.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <unistd.h>

#include "../support/run.hpp"

namespace tumble {
namespace {

using test::json_numbers;
using test::run_tumble;

TEST(InertiaCli, BoxJsonMatchesClosedForm) {
  const auto r = run_tumble("inertia --shape box --size 0.1,0.2,0.3 --density 1000 --json");
  ASSERT_EQ(r.status, 0) << r.output;
  // m = ρabc = 6 kg; I_xx = m(b² + c²)/12 etc.; printed with round-trip precision, so the only error
  // is the library's rounding (a few ulps).
  const double m = 6.0;
  EXPECT_NEAR(json_numbers(r.output, "mass").at(0), m, 1e-14);
  EXPECT_NEAR(json_numbers(r.output, "volume").at(0), 0.006, 1e-17);
  const auto I = json_numbers(r.output, "inertia");
  ASSERT_EQ(I.size(), 9u);
  EXPECT_NEAR(I[0], m * (0.04 + 0.09) / 12, 1e-15);
  EXPECT_NEAR(I[4], m * (0.01 + 0.09) / 12, 1e-15);
  EXPECT_NEAR(I[8], m * (0.01 + 0.04) / 12, 1e-15);
  EXPECT_EQ(I[1], 0.0);
  const auto L = json_numbers(r.output, "principal_moments");
  ASSERT_EQ(L.size(), 3u);
  EXPECT_NEAR(L[0], m * 0.05 / 12, 1e-15);  // ascending: the z axis has the smallest moment
  EXPECT_NEAR(L[2], m * 0.13 / 12, 1e-15);
  const auto U = json_numbers(r.output, "principal_axes");
  ASSERT_EQ(U.size(), 9u);
  // Row-major rows of U. First column (smallest moment) is +z, second +y, third their cross product
  // z × y = −x (det U = +1): U = [[0, 0, −1], [0, 1, 0], [1, 0, 0]].
  EXPECT_EQ(U, (std::vector<double>{0, 0, -1, 0, 1, 0, 1, 0, 0}));
  EXPECT_EQ(json_numbers(r.output, "center_of_mass"), (std::vector<double>{0, 0, 0}));
}

TEST(InertiaCli, AboutAPointAndAnAxisFollowTheParallelAxisTheorem) {
  // The box of 6 kg about its corner (a/2, b/2, c/2): I_xx = m(b² + c²)/12 + m(b² + c²)/4 = m(b² + c²)/3,
  // I_xy = −m (a/2)(b/2); the x axis through the corner has the moment I_xx and k = sqrt(I_xx/m).
  const auto r =
      run_tumble("inertia --shape box --size 0.1,0.2,0.3 --mass 6 --about 0.05,0.1,0.15 --axis 1,0,0 --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const double m = 6.0, Ixx = m * (0.04 + 0.09) / 3;
  const auto I = json_numbers(r.output, "inertia");
  ASSERT_EQ(I.size(), 9u);
  EXPECT_NEAR(I[0], Ixx, 1e-15);
  EXPECT_NEAR(I[1], -m * 0.05 * 0.1, 1e-16);
  EXPECT_NEAR(I[5], -m * 0.1 * 0.15, 1e-16);
  EXPECT_NEAR(json_numbers(r.output, "axis_moment").at(0), Ixx, 1e-15);
  EXPECT_NEAR(json_numbers(r.output, "radius_of_gyration").at(0), std::sqrt(Ixx / m), 1e-15);
  EXPECT_EQ(json_numbers(r.output, "about"), (std::vector<double>{0.05, 0.1, 0.15}));
  // The body diagonal through the centre: all three moments are equal along it for a cube, and for
  // this box n·I·n with n = (a, b, c)/|(a, b, c)|.
  const auto d = run_tumble("inertia --shape box --size 0.1,0.2,0.3 --mass 6 --axis 0.1,0.2,0.3 --json");
  ASSERT_EQ(d.status, 0) << d.output;
  const double n2 = 0.01 + 0.04 + 0.09;
  const double In = (0.01 * m * 0.13 + 0.04 * m * 0.10 + 0.09 * m * 0.05) / 12 / n2;
  EXPECT_NEAR(json_numbers(d.output, "axis_moment").at(0), In, 1e-15);
}

TEST(InertiaCli, WithoutAMaterialTheDensityIsOne) {
  // The mass is then the volume, and the tensor the closed form at ρ = 1.
  const auto r = run_tumble("inertia --shape box --size 1,2,3 --json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(json_numbers(r.output, "mass").at(0), 6.0);
  EXPECT_EQ(json_numbers(r.output, "volume").at(0), 6.0);
  EXPECT_NEAR(json_numbers(r.output, "inertia").at(0), 6.0 * (4 + 9) / 12, 1e-14);
  const auto human = run_tumble("inertia --shape box --size 1,2,3");
  EXPECT_NE(human.output.find("unit density (1 kg/m^3): the mass is the volume"), std::string::npos)
      << human.output;
}

TEST(InertiaCli, ThePrincipalFrameMakesTheTensorDiagonal) {
  // The T-handle mesh (off-centre): in principal axes the tensor is diag(λ₁, λ₂, λ₃), to the
  // rounding of Uᵀ I U (a few ε of the largest moment).
  const auto r = run_tumble(std::string("inertia ") + TUMBLE_SOURCE_DIR +
                            "/examples/meshes/t_handle.stl --density 2700 --frame principal --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto I = json_numbers(r.output, "inertia");
  const auto L = json_numbers(r.output, "principal_moments");
  ASSERT_EQ(I.size(), 9u);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(I[static_cast<size_t>(3 * i + j)], i == j ? L.at(static_cast<size_t>(i)) : 0.0,
                  1e-15 * L[2]);
    }
  }
}

TEST(InertiaCli, ASceneReportsEachBodyAsTheSceneBuildsIt) {
  const std::string scene = std::string(TUMBLE_SOURCE_DIR) + "/examples/t_handle.toml";
  const auto r = run_tumble("inertia " + scene + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.front(), '[') << "a list, one object per body";
  EXPECT_NE(r.output.find("\"name\": \"handle\""), std::string::npos) << r.output;
  // The same mass as the mesh at the scene's density (2700 kg/m^3).
  const auto mesh = run_tumble(std::string("inertia ") + TUMBLE_SOURCE_DIR +
                               "/examples/meshes/t_handle.stl --density 2700 --json");
  EXPECT_EQ(json_numbers(r.output, "mass"), json_numbers(mesh.output, "mass"));
  const auto missing = run_tumble("inertia " + scene + " --body wheel");
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.output.find("has no body named 'wheel'; its bodies are: handle"), std::string::npos)
      << missing.output;
}

TEST(InertiaCli, AnOpenMeshSuggestsTheShellFlags) {
  const auto dir = std::filesystem::temp_directory_path() / ("tumble_open_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "open.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n";
  const auto r = run_tumble("inertia " + (dir / "open.obj").string() + " --density 1000");
  std::filesystem::remove_all(dir);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("3 boundary edges"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("add --shell (with --thickness T and --density, or with --mass)"),
            std::string::npos)
      << r.output;
}

TEST(InertiaCli, ShellSphereAndHumanOutput) {
  const auto r = run_tumble("inertia --shape sphere --size 0.5 --shell --mass 3");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("mass              3 kg"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0.5"), std::string::npos);  // I = 2/3 m r² = 0.5
  EXPECT_NE(r.output.find("principal moments"), std::string::npos);
}

TEST(InertiaCli, MeshFileGivesItsMassProperties) {
  const auto r = run_tumble(std::string("inertia ") + TUMBLE_SOURCE_DIR +
                            "/examples/meshes/t_handle.stl --density 2700 --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto m = json_numbers(r.output, "mass");
  const auto V = json_numbers(r.output, "volume");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NEAR(m[0], 2700 * V.at(0), 1e-12 * m[0]);
}

TEST(InertiaCli, SeveralObjectsAreMergedWithAWarningOrOnePicked) {
  // Two unit cubes as two OBJ objects, the second twice as tall: merged they make 3 m^3 with a warning
  // that counts them; --part 2 measures the tall one alone, without a warning.
  const auto path = std::filesystem::temp_directory_path() /
                    ("tumble_cli_parts_" + std::to_string(::getpid()) + ".obj");
  {
    std::ofstream out(path);
    for (int k = 0; k < 2; ++k) {
      out << "o cube" << k + 1 << "\n";
      for (int i = 0; i < 8; ++i)
        out << "v " << 3 * k + (i & 1) << " " << ((i >> 1) & 1) << " " << (k + 1) * ((i >> 2) & 1) << "\n";
      const int b = 8 * k + 1;
      const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                               {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
      for (const auto& q : quads)
        out << "f " << b + q[0] << " " << b + q[1] << " " << b + q[2] << " " << b + q[3] << "\n";
    }
  }
  const auto all = run_tumble("inertia " + path.string() + " --density 1 --json");
  ASSERT_EQ(all.status, 0) << all.output;
  EXPECT_NE(all.output.find("holds 2 objects ('cube1', 'cube2'); they were merged into one body"),
            std::string::npos)
      << all.output;
  EXPECT_DOUBLE_EQ(json_numbers(all.output, "volume").at(0), 3.0);
  const auto second = run_tumble("inertia " + path.string() + " --density 1 --part 2");
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(second.output.find("warning"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("part 2 of 2; OBJ (text): every digit"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("volume            2 m^3"), std::string::npos) << second.output;
  const auto third = run_tumble("inertia " + path.string() + " --density 1 --part 3");
  EXPECT_NE(third.status, 0);
  EXPECT_NE(third.output.find("part 3 does not exist: the file has 2 objects"), std::string::npos)
      << third.output;
  std::filesystem::remove(path);
}

void expect_error(const std::string& args, const std::string& expected) {
  const auto r = run_tumble(args);
  EXPECT_NE(r.status, 0) << args;
  EXPECT_NE(r.output.find(expected), std::string::npos) << args << "\n" << r.output;
}

TEST(InertiaCli, BadInputGetsOneClearLine) {
  expect_error("inertia --shape box --size 0.1,0.2 --density 1000", "takes --size with 3 number(s)");
  expect_error("inertia --shape blob --size 1 --density 1", "unknown shape 'blob'");
  expect_error("inertia --shape sphere --size -1 --density 1000", "sphere radius is -1 m");
  expect_error("inertia --shape sphere --size 1 --frame body", "--frame");
  expect_error("inertia --shape sphere --size 1 --density 1 --mass 2", "excludes");
  expect_error("inertia --shape sphere --size 1 --density nan", "density nan kg/m^3 is invalid");
  expect_error("inertia --shape sphere --size 1 --shell --density 1", "--thickness");
  expect_error("inertia no/such/file.stl --density 1", "no/such/file.stl");
  expect_error("inertia", "either a mesh FILE or --shape");
}

TEST(InertiaCli, HelpTeachesWithExamplesAndVersionIsPrinted) {
  const auto help = run_tumble("inertia --help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.output.find("Examples:"), std::string::npos);
  EXPECT_NE(help.output.find("--scale"), std::string::npos);
  EXPECT_NE(help.output.find("--part"), std::string::npos);
  EXPECT_NE(help.output.find("read exactly"), std::string::npos);  // the precision of each format
  const auto version = run_tumble("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_NE(version.output.find("tumble 0."), std::string::npos);
}

}  // namespace
}  // namespace tumble
