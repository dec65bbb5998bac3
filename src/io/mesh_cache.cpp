#include "mesh_cache.hpp"

#include <deque>
#include <mutex>

namespace tumble::scene {
namespace {

struct Key {
  std::string path;
  std::uintmax_t size;
  std::filesystem::file_time_type mtime;
  double scale;
  std::size_t part;
  bool operator==(const Key&) const = default;
};

std::mutex lock;
std::deque<std::pair<Key, LoadedMesh>> cache;  // most recent first
constexpr size_t kCapacity = 16;

}  // namespace

LoadedMesh load_mesh_cached(const std::filesystem::path& path, const MeshLoadOptions& options) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  const auto mtime = std::filesystem::last_write_time(path, ec);
  if (ec) return load_mesh(path, options);  // load_mesh says what is wrong with the file
  const Key key{std::filesystem::absolute(path).lexically_normal().string(), size, mtime, options.scale,
                options.part};
  {
    const std::lock_guard<std::mutex> guard(lock);
    for (const auto& [k, mesh] : cache) {
      if (k == key) return mesh;
    }
  }
  LoadedMesh loaded = load_mesh(path, options);  // outside the lock: other threads go on meanwhile
  const std::lock_guard<std::mutex> guard(lock);
  cache.emplace_front(key, loaded);
  if (cache.size() > kCapacity) cache.pop_back();
  return loaded;
}

}  // namespace tumble::scene
