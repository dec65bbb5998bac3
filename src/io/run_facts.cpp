#include "run_facts.hpp"

#include "number_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "tumble/error.hpp"

namespace tumble::io {
namespace {

using nlohmann::json;

Vec3 to_vec(const json& j) {
  return Vec3(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

/// JSON text appended to a string: numbers shortest round trip, strings escaped by nlohmann (invalid
/// UTF-8 replaced, never thrown on).
class JsonText {
 public:
  explicit JsonText(const std::function<void(std::string_view)>& write) : write_(write) {}
  std::string out;
  JsonText& raw(std::string_view s) {
    out += s;
    if (out.size() > (1u << 20)) flush();  // 10⁵ bodies' facts would be 20 MB held at once
    return *this;
  }
  void flush() {
    write_(out);
    out.clear();
  }
  JsonText& number(double x) {
    if (!std::isfinite(x)) return raw("null");  // JSON has no NaN (nlohmann wrote null too)
    return raw(NumberText(x));
  }
  JsonText& integer(long x) {
    char buffer[24];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
    out.append(buffer, end);
    return *this;
  }
  /// A JSON string, escaped a line at a time: ASCII here (the scene's text is 48 MB for 10⁵ bodies,
  /// which a json value would copy twice), a line with another control character or a byte above
  /// ASCII by nlohmann, which also replaces invalid UTF-8.
  JsonText& text(std::string_view s) {
    const auto plain = [](char c) {
      const auto u = static_cast<unsigned char>(c);
      return u >= 0x20 && u < 0x80 && c != '"' && c != '\\';
    };
    raw("\"");
    for (size_t i = 0; i < s.size();) {
      size_t j = i;
      while (j < s.size() && plain(s[j])) ++j;
      raw(s.substr(i, j - i));
      if (j == s.size()) break;
      const char c = s[j];
      const char* escape = c == '"'    ? "\\\""
                           : c == '\\' ? "\\\\"
                           : c == '\n' ? "\\n"
                           : c == '\r' ? "\\r"
                           : c == '\t' ? "\\t"
                                       : nullptr;
      if (escape) {
        raw(escape);
        i = j + 1;
        continue;
      }
      const size_t end = std::min(s.find('\n', j), s.size());  // '\n' is never inside a UTF-8 sequence
      const std::string quoted =
          json(s.substr(j, end - j)).dump(-1, ' ', false, json::error_handler_t::replace);
      raw(std::string_view(quoted).substr(1, quoted.size() - 2));
      i = end;
    }
    return raw("\"");
  }
  JsonText& vec(const Vec3& v) {
    raw("[").number(v.x()).raw(",").number(v.y()).raw(",").number(v.z());
    return raw("]");
  }
  JsonText& texts(const std::vector<std::string>& list) {
    raw("[");
    for (size_t i = 0; i < list.size(); ++i) (i ? raw(",") : *this).text(list[i]);
    return raw("]");
  }
  JsonText& key(std::string_view k) { return raw("\"").raw(k).raw("\":"); }

 private:
  const std::function<void(std::string_view)>& write_;
};

/// The bodies' geometries with the equal ones (mass properties and mesh, bit for bit) once: `kinds`
/// holds each distinct one, the result the kind of each body. Found by a hash of their bytes, then
/// compared.
std::vector<size_t> distinct_kinds(const std::vector<BodyGeometry>& bodies,
                                   std::vector<const BodyGeometry*>& kinds) {
  const auto same = [](const BodyGeometry& a, const BodyGeometry& b) {
    return a.mass == b.mass && a.com == b.com && a.U == b.U && a.Lambda == b.Lambda &&
           (a.mesh == b.mesh ||
            (a.surface().vertices == b.surface().vertices && a.surface().triangles == b.surface().triangles));
  };
  // A hash of each body's mass properties and mesh size (std::hash of the bytes), sorted: bodies with
  // the same hash are neighbours, compared in full (vertices and triangles too). A sort of 10⁵ pairs
  // touches memory in order, where a hash table of them missed the cache at every insertion.
  const size_t n = bodies.size();
  std::vector<std::pair<std::uint64_t, size_t>> order(n);
  for (size_t i = 0; i < n; ++i) {
    const BodyGeometry& g = bodies[i];
    std::array<double, 18> key{g.mass, static_cast<double>(g.surface().vertices.size()),
                               static_cast<double>(g.surface().triangles.size())};
    std::copy_n(g.com.data(), 3, key.begin() + 3);
    std::copy_n(g.U.data(), 9, key.begin() + 6);
    std::copy_n(g.Lambda.data(), 3, key.begin() + 15);
    order[i] = {std::hash<std::string_view>{}(
                    std::string_view(reinterpret_cast<const char*>(key.data()), sizeof key)),
                i};
  }
  std::sort(order.begin(), order.end());
  // The first body equal to each (within its hash's run, which is in body order).
  std::vector<size_t> first(n);
  for (size_t a = 0, b = 0; a < n; a = b) {
    while (b < n && order[b].first == order[a].first) ++b;
    for (size_t k = a; k < b; ++k) {
      const size_t i = order[k].second;
      first[i] = i;
      for (size_t m = a; m < k; ++m) {
        const size_t j = order[m].second;
        if (first[j] == j && same(bodies[j], bodies[i])) {
          first[i] = j;
          break;
        }
      }
    }
  }
  // Kinds numbered in the order of their first body.
  std::vector<size_t> kind(n);
  for (size_t i = 0; i < n; ++i) {
    if (first[i] == i) {
      kind[i] = kinds.size();
      kinds.push_back(&bodies[i]);
    } else {
      kind[i] = kind[first[i]];
    }
  }
  return kind;
}

}  // namespace

void run_facts_head(const TrajectoryInfo& info, const std::vector<std::string>& names,
                    const std::function<void(std::string_view)>& write) {
  static const SceneGeometry none;
  const SceneGeometry& g = info.geometry ? *info.geometry : none;
  std::vector<const BodyGeometry*> kinds;
  const std::vector<size_t> kind_of = distinct_kinds(g.bodies, kinds);
  JsonText j(write);
  j.raw("{\n").key("format").text("tumble-run").raw(",\n").key("version").integer(2).raw(",\n");
  j.key("tumble_version").text(info.tumble_version).raw(",\n").key("scene_file").text(info.scene_path);
  j.raw(",\n").key("scene").text(info.scene_text).raw(",\n");
  j.key("integrator").text(info.settings.integrator).raw(",\n");
  j.key("formulation").text(formulation_name(info.settings.formulation)).raw(",\n");
  j.key("timestep").number(info.settings.timestep).raw(",\n").key("duration").number(info.settings.duration);
  j.raw(",\n").key("output_interval").number(info.settings.output_interval).raw(",\n");
  j.key("names").texts(names).raw(",\n");
  j.key("kinds").raw("[");
  for (size_t k = 0; k < kinds.size(); ++k) {
    const BodyGeometry& b = *kinds[k];
    j.raw(k ? ",\n" : "\n").raw("{").key("mass").number(b.mass).raw(",").key("center_of_mass").vec(b.com);
    j.raw(",").key("principal_axes").raw("[");
    for (int r = 0; r < 3; ++r) (r ? j.raw(",") : j).vec(b.U.row(r).transpose());
    j.raw("],").key("principal_moments").vec(b.Lambda).raw(",").key("vertices").raw("[");
    const TriangleMesh& mesh = b.surface();
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
      const Vec3& x = mesh.vertices[v];
      (v ? j.raw(",") : j).number(x.x()).raw(",").number(x.y()).raw(",").number(x.z());
    }
    j.raw("],").key("triangles").raw("[");
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      (t ? j.raw(",") : j).integer(tri[0]).raw(",").integer(tri[1]).raw(",").integer(tri[2]);
    }
    j.raw("]}");
  }
  // The kind of each body, run-length coded: [kind, count] for consecutive bodies of one kind.
  j.raw("],\n").key("body_kinds").raw("[");
  for (size_t i = 0, runs = 0; i < kind_of.size(); ++runs) {
    size_t n = 1;
    while (i + n < kind_of.size() && kind_of[i + n] == kind_of[i]) ++n;
    (runs ? j.raw(",") : j)
        .raw("[")
        .integer(static_cast<long>(kind_of[i]))
        .raw(",")
        .integer(static_cast<long>(n))
        .raw("]");
    i += n;
  }
  j.raw("],\n").key("springs").raw("[");
  for (size_t k = 0; k < g.springs.size(); ++k) {
    const SpringGeometry& s = g.springs[k];
    (k ? j.raw(",\n") : j.raw("\n")).raw("{").key("a").integer(s.a).raw(",").key("b").integer(s.b);
    j.raw(",").key("point_a").vec(s.point_a).raw(",").key("point_b").vec(s.point_b).raw("}");
  }
  j.raw("],\n");
  j.flush();
}

void run_facts_tail(const std::vector<std::string>& warnings,
                    const std::function<void(std::string_view)>& write) {
  JsonText j(write);
  j.key("warnings").texts(warnings).raw("\n}\n");
  j.flush();
}

namespace {

/// A mesh from its arrays in a run file: triples, every index a vertex.
TriangleMesh read_mesh(const json& vertices, const json& triangles) {
  const auto v = vertices.get<std::vector<double>>();
  const auto t = triangles.get<std::vector<std::uint32_t>>();
  if (v.size() % 3 != 0 || t.size() % 3 != 0) throw InvalidArgument("a mesh's arrays are not triples");
  TriangleMesh m;
  for (size_t i = 0; i < v.size(); i += 3) m.vertices.emplace_back(v[i], v[i + 1], v[i + 2]);
  for (size_t i = 0; i < t.size(); i += 3) {
    for (size_t k = 0; k < 3; ++k) {
      if (t[i + k] >= m.vertices.size()) throw InvalidArgument("a triangle names a vertex that is not there");
    }
    m.triangles.push_back({t[i], t[i + 1], t[i + 2]});
  }
  return m;
}

}  // namespace

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
    const long version = j.at("version").get<long>();
    if (version != 1 && version != 2)
      throw InvalidArgument(fmt::format("format version {} is unknown", version));
    const auto read_body = [](const json& b, BodyGeometry& g) {
      g.mass = b.at("mass").get<double>();
      g.com = to_vec(b.at("center_of_mass"));
      for (int row = 0; row < 3; ++row) g.U.row(row) = to_vec(b.at("principal_axes").at(row)).transpose();
      g.Lambda = to_vec(b.at("principal_moments"));
      TriangleMesh mesh = read_mesh(b.at("vertices"), b.at("triangles"));
      if (!mesh.triangles.empty()) g.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
    };
    if (version == 1) {  // each body with its own geometry
      for (const json& b : j.at("bodies")) read_body(b, r.geometry.bodies.emplace_back());
    } else {  // the distinct kinds, and each body's kind run-length coded
      std::vector<BodyGeometry> kinds;
      for (const json& b : j.at("kinds")) read_body(b, kinds.emplace_back());
      for (const json& run : j.at("body_kinds")) {
        const auto k = run.at(0).get<size_t>(), n = run.at(1).get<size_t>();
        if (k >= kinds.size()) throw InvalidArgument("a body names a kind that is not there");
        if (n > r.names.size() - r.geometry.bodies.size()) throw InvalidArgument("more bodies than names");
        r.geometry.bodies.insert(r.geometry.bodies.end(), n, kinds[k]);
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
