// Telemetry files: what is read, and every error naming the file, the line and (for one field) the
// column, so that a user finds the fault in a long file.
#include <gtest/gtest.h>

#include <string>

#include "fit_support.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

/// The message parse_telemetry throws for `text` (named "gyro.csv"), or "" when it reads.
std::string error_of(const std::string& text) {
  try {
    (void)fit::parse_telemetry(text, "gyro.csv");
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

/// `rows` well-formed samples after the header `header`, one per line from line 2.
std::string samples(int rows, const std::string& header = "t,wx,wy,wz", const std::string& extra = "") {
  std::string text = header + "\n";
  for (int k = 0; k < rows; ++k) text += fmt::format("{},0.1,0.2,0.3{}\n", 0.1 * k, extra);
  return text;
}

TEST(TelemetryCsv, ReadsColumnsInAnyOrderWithTorqueAndWheelMomentum) {
  const std::string text =
      "# a comment before the header\n"
      "wz, t ,wy,wx,h_x,h_y,h_z,tau_x,tau_y,tau_z\r\n"
      "3,0,2,1,7,8,9,4,5,6\r\n"
      "\n"
      "# a comment between samples\n"
      "3.5,0.5,2,+1,7,8,9,4,5,6e-1\n" +
      [] {
        std::string more;
        for (int k = 2; k < 12; ++k) more += fmt::format("3,{},2,1,7,8,9,4,5,6\n", k);
        return more;
      }();
  const fit::Telemetry d = fit::parse_telemetry(text, "gyro.csv");
  ASSERT_EQ(d.t.size(), 12u);
  EXPECT_EQ(d.t[1], 0.5);
  EXPECT_EQ(d.omega[1], Vec3(1, 2, 3.5));
  EXPECT_EQ(d.tau[1], Vec3(4, 5, 0.6));
  EXPECT_EQ(d.h[0], Vec3(7, 8, 9));
  EXPECT_EQ(d.line[0], 3);
  EXPECT_EQ(d.line[1], 6);
  const fit::Telemetry plain = fit::parse_telemetry(samples(10), "gyro.csv");
  EXPECT_TRUE(plain.tau.empty());
  EXPECT_TRUE(plain.h.empty());
}

TEST(TelemetryCsv, EachErrorNamesTheLine) {
  // Unsorted and repeated times: the line and the previous sample's line.
  std::string text = samples(12);
  text.replace(text.find("0.5,"), 3, "0.2");  // line 7: t = 0.2 after t = 0.4 on line 6
  EXPECT_EQ(
      error_of(text),
      "gyro.csv:7: t = 0.2 is before the previous sample's t = 0.4 (gyro.csv:6): the samples must be in "
      "time order, without repeated times");
  text = samples(12);
  text.replace(text.find("0.5,"), 3, "0.4");
  EXPECT_EQ(
      error_of(text),
      "gyro.csv:7: t = 0.4 repeats the previous sample's t = 0.4 (gyro.csv:6): the samples must be in time "
      "order, without repeated times");
  // NaN and infinity: line and column.
  EXPECT_EQ(error_of(samples(3) + "0.3,nan,0.2,0.3\n" + samples(8).substr(11)),
            "gyro.csv:5:5: 'nan' in column 'wx' is not finite: every value must be a finite number (drop the "
            "sample "
            "instead)");
  EXPECT_EQ(error_of("t,wx,wy,wz\n0,1,2,-inf\n"),
            "gyro.csv:2:7: '-inf' in column 'wz' is not finite: every value must be a finite number (drop "
            "the sample "
            "instead)");
  // Not a number; an empty field.
  EXPECT_EQ(error_of("t,wx,wy,wz\n0,1,2,3\n0.1, 1,2x,3\n"),
            "gyro.csv:3:8: '2x' in column 'wy' is not a number");
  EXPECT_EQ(error_of("t,wx,wy,wz\n0,1,,3\n"),
            "gyro.csv:2:5: column 'wy' is empty: every sample needs a value");
  // Wrong number of fields.
  EXPECT_EQ(error_of("t,wx,wy,wz\n0,1,2,3\n0.1,1,2\n"),
            "gyro.csv:3: 3 fields where the header (line 1) names 4 columns");
  EXPECT_EQ(error_of("t,wx,wy,wz\n0,1,2,3,4\n"),
            "gyro.csv:2: 5 fields where the header (line 1) names 4 columns");
  // The header: unknown, missing, repeated, partial groups, a number where the header should be.
  const std::string columns =
      "the columns are t (s), wx, wy, wz (the gyro's angular velocity, rad/s) and optionally tau_x, tau_y, "
      "tau_z "
      "(a known applied torque, N m) and h_x, h_y, h_z (a known wheel angular momentum, N m s), all in "
      "sensor axes";
  EXPECT_EQ(error_of("t,wx,wy,omega_z\n"),
            "gyro.csv:1:9: unknown column 'omega_z' in the header; " + columns);
  EXPECT_EQ(error_of("t,wx,wy\n"), "gyro.csv:1: the header has no column 'wz'; " + columns);
  EXPECT_EQ(error_of("t,wx,wy,wz,wx\n"), "gyro.csv:1:12: column 'wx' appears twice in the header");
  EXPECT_EQ(
      error_of("t,wx,wy,wz,tau_x,tau_y\n"),
      "gyro.csv:1: the header has no column 'tau_z' beside the other tau columns: a torque needs all three "
      "components");
  EXPECT_EQ(
      error_of("0,1,2,3\n"),
      "gyro.csv:1:1: '0' looks like a number, but the first line must be the header naming the columns, e.g. "
      "t,wx,wy,wz; " +
          columns);
  EXPECT_EQ(error_of("# only a comment\n\n"),
            "gyro.csv: no header line: the first line must name the columns, e.g. t,wx,wy,wz; " + columns);
  // Too few samples.
  EXPECT_EQ(error_of(samples(9)),
            "gyro.csv:10: 9 samples (lines 2 to 10): the fit needs at least 10 (3 components each, against "
            "up to 12 "
            "unknowns, with residuals to spare)");
}

TEST(TelemetryCsv, ArraysAreCheckedWithTheSampleIndex) {
  fit::Telemetry d = test::torque_free_telemetry(test::tumbling_satellite(), 12, 0.1);
  d.t[5] = d.t[3];
  try {
    fit::check_telemetry(d);
    ADD_FAILURE();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(std::string(e.what()),
              "telemetry: sample 5: t = 0.30000000000000004 is before the previous sample's t = 0.4 "
              "(telemetry: sample "
              "4): the samples must be in time order, without repeated times");
  }
  d = test::torque_free_telemetry(test::tumbling_satellite(), 12, 0.1);
  d.tau.resize(3);
  EXPECT_THROW(fit::check_telemetry(d), InvalidArgument);
  d.tau.clear();
  d.omega[2].y() = std::nan("");
  EXPECT_THROW(fit::check_telemetry(d), InvalidArgument);
}

TEST(TelemetryCsv, AFileThatIsNotThereNamesItsPath) {
  try {
    (void)fit::read_telemetry("/nonexistent/gyro.csv");
    ADD_FAILURE();
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/gyro.csv"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tumble
