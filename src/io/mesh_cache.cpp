#include "mesh_cache.hpp"

#include <sys/stat.h>

#include <deque>

#include <mutex>
#include "tumble/mass/mesh_decimate.hpp"

namespace tumble::scene {
namespace {

struct Key {
  dev_t device;
  ino_t inode;
  off_t size;
  std::int64_t mtime_s, mtime_ns;
  double scale;
  std::size_t part;
  bool operator==(const Key&) const = default;
};

std::mutex lock;
std::deque<std::pair<Key, std::shared_ptr<const CachedMesh>>> cache;  // most recent first
constexpr size_t kCapacity = 16;

}  // namespace

MeshMassResult CachedMesh::unit_solid(const std::string& name) const {
  const std::lock_guard<std::mutex> guard(lock_);
  if (!unit_ || unit_->first != name) unit_.emplace(name, solid_unit_properties(loaded_.mesh, name));
  return unit_->second;
}

std::shared_ptr<const TriangleMesh> CachedMesh::display() const {
  std::call_once(display_once_, [this] {
    display_ = std::make_shared<const TriangleMesh>(decimate(loaded_.mesh, kDisplayTriangles));
  });
  return display_;
}

std::shared_ptr<const CachedMesh> load_mesh_cached(const std::filesystem::path& path,
                                                   const MeshLoadOptions& options) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    return std::make_shared<const CachedMesh>(load_mesh(path, options));  // load_mesh says what is wrong
  }
  const Key key{st.st_dev,          st.st_ino,     st.st_size,  st.st_mtim.tv_sec,
                st.st_mtim.tv_nsec, options.scale, options.part};
  {
    const std::lock_guard<std::mutex> guard(lock);
    for (const auto& [k, mesh] : cache) {
      if (k == key) return mesh;
    }
  }
  // Outside the lock: other threads go on meanwhile.
  auto loaded = std::make_shared<const CachedMesh>(load_mesh(path, options));
  const std::lock_guard<std::mutex> guard(lock);
  cache.emplace_front(key, loaded);
  if (cache.size() > kCapacity) cache.pop_back();
  return loaded;
}

}  // namespace tumble::scene
