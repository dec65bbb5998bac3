// Reading meshes with assimp: every mesh of the scene, node transforms applied, polygons triangulated,
// then welded (mesh_weld.cpp says why assimp's own joining is not used).
#include "tumble/mass/mesh_io.hpp"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cmath>
#include <fmt/format.h>
#include <system_error>

#include "tumble/error.hpp"
#include "tumble/mass/mesh_weld.hpp"

namespace tumble {
namespace {

void require_readable_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) {
    throw FileError(fmt::format("{}: no such file; check the path and the working directory", path.string()));
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw FileError(fmt::format("{}: not a regular file (a directory?); give a mesh file", path.string()));
  }
}

/// Names the bad vertex by the first face that uses it: assimp renumbers vertices (OBJ corners are
/// split per face), but faces keep the file's order, so "face 12 of mesh 0" is findable in the file.
[[noreturn]] void throw_non_finite(const std::filesystem::path& path, const aiMesh& part, unsigned mesh_index,
                                   unsigned vertex, double scale) {
  const aiVector3D& p = part.mVertices[vertex];
  std::string where = fmt::format("vertex {} of mesh {}", vertex, mesh_index);
  for (unsigned f = 0; f < part.mNumFaces; ++f) {
    const aiFace& face = part.mFaces[f];
    for (unsigned k = 0; k < face.mNumIndices; ++k) {
      if (face.mIndices[k] == vertex) {
        where = fmt::format("corner {} of face {} of mesh {}", k, f, mesh_index);
        f = part.mNumFaces - 1;  // stop at the first face that uses it
        break;
      }
    }
  }
  throw FileError(fmt::format("{}: {} has non-finite coordinates ({}, {}, {}){}; fix the file", path.string(),
                              where, p.x, p.y, p.z,
                              scale == 1.0 ? "" : fmt::format(" after scaling by {}", scale)));
}

}  // namespace

TriangleMesh load_mesh(const std::filesystem::path& path, const MeshLoadOptions& options) {
  if (!std::isfinite(options.scale) || !(options.scale > 0.0)) {
    throw InvalidArgument(
        fmt::format("{}: mesh scale {} is invalid: give a positive factor (e.g. 0.001 for millimetres)",
                    path.string(), options.scale));
  }
  require_readable_file(path);

  Assimp::Importer importer;
  // Points and lines carry no surface: SortByPType splits them off and this drops them.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (scene == nullptr) {
    throw FileError(fmt::format("{}: cannot read the mesh: {}", path.string(), importer.GetErrorString()));
  }

  TriangleMesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* part = scene->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (unsigned i = 0; i < part->mNumVertices; ++i) {
      const aiVector3D& p = part->mVertices[i];
      const Vec3 v = options.scale *
                     Vec3(static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z));
      if (!v.allFinite()) throw_non_finite(path, *part, m, i, options.scale);
      mesh.vertices.push_back(v);
    }
    for (unsigned f = 0; f < part->mNumFaces; ++f) {
      const aiFace& face = part->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left over in a mixed mesh
      mesh.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  if (mesh.triangles.empty()) {
    throw FileError(
        fmt::format("{}: the file holds no triangles ({} meshes, only points or lines, or empty); export the "
                    "surface as triangles or polygons",
                    path.string(), scene->mNumMeshes));
  }
  return weld_identical_vertices(mesh);
}

}  // namespace tumble
