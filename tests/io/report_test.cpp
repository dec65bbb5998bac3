// Reports: what `tumble run --report` records and what `tumble report` reads back from CSV and HDF5
// files are the same report; the HTML holds the JSON the viewer decodes; long runs are thinned.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstring>
#include <fmt/format.h>
#include <functional>
#include <nlohmann/json.hpp>

#include "../support/run.hpp"
#include "../support/scene_files.hpp"
#include "tumble/error.hpp"
#include "tumble/io/report.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/math/rotations.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

const fs::path kTHandle = fs::path(TUMBLE_SOURCE_DIR) / "examples" / "t_handle.toml";

/// Bytes of a {dtype, shape, base64} array of the report's JSON, decoded.
std::vector<unsigned char> bytes(const nlohmann::json& a) {
  static const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const std::string s = a.at("base64").get<std::string>();
  std::vector<unsigned char> out;
  unsigned v = 0;
  int bits = 0;
  for (const char c : s) {
    if (c == '=') break;
    v = (v << 6) | static_cast<unsigned>(digits.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((v >> bits) & 0xff));
    }
  }
  return out;
}

template <class T>
std::vector<T> decode(const nlohmann::json& a) {
  const auto b = bytes(a);
  std::vector<T> out(b.size() / sizeof(T));
  std::memcpy(out.data(), b.data(), out.size() * sizeof(T));
  return out;
}

TEST(Report, TheCsvAndHdf5FilesGiveTheReportTheRunRecorded) {
  const test::TempDir dir("report_files");
  const auto csv = test::run_tumble("run " + kTHandle.string() + " -o " + (dir / "t.csv").string() +
                                    " --report " + (dir / "live.html").string() + " --quiet");
  ASSERT_EQ(csv.status, 0) << csv.output;
  const auto h5 =
      test::run_tumble("run " + kTHandle.string() + " -o " + (dir / "t.h5").string() + " --quiet");
  ASSERT_EQ(h5.status, 0) << h5.output;
  const Report from_csv = read_report(dir / "t.csv");
  const Report from_h5 = read_report(dir / "t.h5");
  for (const Report* r : {&from_csv, &from_h5}) {
    EXPECT_EQ(r->names, std::vector<std::string>{"handle"});
    EXPECT_EQ(r->samples_total, 2001);
    ASSERT_EQ(r->t.size(), 2001u) << "within the size budget: nothing thinned";
    ASSERT_EQ(r->geometry.bodies.size(), 1u);
    EXPECT_FALSE(r->geometry.bodies[0].surface().triangles.empty())
        << "the T-handle's mesh travels with the file";
    ASSERT_EQ(r->events.size(), 4u);
    EXPECT_EQ(r->events[0].name, "flip");
    EXPECT_EQ(r->integrator, "rk4");
    EXPECT_NE(r->scene_text.find("[[events]]"), std::string::npos);
    EXPECT_FALSE(r->wall_time_s.has_value()) << "files are byte-identical run to run: no wall time";
  }
  // CSV holds 17 significant digits and HDF5 the doubles: the same numbers.
  EXPECT_EQ(from_csv.t, from_h5.t);
  EXPECT_EQ(from_csv.quaternion, from_h5.quaternion);
  EXPECT_EQ(from_csv.omega_world, from_h5.omega_world);
  EXPECT_EQ(from_csv.energy_drift, from_h5.energy_drift);
  EXPECT_EQ(from_csv.geometry.bodies[0].surface().vertices, from_h5.geometry.bodies[0].surface().vertices);

  // ω in principal axes, recomputed from the file as Uᵀ R_refᵀ ω, against the run's own
  // angular_velocity_principal column: equal to rounding (a few ulp of |ω| = 20 rad/s).
  const auto principal = test::run_tumble("run " + kTHandle.string() + " -o " + (dir / "p.csv").string() +
                                          " --fields angular_velocity_principal --quiet");
  ASSERT_EQ(principal.status, 0) << principal.output;
  const std::string text = test::read_text(dir / "p.csv");
  size_t line_start = text.find('\n') + 1;
  for (size_t k = 0; k < from_csv.t.size(); ++k) {
    const size_t end = text.find('\n', line_start);
    const std::string line = text.substr(line_start, end - line_start);
    line_start = end + 1;
    double w[3];
    std::sscanf(line.c_str(), "%*[^,],%*[^,],%lf,%lf,%lf", &w[0], &w[1], &w[2]);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(from_csv.omega_principal[3 * k + static_cast<size_t>(c)], w[c], 1e-13) << k;
  }

  // The live report holds what the file's report holds (the same samples, geometry, events), but for
  // its wall time, which differs run to run.
  Report live_like = from_csv;
  const std::string html = report_html(live_like);
  const std::string page = test::read_text(dir / "live.html");
  const auto data = [](const std::string& h) {
    const std::string open = "<script id=\"tumble-data\" type=\"application/json\">";
    const size_t a = h.find(open) + open.size();
    return nlohmann::json::parse(h.substr(a, h.find("</script>", a) - a));
  };
  nlohmann::json a = data(html), b = data(page);
  a["meta"].erase("wall_time_s");
  b["meta"].erase("wall_time_s");
  // ω in principal axes is recomputed from the file (checked to 1e-13 above); its float32 may differ in
  // the last bit from the one the run recorded.
  a["series"].erase("omega_principal");
  b["series"].erase("omega_principal");
  std::vector<std::string> differ;  // paths only: the arrays are long
  for (const auto& op : nlohmann::json::diff(a, b)) differ.push_back(op.at("path").get<std::string>());
  EXPECT_TRUE(differ.empty()) << ::testing::PrintToString(differ);
}

