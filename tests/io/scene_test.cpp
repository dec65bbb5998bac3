// Scene files that are right: what they describe becomes the closed-form mass properties, the
// initial state in the frames the format documents, the run settings, and the conservation flags.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <numbers>

#include "../support/scene_files.hpp"
#include "tumble/dynamics/orbit_frame.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/math/rotations.hpp"
#include "tumble/sim/diagnostics.hpp"
#include "tumble/sim/output_fields.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {
namespace {

using std::numbers::pi;

const std::string kSim = "[simulation]\nduration = 1.0\n";

Scene parse(const std::string& body) { return parse_scene(kSim + body, "test.toml"); }

TEST(SceneFile, BoxHasClosedFormMassPropertiesAndDefaults) {
  const Scene s = parse(R"(
[[bodies]]
name = "box"
shape = { type = "box", size = [0.1, 0.2, 0.3] }
density = 1000
)");
  ASSERT_EQ(s.model.bodies.size(), 1u);
  const RigidBody& b = s.model.bodies[0];
  // m = ρabc = 6 kg; I = m(b² + c²)/12 ...; closed forms evaluated in double: a few ulps.
  EXPECT_NEAR(b.mass(), 6.0, 1e-14);
  EXPECT_NEAR(b.Lambda()(0), 6.0 * (0.01 + 0.04) / 12, 1e-15);
  EXPECT_NEAR(b.Lambda()(1), 6.0 * (0.01 + 0.09) / 12, 1e-15);
  EXPECT_NEAR(b.Lambda()(2), 6.0 * (0.04 + 0.09) / 12, 1e-15);
  // Defaults documented in docs/scene-format.md.
  EXPECT_EQ(s.settings.duration, 1.0);
  EXPECT_EQ(s.settings.timestep, 1e-3);
  EXPECT_EQ(s.settings.output_interval, 0.01);
  EXPECT_EQ(s.settings.integrator, "rk4");
  EXPECT_EQ(s.settings.formulation, Formulation::mixed);
  EXPECT_EQ(s.settings.drift_threshold, 1e-6);
  EXPECT_TRUE(s.model.forces.empty());  // no [world]: no gravity
  EXPECT_EQ(s.initial.bodies[0].o, Vec3::Zero());
  EXPECT_EQ(s.initial.bodies[0].v, Vec3::Zero());
  EXPECT_TRUE(s.conserved.energy && s.conserved.linear_momentum && s.conserved.angular_momentum);
  EXPECT_EQ(s.text, kSim + R"(
[[bodies]]
name = "box"
shape = { type = "box", size = [0.1, 0.2, 0.3] }
density = 1000
)");
}

// A body whose reference frame is neither at its centre of mass nor along its principal axes: explicit
// inertia with products, c off the origin. Used by the frame and velocity tests below.
const std::string kSkewBody = R"(
[[bodies]]
name = "part"
mass = 2.0
inertia = [[0.3, -0.02, 0.01], [-0.02, 0.4, 0.0], [0.01, 0.0, 0.5]]
center_of_mass = [0.1, -0.2, 0.05]
position = [1.0, 2.0, 3.0]
orientation = [0.8, 0.0, 0.6, 0.0]
)";

TEST(SceneFile, AngularVelocityInPrincipalAxesIsOmegaB) {
  // angular_velocity_frame = "principal": the components are ^bω, the body's Euler ω₁ ω₂ ω₃ — a spin
  // about the intermediate axis needs no hand-copied column of U. ω_w = R ^bω, to a few ulp.
  const Scene s =
      parse(kSkewBody + "angular_velocity = [0.0, 5.0, 0.1]\nangular_velocity_frame = \"principal\"\n");
  EXPECT_LT((s.initial.bodies[0].omega_b() - Vec3(0.0, 5.0, 0.1)).norm(), 4e-15 * 5.0);
  // "reference" (and its older name "body") are the reference frame's axes: ω_w = R_ref ^rω.
  for (const char* frame : {"reference", "body"}) {
    const Scene r =
        parse(kSkewBody + "angular_velocity = [0.0, 5.0, 0.1]\nangular_velocity_frame = \"" + frame + "\"\n");
    const Quat q_ref(0.8, 0.0, 0.6, 0.0);
    EXPECT_LT((r.initial.bodies[0].omega_w - q_ref * Vec3(0.0, 5.0, 0.1)).norm(), 4e-15 * 5.0) << frame;
  }
}

