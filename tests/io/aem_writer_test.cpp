// CCSDS Attitude Ephemeris Messages (make_aem_writer) and the calendar dates they carry
// (io/utc_time.hpp), read back as a parser of the standard (CCSDS 504.0-B-2, ADM 2.0) reads them:
// keys in the standard's order, the quaternion scalar last and frame A → B, rates in deg/s in the
// body's axes, one segment per body, each with its START and STOP times. The states written are those
// of a free symmetric top, whose attitude is known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

#include "../support/scene_files.hpp"
#include "io/utc_time.hpp"
#include "tumble/error.hpp"
#include "tumble/io/trajectory_writer.hpp"

namespace tumble {
namespace {

constexpr double pi = std::numbers::pi;

TEST(CalendarTime, DatesAreEpochPlusSecondsOnTheGregorianCalendar) {
  const io::CalendarTime epoch = io::parse_calendar_time("2026-12-03T15:00:00", "--epoch");
  EXPECT_EQ(epoch.days, 20790);  // 2026-12-03 is day 20790 after 1970-01-01 (56 years, 14 leap days)
  EXPECT_EQ(io::format_calendar_time(epoch, 0.0), "2026-12-03T15:00:00.000");
  EXPECT_EQ(io::format_calendar_time(epoch, 30 * 86400.0), "2027-01-02T15:00:00.000");
  EXPECT_EQ(io::format_calendar_time(epoch, -15 * 3600.0 - 1e-3), "2026-12-02T23:59:59.999");
  EXPECT_EQ(io::format_calendar_time(epoch, 1e-9), "2026-12-03T15:00:00.000000001");
  EXPECT_EQ(io::format_calendar_time(epoch, 0.25), "2026-12-03T15:00:00.250");
  // A leap day, and the fraction of the epoch itself.
  const io::CalendarTime leap = io::parse_calendar_time("2024-02-28T23:59:59.5Z", "--epoch");
  EXPECT_EQ(io::format_calendar_time(leap, 1.0), "2024-02-29T00:00:00.500");
  EXPECT_EQ(io::format_calendar_time(io::parse_calendar_time("2000-01-01T12:00:00.000", "e"), 0.0),
            "2000-01-01T12:00:00.000");
}

TEST(CalendarTime, AMalformedDateSaysWhatIsWrong) {
  auto message = [](const char* text) {
    try {
      (void)io::parse_calendar_time(text, "--epoch");
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("2026-02-30T00:00:00").find("--epoch 2026-02-30T00:00:00: no such day"),
            std::string::npos);
  EXPECT_NE(message("2026-12-03 15:00:00").find("the day is not 2 digits and 'T'"), std::string::npos);
  EXPECT_NE(message("2026-12-03T24:00:00").find("the time of day is out of range"), std::string::npos);
  EXPECT_NE(message("2026-12-03T15:00:00.1234567891").find("more than 9 decimals"), std::string::npos);
  EXPECT_NE(message("2026-12-03T15:00:00+01:00").find("unexpected '+01:00'"), std::string::npos);
  EXPECT_NE(message("26-12-03T15:00:00").find("the year is not 4 digits"), std::string::npos);
}

/// Keys and values of a KVN file's lines, and its data lines, by segment.
struct Aem {
  std::vector<std::pair<std::string, std::string>> keys;    // in file order (all segments)
  std::vector<std::vector<std::vector<std::string>>> data;  // segment → line → fields
};
Aem read_aem(const std::filesystem::path& path) {
  Aem a;
  std::istringstream in(test::read_text(path));
  std::string line;
  bool in_data = false;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line == "DATA_START") {
      in_data = true;
      a.data.emplace_back();
    } else if (line == "DATA_STOP") {
      in_data = false;
    } else if (in_data) {
      std::istringstream fields(line);
      std::vector<std::string> f;
      for (std::string x; fields >> x;) f.push_back(x);
      a.data.back().push_back(f);
    } else if (line.starts_with("COMMENT")) {
      a.keys.emplace_back("COMMENT", line.size() > 8 ? line.substr(8) : "");
    } else if (const size_t eq = line.find(" = "); eq != std::string::npos) {
      a.keys.emplace_back(line.substr(0, eq), line.substr(eq + 3));
    } else {
      const size_t space = line.find(' ');
      a.keys.emplace_back(line.substr(0, space), space == std::string::npos ? "" : line.substr(space + 1));
    }
  }
  return a;
}

TEST(AemWriter, WritesEachBodysAttitudeAsTheStandardReadsIt) {
  // Two symmetric tops spinning about their symmetry axes (principal z = reference z: from_principal_
  // moments), torque-free: q(t) = q₀ exp(Ωt/2 ẑ_body), ω_body = Ω ẑ, constant; and a particle, which
  // has no attitude.
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1.0, 1.0, 2.0), "sat_a"));
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1.0, 1.0, 2.0), "sat_b"));
  model.add_particle(Particle{"pebble", 0.1});
  const Quat q0[2] = {Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized())), Quat::Identity()};
  const double Omega[2] = {0.2, -1.5};
  auto state = [&](double t) {
    SystemState s{t, {}, {ParticleState{}}};
    for (int b = 0; b < 2; ++b) {
      BodyState x;
      x.q = q0[b] * Quat(Eigen::AngleAxisd(Omega[b] * t, Vec3::UnitZ()));
      x.omega_w = x.q * Vec3(0.0, 0.0, Omega[b]);
      s.bodies.push_back(x);
    }
    return s;
  };
  test::TempDir dir("aem");
  RunSettings settings;
  const TrajectoryInfo info{"", "tops.toml", "0", settings, {}, false, nullptr};
  AemHeader header;
  header.epoch = "2026-12-03T15:00:00";
  auto writer = make_aem_writer(dir / "tops.aem", model, info, header);
  EXPECT_FALSE(std::filesystem::exists(dir / "tops.aem")) << "nothing under the final name before commit";
  for (int k = 0; k <= 4; ++k) writer->write(model, state(0.5 * k), DriftSample{});
  writer->commit(true);

  const Aem a = read_aem(dir / "tops.aem");
  ASSERT_FALSE(a.keys.empty());
  EXPECT_EQ(a.keys[0], (std::pair<std::string, std::string>{"CCSDS_AEM_VERS", "2.0"})) << "the first line";
  // The keys in the standard's order (table 4-3), with no version-1 key (ATTITUDE_DIR, QUATERNION_TYPE,
  // RATE_FRAME: version 2 refuses them).
  std::vector<std::string> order;
  for (const auto& [k, v] : a.keys) order.push_back(k);
  const std::vector<std::string> segment = {
      "META_START",           "OBJECT_NAME",          "OBJECT_ID", "REF_FRAME_A",   "REF_FRAME_B",
      "TIME_SYSTEM",          "START_TIME",           "STOP_TIME", "ATTITUDE_TYPE", "ANGVEL_FRAME",
      "INTERPOLATION_METHOD", "INTERPOLATION_DEGREE", "META_STOP"};
  std::vector<std::string> expected = {"CCSDS_AEM_VERS", "COMMENT", "CREATION_DATE", "ORIGINATOR"};
  for (int s = 0; s < 2; ++s) expected.insert(expected.end(), segment.begin(), segment.end());
  EXPECT_EQ(order, expected);
  std::multimap<std::string, std::string> kv(a.keys.begin(), a.keys.end());
  EXPECT_EQ(kv.find("OBJECT_NAME")->second, "sat_a");
  EXPECT_EQ(kv.find("ATTITUDE_TYPE")->second, "QUATERNION/ANGVEL");
  EXPECT_EQ(kv.find("REF_FRAME_A")->second, "EME2000");
  EXPECT_EQ(kv.find("START_TIME")->second, "2026-12-03T15:00:00.000");
  EXPECT_EQ(kv.find("STOP_TIME")->second, "2026-12-03T15:00:02.000");

  ASSERT_EQ(a.data.size(), 2u) << "one segment per body, none for the particle";
  for (int b = 0; b < 2; ++b) {
    ASSERT_EQ(a.data[b].size(), 5u);
    for (int k = 0; k <= 4; ++k) {
      const std::vector<std::string>& f = a.data[b][k];
      ASSERT_EQ(f.size(), 8u) << "epoch, Q1 Q2 Q3 QC, three rates";
      EXPECT_EQ(f[0], io::format_calendar_time(io::parse_calendar_time("2026-12-03T15:00:00", "e"), 0.5 * k));
      auto num = [&](int i) { return std::stod(f[static_cast<size_t>(i)]); };
      // Frame A → B, scalar last: Quat(QC, Q1, Q2, Q3) maps body coordinates to A's, as tumble's q.
      const Quat q(num(4), num(1), num(2), num(3));
      const Quat exact = q0[b] * Quat(Eigen::AngleAxisd(Omega[b] * 0.5 * k, Vec3::UnitZ()));
      // 16 significant digits carry each component to ~1e-16; the closed form's own rounding is ~1e-16.
      EXPECT_LT((q.coeffs() - exact.coeffs()).cwiseAbs().maxCoeff(), 5e-16) << b << " " << k;
      EXPECT_NEAR(num(5), 0.0, 1e-14);
      EXPECT_NEAR(num(6), 0.0, 1e-14);
      EXPECT_NEAR(num(7), Omega[b] * 180.0 / pi, 1e-13) << "deg/s about the body's own z";
    }
  }
}