// The run file holds each distinct body geometry once ("kinds") and each body's kind: 40 identical
// boxes and 2 others are 3 kinds, read back per body as the scene made them; a run file of format 1
// (every body with its own geometry) is still read.
TEST(Report, TheRunFileHoldsEachDistinctGeometryOnce) {
  const test::TempDir dir("report_kinds");
  std::string scene = "[simulation]\nduration = 0.01\ntimestep = 1e-3\n";
  for (int i = 0; i < 42; ++i) {
    const double size = i == 7 ? 0.3 : i == 30 ? 0.5 : 0.2;
    scene += fmt::format(
        "[[bodies]]\nname = \"box{}\"\nshape = {{ type = \"box\", size = [{}, 0.1, 0.05] }}\n"
        "density = 1000.0\nposition = [{}.0, 0.0, 0.0]\n",
        i, size, i);
  }
  dir.write("boxes.toml", scene);
  const auto run =
      test::run_tumble("run " + (dir / "boxes.toml").string() + " -o " + (dir / "b.csv").string() + " -q");
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json facts = nlohmann::json::parse(test::read_text(dir / "b.run.json"));
  EXPECT_EQ(facts.at("version"), 2);
  EXPECT_EQ(facts.at("kinds").size(), 3u);
  EXPECT_EQ(facts.at("body_kinds"), nlohmann::json::parse("[[0,7],[1,1],[0,22],[2,1],[0,11]]"));
  const Report r = read_report(dir / "b.csv");
  const Scene s = load_scene(dir / "boxes.toml");
  ASSERT_EQ(r.geometry.bodies.size(), 42u);
  for (size_t i = 0; i < 42; ++i) {
    EXPECT_EQ(r.geometry.bodies[i].mass, s.model.bodies[i].mass()) << i;
    EXPECT_EQ(r.geometry.bodies[i].Lambda, s.model.bodies[i].Lambda()) << i;
    EXPECT_EQ(r.geometry.bodies[i].surface().vertices, s.body_info[i].display->vertices) << i;
  }
  // Format 1: the kinds written out per body.
  nlohmann::json old = facts;
  old["version"] = 1;
  old["bodies"] = nlohmann::json::array();
  for (const auto& run_of_kind : facts.at("body_kinds")) {
    for (int n = 0; n < run_of_kind.at(1).get<int>(); ++n)
      old["bodies"].push_back(facts.at("kinds").at(run_of_kind.at(0).get<size_t>()));
  }
  old.erase("kinds");
  old.erase("body_kinds");
  dir.write("b.run.json", old.dump(1));
  const Report from_old = read_report(dir / "b.csv");
  ASSERT_EQ(from_old.geometry.bodies.size(), 42u);
  for (size_t i = 0; i < 42; ++i)
    EXPECT_EQ(from_old.geometry.bodies[i].surface().vertices, r.geometry.bodies[i].surface().vertices);
  // A body naming a kind that is not there is refused with the file's name.
  nlohmann::json bad = facts;
  bad["body_kinds"][0][0] = 9;
  dir.write("b.run.json", bad.dump());
  try {
    (void)read_report(dir / "b.csv");
    FAIL() << "a missing kind was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("a body names a kind that is not there"), std::string::npos)
        << e.what();
  }
}