TEST(SceneFile, ATorqueInPrincipalAxesSpinsUpAboutThatAxis) {
  // From rest, a constant torque τ along principal axis 1 gives ^bω = τ t / λ₁ along it (ω × Λω = 0 on
  // a principal axis), a ramp RK4 integrates exactly: to rounding. In the reference axes the same
  // numbers would point elsewhere on this body (U ≠ I).
  const Scene s = parse(kSkewBody + R"(
[[forces]]
type = "torque"
body = "part"
torque = [0.2, 0.0, 0.0]
frame = "principal"
)");
  RunSettings settings;
  settings.duration = 0.01;
  settings.timestep = 1e-3;
  const SystemState end = simulate(s.model, s.initial, settings);
  const double lambda1 = s.model.bodies[0].Lambda()(0);
  EXPECT_LT((end.bodies[0].omega_b() - Vec3(0.2 * 0.01 / lambda1, 0, 0)).norm(),
            1e-14 * 0.2 * 0.01 / lambda1);
}

TEST(SceneFile, VelocityOfTheCentreOfMass) {
  // velocity_of = "com": an off-centre part spun "at rest" stays in place, with no hand-computed
  // compensation; the default is the velocity of the reference origin, v = v_p + ω × (o − p).
  const Scene com =
      parse(kSkewBody + "velocity = [0, 0, 0]\nvelocity_of = \"com\"\nangular_velocity = [0, 0, 10]\n");
  EXPECT_EQ(com.initial.bodies[0].v, Vec3::Zero());
  const Scene origin = parse(kSkewBody + "velocity = [0, 0, 0]\nangular_velocity = [0, 0, 10]\n");
  const BodyState& b = origin.initial.bodies[0];
  EXPECT_LT((b.v - Vec3(0, 0, 10).cross(b.o - Vec3(1.0, 2.0, 3.0))).norm(), 1e-15 * 10);
  EXPECT_GT(b.v.norm(), 1.0) << "this part at 10 rad/s would drift at over 1 m/s";
}

TEST(SceneFile, OrientationAsEulerAnglesAxisAngleOrRodriguesParameters) {
  // The same rotation six ways: a quaternion, ZYX and ZXZ angles, axis–angle (rad), and modified
  // Rodrigues parameters (the principal set and its shadow), to rounding.
  const Quat q(Eigen::AngleAxisd(0.7, Vec3(1.0, -2.0, 0.5).normalized()));
  const Mat3 R = q.toRotationMatrix();
  const Vec3 zyx = euler_zyx(R), zxz = euler_zxz(R), sigma = mrp(q), shadow = -sigma / sigma.squaredNorm();
  const std::string shape =
      "[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 1.0 }\ndensity = 1\n";
  auto orientation_of = [&](const std::string& line) { return parse(shape + line).initial.bodies[0].q; };
  const std::string ways[] = {
      fmt::format("orientation = [{:.17g}, {:.17g}, {:.17g}, {:.17g}]\n", q.w(), q.x(), q.y(), q.z()),
      fmt::format("orientation = {{ euler_zyx = [{:.17g}, {:.17g}, {:.17g}] }}\n", zyx(0), zyx(1), zyx(2)),
      fmt::format("orientation = {{ euler_zxz = [{:.17g}, {:.17g}, {:.17g}] }}\n", zxz(0), zxz(1), zxz(2)),
      fmt::format("orientation = {{ axis = [1.0, -2.0, 0.5], angle = 0.7 }}\n"),
      fmt::format("orientation = {{ mrp = [{:.17g}, {:.17g}, {:.17g}] }}\n", sigma(0), sigma(1), sigma(2)),
      fmt::format("orientation = {{ mrp = [{:.17g}, {:.17g}, {:.17g}] }}\n", shadow(0), shadow(1), shadow(2)),
  };
  for (const std::string& way : ways) {
    // A sphere's principal frame is its reference frame (U = I), so q is the orientation given.
    EXPECT_LT((orientation_of(way).toRotationMatrix() - R).cwiseAbs().maxCoeff(), 1e-15) << way;
  }
  EXPECT_THROW(parse(shape + "orientation = { euler_zyx = [0, 0, 0], angle = 1 }\n"), SceneError);
  EXPECT_THROW(parse(shape + "orientation = { axis = [0, 0, 0], angle = 1 }\n"), SceneError);
  EXPECT_THROW(parse(shape + "orientation = { mrp = [0.1, 0.2, 0.3], angle = 1 }\n"), SceneError);
}