TEST(AemWriter, AnIncompleteRunSaysSoAndBadHeadersAreRefused) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1.0, 2.0, 3.0), "box"));
  test::TempDir dir("aem_incomplete");
  const TrajectoryInfo info{"", "box.toml", "0", RunSettings{}, {}, false, nullptr};
  auto writer = make_aem_writer(dir / "box.aem", model, info, AemHeader{});
  writer->write(model, SystemState{0.0, {BodyState{}}, {}}, DriftSample{});
  writer->write(model, SystemState{0.1, {BodyState{}}, {}}, DriftSample{});
  writer->commit(false);
  const std::string text = test::read_text(dir / "box.aem");
  EXPECT_NE(text.find("COMMENT incomplete: the run stopped at time 0.1 s"), std::string::npos) << text;
  EXPECT_NE(text.find("START_TIME = 2000-01-01T12:00:00.000"), std::string::npos) << "J2000 by default";

  AemHeader bad;
  bad.ref_frame = "SC_BODY_1";
  EXPECT_THROW((void)make_aem_writer(dir / "x.aem", model, info, bad), InvalidArgument);
  bad.ref_frame = "eme2000";
  EXPECT_THROW((void)make_aem_writer(dir / "x.aem", model, info, bad), InvalidArgument);
  AemHeader late;
  late.epoch = "2026-13-01T00:00:00";
  EXPECT_THROW((void)make_aem_writer(dir / "x.aem", model, info, late), InvalidArgument);
  Model particles;
  particles.add_particle(Particle{"p", 1.0});
  EXPECT_THROW((void)make_aem_writer(dir / "x.aem", particles, info, AemHeader{}), InvalidArgument);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.aem"));
}

}  // namespace
}  // namespace tumble