TEST(Report, TheRunFileKeepsTheSceneTextByteForByte) {
  // The scene's text is escaped into OUT.run.json a line at a time: quotes, backslashes, tabs, CR LF
  // line ends and UTF-8 beyond ASCII (comments in any language) come back as they were written.
  const test::TempDir dir("report_text");
  const std::string scene =
      "# Kreisel über \"Achse\" \\ 回転\r\n[simulation]\r\nduration = 0.01\t# s\r\ntimestep = 1e-3\n"
      "[[bodies]]\nname = \"b\"  # 'ß'\nshape = { type = \"sphere\", radius = 0.1 }\ndensity = 1000.0\n";
  dir.write("s.toml", scene);
  const auto run =
      test::run_tumble("run " + (dir / "s.toml").string() + " -o " + (dir / "s.csv").string() + " -q");
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json facts = nlohmann::json::parse(test::read_text(dir / "s.run.json"));
  EXPECT_EQ(facts.at("scene").get<std::string>(), scene);
  EXPECT_EQ(read_report(dir / "s.csv").scene_text, scene);
}

TEST(Report, TheHtmlHoldsTheJsonTheViewerDecodes) {
  const test::TempDir dir("report_html");
  const auto run =
      test::run_tumble("run " + kTHandle.string() + " -o " + (dir / "t.h5").string() + " --quiet");
  ASSERT_EQ(run.status, 0) << run.output;
  Report r = read_report(dir / "t.h5");
  r.scene_text += "\n# </script><!-- a scene comment that must not end the data";
  const std::string html = report_html(r);
  EXPECT_EQ(html.find("__TUMBLE_DATA__"), std::string::npos);
  const std::string open = "<script id=\"tumble-data\" type=\"application/json\">";
  const size_t a = html.find(open) + open.size();
  const size_t end = html.find("</script>", a);
  const std::string json_text = html.substr(a, end - a);
  EXPECT_EQ(json_text.find('<'), std::string::npos) << "every '<' is written \\u003c";
  const auto j = nlohmann::json::parse(json_text);
  EXPECT_EQ(j.at("meta").at("scene_text").get<std::string>(), r.scene_text)
      << "the text survives the escaping";
  EXPECT_EQ(j.at("format"), "tumble-report");
  const size_t T = r.t.size();
  EXPECT_EQ(j.at("meta").at("samples_shown").get<size_t>(), T);
  EXPECT_EQ(decode<double>(j.at("t")), r.t);
  const auto q = decode<float>(j.at("series").at("quaternion"));
  ASSERT_EQ(q.size(), 4 * T);
  for (size_t i = 0; i < q.size(); ++i) EXPECT_EQ(q[i], static_cast<float>(r.quaternion[i])) << i;
  EXPECT_EQ(decode<double>(j.at("system").at("energy_drift")).size(), T);
  const auto& body = j.at("bodies").at(0);
  EXPECT_EQ(body.at("kind"), "body");
  const auto& mesh = j.at("meshes").at(body.at("mesh").get<size_t>());
  EXPECT_EQ(decode<float>(mesh.at("positions")).size(), 3 * r.geometry.bodies[0].surface().vertices.size());
  EXPECT_EQ(decode<std::uint32_t>(mesh.at("indices")).size(),
            3 * r.geometry.bodies[0].surface().triangles.size());
  EXPECT_EQ(j.at("events").size(), 4u);
}