TEST(SceneFile, OutputFieldsAreChosenInTheScene) {
  const std::string body =
      "[[bodies]]\nname = \"b\"\nshape = { type = \"sphere\", radius = 1.0 }\ndensity = 1\n";
  const Scene s = parse("[output]\nfields = [\"euler_zyx\", \"com_position\"]\n" + body);
  EXPECT_EQ(s.output_fields, (std::vector<std::string>{"euler_zyx", "com_position"}));
  try {
    parse("[output]\nfields = [\"euler\"]\n" + body);
    FAIL() << "an unknown field was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("test.toml:4:10: [output]: unknown output field 'euler'"),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneFile, TubeFromPartsWithAHoleIsTheClosedForm) {
  // A cylinder minus a coaxial cylinder: m = ρπ(R² − r²)L, I_zz = m(R² + r²)/2,
  // I_xx = m(3(R² + r²) + L²)/12; placed at z = 0.2, so the centre of mass is there.
  const Scene s = parse(R"(
[[bodies]]
name = "tube"
density = 2000.0
  [[bodies.parts]]
  shape = { type = "cylinder", radius = 0.05, length = 0.4 }
  position = [0.0, 0.0, 0.2]
  [[bodies.parts]]
  shape = { type = "cylinder", radius = 0.04, length = 0.4 }
  position = [0.0, 0.0, 0.2]
  hole = true
)");
  const double R2 = 0.05 * 0.05, r2 = 0.04 * 0.04, L = 0.4;
  const double m = 2000.0 * pi * (R2 - r2) * L;
  const MassProperties mp = s.model.bodies[0].mass_properties();  // U Λ Uᵀ: rounding of ~1e-16
  // The difference of two masses 2.8 times larger than the result: rounding is amplified ~3x.
  EXPECT_NEAR(mp.mass, m, 1e-14 * m);
  EXPECT_NEAR(mp.center_of_mass.z(), 0.2, 1e-15);
  EXPECT_NEAR(mp.inertia(2, 2), m * (R2 + r2) / 2, 1e-13 * m * R2);
  EXPECT_NEAR(mp.inertia(0, 0), m * (3 * (R2 + r2) + L * L) / 12, 1e-13 * m * L * L);
  EXPECT_NE(s.body_info[0].source->find("2 parts (1 holes)"), std::string::npos) << *s.body_info[0].source;
}

TEST(SceneFile, RotatedPartsAndTotalMass) {
  // Two spheres at x = ±d with total mass M: I_yy = I_zz = 2(2/5 (M/2) r² + (M/2) d²), I_xx = 2/5 M r².
  // The second sphere is rotated; a sphere does not care, which checks that orientations are read.
  const Scene s = parse(R"(
[[bodies]]
name = "dumbbell"
mass = 3.0
  [[bodies.parts]]
  shape = { type = "sphere", radius = 0.1 }
  position = [0.5, 0.0, 0.0]
  [[bodies.parts]]
  shape = { type = "sphere", radius = 0.1 }
  position = [-0.5, 0.0, 0.0]
  orientation = [0.0, 0.0, 1.0, 0.0]
)");
  const RigidBody& b = s.model.bodies[0];
  const double M = 3.0, r2 = 0.01, d2 = 0.25;
  EXPECT_NEAR(b.mass(), M, 1e-15);
  EXPECT_NEAR(b.Lambda()(0), 0.4 * M * r2, 1e-15);
  EXPECT_NEAR(b.Lambda()(1), 0.4 * M * r2 + M * d2, 1e-14);
  EXPECT_NEAR(b.Lambda()(2), 0.4 * M * r2 + M * d2, 1e-14);
}

TEST(SceneFile, PolynomialDensityIsIntegratedExactly) {
  // Cube of side a with ρ = ρ₀ + k z: m = ρ₀a³ (the odd term integrates to 0) and
  // c_z = (1/m) ∫ k z² dV = k a²/(12 ρ₀). Degree-1 density: the rules are exact, only rounding remains.
  const Scene s = parse(R"(
[[bodies]]
name = "graded"
shape = { type = "box", size = [0.2, 0.2, 0.2] }
density = { polynomial = [[1000.0, 0, 0, 0], [2000.0, 0, 0, 1]] }
)");
  const MassProperties mp = s.model.bodies[0].mass_properties();  // U Λ Uᵀ: rounding of ~1e-16
  EXPECT_NEAR(mp.mass, 1000.0 * 0.008, 1e-13);
  EXPECT_NEAR(mp.center_of_mass.z(), 2000.0 * 0.04 / (12 * 1000.0), 1e-15);
  EXPECT_NEAR(mp.center_of_mass.x(), 0.0, 1e-16);
}

TEST(SceneFile, ExplicitInertiaAsDiagonalOrFullTensor) {
  const Scene s = parse(R"(
[[bodies]]
name = "diag"
mass = 2.0
inertia = [0.1, 0.2, 0.25]
center_of_mass = [0.0, 0.0, 0.1]

[[bodies]]
name = "full"
mass = 2.0
inertia = [[0.2, -0.05, 0.0], [-0.05, 0.2, 0.0], [0.0, 0.0, 0.3]]
)");
  EXPECT_EQ(s.model.bodies[0].Lambda(), Vec3(0.1, 0.2, 0.25));
  EXPECT_EQ(s.model.bodies[0].center_of_mass(), Vec3(0, 0, 0.1));
  // Eigenvalues of [[0.2, −0.05], [−0.05, 0.2]] are 0.2 ∓ 0.05; the solver is accurate to rounding.
  const Vec3& L = s.model.bodies[1].Lambda();
  EXPECT_NEAR(L(0), 0.15, 1e-15);
  EXPECT_NEAR(L(1), 0.25, 1e-15);
  EXPECT_NEAR(L(2), 0.3, 1e-15);
}

TEST(SceneFile, InitialStateInTheDocumentedFrames) {
  // Reference frame turned 90° about z; ω given in body axes along x is world y. The centre of mass
  // (0, 0, 0.1) in the reference frame is unmoved by the turn; the velocity given is of the origin,
  // so the centre moves at v + ω × (o − p) = (0, 0, 0) + (0, 2, 0) × (0, 0, 0.1) = (0.2, 0, 0).
  const Scene s = parse(R"(
[[bodies]]
name = "b"
mass = 1.0
inertia = [0.1, 0.2, 0.25]
center_of_mass = [0.0, 0.0, 0.1]
position = [1.0, 2.0, 3.0]
orientation = [0.7071067811865476, 0.0, 0.0, 0.7071067811865476]
angular_velocity = [2.0, 0.0, 0.0]
angular_velocity_frame = "body"
)");
  const BodyState& b = s.initial.bodies[0];
  EXPECT_LT((b.omega_w - Vec3(0, 2, 0)).norm(), 1e-15);
  EXPECT_LT((b.o - Vec3(1, 2, 3.1)).norm(), 1e-15);
  EXPECT_LT((b.v - Vec3(0.2, 0, 0)).norm(), 1e-15);
}

TEST(SceneFile, NearlyUnitQuaternionsAreNormalised) {
  // 0.7071 has four digits: |q| − 1 ≈ −1.4e-5, inside the slack; the rotation is q/|q|.
  const Scene s = parse(R"(
[[bodies]]
name = "b"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
orientation = [0.7071, 0.7071, 0.0, 0.0]
)");
  const Quat q = s.initial.bodies[0].q;
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  EXPECT_NEAR(q.w(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(q.x(), std::sqrt(0.5), 1e-15);
}

TEST(SceneFile, MeshPathIsRelativeToTheSceneFile) {
  test::TempDir dir("scene_mesh");
  std::filesystem::create_directories(dir / "scenes/meshes");
  std::filesystem::copy_file(std::filesystem::path(TUMBLE_SOURCE_DIR) / "examples/meshes/t_handle.stl",
                             dir / "scenes/meshes/t_handle.stl");
  const auto file = dir.write("scenes/handle.toml", kSim + R"(
[[bodies]]
name = "handle"
mesh = "meshes/t_handle.stl"
scale = 2.0
density = 2700.0
)");
  const Scene s = load_scene(file);
  // T volume 0.1·0.02·0.02 + 0.06·0.02·0.02 = 6.4e-5 m³, ×8 for scale 2. The STL stores float32
  // coordinates (relative rounding up to 6e-8 each), so the volume is exact to ~2e-7 relative.
  EXPECT_NEAR(s.model.bodies[0].mass(), 2700.0 * 6.4e-5 * 8, 2e-7 * 1.3824);
  EXPECT_NE(s.body_info[0].source->find("scale 2"), std::string::npos);
}

TEST(SceneFile, ForcesByNameAndWhatTheyConserve) {
  const std::string two_bodies = R"(
[[bodies]]
name = "a"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
[[bodies]]
name = "b"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
position = [1.0, 0.0, 0.0]
)";
  auto conserved = [&](const std::string& forces) {
    const Conservation c = parse(two_bodies + forces).conserved;
    return std::array<bool, 3>{c.energy, c.linear_momentum, c.angular_momentum};
  };
  using A = std::array<bool, 3>;
  // A spring between two bodies is internal and central: everything is conserved.
  EXPECT_EQ(conserved("[[forces]]\ntype = \"spring\"\na = { body = \"a\" }\nb = { body = \"b\" }\nstiffness "
                      "= 10.0\n"),
            (A{true, true, true}));
  // Tied to the world: energy only.
  EXPECT_EQ(conserved("[[forces]]\ntype = \"spring\"\na = { body = \"a\" }\nb = { anchor = [0, 0, 1] "
                      "}\nstiffness = 10.0\n"),
            (A{true, false, false}));
  // Damped: the energy is lost, but the pair of forces is still internal and central.
  EXPECT_EQ(conserved("[[forces]]\ntype = \"spring\"\na = { body = \"a\" }\nb = { body = \"b\" }\nstiffness "
                      "= 10.0\n"
                      "damping = 0.1\n"),
            (A{false, true, true}));
  EXPECT_EQ(conserved("[world]\ngravity = [0, 0, -9.81]\n"), (A{true, false, false}));
  EXPECT_EQ(conserved("[[forces]]\ntype = \"gravity_gradient\"\nmu = 1.0\n"), (A{true, false, true}));
  EXPECT_EQ(conserved("[[forces]]\ntype = \"gravity_gradient\"\nmu = 1.0\ncenter = [0, 0, 1]\n"),
            (A{true, false, false}));
  EXPECT_EQ(conserved("[[forces]]\ntype = \"drag\"\nlinear = 0.1\n"), (A{false, false, false}));
  EXPECT_EQ(conserved("[[forces]]\ntype = \"torque\"\nbody = \"b\"\ntorque = [0, 0, 1]\nframe = \"body\"\n"),
            (A{false, false, false}));

  const Scene s = parse(two_bodies + R"(
[[forces]]
type = "force"
body = "b"
force = [0.0, 0.0, 2.0]
frame = "body"
point = [0.0, 0.5, 0.0]
)");
  ASSERT_EQ(s.model.forces.size(), 1u);
  // The force acts on body #1 ("b"), at a body point: f = (0, 0, 2) N, τ = r × f = (1, 0, 0) N·m.
  const Loads loads = evaluate_loads(s.model, s.initial);
  EXPECT_EQ(loads.bodies[0].force, Vec3::Zero());
  EXPECT_LT((loads.bodies[1].force - Vec3(0, 0, 2)).norm(), 1e-15);
  EXPECT_LT((loads.bodies[1].torque - Vec3(1, 0, 0)).norm(), 1e-15);
}

TEST(SceneFile, SimulationSettingsAndParticles) {
  const Scene s = parse_scene(R"(
[simulation]
duration = 2.5
timestep = 0.01
integrator = "dopri45"
formulation = "body"
output_interval = 0
rtol = 1e-8
atol = 1e-11
drift_threshold = 0

[[particles]]
name = "p"
mass = 0.5
position = [1, 2, 3]
velocity = [0, 0, 1]
)",
                              "p.toml");
  EXPECT_EQ(s.settings.duration, 2.5);
  EXPECT_EQ(s.settings.timestep, 0.01);
  EXPECT_EQ(s.settings.integrator, "dopri45");
  EXPECT_EQ(s.settings.formulation, Formulation::body);
  EXPECT_EQ(s.settings.output_interval, 0.0);
  EXPECT_EQ(s.settings.tolerances.relative, 1e-8);
  EXPECT_EQ(s.settings.tolerances.absolute, 1e-11);
  EXPECT_EQ(s.settings.drift_threshold, 0.0);
  ASSERT_EQ(s.model.particles.size(), 1u);
  EXPECT_EQ(s.model.particles[0].mass, 0.5);
  EXPECT_EQ(s.initial.particles[0].x, Vec3(1, 2, 3));
  EXPECT_EQ(s.initial.particles[0].v, Vec3(0, 0, 1));
}

TEST(SceneFile, ThinShellsFromShapesAndOpenMeshes) {
  // A hollow sphere of radius r: m = ρ·t·4πr², I = 2/3 m r² (thin-wall limit).
  const Scene s = parse_scene(R"([simulation]
duration = 1.0
[[bodies]]
name = "ball"
shape = { type = "sphere", radius = 0.5 }
thickness = 0.002
density = 2700
)",
                              "shell.toml");
  const double m = 2700 * 0.002 * 4 * std::numbers::pi * 0.25;
  EXPECT_NEAR(s.model.bodies[0].mass(), m, 1e-13 * m);
  EXPECT_NEAR(s.model.bodies[0].Lambda()(0), 2.0 / 3.0 * m * 0.25, 1e-13 * m);
  // A polynomial density is for solids.
  try {
    parse_scene(R"([simulation]
duration = 1.0
[[bodies]]
name = "ball"
shape = { type = "sphere", radius = 0.5 }
thickness = 0.002
density = { polynomial = [[1000, 0, 0, 0]] }
)",
                "shell.toml");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("shell.toml:6:13"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("solids only"), std::string::npos) << e.what();
  }
}

