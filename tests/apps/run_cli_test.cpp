// `tumble run` and `tumble check` end to end: outputs where the user asked, command-line overrides,
// the drift warning, one-line errors, nothing half-written after an error, and Ctrl-C.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include "../support/run.hpp"
#include "../support/scene_files.hpp"
#include "tumble/io/report.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/math/rotations.hpp"

extern char** environ;

namespace tumble {
namespace {

using test::run_tumble;

std::string example(const std::string& name) { return std::string(TUMBLE_SOURCE_DIR) + "/examples/" + name; }

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::vector<std::string> file_lines(const std::filesystem::path& p) {
  std::vector<std::string> out(1);
  for (char c : test::read_text(p)) {
    if (c == '\n') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  out.pop_back();
  return out;
}

bool has_temporaries(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.path().string().find(".tmp-") != std::string::npos) return true;
  }
  return false;
}

TEST(RunCli, WritesTrajectoryAndDiagnosticsAndSaysWhere) {
  test::TempDir dir("run_cli");
  const auto out = dir / "out/box.csv";
  const auto r = run_tumble("run " + example("thrown_box.toml") + " -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("trajectory:  " + out.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("diagnostics: " + (dir / "out/box.diagnostics.csv").string()), std::string::npos);
  // 1.2 s every 0.01 s: 121 samples of one body, plus the header.
  const auto rows = file_lines(out);
  ASSERT_EQ(rows.size(), 122u);
  EXPECT_EQ(rows[0], "t,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
  EXPECT_EQ(rows.back().substr(0, 8), "1.2,box,");
  EXPECT_EQ(file_lines(dir / "out/box.diagnostics.csv").size(), 122u);
  EXPECT_FALSE(has_temporaries(dir.path()));
}

// A negative zero (here typed in the scene; elsewhere left by rounding) is printed as 0: in the CSV's
// first sample and in `tumble check`'s summary of the bodies.
TEST(RunCli, NegativeZerosArePrintedAsZero) {
  test::TempDir dir("run_cli_negative_zero");
  const auto scene = dir.write("s.toml", R"([simulation]
duration = 0.01
timestep = 0.01
[[bodies]]
name = "a"
shape = { type = "box", size = [1.0, 2.0, 3.0] }
density = 1000
position = [-0.0, 0.0, 1.0]
velocity = [-0.0, -0.0, 0.0]
angular_velocity = [0.0, -0.0, 1.0]
)");
  const auto r = run_tumble("run " + scene.string() + " -o " + (dir / "a.csv").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto rows = file_lines(dir / "a.csv");
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows[1], "0,a,0,0,1,1,0,0,0,0,0,0,0,0,1");
  const auto check = run_tumble("check " + scene.string());
  ASSERT_EQ(check.status, 0) << check.output;
  EXPECT_EQ(check.output.find("-0,"), std::string::npos) << check.output;
  EXPECT_EQ(check.output.find("(-0"), std::string::npos) << check.output;
}

TEST(RunCli, CommandLineOverridesTheFile) {
  test::TempDir dir("run_overrides");
  // Every [simulation] value overridden; .dat with --format hdf5 is HDF5 whatever its name.
  const auto h5 = dir / "top.dat";
  const auto r = run_tumble("run " + example("symmetric_top.toml") + " -o " + h5.string() +
                            " --format hdf5 --duration 0.5 --timestep 1e-2 --output-interval 0.1"
                            " --integrator euler --formulation world --drift-threshold 0 --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "") << "--quiet prints nothing on success";
  EXPECT_EQ(test::read_text(h5).substr(0, 8), "\x89HDF\r\n\x1a\n");

  const auto csv = dir / "top.csv";
  const auto r2 = run_tumble("run " + example("symmetric_top.toml") + " -o " + csv.string() +
                             " --duration 0.5 --timestep 1e-2 --output-interval 0.1 --integrator euler"
                             " --drift-threshold 0");
  ASSERT_EQ(r2.status, 0) << r2.output;
  EXPECT_NE(r2.output.find("for 0.5 s (euler, mixed formulation): 6 samples"), std::string::npos)
      << r2.output;
  const auto diag = file_lines(dir / "top.diagnostics.csv");
  ASSERT_EQ(diag.size(), 7u);  // t = 0, 0.1, ..., 0.5
  EXPECT_EQ(diag.back().substr(0, 4), "0.5,");
  // Explicit Euler on Euler's equations gains energy on a free rotor: ω̇ is Λ-orthogonal to ω, so
  // E(n+1) = E(n) + ½h² ω̇ᵀΛω̇ > E(n). A positive drift in the last sample (0.13 here; rk4 at the
  // file's settings drifts 1e-10) is the signature of the overridden integrator and step.
  const std::string last = diag.back();
  const auto fields = [&] {
    std::vector<std::string> f(1);
    for (char c : last) {
      if (c == ',') {
        f.emplace_back();
      } else {
        f.back() += c;
      }
    }
    return f;
  }();
  ASSERT_EQ(fields.size(), 13u);
  EXPECT_GT(std::stod(fields[10]), 1e-4) << last;
}

TEST(RunCli, ChosenFieldsDescribeTheSameMotion) {
  // The T-handle with every field beside the default pose: the fields computed from one state by
  // different formulas must agree with each other and with the physics of a free body.
  test::TempDir dir("run_fields");
  const auto out = dir / "t.csv";
  const std::string fields =
      "orientation,com_position,com_velocity,angular_velocity,angular_velocity_reference,"
      "angular_velocity_principal,euler_zyx,euler_zxz,axis_angle";
  const auto r = run_tumble("run " + example("t_handle.toml") +
                            " --duration 6 --output-interval 0.5 --quiet" + " --fields " + fields + " -o " +
                            out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto rows = file_lines(out);
  EXPECT_EQ(
      rows[0],
      "t,body,qw,qx,qy,qz,com_x,com_y,com_z,com_vx,com_vy,com_vz,wx,wy,wz,wx_ref,wy_ref,wz_ref,w1,w2,w3,"
      "yaw,pitch,roll,phi,theta,psi,axis_x,axis_y,axis_z,angle");
  ASSERT_EQ(rows.size(), 14u);  // 0, 0.5, …, 6 s
  auto values = [](const std::string& row) {
    std::vector<double> v;
    std::stringstream in(row);
    std::string item;
    std::getline(in, item, ',');  // t
    std::getline(in, item, ',');  // body
    while (std::getline(in, item, ',')) v.push_back(std::stod(item));
    return v;
  };
  const std::vector<double> first = values(rows[1]);
  // The principal moments λ₁ ≤ λ₂ ≤ λ₃ of the handle, and |L| = |Λ ^bω| and 2T = ^bω·Λ ^bω at t = 0.
  const Vec3 Lambda = load_scene(example("t_handle.toml")).model.bodies[0].Lambda();
  const Vec3 w_b0(first[16], first[17], first[18]);
  const double L0 = Lambda.cwiseProduct(w_b0).norm(), T0 = w_b0.dot(Lambda.cwiseProduct(w_b0));
  for (size_t i = 1; i < rows.size(); ++i) {
    const std::vector<double> v = values(rows[i]);
    const Quat q(v[0], v[1], v[2], v[3]);
    const Mat3 R_ref = q.toRotationMatrix();
    // ZYX and ZXZ angles and axis–angle rebuild the quaternion's rotation (to rounding, ~1e-15).
    EXPECT_LT((from_euler_zyx(Vec3(v[19], v[20], v[21])) - R_ref).cwiseAbs().maxCoeff(), 1e-14) << i;
    EXPECT_LT((from_euler_zxz(Vec3(v[22], v[23], v[24])) - R_ref).cwiseAbs().maxCoeff(), 1e-14) << i;
    const Mat3 R_axis = Eigen::AngleAxisd(v[28], Vec3(v[25], v[26], v[27])).toRotationMatrix();
    EXPECT_LT((R_axis - R_ref).cwiseAbs().maxCoeff(), 1e-14) << i;
    // ω in reference axes is R_refᵀ ω (world); |ω| is the same in every frame.
    const Vec3 w(v[10], v[11], v[12]), w_ref(v[13], v[14], v[15]), w_b(v[16], v[17], v[18]);
    EXPECT_LT((R_ref.transpose() * w - w_ref).norm(), 1e-13 * w.norm()) << i;
    EXPECT_NEAR(w_b.norm(), w.norm(), 1e-13 * w.norm()) << i;
    // The principal components obey Euler–Poinsot: |L| and T are constant, to RK4's error at ωh = 0.02
    // (the run's energy drift is ~1e-10 in 6 s; 1e-8 leaves room without hiding a wrong frame, which
    // would change |Λ ^bω| by tens of percent on this body).
    EXPECT_NEAR(Lambda.cwiseProduct(w_b).norm(), L0, 1e-8 * L0) << i;
    EXPECT_NEAR(w_b.dot(Lambda.cwiseProduct(w_b)), T0, 1e-8 * T0) << i;
    // A free body: the centre of mass moves uniformly (here it rests); no force, so its velocity keeps
    // every bit, and o(t) = o(0) + v t to the rounding of the sum (|o| ≲ 0.1 m, t ≤ 6 s).
    const double t = 0.5 * static_cast<double>(i - 1);
    for (size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(first[7 + k], 0.0) << "the scene gives velocity_of = \"com\": at rest";
      EXPECT_EQ(v[7 + k], first[7 + k]) << i;
      EXPECT_NEAR(v[4 + k], first[4 + k] + t * first[7 + k], 1e-15) << i;
    }
  }
}

TEST(RunCli, ExactSamplesAreAnalyticAndATorqueIsRefusedByCheckAndRun) {
  test::TempDir dir("run_exact");
  const std::string body =
      "[[bodies]]\nname = \"box\"\nshape = { type = \"box\", size = [0.1, 0.2, 0.3] }\ndensity = 1000\n"
      "angular_velocity = [0.1, 5.0, 0.2]\n";
  const auto free = dir.write("free.toml",
                              "[simulation]\nduration = 3\nintegrator = \"exact\"\n[world]\n"
                              "gravity = [0, 0, -9.81]\n" +
                                  body);
  const auto c = run_tumble("check " + free.string());
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_NE(c.output.find("samples are analytic"), std::string::npos) << c.output;
  const auto r = run_tumble("run " + free.string() + " --quiet -o " + (dir / "free.csv").string());
  EXPECT_EQ(r.status, 0) << r.output;

  const auto damped = dir.write("damped.toml",
                                "[simulation]\nduration = 1\nintegrator = \"exact\"\n[[forces]]\n"
                                "type = \"damping\"\n"
                                "linear = 0.1\nangular = 0.01\n" +
                                    body);
  for (const std::string& command :
       {std::string("check "), "run -o " + (dir / "damped.csv").string() + " "}) {
    const auto bad = run_tumble(command + damped.string());
    EXPECT_EQ(bad.status, 1) << command << bad.output;
    EXPECT_NE(bad.output.find("integrator 'exact' solves torque-free motion only"), std::string::npos)
        << bad.output;
    EXPECT_NE(bad.output.find("'splitting'"), std::string::npos) << bad.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "damped.csv"));
}

TEST(RunCli, CheckPlansTheHdf5FileItsRunWrites) {
  // `tumble check` said "about 1.25 kB (HDF5)" for a run of 6 samples whose file was 6.3 MB: every
  // dataset was stored in chunks of up to 65 536 samples whatever the run's length. Chunks are now sized
  // from the plan, and the estimate counts whole chunks and the datasets' records, so it is the file's
  // size to within the geometry's values (a box: 8 vertices) and the diagnostics a run does not define.
  const test::TempDir dir("run_hdf5_plan");
  for (const auto& [duration, samples] : {std::pair{"0.05", 6}, std::pair{"20", 2001}}) {
    SCOPED_TRACE(duration);
    const auto scene =
        dir.write("s.toml", std::string("[simulation]\nduration = ") + duration +
                                "\ntimestep = 0.01\n[[bodies]]\nname = \"a\"\nshape = { type = "
                                "\"box\", size = [1, 2, 3] }\ndensity = 1000\nangular_velocity "
                                "= [0.5, 5, 0.5]\n");
    const auto check = run_tumble("check " + scene.string());
    ASSERT_EQ(check.status, 0) << check.output;
    ASSERT_NE(check.output.find(std::to_string(samples) + " samples"), std::string::npos) << check.output;
    const size_t at = check.output.find(" (HDF5)");
    ASSERT_NE(at, std::string::npos) << check.output;
    const size_t from = check.output.rfind("about ", at) + 6;
    std::istringstream estimate_text(check.output.substr(from, at - from));
    double estimate = 0;
    std::string unit;
    estimate_text >> estimate >> unit;
    estimate *= unit == "kB" ? 1e3 : unit == "MB" ? 1e6 : unit == "B" ? 1 : std::nan("");
    const auto run = run_tumble("run " + scene.string() + " -o " + (dir / "o.h5").string() + " -q");
    ASSERT_EQ(run.status, 0) << run.output;
    const auto bytes = static_cast<double>(std::filesystem::file_size(dir / "o.h5"));
    EXPECT_NEAR(bytes / estimate, 1.0, 0.15) << bytes << " bytes, planned " << estimate;
  }
}

TEST(RunCli, DriftWarningOnceWithAdvice) {
  test::TempDir dir("run_drift");
  const auto r = run_tumble("run " + example("t_handle.toml") + " -o " + (dir / "t.csv").string() +
                            " --integrator euler --duration 2 --drift-threshold 1e-6");
  ASSERT_EQ(r.status, 0) << r.output;
  // Once as it happens, once more at the end of the summary.
  EXPECT_EQ(count(r.output, "tumble: warning:"), 2u) << r.output;
  // Angular momentum passes 1e-6 first (t = 0.03 s); the energy warning is not repeated after it.
  EXPECT_NE(r.output.find("tumble: warning: angular momentum drifted by"), std::string::npos) << r.output;
  // A free body: the advice names the integrators that are exact here, not lower-order ones.
  EXPECT_NE(r.output.find("integration error of 'euler': no torque acts in this scene, so 'exact' or "
                          "'splitting' (the analytic motion, or exact at any step here) removes the error; "
                          "or reduce the timestep (now 0.001 s)"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("semi_implicit_euler"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("tumble: warning: the results carry integration error past the drift threshold"),
            std::string::npos)
      << r.output;
  // The file keeps the warning (OUT.run.json, written at the end of the run) for `tumble report`.
  const std::vector<std::string> kept = read_report(dir / "t.csv").warnings;
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].rfind("angular momentum drifted by", 0), 0u) << kept[0];
  const auto strict = run_tumble("run " + example("t_handle.toml") + " -o " + (dir / "s.csv").string() +
                                 " --integrator euler --duration 2 --drift-threshold 1e-6 --strict --quiet");
  EXPECT_EQ(strict.status, 3) << strict.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "s.csv")) << "--strict still writes every file";
  // With a torque (the satellite's gravity gradient) the advice is a smaller step or a higher order.
  const auto orbit = run_tumble("run " + example("satellite.toml") + " -o " + (dir / "o.csv").string() +
                                " --integrator splitting --timestep 10 --drift-threshold 1e-9 --quiet");
  EXPECT_NE(orbit.output.find("integration error of 'splitting': reduce the timestep (now 10 s), or use "
                              "'splitting4' or 'dopri45'"),
            std::string::npos)
      << orbit.output;
  // rk4 at the scene's own settings stays below the default threshold: no warning.
  const auto quiet = run_tumble("run " + example("t_handle.toml") + " -o " + (dir / "t2.csv").string());
  EXPECT_EQ(count(quiet.output, "warning"), 0u) << quiet.output;
}

TEST(RunCli, TheOutputIsByteIdenticalForAnyThreadCount) {
  // 300 boxes spread over five blocks of the engine, with damping (velocities in world axes): the files
  // of a run on 1 and on 2 threads are the same, byte for byte.
  test::TempDir dir("run_threads");
  std::string toml =
      "[simulation]\nduration = 0.05\ntimestep = 1e-3\noutput_interval = 0.025\nintegrator = \"rk4\"\n"
      "[world]\ngravity = [0, 0, -9.81]\n"
      "[[forces]]\ntype = \"damping\"\nlinear = 0.1\nangular = 0.01\n";
  for (int i = 0; i < 300; ++i) {
    toml += "[[bodies]]\nname = \"box" + std::to_string(i) +
            "\"\nshape = { type = \"box\", size = [0.1, 0.2, 0.3] }\n"
            "density = 1000\nposition = [" +
            std::to_string(i) + ", 0, 0]\nangular_velocity = [" + std::to_string(1 + i % 7) + ", -3, " +
            std::to_string(i % 5) + "]\n";
  }
  const auto scene = dir.write("boxes.toml", toml);
  const auto one = dir / "one.csv", two = dir / "two.csv";
  const auto r1 = run_tumble("run " + scene.string() + " -o " + one.string() + " --threads 1 --quiet");
  ASSERT_EQ(r1.status, 0) << r1.output;
  const auto r = run_tumble("run " + scene.string() + " -o " + two.string() + " --threads 2 --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(test::read_text(one), test::read_text(two));
  EXPECT_EQ(file_lines(one).size(), 1u + 3u * 300u);  // header, 3 samples of 300 bodies
}

TEST(RunCli, BadInputGetsOneReadableLine) {
  test::TempDir dir("run_bad");
  auto expect_error = [&](const std::string& args, const std::string& expected) {
    const auto r = run_tumble(args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
    EXPECT_EQ(count(r.output, "\n"), 1u) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << args << "\n" << r.output;
  };
  const std::string scene = example("t_handle.toml") + " -o " + (dir / "x.csv").string();
  expect_error("run " + scene + " --timestep -1",
               "tumble: error: timestep -1 s is invalid: give a positive step");
  expect_error("run " + scene + " --integrator rk5",
               "tumble: error: unknown integrator 'rk5'; choose one of: ");
  expect_error("run " + scene + " --formulation sideways",
               "unknown formulation 'sideways'; choose world, mixed or body");
  expect_error("run " + scene + " --drift-threshold -1", "drift threshold -1 is invalid");
  expect_error("run " + scene + " --threads -2",
               "threads = -2 is invalid: give a count from 1 to 4096, or 0");
  expect_error("run " + example("t_handle.toml") + " -o " + dir.path().string(),
               "is a directory: give a file name, e.g. ");
  expect_error("run no/such/scene.toml",
               "tumble: error: cannot read scene file no/such/scene.toml: no such file");
  const auto bad = dir.write(
      "bad.toml", "[simulation]\nduration = 1\n[[bodies]]\nname = \"a\"\nmass = -1\ninertia = [1, 1, 1]\n");
  expect_error("run " + bad.string(),
               "tumble: error: " + bad.string() + ":5:8: body 'a': mass is -1 kg: it must be positive");
  expect_error("check " + bad.string(), bad.string() + ":5:8:");
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()) ||
              (std::filesystem::exists(dir / "bad.toml") && !std::filesystem::exists(dir / "x.csv")));
}

TEST(RunCli, BlowUpLeavesNoOutputUnderItsName) {
  test::TempDir dir("run_blowup");
  // Explicit Euler on a stiff spring (ω = 1e6 rad/s, h = 1e-3: ω h = 1000) grows ×1000 a step and
  // overflows within ~100 steps; simulate() stops with the body, time and step.
  const auto scene = dir.write("stiff.toml", R"([simulation]
duration = 10.0
timestep = 1e-3
integrator = "euler"
[[bodies]]
name = "b"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
position = [1.0, 0.0, 0.0]
[[forces]]
type = "spring"
a = { body = "b" }
b = { anchor = [0.0, 0.0, 0.0] }
stiffness = 1e12
)");
  const auto r = run_tumble("run " + scene.string() + " -o " + (dir / "out/stiff.csv").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("tumble: error: the state of body 'b' became non-finite at t = "),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out/stiff.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out/stiff.diagnostics.csv"));
  EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(RunCli, CtrlCStopsCleanlyAndKeepsAValidFile) {
  test::TempDir dir("run_interrupt");
  const std::string out = (dir / "long.csv").string();
  const std::string scene = example("t_handle.toml");
  // A run far longer than the test: 1e6 s of simulated time.
  std::vector<std::string> args = {TUMBLE_CLI, "run", scene, "-o", out, "--duration", "1e6", "--quiet"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, (dir / "stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, TUMBLE_CLI, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Wait until it has written samples (the temporary grows), then interrupt it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (std::chrono::steady_clock::now() < deadline && !has_temporaries(dir.path())) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "it stopped by itself, not killed by the signal";
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const std::string err = test::read_text(dir / "stderr.txt");
  EXPECT_NE(err.find("tumble: interrupted at t = "), std::string::npos) << err;
  EXPECT_NE(err.find(out + " holds the "), std::string::npos) << err;
  // Valid: the header, then complete rows of 15 fields in time order, as many as the diagnostics.
  const auto rows = file_lines(out);
  ASSERT_GT(rows.size(), 2u);
  EXPECT_EQ(rows[0], "t,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
  for (size_t i = 1; i < rows.size(); ++i) EXPECT_EQ(count(rows[i], ","), 14u) << "row " << i;
  EXPECT_EQ(file_lines(dir / "long.diagnostics.csv").size(), rows.size());
  EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(RunCli, ProgressBarWhenAsked) {
  test::TempDir dir("run_progress");
  const auto r =
      run_tumble("run " + example("thrown_box.toml") + " -o " + (dir / "b.csv").string() + " --progress");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("100%  t = 1.2 / 1.2 s  elapsed "), std::string::npos) << r.output;
  // Not a terminal and not asked: no bar.
  const auto quiet = run_tumble("run " + example("thrown_box.toml") + " -o " + (dir / "c.csv").string());
  EXPECT_EQ(quiet.output.find("elapsed"), std::string::npos) << quiet.output;
}

TEST(CheckCli, SummarisesWithoutSimulating) {
  const auto r = run_tumble("check " + example("t_handle.toml"));
  ASSERT_EQ(r.status, 0) << r.output;
  // The T-handle's closed form: volume 6.4e-5 m³ × 2700 kg/m³ = 0.1728 kg (float32 STL: 4e-8 off).
  EXPECT_NE(r.output.find("mass               0.17279999"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("principal moments  9.35999"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("initial      kinetic energy "), std::string::npos);
  EXPECT_NE(r.output.find("angular momentum ("), std::string::npos);
  EXPECT_NE(r.output.find("conserved    energy, linear momentum, angular momentum"), std::string::npos);
}

TEST(RunCli, HelpExplainsWithExamples) {
  for (const std::string cmd : {"run", "check"}) {
    const auto r = run_tumble(cmd + " --help");
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.output.find("Example"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("tumble " + cmd + " examples/"), std::string::npos) << r.output;
  }
  const auto r = run_tumble("run --help");
  for (const char* option : {"--output", "--format", "--integrator", "--formulation", "--timestep",
                             "--duration", "--quiet", "--progress", "--drift-threshold"}) {
    EXPECT_NE(r.output.find(option), std::string::npos) << option;
  }
}

TEST(RunCli, RunsThatWouldNotEndAreRefusedBeforeWritingAnything) {
  test::TempDir dir("run_plan");
  const auto out = dir / "x.csv";
  const std::string scene = example("t_handle.toml");
  struct Case {
    std::string options, message;
  };
  const std::vector<Case> cases = {
      {"--duration 1e300",
       "tumble: error: timestep 0.001 s is too small for duration 1e+300 s: 1e+303 steps, more than 2^53, "
       "where a "
       "step no longer advances the clock; give a larger timestep or a shorter duration"},
      {"--timestep 5e-324",
       "tumble: error: timestep 5e-324 s is too small for duration 20 s: inf steps, more than 2^53, where a "
       "step "
       "no longer advances the clock; give a larger timestep or a shorter duration"},
      {"--output-interval 1e-300",
       "tumble: error: output interval 1e-300 s is too small for duration 20 s: 2e+301 samples, more than "
       "2^53; "
       "give a larger output interval (0 = every step)"},
      // 10¹² steps of rk4: weeks on any machine (the estimate times the first steps here).
      {"--duration 1e9", "tumble: error: this run would take about "},
      // 10¹¹ samples, each a 15-column row: terabytes.
      {"--duration 1e8 --timestep 0.01 --output-interval 0.001", "tumble: error: this run would "},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.options);
    const auto r = run_tumble("run " + scene + " -o " + out.string() + " " + c.options);
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_EQ(r.output.rfind(c.message, 0), 0u) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_FALSE(has_temporaries(dir.path()));
  }
  // Few samples, but 10¹² steps: refused for its time alone, with what to change.
  const auto slow =
      run_tumble("run " + scene + " -o " + out.string() + " --duration 1e9 --output-interval 1e7");
  EXPECT_NE(slow.output.find("(1000000000000 steps, 101 samples): shorten the duration or enlarge the "
                             "timestep, or give --force to run it anyway"),
            std::string::npos)
      << slow.output;
}

TEST(CheckCli, StatesTheRunsStepsSamplesSizeAndTime) {
  // t_handle: 20 s at h = 1e-3 with samples every 0.01 s, one body.
  const auto r = run_tumble("check " + example("t_handle.toml"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("  plan         20000 steps, 2001 samples of 1 row; output up to "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(" on this machine (one thread)"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

using test::run_tumble;

TEST(RunCli, UnwrappedAnglesFollowASpinPastEveryHalfTurn) {
  // A sphere spinning at 3 rad/s about the world z axis: its yaw is 3t exactly (a spin about a principal
  // axis of a free body stays one; rk4's error on a constant rotation is ~(ωh)⁵/120 a step, 1e-14 rad over
  // the run). Wrapped, yaw jumps by −2π at each half turn; unwrapped it is 3t, through 30 rad.
  test::TempDir dir("run_unwrap");
  const auto scene = dir.write("spin.toml", R"([simulation]
duration = 10.0
timestep = 0.001
output_interval = 0.1
[[bodies]]
name = "ball"
shape = { type = "sphere", radius = 0.5 }
density = 1000
angular_velocity = [0.0, 0.0, 3.0]
)");
  for (const bool unwrap : {false, true}) {
    const auto out = dir / (unwrap ? "unwrapped.csv" : "wrapped.csv");
    const auto r = run_tumble("run " + scene.string() + " --fields euler_zyx -q -o " + out.string() +
                              (unwrap ? " --unwrap-angles" : ""));
    ASSERT_EQ(r.status, 0) << r.output;
    const auto rows = file_lines(out);
    ASSERT_EQ(rows.size(), 102u);  // header, 101 samples
    double largest_jump = 0.0, previous = 0.0;
    for (size_t k = 1; k < rows.size(); ++k) {
      std::stringstream in(rows[k]);
      std::string t, name, yaw;
      std::getline(in, t, ',');
      std::getline(in, name, ',');
      std::getline(in, yaw, ',');
      const double y = std::stod(yaw);
      if (unwrap) {
        EXPECT_NEAR(y, 3.0 * std::stod(t), 1e-11) << rows[k];  // rk4 and rounding: ~1e-13
      }
      if (k > 1) largest_jump = std::max(largest_jump, std::abs(y - previous));
      previous = y;
    }
    if (unwrap) {
      EXPECT_LT(largest_jump, 0.31);  // 3 rad/s × 0.1 s
      EXPECT_NEAR(previous, 30.0, 1e-11);
    } else {
      EXPECT_GT(largest_jump, 5.9);  // the sawtooth: 0.3 − 2π
    }
  }
  // Refused where it cannot hold: a checkpointed run, an attitude message.
  EXPECT_NE(run_tumble("run " + scene.string() + " --unwrap-angles -o " + (dir / "c.csv").string() +
                       " --checkpoint " + (dir / "c.ckpt").string())
                .status,
            0);
  EXPECT_NE(run_tumble("run " + scene.string() + " --unwrap-angles -o " + (dir / "a.aem").string()).status,
            0);
}

}  // namespace
}  // namespace tumble
