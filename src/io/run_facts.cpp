#include "run_facts.hpp"

#include <fmt/format.h>

#include "tumble/error.hpp"

namespace tumble::io {
namespace {

using nlohmann::json;

json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

Vec3 to_vec(const json& j) {
  return Vec3(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

}  // namespace

json run_facts(const TrajectoryInfo& info, const std::vector<std::string>& names,
               const std::vector<std::string>& warnings) {
  json bodies = json::array();
  if (info.geometry) {
    for (const BodyGeometry& g : info.geometry->bodies) {
      json vertices = json::array(), triangles = json::array();
      for (const Vec3& v : g.mesh.vertices) vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
      for (const auto& t : g.mesh.triangles) triangles.insert(triangles.end(), {t[0], t[1], t[2]});
      json U = json::array();
      for (int r = 0; r < 3; ++r) U.push_back(json::array({g.U(r, 0), g.U(r, 1), g.U(r, 2)}));
      bodies.push_back({{"mass", g.mass},
                        {"center_of_mass", vec(g.com)},
                        {"principal_axes", U},
                        {"principal_moments", vec(g.Lambda)},
                        {"vertices", vertices},
                        {"triangles", triangles}});
    }
  }
  json springs = json::array();
  if (info.geometry) {
    for (const SpringGeometry& s : info.geometry->springs) {
      springs.push_back({{"a", s.a}, {"b", s.b}, {"point_a", vec(s.point_a)}, {"point_b", vec(s.point_b)}});
    }
  }
  return {{"format", "tumble-run"},
          {"version", 1},
          {"tumble_version", info.tumble_version},
          {"scene_file", info.scene_path},
          {"scene", info.scene_text},
          {"integrator", info.settings.integrator},
          {"formulation", formulation_name(info.settings.formulation)},
          {"timestep", info.settings.timestep},
          {"duration", info.settings.duration},
          {"output_interval", info.settings.output_interval},
          {"warnings", warnings},
          {"names", names},
          {"bodies", bodies},
          {"springs", springs}};
}

void read_run_facts(const json& j, const std::string& file, Report& r) {
  try {
    if (j.at("format") != "tumble-run") throw InvalidArgument("not a tumble run file");
    r.tumble_version = j.at("tumble_version").get<std::string>();
    r.scene_path = j.at("scene_file").get<std::string>();
    r.scene_text = j.at("scene").get<std::string>();
    r.integrator = j.at("integrator").get<std::string>();
    r.formulation = j.at("formulation").get<std::string>();
    r.timestep = j.at("timestep").get<double>();
    r.duration = j.at("duration").get<double>();
    r.warnings = j.at("warnings").get<std::vector<std::string>>();
    r.names = j.at("names").get<std::vector<std::string>>();
    r.geometry = {};
    for (const json& b : j.at("bodies")) {
      BodyGeometry& g = r.geometry.bodies.emplace_back();
      g.mass = b.at("mass").get<double>();
      g.com = to_vec(b.at("center_of_mass"));
      for (int row = 0; row < 3; ++row) g.U.row(row) = to_vec(b.at("principal_axes").at(row)).transpose();
      g.Lambda = to_vec(b.at("principal_moments"));
      const auto v = b.at("vertices").get<std::vector<double>>();
      const auto t = b.at("triangles").get<std::vector<std::uint32_t>>();
      if (v.size() % 3 != 0 || t.size() % 3 != 0) throw InvalidArgument("a mesh's arrays are not triples");
      for (size_t i = 0; i < v.size(); i += 3) g.mesh.vertices.emplace_back(v[i], v[i + 1], v[i + 2]);
      for (size_t i = 0; i < t.size(); i += 3) {
        for (size_t k = 0; k < 3; ++k) {
          if (t[i + k] >= g.mesh.vertices.size())
            throw InvalidArgument("a triangle names a vertex that is not there");
        }
        g.mesh.triangles.push_back({t[i], t[i + 1], t[i + 2]});
      }
    }
    for (const json& s : j.at("springs")) {
      r.geometry.springs.push_back(
          {s.at("a").get<long>(), s.at("b").get<long>(), to_vec(s.at("point_a")), to_vec(s.at("point_b"))});
    }
    if (r.geometry.bodies.size() > r.names.size()) throw InvalidArgument("more bodies than names");
  } catch (const json::exception& e) {
    throw InvalidArgument(
        fmt::format("{} is not a run file that tumble run wrote ({}); run again", file, e.what()));
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(
        fmt::format("{} is not a run file that tumble run wrote ({}); run again", file, e.what()));
  }
}

}  // namespace tumble::io