TEST(SceneFile, SpringsBetweenParticlesAndBodiesConserveMomentaAndEnergy) {
  // Two particles on a spring and one tied to a body: internal, central forces, so the total linear
  // and angular momentum and the energy are conserved (the scene says so, and RK4 keeps them to its
  // error, (h ω)⁴ t with ω = √(k/m) ≈ 7 rad/s, h = 1e-3: ~1e-11).
  const Scene s = parse_scene(R"([simulation]
duration = 2.0
timestep = 1e-3
[[bodies]]
name = "hub"
shape = { type = "sphere", radius = 0.1 }
mass = 2.0
angular_velocity = [0.0, 0.0, 3.0]
[[particles]]
name = "p"
mass = 0.5
position = [1.0, 0.0, 0.0]
velocity = [0.0, 1.0, 0.0]
[[particles]]
name = "q"
mass = 0.5
position = [1.5, 0.5, 0.0]
[[forces]]
type = "spring"
a = { particle = "p" }
b = { particle = "q" }
stiffness = 25.0
rest_length = 0.3
[[forces]]
type = "spring"
a = { body = "hub", point = [0.1, 0.0, 0.0] }
b = { particle = "p" }
stiffness = 25.0
)",
                              "springs.toml");
  EXPECT_TRUE(s.conserved.energy);
  EXPECT_TRUE(s.conserved.linear_momentum);
  EXPECT_TRUE(s.conserved.angular_momentum);
  const Invariants a = invariants(s.model, s.initial);
  const Invariants b = invariants(s.model, simulate(s.model, s.initial, s.settings));
  EXPECT_LT((b.linear_momentum - a.linear_momentum).norm(), 1e-12);
  EXPECT_LT((b.angular_momentum - a.angular_momentum).norm(), 1e-10);
  EXPECT_NEAR(*b.total_energy(), *a.total_energy(), 1e-10 * *a.total_energy());
  // A name that is not a particle is refused with the closest one suggested.
  try {
    parse_scene(R"([simulation]
duration = 1.0
[[particles]]
name = "p"
mass = 1.0
[[forces]]
type = "spring"
a = { particle = "pp" }
b = { anchor = [0.0, 0.0, 0.0] }
stiffness = 1.0
)",
                "springs.toml");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no particle named \"pp\"; did you mean \"p\"?"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

