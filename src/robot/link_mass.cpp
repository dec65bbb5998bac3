#include "link_mass.hpp"

#include <array>
#include <atomic>
#include <cstdlib>
#include <set>
#include <system_error>
#include <thread>

#include <fmt/format.h>

#include "tumble/error.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/winding_number.hpp"

namespace tumble::robot {

namespace fs = std::filesystem;

namespace {

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

/// The directories of a colon-separated environment variable.
std::vector<fs::path> env_paths(const char* name) {
  std::vector<fs::path> out;
  const char* v = std::getenv(name);
  if (!v) return out;
  std::string s = v;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = std::min(s.find(':', start), s.size());
    if (end > start) out.emplace_back(s.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

/// PKG/rest of a package:// or model:// URI in the directories given, then those of the environment.
fs::path find_in_packages(const std::string& package, const std::string& rest,
                          const std::vector<fs::path>& given, bool model_uri, std::vector<fs::path>& tried) {
  std::vector<fs::path> dirs = given;
  static constexpr std::array<const char*, 4> kModelVariables{"GZ_SIM_RESOURCE_PATH", "GAZEBO_MODEL_PATH",
                                                              "IGN_GAZEBO_RESOURCE_PATH", "ROS_PACKAGE_PATH"};
  for (std::size_t k = model_uri ? 0 : 3; k < kModelVariables.size(); ++k) {
    for (fs::path& d : env_paths(kModelVariables[k])) dirs.push_back(std::move(d));
  }
  for (const fs::path& d : dirs) {
    for (const fs::path& candidate : {d / package / rest, d.filename() == package ? d / rest : fs::path()}) {
      if (candidate.empty()) continue;
      tried.push_back(candidate);
      if (is_file(candidate)) return candidate;
    }
  }
  for (const fs::path& prefix : env_paths("AMENT_PREFIX_PATH")) {
    const fs::path candidate = prefix / "share" / package / rest;
    tried.push_back(candidate);
    if (is_file(candidate)) return candidate;
  }
  return {};
}

}  // namespace

fs::path resolve_mesh(const Geometry& g, const fs::path& model_dir,
                      const std::vector<fs::path>& package_paths, std::string& why) {
  if (!g.mesh_path.empty()) {
    if (is_file(g.mesh_path)) return g.mesh_path;
    why = fmt::format("{} does not exist (or is not a regular file)", g.mesh_path.string());
    return {};
  }
  const std::string& uri = g.mesh_uri;
  for (const char* scheme : {"package://", "model://"}) {
    const std::size_t n = std::char_traits<char>::length(scheme);
    if (uri.compare(0, n, scheme) != 0) continue;
    const std::string tail = uri.substr(n);
    const std::size_t slash = tail.find('/');
    if (slash == std::string::npos || slash == 0) {
      why = fmt::format("\"{}\" names no file inside a package ({}PKG/path/to/mesh)", uri, scheme);
      return {};
    }
    std::vector<fs::path> tried;
    const bool model_uri = scheme[0] == 'm';
    fs::path found =
        find_in_packages(tail.substr(0, slash), tail.substr(slash + 1), package_paths, model_uri, tried);
    if (!found.empty()) return found;
    why = tried.empty()
              ? fmt::format(
                    "package '{}' of \"{}\" is nowhere to look: give the directory that holds "
                    "it with --package-path (or set {})",
                    tail.substr(0, slash), uri, model_uri ? "GZ_SIM_RESOURCE_PATH" : "ROS_PACKAGE_PATH")
              : fmt::format(
                    "\"{}\" is not in the package paths (tried {}{}): give the directory that "
                    "holds package '{}' with --package-path",
                    uri, tried.front().string(), tried.size() > 1 ? ", ..." : "", tail.substr(0, slash));
    return {};
  }
  if (uri.find("://") != std::string::npos && uri.compare(0, 7, "file://") != 0) {
    why = fmt::format("\"{}\": tumble reads files, package:// and model:// URIs only", uri);
    return {};
  }
  fs::path p = uri.compare(0, 7, "file://") == 0 ? fs::path(uri.substr(7)) : fs::path(uri);
  if (p.is_relative()) p = model_dir / p;
  if (is_file(p)) return p;
  why = fmt::format("{} does not exist (or is not a regular file)", p.string());
  return {};
}

MeshLibrary::Key MeshLibrary::key_of(const fs::path& file, const Vec3& scale) {
  return {file.string(), std::array<double, 3>{scale.x(), scale.y(), scale.z()}};
}

const MeshLibrary::Entry& MeshLibrary::get(const fs::path& file, const Vec3& scale) {
  const Key key = key_of(file, scale);
  {
    const std::lock_guard<std::mutex> guard(lock_);
    if (const auto it = solids_.find(key); it != solids_.end()) return it->second;
  }
  Entry entry = load(file, scale);  // not preloaded: read here, the lock free meanwhile
  const std::lock_guard<std::mutex> guard(lock_);
  return solids_.try_emplace(key, std::move(entry)).first->second;  // a map's elements never move
}

void for_each_index(std::size_t n, unsigned threads, const std::function<void(std::size_t)>& f) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr failed;
  std::mutex failure;
  const auto work = [&] {
    for (std::size_t i = next++; i < n; i = next++) {
      try {
        f(i);
      } catch (...) {
        const std::lock_guard<std::mutex> guard(failure);
        if (!failed) failed = std::current_exception();
      }
    }
  };
  const unsigned wanted = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  const auto count = static_cast<unsigned>(std::min<std::size_t>(wanted, n));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < count; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failed) std::rethrow_exception(failed);
}

void MeshLibrary::preload(const std::vector<std::pair<fs::path, Vec3>>& meshes, unsigned threads) {
  std::vector<std::pair<fs::path, Vec3>> todo;
  std::set<Key> seen;
  for (const auto& [file, scale] : meshes) {
    const Key key = key_of(file, scale);
    if (!solids_.count(key) && seen.insert(key).second) todo.emplace_back(file, scale);
  }
  std::vector<Entry> loaded(todo.size());
  for_each_index(todo.size(), threads,
                 [&](std::size_t i) { loaded[i] = load(todo[i].first, todo[i].second); });
  for (std::size_t i = 0; i < todo.size(); ++i)
    solids_[key_of(todo[i].first, todo[i].second)] = std::move(loaded[i]);
}

MeshLibrary::Entry MeshLibrary::load(const fs::path& file, const Vec3& scale) {
  Entry entry;
  try {
    LoadedMesh loaded = load_mesh(file);
    MeshSolid solid;
    solid.mesh = std::move(loaded.mesh);
    for (Vec3& v : solid.mesh.vertices) v = v.cwiseProduct(scale);
    MeshMassResult r = solid_unit_properties(solid.mesh, file.filename().string());
    solid.unit = r.properties;
    solid.notes = std::move(loaded.warnings);
    for (std::string& w : r.warnings) solid.notes.push_back(std::move(w));
    entry.first = std::move(solid);
  } catch (const Error& e) {  // unreadable, open, non-manifold: the mesh's own report
    entry.second = e.what();
  } catch (const std::bad_alloc&) {
    entry.second = "not enough memory to read and integrate it";
  }
  return entry;
}

bool contains(const Shape& shape, const Vec3& x, double tolerance) {
  struct Inside {
    const Vec3& p;
    double t;
    bool operator()(const Box& b) const { return (p.cwiseAbs() - b.size / 2).maxCoeff() <= t; }
    bool operator()(const Sphere& s) const { return p.norm() <= s.radius + t; }
    bool operator()(const Ellipsoid& e) const {
      return p.cwiseQuotient(e.semi_axes).norm() <= 1 + t / e.semi_axes.minCoeff();
    }
    bool operator()(const Cylinder& c) const {
      return p.head<2>().norm() <= c.radius + t && std::abs(p.z()) <= c.length / 2 + t;
    }
    bool operator()(const Capsule& c) const {
      const double z = std::clamp(p.z(), -c.length / 2, c.length / 2);
      return (p - Vec3(0, 0, z)).norm() <= c.radius + t;
    }
    bool operator()(const Cone& c) const {
      return p.z() >= -t && p.z() <= c.height + t &&
             p.head<2>().norm() <= c.radius * (1 - p.z() / c.height) + t;
    }
    bool operator()(const Torus& r) const {
      return std::hypot(p.head<2>().norm() - r.major_radius, p.z()) <= r.minor_radius + t;
    }
  };
  return std::visit(Inside{x, tolerance}, shape);
}

bool LinkSolids::contains(const Vec3& x, double tolerance) const {
  for (const Solid& s : solids) {
    const Vec3 local = s.pose.R.transpose() * (x - s.pose.p);
    if (s.shape ? robot::contains(*s.shape, local, tolerance) : winding_number(*s.mesh, local) > 0.5)
      return true;
  }
  return false;
}

namespace {

/// The point of conv(W) nearest to the origin (W: 1 to 4 points), and the points of W it needs: every
/// face of the simplex tried (15 at most), its affine projection kept where its weights are ≥ 0.
Vec3 nearest_in_simplex(std::vector<Vec3>& W) {
  const int n = static_cast<int>(W.size());
  double best = std::numeric_limits<double>::infinity();
  Vec3 nearest = W[0];
  int best_subset = 1;
  for (int subset = 1; subset < (1 << n); ++subset) {
    std::vector<Vec3> s;
    for (int i = 0; i < n; ++i)
      if (subset & (1 << i)) s.push_back(W[static_cast<std::size_t>(i)]);
    // Minimise |s0 + Σ μ_k (s_k − s0)| over μ: the normal equations of the edges from s0.
    const int k = static_cast<int>(s.size()) - 1;
    Eigen::VectorXd lambda(k + 1);
    if (k == 0) {
      lambda << 1.0;
    } else {
      Eigen::MatrixXd E(3, k);
      for (int j = 0; j < k; ++j) E.col(j) = s[static_cast<std::size_t>(j + 1)] - s[0];
      const Eigen::VectorXd mu = (E.transpose() * E).ldlt().solve(-E.transpose() * s[0]);
      if (!mu.allFinite()) continue;
      lambda(0) = 1.0 - mu.sum();
      lambda.tail(k) = mu;
    }
    if (lambda.minCoeff() < -1e-12) continue;
    Vec3 x = Vec3::Zero();
    for (int j = 0; j <= k; ++j) x += lambda(j) * s[static_cast<std::size_t>(j)];
    if (x.norm() < best) {
      best = x.norm();
      nearest = x;
      best_subset = subset;
    }
  }
  std::vector<Vec3> kept;
  for (int i = 0; i < n; ++i)
    if (best_subset & (1 << i)) kept.push_back(W[static_cast<std::size_t>(i)]);
  W = std::move(kept);
  return nearest;
}

}  // namespace

double distance_to_hull(const std::vector<Vec3>& points, const Vec3& x) {
  // Gilbert's algorithm (the GJK distance iteration for a point): the nearest point of a simplex of
  // support points, grown by the support point in the direction of x, until no point of the set comes
  // nearer. One pass over the points a step; a handful of steps.
  if (points.empty()) return std::numeric_limits<double>::infinity();
  std::vector<Vec3> W{points[0] - x};
  Vec3 v = W[0];
  double scale = 0.0;
  for (const Vec3& p : points) scale = std::max(scale, (p - x).norm());
  for (int iteration = 0; iteration < 100; ++iteration) {
    if (v.norm() <= 1e-12 * scale) return 0.0;
    Vec3 support = points[0] - x;
    for (const Vec3& p : points)
      if ((p - x).dot(v) < support.dot(v)) support = p - x;
    // No point of the set beyond the plane through v normal to it: v is the nearest.
    if (v.dot(v) - support.dot(v) <= 1e-12 * scale * v.norm()) return v.norm();
    W.push_back(support);
    v = nearest_in_simplex(W);
  }
  return v.norm();
}

}  // namespace tumble::robot