TEST(Report, LongRunsAreThinnedToTheBudgetKeepingTheEnds) {
  const test::TempDir dir("report_thin");
  // 10⁵ + 1 samples of one body: more than the 16 MB budget holds.
  const auto run = test::run_tumble("run " + kTHandle.string() + " -o " + (dir / "t.h5").string() +
                                    " --output-interval 2e-4 --timestep 2e-4 --report " +
                                    (dir / "r.html").string() + " --quiet");
  ASSERT_EQ(run.status, 0) << run.output;
  const long limit = report_sample_limit(1);
  ASSERT_LT(limit, 100001);
  const Report r = read_report(dir / "t.h5");
  EXPECT_EQ(r.samples_total, 100001);
  EXPECT_LE(static_cast<long>(r.t.size()), limit);
  EXPECT_GT(static_cast<long>(r.t.size()), limit / 2);
  EXPECT_EQ(r.t.front(), 0.0);
  EXPECT_EQ(r.t.back(), 20.0) << "the last sample is always shown";
  EXPECT_LT(fs::file_size(dir / "r.html"), 20u * 1000 * 1000) << "the issue's limit";
  const std::string page = test::read_text(dir / "r.html");
  EXPECT_NE(page.find("\"samples_total\":100001"), std::string::npos);
}

/// Replaces the dataset `name` of the HDF5 file with what `make` creates in its place (given the file
/// and the name).
void replace_dataset(const fs::path& file, const char* name,
                     const std::function<void(hid_t, const char*)>& make) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  ASSERT_GE(H5Ldelete(f, name, H5P_DEFAULT), 0);
  make(f, name);
  H5Fclose(f);
}