/// The crossings of a scene's [[events]] in a run of it.
std::vector<EventHit> crossings(const Scene& s) {
  RunHooks hooks;
  hooks.events = make_events(s.model, s.events);
  std::vector<EventHit> hits;
  hooks.on_event = [&](const EventHit& hit) { hits.push_back(hit); };
  simulate(s.model, s.initial, s.settings, hooks);
  return hits;
}

// A box spun near its intermediate axis: ω₂ (column w2) changes sign at (k + ½)·2K/λ, the exact
// Euler–Poinsot flip interval (ω₂ starts at its extreme). The exact integrator's states are the closed
// form to rounding and the crossing is located to 4 ulp of t, so the times agree to ~1e-12 s; 1e-9 s
// leaves room for the rounding of the elliptic functions near a zero of ω₂ (slope ~ |ω|²).
TEST(SceneEvents, AColumnCrossingFindsEveryFlipAtTheExactSolutionsTimes) {
  const Scene s = parse_scene(R"([simulation]
duration = 10.0
timestep = 0.01
integrator = "exact"
[[bodies]]
name = "racket"
shape = { type = "box", size = [0.1, 0.2, 0.3] }
mass = 1.0
angular_velocity = [0.01, 5.0, 0.0]
angular_velocity_frame = "principal"
[[events]]
name = "flip"
body = "racket"
column = "w2"
)",
                              "flips.toml");
  ASSERT_EQ(s.events.size(), 1u);
  const RigidBody& b = s.model.bodies[0];
  const double T = EulerPoinsot(b.Lambda(), Quat::Identity(), Vec3(0.01, 5.0, 0.0)).flip_interval();
  const std::vector<EventHit> hits = crossings(s);
  ASSERT_EQ(hits.size(), static_cast<size_t>(std::floor(10.0 / T + 0.5))) << "T = " << T;
  for (size_t k = 0; k < hits.size(); ++k) {
    EXPECT_EQ(hits[k].name, "flip");
    EXPECT_EQ(hits[k].index, 0u);
    EXPECT_NEAR(hits[k].state.t, (static_cast<double>(k) + 0.5) * T, 1e-9) << k;
  }
}

