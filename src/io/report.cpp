// Reports: the samples a report keeps, and the report as one HTML file (the viewer page with the run's
// JSON in it). The JSON follows viewer/README.md ("Data contract"): arrays as {dtype, shape, base64} of
// little-endian bytes, per-body series in float32 (display precision, a quarter of the text size),
// times and system quantities in float64 (drifts of 1e-12 must survive).
#include "tumble/io/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "staged_file.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_decimate.hpp"
#include "tumble/mass/shapes.hpp"
#include "tumble/mass/tessellate.hpp"
#include "tumble/sim/output_fields.hpp"

#include <fstream>
#include <map>

namespace tumble {
namespace {

using nlohmann::json;

static_assert(std::endian::native == std::endian::little, "the report's arrays are little-endian bytes");

/// Base64 (RFC 4648) of raw bytes. Written here because none of the project's libraries offers it
/// publicly (Boost's encoder is an internal detail of Beast); it is the 20 lines below.
std::string base64(const void* data, size_t size) {
  static constexpr char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const unsigned v = (p[i] << 16) | (p[i + 1] << 8) | p[i + 2];
    for (int k = 18; k >= 0; k -= 6) out += digits[(v >> k) & 63];
  }
  if (const size_t rest = size - i; rest > 0) {
    const unsigned v = (p[i] << 16) | (rest == 2 ? p[i + 1] << 8 : 0);
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += rest == 2 ? digits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

json array_f64(const std::vector<double>& v, std::vector<size_t> shape) {
  return {{"dtype", "f64"}, {"shape", shape}, {"base64", base64(v.data(), v.size() * sizeof(double))}};
}

json array_f32(const std::vector<double>& v, std::vector<size_t> shape) {
  std::vector<float> f(v.begin(), v.end());
  return {{"dtype", "f32"}, {"shape", shape}, {"base64", base64(f.data(), f.size() * sizeof(float))}};
}

/// A surface as the report's {positions, indices}.
json mesh_json(const TriangleMesh& mesh) {
  std::vector<float> positions;
  positions.reserve(mesh.vertices.size() * 3);
  for (const Vec3& v : mesh.vertices)
    positions.insert(positions.end(), {float(v.x()), float(v.y()), float(v.z())});
  std::vector<std::uint32_t> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
  return {{"positions",
           {{"dtype", "f32"},
            {"shape", {mesh.vertices.size() * 3}},
            {"base64", base64(positions.data(), positions.size() * sizeof(float))}}},
          {"indices",
           {{"dtype", "u32"},
            {"shape", {indices.size()}},
            {"base64", base64(indices.data(), indices.size() * sizeof(std::uint32_t))}}}};
}

/// The report's meshes, each surface once: bodies of one mesh file share it, and every body drawn as
/// the box of its principal moments shares the unit cube (scaled by its "box" edges). 10⁵ bodies of
/// one shape were 10⁵ copies, 70 MB of the page.
class MeshTable {
 public:
  /// The index of g's surface (its display mesh, or the unit cube when it has none).
  std::size_t index_of(const BodyGeometry& g) {
    const TriangleMesh* key = g.mesh && !g.mesh->triangles.empty() ? g.mesh.get() : nullptr;
    const auto [at, added] = index_.try_emplace(key, meshes_.size());
    if (added) meshes_.push_back(key ? mesh_json(*key) : mesh_json(tessellate(Box{Vec3::Ones()}, 4)));
    return at->second;
  }
  json take() && { return std::move(meshes_); }

 private:
  std::map<const TriangleMesh*, std::size_t> index_;
  json meshes_ = json::array();
};

double bounding_radius(const BodyGeometry& g) {
  double r = 0.0;
  for (const Vec3& v : g.surface().vertices) r = std::max(r, (v - g.com).norm());
  if (r > 0) return r;
  // No mesh: the half diagonal of its inertia box.
  const Vec3 L = g.Lambda;
  return std::sqrt(
      std::max(0.0, 6.0 * (L.sum()) / std::max(g.mass, std::numeric_limits<double>::min()) / 4.0));
}

json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

json to_json(const Report& r) {
  const size_t T = r.t.size(), N = r.names.size(), B = r.geometry.bodies.size();
  MeshTable meshes;
  json bodies = json::array();
  for (size_t i = 0; i < N; ++i) {
    json b{{"name", r.names[i]}, {"kind", i < B ? "body" : "particle"}};
    if (i < B) {
      const BodyGeometry& g = r.geometry.bodies[i];
      b["mesh"] = meshes.index_of(g);
      // No surface: the unit cube, scaled by the inertia box's edges along the principal axes at the
      // centre of mass.
      if (!g.mesh || g.mesh->triangles.empty()) b["box"] = vec(inertia_box_edges(g.mass, g.Lambda));
      b["com"] = vec(g.com);
      json U = json::array();
      for (int row = 0; row < 3; ++row) U.push_back(json::array({g.U(row, 0), g.U(row, 1), g.U(row, 2)}));
      b["principal_axes"] = U;
      b["principal_moments"] = vec(g.Lambda);
      b["size"] = bounding_radius(g);
    } else {
      b["mesh"] = nullptr;
      b["com"] = vec(Vec3::Zero());
      b["principal_axes"] =
          json::array({json::array({1, 0, 0}), json::array({0, 1, 0}), json::array({0, 0, 1})});
      b["principal_moments"] = vec(Vec3::Zero());
      b["size"] = 0.0;
    }
    bodies.push_back(std::move(b));
  }
  json springs = json::array();
  for (const SpringGeometry& s : r.geometry.springs) {
    springs.push_back({{"a", s.a < 0 ? json(nullptr) : json(s.a)},
                       {"b", s.b < 0 ? json(nullptr) : json(s.b)},
                       {"point_a", vec(s.point_a)},
                       {"point_b", vec(s.point_b)}});
  }
  json events = json::array();
  for (const ReportEvent& e : r.events) {
    events.push_back({{"name", e.name}, {"t", e.t}, {"body", e.row < 0 ? json(nullptr) : json(e.row)}});
  }
  json meta{{"tumble_version", r.tumble_version},
            {"scene_path", r.scene_path},
            {"scene_text", r.scene_text},
            {"integrator", r.integrator},
            {"formulation", r.formulation},
            {"timestep", r.timestep},
            {"duration", r.duration},
            {"wall_time_s", r.wall_time_s ? json(*r.wall_time_s) : json(nullptr)},
            {"samples_total", r.samples_total},
            {"samples_shown", T},
            {"warnings", r.warnings}};
  return {{"format", "tumble-report"},
          {"version", 1},
          {"meta", meta},
          {"t", array_f64(r.t, {T})},
          {"meshes", std::move(meshes).take()},
          {"bodies", bodies},
          {"springs", springs},
          {"series",
           {{"position", array_f32(r.position, {T, N, 3})},
            {"quaternion", array_f32(r.quaternion, {T, N, 4})},
            {"omega_world", array_f32(r.omega_world, {T, N, 3})},
            {"omega_principal", array_f32(r.omega_principal, {T, N, 3})}}},
          {"system",
           {{"kinetic_energy", array_f64(r.kinetic_energy, {T})},
            {"potential_energy", array_f64(r.potential_energy, {T})},
            {"total_energy", array_f64(r.total_energy, {T})},
            {"energy_drift", array_f64(r.energy_drift, {T})},
            {"angular_momentum", array_f64(r.angular_momentum, {T, 3})},
            {"angular_momentum_drift", array_f64(r.angular_momentum_drift, {T})}}},
          {"events", events}};
}

const BodyField& field(std::string_view name) { return *body_fields({std::string(name)}).front(); }

}  // namespace

long report_sample_limit(std::size_t rows, double budget_bytes) {
  // Per sample: 13 float32 per row, t and 9 system float64; base64 makes 4 characters of 3 bytes.
  const double bytes = (static_cast<double>(rows) * 13 * 4 + 10 * 8) * 4.0 / 3.0;
  return std::max(2L, static_cast<long>(budget_bytes / bytes));
}

void add_report_sample(Report& r, const Model& model, const SystemState& state, const DriftSample& d) {
  static const BodyField& position = field("position");
  static const BodyField& orientation = field("orientation");
  static const BodyField& omega_world = field("angular_velocity");
  static const BodyField& omega_principal = field("angular_velocity_principal");
  r.t.push_back(state.t);
  const size_t rows = model.bodies.size() + model.particles.size();
  double x[4];
  for (size_t i = 0; i < rows; ++i) {
    field_of_row(position, model, state, i, x);
    r.position.insert(r.position.end(), x, x + 3);
    field_of_row(orientation, model, state, i, x);
    r.quaternion.insert(r.quaternion.end(), x, x + 4);
    field_of_row(omega_world, model, state, i, x);
    r.omega_world.insert(r.omega_world.end(), x, x + 3);
    field_of_row(omega_principal, model, state, i, x);
    r.omega_principal.insert(r.omega_principal.end(), x, x + 3);
  }
  // The system quantities as the diagnostics files have them (the same table), NaN where undefined.
  const auto put = [&d](std::string_view name, std::vector<double>& out) {
    for (const SystemField& f : system_fields()) {
      if (f.name != name) continue;
      double v[3];
      const bool defined = f.of_sample(d, v);
      for (int k = 0; k < f.width; ++k)
        out.push_back(defined ? v[k] : std::numeric_limits<double>::quiet_NaN());
      return;
    }
    throw Error(fmt::format("no diagnostics field {}", name));
  };
  put("kinetic_energy", r.kinetic_energy);
  put("potential_energy", r.potential_energy);
  put("total_energy", r.total_energy);
  put("energy_drift", r.energy_drift);
  put("angular_momentum", r.angular_momentum);
  put("angular_momentum_drift", r.angular_momentum_drift);
}

ReportRecorder::ReportRecorder(Report& report, double planned_samples) : report_(&report) {
  const double limit = static_cast<double>(report_sample_limit(report.names.size()));
  stride_ = planned_samples > limit ? static_cast<long>(std::ceil(planned_samples / (limit - 1))) : 1;
}

void ReportRecorder::sample(const Model& model, const SystemState& state, const DriftSample& d) {
  ++report_->samples_total;
  if (seen_++ % stride_ == 0) {
    add_report_sample(*report_, model, state, d);
    last_.reset();
  } else {
    last_.emplace(state, d);
  }
}

void ReportRecorder::finish(const Model& model) {
  if (last_) add_report_sample(*report_, model, last_->first, last_->second);
  last_.reset();
}

std::string report_html(const Report& report) {
  const std::string_view page = report_template();
  if (page.empty()) {
    throw InvalidArgument(
        "this tumble was built without the report viewer (node and npm were not found when it was built): "
        "install them (scripts/install-deps.sh) and build again");
  }
  constexpr std::string_view placeholder = "__TUMBLE_DATA__";
  const size_t at = page.find(placeholder);
  if (at == std::string_view::npos) throw Error("the embedded report page has no data placeholder");
  // The JSON sits in a <script> element, where "</script" would end it early and "<!--" can make the
  // browser misplace its end: every '<' is written \u003c, the same string to JSON ('<' occurs only
  // inside strings). NaN and infinities are null, which the viewer reads as NaN.
  const std::string data = to_json(report).dump(-1, ' ', false, json::error_handler_t::replace);
  std::string escaped;
  escaped.reserve(data.size());
  for (const char c : data) {
    if (c == '<') {
      escaped += "\\u003c";
    } else {
      escaped += c;
    }
  }
  std::string html;
  html.reserve(page.size() + escaped.size());
  html.append(page.substr(0, at)).append(escaped).append(page.substr(at + placeholder.size()));
  return html;
}

void write_report(const std::filesystem::path& path, const Report& report) {
  const std::string html = report_html(report);
  io::StagedFile staged(path);
  if (staged.kind() == io::OutputKind::standard_output) {
    if (std::fwrite(html.data(), 1, html.size(), stdout) != html.size() || std::fflush(stdout) != 0) {
      throw FileError(fmt::format("writing the report to standard output failed: {}", std::strerror(errno)));
    }
    return;
  }
  {
    std::ofstream out(staged.temporary(), std::ios::binary);
    out.write(html.data(), static_cast<std::streamsize>(html.size()));
    out.close();
    if (!out) {
      staged.abandon();
      throw FileError(fmt::format("writing the report {} failed: {}; nothing was kept under that name",
                                  path.string(), std::strerror(errno)));
    }
  }
  staged.commit();
}

std::filesystem::path run_facts_path(const std::filesystem::path& trajectory) {
  std::filesystem::path p = trajectory;
  p.replace_extension(".run.json");
  return p;
}

}  // namespace tumble
