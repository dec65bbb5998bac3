// read_report(): a report from a trajectory that `tumble run` wrote, HDF5 or CSV with its companions.
// The samples are read whole, then every stride-th of them (and the last) kept for display.
#include <hdf5.h>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "run_facts.hpp"
#include "tumble/error.hpp"
#include "tumble/io/geometry.hpp"
#include "tumble/io/report.hpp"
#include "tumble/io/trajectory_writer.hpp"
#include "tumble/mass/input_file.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Everything a trajectory file holds that a report shows, before down-sampling.
struct Samples {
  std::vector<double> t;
  std::vector<double> position, orientation, omega_world;                   // (T, N, 3 or 4)
  std::vector<double> kinetic, potential, total, energy_drift, L, L_drift;  // (T) or (T, 3); NaN if absent
};

// ---- HDF5 -------------------------------------------------------------------------------------------

/// An HDF5 identifier closed with its function.
struct Id {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Id() {
    if (id >= 0) close(id);
  }
};

class Hdf5Reader {
 public:
  explicit Hdf5Reader(const std::filesystem::path& path) : path_(path.string()) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    file_ = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_ < 0) throw FileError(fmt::format("cannot open {} as HDF5", path_));
    std::error_code ec;
    file_bytes_ = std::filesystem::file_size(path, ec);
  }
  ~Hdf5Reader() { H5Fclose(file_); }
  Hdf5Reader(const Hdf5Reader&) = delete;
  Hdf5Reader& operator=(const Hdf5Reader&) = delete;

  /// Whether the file has an object at `name` (e.g. "geometry/vertices"), every link on the way a link
  /// inside this file: an external or soft link is refused, not followed (H5Lexists would follow an
  /// external link into another file).
  bool has(const std::string& name) const {
    for (size_t end = name.find('/');; end = name.find('/', end + 1)) {
      const std::string prefix = name.substr(0, end);
      if (H5Lexists(file_, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
      H5L_info_t link;
      if (H5Lget_info(file_, prefix.c_str(), &link, H5P_DEFAULT) < 0) return false;
      if (link.type != H5L_TYPE_HARD) {
        throw FileError(fmt::format(
            "{}: '{}' is {} link: tumble reads only data inside the trajectory file (a link may point at "
            "any file on this machine); refused",
            path_, prefix, link.type == H5L_TYPE_EXTERNAL ? "an external" : "a soft"));
      }
      if (end == std::string::npos) return true;
    }
  }

  /// A dataset of doubles (or integers, converted) and its shape.
  std::vector<double> doubles(const std::string& name, std::vector<hsize_t>* shape = nullptr) const {
    const Id set{open(name), H5Dclose};
    const Id space{H5Dget_space(set.id), H5Sclose};
    std::vector<hsize_t> dims(static_cast<size_t>(std::max(0, H5Sget_simple_extent_ndims(space.id))));
    H5Sget_simple_extent_dims(space.id, dims.data(), nullptr);
    size_t n = 1;
    for (hsize_t d : dims) n *= d;
    std::vector<double> out(n);
    if (n > 0 && H5Dread(set.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
      fail(name);
    if (shape) *shape = dims;
    return out;
  }

  std::vector<std::uint32_t> uint32s(const std::string& name) const {
    const Id set{open(name), H5Dclose};
    const Id space{H5Dget_space(set.id), H5Sclose};
    const auto n = static_cast<size_t>(H5Sget_simple_extent_npoints(space.id));
    std::vector<std::uint32_t> out(n);
    if (n > 0 && H5Dread(set.id, H5T_NATIVE_UINT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
      fail(name);
    return out;
  }

  std::vector<std::string> strings(const std::string& name) const {
    const Id set{open(name), H5Dclose};
    const Id space{H5Dget_space(set.id), H5Sclose};
    const auto n = static_cast<size_t>(H5Sget_simple_extent_npoints(space.id));
    const Id type{string_type(), H5Tclose};
    std::vector<char*> raw(n, nullptr);
    if (n > 0 && H5Dread(set.id, type.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) < 0) fail(name);
    std::vector<std::string> out;
    for (char* s : raw) out.emplace_back(s ? s : "");
    if (n > 0) H5Dvlen_reclaim(type.id, space.id, H5P_DEFAULT, raw.data());
    return out;
  }

  std::optional<std::string> string_attribute(const char* name) const {
    if (H5Aexists(file_, name) <= 0) return std::nullopt;
    const Id attr{H5Aopen(file_, name, H5P_DEFAULT), H5Aclose};
    const Id type{string_type(), H5Tclose};
    char* s = nullptr;
    if (H5Aread(attr.id, type.id, &s) < 0) fail(name);
    std::string out = s ? s : "";
    H5free_memory(s);
    return out;
  }

  std::optional<double> number_attribute(const char* name) const {
    if (H5Aexists(file_, name) <= 0) return std::nullopt;
    const Id attr{H5Aopen(file_, name, H5P_DEFAULT), H5Aclose};
    double x = 0.0;
    if (H5Aread(attr.id, H5T_NATIVE_DOUBLE, &x) < 0) fail(name);
    return x;
  }

 private:
  hid_t open(const std::string& name) const {
    const hid_t id = has(name) ? H5Dopen2(file_, name.c_str(), H5P_DEFAULT) : -1;
    if (id >= 0) {
      try {
        check_storage(id, name);
      } catch (...) {
        H5Dclose(id);
        throw;
      }
    }
    if (id < 0) {
      throw InvalidArgument(
          fmt::format("{} has no dataset '{}': it is not a trajectory that tumble run wrote{}", path_, name,
                      name == "position" || name == "orientation" || name == "angular_velocity"
                          ? " with the default fields (a report needs position, orientation "
                            "and angular_velocity: run again without --fields, or add them)"
                          : ""));
    }
    return id;
  }
  /// Refuses a dataset whose data is not in this file (external storage, a virtual dataset: either
  /// reads any file on this machine, and the report would embed it) or that claims more data than the
  /// file can hold (a 49 KiB file claiming 2·10⁸ samples would exhaust memory). tumble writes chunks
  /// without filters, so a dataset's data is at most the file's size; a fill value read for chunks never
  /// written is allowed a few MiB.
  void check_storage(hid_t set, const std::string& name) const {
    const Id plist{H5Dget_create_plist(set), H5Pclose};
    const bool virtual_set = H5Pget_layout(plist.id) == H5D_VIRTUAL;
    if (virtual_set || H5Pget_external_count(plist.id) > 0) {
      throw FileError(fmt::format(
          "{}: dataset '{}' keeps its data in other files (HDF5 {}): tumble reads only data inside the "
          "trajectory file; refused",
          path_, name, virtual_set ? "virtual dataset" : "external storage"));
    }
    const Id space{H5Dget_space(set), H5Sclose};
    const Id type{H5Dget_type(set), H5Tclose};
    const hssize_t points = H5Sget_simple_extent_npoints(space.id);
    const size_t element = std::max<size_t>(H5Tget_size(type.id), 1);
    constexpr std::uint64_t kFillAllowance = std::uint64_t{8} << 20;
    if (points < 0 || static_cast<double>(points) * static_cast<double>(element) >
                          static_cast<double>(file_bytes_) + static_cast<double>(kFillAllowance)) {
      throw FileError(fmt::format(
          "{}: dataset '{}' claims {} values of {} bytes, more than the file's {} bytes hold: the file is "
          "truncated or forged; refused",
          path_, name, points, element, file_bytes_));
    }
  }
  static hid_t string_type() {
    const hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    return t;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw FileError(fmt::format("reading {} from {} failed", what, path_));
  }

  std::string path_;
  hid_t file_ = -1;
  std::uintmax_t file_bytes_ = 0;  // bounds what a dataset may claim
};

/// The names, geometry and text of `scene` in `r`: a report of a file written without them.
void use_scene(const Scene& scene, Report& r) {
  r.names = row_names(scene.model);
  r.geometry = scene_geometry(scene);
  r.scene_text = scene.text;
  r.scene_path = scene.path.string();
}

/// The viewer's rules for what a file says happened when, checked here so that a damaged or edited
/// file is refused with its place (where(), built only then) rather than shown as a page that "cannot
/// be shown": a time is finite and none comes before the one before it.
template <class Where>
void check_time(double t, double previous, const Where& where) {
  if (std::isfinite(t) && t >= previous) return;
  if (!std::isfinite(t)) {
    throw InvalidArgument(fmt::format(
        "{}: t = {} is not a time: the file is damaged or was edited; run the scene again", where(), t));
  }
  if (t < previous) {
    throw InvalidArgument(
        fmt::format("{}: t = {} comes after t = {}, but times never decrease: the file is "
                    "damaged or was edited; run the scene again",
                    where(), t, previous));
  }
}

Samples read_hdf5(const std::filesystem::path& path, Report& r, const Scene* scene) {
  const Hdf5Reader h(path);
  r.tumble_version = h.string_attribute("tumble_version").value_or("");
  r.scene_text = h.string_attribute("scene").value_or("");
  r.scene_path = h.string_attribute("scene_file").value_or("");
  r.integrator = h.string_attribute("integrator").value_or("");
  r.formulation = h.string_attribute("formulation").value_or("");
  r.timestep = h.number_attribute("timestep").value_or(kNaN);
  r.duration = h.number_attribute("duration").value_or(kNaN);
  if (const auto w = h.string_attribute("warnings")) {
    std::istringstream lines(*w);
    for (std::string line; std::getline(lines, line);) r.warnings.push_back(line);
  }
  r.names = h.strings("names");
  if (scene) {
    use_scene(*scene, r);
    if (r.names != h.strings("names")) {
      throw InvalidArgument(fmt::format("the scene {} has other bodies than {}: give the scene of this run",
                                        scene->path.string(), path.string()));
    }
  }
  Samples s;
  s.t = h.doubles("t");
  const size_t T = s.t.size(), N = r.names.size();
  for (size_t k = 0; k < T; ++k)
    check_time(s.t[k], k > 0 ? s.t[k - 1] : -kInf,
               [&] { return fmt::format("{}: /t[{}]", path.string(), k); });
  const auto series = [&](const char* name, size_t width) {
    std::vector<hsize_t> shape;
    std::vector<double> v = h.doubles(name, &shape);
    if (shape != std::vector<hsize_t>{T, N, width}) {
      throw InvalidArgument(
          fmt::format("{}: dataset {} is not ({}, {}, {})", path.string(), name, T, N, width));
    }
    return v;
  };
  s.position = series("position", 3);
  s.orientation = series("orientation", 4);
  s.omega_world = series("angular_velocity", 3);
  const auto system = [&](const char* name, size_t width) {
    const std::string key = std::string("diagnostics/") + name;
    std::vector<double> v = h.has(key) ? h.doubles(key) : std::vector<double>(T * width, kNaN);
    if (v.size() != T * width)
      throw InvalidArgument(fmt::format("{}: {} has the wrong length", path.string(), key));
    return v;
  };
  s.kinetic = system("kinetic_energy", 1);
  s.potential = system("potential_energy", 1);
  s.total = system("total_energy", 1);
  s.energy_drift = system("energy_drift", 1);
  s.L = system("angular_momentum", 3);
  s.L_drift = system("angular_momentum_drift", 1);
  if (h.has("events")) {
    const auto t = h.doubles("events/t");
    const auto names = h.strings("events/event");
    const auto rows = h.doubles("events/body");
    if (names.size() != t.size() || rows.size() != t.size()) {
      throw InvalidArgument(
          fmt::format("{}: /events/t, /events/event and /events/body differ in length "
                      "({}, {}, {}): the file is damaged or was edited",
                      path.string(), t.size(), names.size(), rows.size()));
    }
    for (size_t i = 0; i < t.size(); ++i) {
      const auto where = [&] { return fmt::format("{}: /events[{}]", path.string(), i); };
      check_time(t[i], -kInf, where);
      if (!(rows[i] >= 0.0 && rows[i] < static_cast<double>(r.names.size()) &&
            rows[i] == std::floor(rows[i]))) {
        throw InvalidArgument(
            fmt::format("{}: body {} is not one of the {} in /names: the file is damaged or "
                        "was edited; run the scene again",
                        where(), rows[i], r.names.size()));
      }
      r.events.push_back({names[i], t[i], static_cast<long>(rows[i])});
    }
  }
  if (scene) return s;
  if (!h.has("geometry")) {
    throw InvalidArgument(
        fmt::format("{} has no geometry group: it was written by a tumble before reports; run "
                    "the scene again",
                    path.string()));
  }
  std::vector<hsize_t> shape;
  const auto mass = h.doubles("geometry/mass");
  const auto com = h.doubles("geometry/center_of_mass");
  const auto U = h.doubles("geometry/principal_axes");
  const auto Lambda = h.doubles("geometry/principal_moments");
  const auto vo = h.doubles("geometry/vertex_offsets");
  const auto to = h.doubles("geometry/triangle_offsets");
  const auto vertices = h.doubles("geometry/vertices");
  const auto triangles = h.uint32s("geometry/triangles");
  const size_t B = mass.size();
  if (B > N || com.size() != 3 * B || U.size() != 9 * B || Lambda.size() != 3 * B || vo.size() != B + 1 ||
      to.size() != B + 1 || vo.back() * 3 != static_cast<double>(vertices.size()) ||
      to.back() * 3 != static_cast<double>(triangles.size())) {
    throw InvalidArgument(
        fmt::format("{}: the geometry group's datasets do not fit together", path.string()));
  }
  // Offsets from a file are trusted only once they run from 0 upwards, in whole numbers, to the end.
  const auto ascending = [](const std::vector<double>& offsets) {
    if (offsets.front() != 0.0) return false;
    for (size_t k = 1; k < offsets.size(); ++k) {
      if (!(offsets[k] >= offsets[k - 1]) || offsets[k] != std::floor(offsets[k])) return false;
    }
    return true;
  };
  if (!ascending(vo) || !ascending(to)) {
    throw InvalidArgument(fmt::format(
        "{}: the geometry group's offsets are not ascending whole numbers from 0", path.string()));
  }
  for (size_t b = 0; b < B; ++b) {
    BodyGeometry& g = r.geometry.bodies.emplace_back();
    g.mass = mass[b];
    g.com = Vec3(com[3 * b], com[3 * b + 1], com[3 * b + 2]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) g.U(i, j) = U[9 * b + 3 * static_cast<size_t>(i) + static_cast<size_t>(j)];
    g.Lambda = Vec3(Lambda[3 * b], Lambda[3 * b + 1], Lambda[3 * b + 2]);
    const auto v0 = static_cast<size_t>(vo[b]), v1 = static_cast<size_t>(vo[b + 1]);
    TriangleMesh mesh;
    for (size_t v = v0; v < v1; ++v)
      mesh.vertices.emplace_back(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]);
    for (auto f = static_cast<size_t>(to[b]); f < static_cast<size_t>(to[b + 1]); ++f) {
      const std::array<std::uint32_t, 3> tri{triangles[3 * f], triangles[3 * f + 1], triangles[3 * f + 2]};
      for (std::uint32_t k : tri) {
        if (k >= v1 - v0)
          throw InvalidArgument(
              fmt::format("{}: geometry triangle {} names a missing vertex", path.string(), f));
      }
      mesh.triangles.push_back(tri);
    }
    if (!mesh.triangles.empty()) g.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  }
  std::vector<hsize_t> spring_shape;
  const auto ends = h.doubles("geometry/springs", &spring_shape);
  const auto points = h.doubles("geometry/spring_points");
  for (size_t i = 0; 2 * i + 1 < ends.size() && 6 * i + 5 < points.size(); ++i) {
    r.geometry.springs.push_back({static_cast<long>(ends[2 * i]), static_cast<long>(ends[2 * i + 1]),
                                  Vec3(points[6 * i], points[6 * i + 1], points[6 * i + 2]),
                                  Vec3(points[6 * i + 3], points[6 * i + 4], points[6 * i + 5])});
  }
  return s;
}

// ---- CSV --------------------------------------------------------------------------------------------

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  for (size_t start = 0;;) {
    const size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

double number(std::string_view s, const std::string& file, size_t line) {
  if (s.empty()) return kNaN;  // an undefined diagnostics value
  double x = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  if (ec != std::errc() || end != s.data() + s.size()) {
    throw InvalidArgument(fmt::format("{}:{}: '{}' is not a number", file, line, s.substr(0, 40)));
  }
  return x;
}

/// The lines of a CSV file and the index of each of its header's columns.
struct Csv {
  std::vector<std::string> lines;
  std::vector<std::string_view> header;
  size_t column(std::string_view name, const std::string& file) const {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    throw InvalidArgument(
        fmt::format("{} has no column {}: a report needs the fields position, orientation and "
                    "angular_velocity (the defaults): run again without --fields, or add them",
                    file, name));
  }
};

Csv read_csv(const std::filesystem::path& path) {
  Csv c;
  std::istringstream in(read_input_file(path, "trajectory"));
  for (std::string line; std::getline(in, line);) c.lines.push_back(std::move(line));
  if (c.lines.empty()) throw InvalidArgument(fmt::format("{} is empty", path.string()));
  c.header = split(c.lines.front());
  return c;
}

Samples read_csv_run(const std::filesystem::path& path, Report& r, const Scene* scene) {
  const std::string file = path.string();
  const std::filesystem::path facts = run_facts_path(path);
  if (scene) {
    use_scene(*scene, r);
  } else if (!std::filesystem::is_regular_file(facts)) {
    throw InvalidArgument(
        fmt::format("{} has no {} beside it (the run's facts and geometry, written by tumble run "
                    "since reports exist): run the scene again, or give the HDF5 file",
                    file, facts.string()));
  } else {
    try {
      io::read_run_facts(nlohmann::json::parse(read_input_file(facts, "run file")), facts.string(), r);
    } catch (const nlohmann::json::exception& e) {
      throw InvalidArgument(fmt::format("{} is not JSON: {}", facts.string(), e.what()));
    }
  }
  const Csv c = read_csv(path);
  if (c.header.size() < 2 || c.header[0] != "t" || c.header[1] != "body") {
    throw InvalidArgument(
        fmt::format("{}:1: the header does not start with t,body: not a trajectory that tumble "
                    "run wrote",
                    file));
  }
  const size_t N = r.names.size();
  if (N == 0 || (c.lines.size() - 1) % N != 0) {
    throw InvalidArgument(fmt::format("{}: {} rows are not whole samples of {} bodies and particles", file,
                                      c.lines.size() - 1, N));
  }
  const size_t px = c.column("px", file), qw = c.column("qw", file), wx = c.column("wx", file);
  Samples s;
  for (size_t line = 1; line < c.lines.size(); ++line) {
    const auto cells = split(c.lines[line]);
    if (cells.size() != c.header.size()) {
      throw InvalidArgument(fmt::format("{}:{}: {} columns where the header has {}", file, line + 1,
                                        cells.size(), c.header.size()));
    }
    const size_t row = (line - 1) % N;
    if (cells[1] != r.names[row]) {
      throw InvalidArgument(
          fmt::format("{}:{}: body '{}' where '{}' was expected", file, line + 1, cells[1], r.names[row]));
    }
    const double t = number(cells[0], file, line + 1);
    const auto where = [&] { return fmt::format("{}:{}", file, line + 1); };
    if (row == 0) {
      check_time(t, s.t.empty() ? -kInf : s.t.back(), where);
      s.t.push_back(t);
    } else if (t != s.t.back()) {
      throw InvalidArgument(
          fmt::format("{}: t = {} within the sample at t = {}: the file is damaged or was "
                      "edited; run the scene again",
                      where(), t, s.t.back()));
    }
    for (size_t k = 0; k < 3; ++k) s.position.push_back(number(cells[px + k], file, line + 1));
    for (size_t k = 0; k < 4; ++k) s.orientation.push_back(number(cells[qw + k], file, line + 1));
    for (size_t k = 0; k < 3; ++k) s.omega_world.push_back(number(cells[wx + k], file, line + 1));
  }
  const size_t T = s.t.size();
  const std::filesystem::path dpath = diagnostics_path(path);
  std::vector<double>* columns[] = {&s.kinetic, &s.potential, &s.total, &s.energy_drift, &s.L_drift};
  const char* names[] = {"kinetic_energy", "potential_energy", "total_energy", "energy_drift",
                         "angular_momentum_drift"};
  if (std::filesystem::is_regular_file(dpath)) {
    const Csv d = read_csv(dpath);
    if (d.lines.size() - 1 != T) {
      throw InvalidArgument(
          fmt::format("{} has {} samples, the trajectory {}", dpath.string(), d.lines.size() - 1, T));
    }
    size_t at[5];
    for (size_t k = 0; k < 5; ++k) at[k] = d.column(names[k], dpath.string());
    const size_t Lx = d.column("Lx", dpath.string());
    for (size_t line = 1; line < d.lines.size(); ++line) {
      const auto cells = split(d.lines[line]);
      if (cells.size() != d.header.size()) {
        throw InvalidArgument(fmt::format("{}:{}: {} columns where the header has {}", dpath.string(),
                                          line + 1, cells.size(), d.header.size()));
      }
      for (size_t k = 0; k < 5; ++k) columns[k]->push_back(number(cells[at[k]], dpath.string(), line + 1));
      for (size_t k = 0; k < 3; ++k) s.L.push_back(number(cells[Lx + k], dpath.string(), line + 1));
    }
  } else {
    for (auto* v : columns) v->assign(T, kNaN);
    s.L.assign(3 * T, kNaN);
  }
  const std::filesystem::path epath = events_path(path);
  if (std::filesystem::is_regular_file(epath)) {
    const Csv e = read_csv(epath);
    for (size_t line = 1; line < e.lines.size(); ++line) {
      const auto cells = split(e.lines[line]);
      if (cells.size() != 3)
        throw InvalidArgument(fmt::format("{}:{}: expected t,event,body", epath.string(), line + 1));
      const auto where = [&] { return fmt::format("{}:{}", epath.string(), line + 1); };
      const auto named = std::find(r.names.begin(), r.names.end(), cells[2]);
      if (named == r.names.end()) {
        throw InvalidArgument(
            fmt::format("{}: body '{}' is not in {}: the file is damaged or was edited; "
                        "run the scene again",
                        where(), cells[2], file));
      }
      const double t = number(cells[0], epath.string(), line + 1);
      check_time(t, -kInf, where);
      r.events.push_back({std::string(cells[1]), t, static_cast<long>(named - r.names.begin())});
    }
  }
  return s;
}

bool is_hdf5(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return in && std::string_view(magic, 8) == std::string_view("\x89HDF\r\n\x1a\n", 8);
}

}  // namespace

/// `tumble ensemble`'s table (a row per run) given where a trajectory belongs: said so, with the
/// trajectories a study writes.
[[noreturn]] void refuse_ensemble_table(const std::filesystem::path& path, bool hdf5) {
  std::filesystem::path run = path;
  run.replace_extension(hdf5 ? ".run-0.h5" : ".run-0.csv");
  throw InvalidArgument(fmt::format(
      "{} is the table of a tumble ensemble study (a row per run), not a trajectory: report one of its "
      "runs' trajectories, e.g. {} (written for the runs that [ensemble.outputs] trajectories chooses: "
      "every = N, worst = N)",
      path.string(), run.string()));
}

Report read_report(const std::filesystem::path& path, const Scene* scene) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw FileError(fmt::format("{} is not a file: give a trajectory that tumble run wrote (.csv or .h5)",
                                path.string()));
  }
  if (is_hdf5(path)) {
    const Hdf5Reader h(path);
    if (h.has("runs") && !h.has("t")) refuse_ensemble_table(path, true);
  } else {
    std::ifstream in(path, std::ios::binary);
    std::string first;
    std::getline(in, first);
    if (first.rfind("run,", 0) == 0) refuse_ensemble_table(path, false);
  }
  Report r;
  const Samples s = is_hdf5(path) ? read_hdf5(path, r, scene) : read_csv_run(path, r, scene);
  const size_t T = s.t.size(), N = r.names.size(), B = r.geometry.bodies.size();
  if (T == 0) throw InvalidArgument(fmt::format("{} holds no samples", path.string()));
  r.samples_total = static_cast<long>(T);
  // Every stride-th sample and the last, within the report's size budget.
  const auto limit = static_cast<size_t>(report_sample_limit(N));
  const size_t stride = T > limit ? (T + limit - 2) / (limit - 1) : 1;
  std::vector<size_t> kept;
  for (size_t k = 0; k < T; k += stride) kept.push_back(k);
  if ((T - 1) % stride != 0) kept.push_back(T - 1);
  for (const size_t k : kept) {
    r.t.push_back(s.t[k]);
    for (size_t i = 0; i < N; ++i) {
      const size_t at = k * N + i;
      const Vec3 omega_w(s.omega_world[3 * at], s.omega_world[3 * at + 1], s.omega_world[3 * at + 2]);
      const Quat q_ref(s.orientation[4 * at], s.orientation[4 * at + 1], s.orientation[4 * at + 2],
                       s.orientation[4 * at + 3]);
      for (int c = 0; c < 3; ++c) r.position.push_back(s.position[3 * at + static_cast<size_t>(c)]);
      for (int c = 0; c < 4; ++c) r.quaternion.push_back(s.orientation[4 * at + static_cast<size_t>(c)]);
      for (int c = 0; c < 3; ++c) r.omega_world.push_back(omega_w(c));
      // ^bω = Rᵀ ω = Uᵀ R_refᵀ ω (R = R_ref U); particles have none.
      const Vec3 omega_p = i < B ? Vec3(r.geometry.bodies[i].U.transpose() * (q_ref.conjugate() * omega_w))
                                 : Vec3::Zero();
      for (int c = 0; c < 3; ++c) r.omega_principal.push_back(omega_p(c));
    }
    r.kinetic_energy.push_back(s.kinetic[k]);
    r.potential_energy.push_back(s.potential[k]);
    r.total_energy.push_back(s.total[k]);
    r.energy_drift.push_back(s.energy_drift[k]);
    r.angular_momentum.insert(r.angular_momentum.end(), {s.L[3 * k], s.L[3 * k + 1], s.L[3 * k + 2]});
    r.angular_momentum_drift.push_back(s.L_drift[k]);
  }
  return r;
}

}  // namespace tumble