// A body spinning steadily about its z axis at ω: its x axis makes the angle ωt with the world x axis
// until t = π/ω, so 60° (rising) is reached at t = (π/3)/ω and, with stop = true, ends the run there.
// RK4 at ωh = 0.02 rad: the steady spin about a principal axis is integrated with O((ωh)⁴) phase error per
// unit time, ~1e-9 rad over the run; located to 4 ulp the time is within ~1e-9 s.
TEST(SceneEvents, AnAngleCrossingStopsTheRunAtTheClosedFormTime) {
  const double omega = 2.0;
  const Scene s = parse_scene(fmt::format(R"([simulation]
duration = 5.0
timestep = 0.01
[[bodies]]
name = "top"
shape = {{ type = "cylinder", radius = 0.1, length = 0.05 }}
mass = 1.0
angular_velocity = [0, 0, {}]
[[events]]
name = "sixty"
body = "top"
axis = [1, 0, 0]
toward = [1, 0, 0]
angle_deg = 60
direction = "rising"
stop = true
)",
                                          omega),
                              "angle.toml");
  const std::vector<EventHit> hits = crossings(s);
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_NEAR(hits[0].state.t, (pi / 3) / omega, 1e-9);
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

TEST(SceneFile, ABodyOnItsOrbitWithItsAttitudeRelativeToTheOrbitFrame) {
  // The orbit places the centre of mass; orientation_frame and angular_velocity_frame = "lvlh" give the
  // attitude and rates as the _lvlh output fields report them, so the fields at t = 0 read them back.
  const std::string scene = R"(
[[bodies]]
name = "sat"
mass = 400.0
inertia = [[300.0, 5.0, -2.0], [5.0, 350.0, 1.0], [-2.0, 1.0, 200.0]]
center_of_mass = [0.1, 0.0, -0.2]
orbit = { a = 7.2e6, e = 0.05, i = 0.9, raan = 0.3, argp = -1.1, nu = 2.0 }
orientation = { euler_zyx = [0.2, -0.4, 0.6] }
orientation_frame = "lvlh"
angular_velocity = [0.01, -0.02, 0.03]
angular_velocity_frame = "lvlh"
[[forces]]
type = "gravity_gradient"
mu = 3.986004418e14
center = [1.0, 2.0, 3.0]
)";
  const Scene s = parse(scene);
  OrbitalElements el;
  el.a = 7.2e6;
  el.e = 0.05;
  el.i = 0.9;
  el.raan = 0.3;
  el.argp = -1.1;
  el.nu = 2.0;
  const auto [r, v] = orbit_state(3.986004418e14, el);
  EXPECT_LT((s.initial.bodies[0].o - (Vec3(1.0, 2.0, 3.0) + r)).norm(), 1e-8) << "m, of 7e6";
  EXPECT_LT((s.initial.bodies[0].v - v).norm(), 1e-11);
  double out[6];
  fields_of_row(body_fields({"euler_zyx_lvlh", "angular_velocity_lvlh"}, s.model), s.model, s.initial, 0,
                out);
  // A rotation composed and taken apart (~1e-15 rad), rates the difference of ω and Ω_lvlh ≈ 1e-3 rad/s.
  EXPECT_LT((Vec3(out[0], out[1], out[2]) - Vec3(0.2, -0.4, 0.6)).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((Vec3(out[3], out[4], out[5]) - Vec3(0.01, -0.02, 0.03)).cwiseAbs().maxCoeff(), 1e-16);
}