TEST(Report, AForgedHdf5FileReadsNothingOutsideItselfAndClaimsNoMoreThanItHolds) {
  // A received trajectory could point its datasets at any file on the machine (external storage, an
  // external link), and `tumble report` would embed that file's bytes in a page made to be shared; or
  // claim 2·10⁸ samples in a small file and exhaust memory. Each is refused, naming the dataset.
  const test::TempDir dir("report_forged");
  const auto run = test::run_tumble("run " + kTHandle.string() + " -o " + (dir / "t.h5").string() + " -q");
  ASSERT_EQ(run.status, 0) << run.output;
  const std::string secret = dir.write("secret.txt", std::string(16008, 'x')).string();
  const auto refused = [&](const char* file, const std::string& what) {
    try {
      read_report(dir / file);
      ADD_FAILURE() << file << " was read";
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fs::copy_file(dir / "t.h5", dir / "external.h5");
  replace_dataset(dir / "external.h5", "t", [&](hid_t f, const char* name) {
    const hsize_t n = 2001;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_external(plist, secret.c_str(), 0, n * 8);
    H5Dclose(H5Dcreate2(f, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, plist, H5P_DEFAULT));
    H5Pclose(plist);
    H5Sclose(space);
  });
  refused("external.h5", "external.h5: dataset 't' keeps its data in other files (HDF5 external storage)");

  fs::copy_file(dir / "t.h5", dir / "link.h5");
  replace_dataset(dir / "link.h5", "position", [&](hid_t f, const char* name) {
    H5Lcreate_external((dir / "t.h5").c_str(), "/position", f, name, H5P_DEFAULT, H5P_DEFAULT);
  });
  refused("link.h5", "link.h5: 'position' is an external link");

  fs::copy_file(dir / "t.h5", dir / "huge.h5");
  replace_dataset(dir / "huge.h5", "t", [&](hid_t f, const char* name) {
    const hsize_t n = 200000000, chunk = 4096;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(plist, 1, &chunk);
    H5Dclose(H5Dcreate2(f, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, plist, H5P_DEFAULT));
    H5Pclose(plist);
    H5Sclose(space);
  });
  refused("huge.h5", "huge.h5: dataset 't' claims 200000000 values of 8 bytes, more than the file's");
  EXPECT_EQ(read_report(dir / "t.h5").t.size(), 2001u) << "the file they were made from is read";
}

/// Overwrites element `index` of the 1-D double dataset `name` of an HDF5 file with `value`.
void poke(const fs::path& file, const char* name, hsize_t index, double value) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t set = H5Dopen2(f, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  const hsize_t one = 1;
  H5Sselect_elements(space, H5S_SELECT_SET, 1, &index);
  const hid_t memory = H5Screate_simple(1, &one, nullptr);
  EXPECT_GE(H5Dwrite(set, H5T_NATIVE_DOUBLE, memory, space, H5P_DEFAULT, &value), 0);
  H5Sclose(memory);
  H5Sclose(space);
  H5Dclose(set);
  H5Fclose(f);
}

TEST(Report, ATamperedHdf5TrajectoryIsRefusedWithThePlace) {
  // What the page's viewer refuses ("This report cannot be shown") is refused by `tumble report` first,
  // naming the dataset and element: a time that is not finite or that comes before the one before it,
  // an event at a body the file does not have. (The CSV twins are rows of the catalogue.)
  const test::TempDir dir("report_tampered");
  const auto run = test::run_tumble("run " + kTHandle.string() + " -o " + (dir / "t.h5").string() + " -q");
  ASSERT_EQ(run.status, 0) << run.output;
  ASSERT_FALSE(read_report(dir / "t.h5").events.empty()) << "the T-handle flips: its file has events";
  const auto refused = [&](const char* file, const std::function<void(const fs::path&)>& tamper,
                           const std::string& what) {
    fs::copy_file(dir / "t.h5", dir / file);
    tamper(dir / file);
    try {
      read_report(dir / file);
      ADD_FAILURE() << file << " was read";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused(
      "nan.h5", [](const fs::path& f) { poke(f, "t", 7, std::nan("")); },
      "nan.h5: /t[7]: t = nan is not a time");
  refused(
      "back.h5", [](const fs::path& f) { poke(f, "t", 7, 1e-3); },
      "back.h5: /t[7]: t = 0.001 comes after t = 0.06, but times never decrease");
  refused(
      "body.h5", [](const fs::path& f) { poke(f, "events/body", 0, 5.0); },
      "body.h5: /events[0]: body 5 is not one of the 1 in /names");
  refused(
      "negative.h5", [](const fs::path& f) { poke(f, "events/body", 0, -1.0); },
      "negative.h5: /events[0]: body -1 is not one of the 1 in /names");
  refused(
      "event_t.h5",
      [](const fs::path& f) { poke(f, "events/t", 0, std::numeric_limits<double>::infinity()); },
      "event_t.h5: /events[0]: t = inf is not a time");
}

TEST(Report, MissingPiecesAreNamed) {
  const test::TempDir dir("report_errors");
  auto r = test::run_tumble("run " + kTHandle.string() + " -o " + (dir / "f.h5").string() +
                            " --fields angular_velocity --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  r = test::run_tumble("report " + (dir / "f.h5").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("has no dataset 'position'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run again without --fields"), std::string::npos) << r.output;

  r = test::run_tumble("run " + kTHandle.string() + " -o " + (dir / "t.csv").string() + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  fs::remove(dir / "t.run.json");
  r = test::run_tumble("report " + (dir / "t.csv").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("t.run.json beside it"), std::string::npos) << r.output;
  // With the scene, the geometry comes from it.
  r = test::run_tumble("report " + (dir / "t.csv").string() + " --scene " + kTHandle.string() + " -o " +
                       (dir / "s.html").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "s.html"));
  r = test::run_tumble("report " + (dir / "t.csv").string() + " -o " + (dir / "t.csv").string() +
                       " --scene " + kTHandle.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("is the trajectory itself"), std::string::npos) << r.output;
  r = test::run_tumble("report " + (dir / "t.csv").string() + " -o " + (dir / "t.diagnostics.csv").string() +
                       " --scene " + kTHandle.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("is the trajectory's diagnostics"), std::string::npos) << r.output;
  r = test::run_tumble("report " + (dir / "none.h5").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("is not a file"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace tumble