TEST(SceneFile, AnOrbitNeedsACentralBodyAndPlacesTheBodyAlone) {
  const std::string body =
      "[[bodies]]\nname = \"sat\"\nshape = { type = \"sphere\", radius = 1.0 }\ndensity = 1\n"
      "orbit = { a = 7e6 }\n";
  const std::string central = "[[forces]]\ntype = \"gravity_gradient\"\nmu = 3.986e14\n";
  auto message = [&](const std::string& text) {
    try {
      (void)parse(text);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NO_THROW((void)parse(body + central));
  EXPECT_NE(message(body).find("an orbit is about a central body"), std::string::npos) << message(body);
  EXPECT_NE(message(body + "position = [1, 0, 0]\n" + central).find("position and orbit both place the body"),
            std::string::npos);
  const std::string open =
      "[[bodies]]\nname = \"sat\"\nshape = { type = \"sphere\", radius = 1.0 }\ndensity = 1\n"
      "orbit = { a = 7e6, e = 1.2 }\n";
  EXPECT_NE(message(open + central).find("test.toml:7:24: body 'sat' orbit: e = 1.2 is not an ellipse"),
            std::string::npos)
      << message(open + central);
  const std::string lvlh =
      "[[bodies]]\nname = \"sat\"\nshape = { type = \"sphere\", radius = 1.0 }\ndensity = 1\n"
      "orientation_frame = \"lvlh\"\n";
  EXPECT_NE(message(lvlh + central).find("\"lvlh\" is relative to the orbit frame of the centre of mass"),
            std::string::npos);
}

}  // namespace
}  // namespace tumble
