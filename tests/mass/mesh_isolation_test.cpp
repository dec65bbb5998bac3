// assimp runs in a child process (src/mass/mesh_assimp.cpp): a file that crashes it, makes it loop
// forever or exhaust memory becomes one line naming the file, and tumble goes on. The hostile files are
// made here from valid ones by one deterministic edit, each found by mutating these files while
// fuzzing assimp 5.2.5: a Collada file whose <float_array> lacks its count (segfault), a Collada
// index list with a letter in it (endless loop), a 3MF whose zip entries carry wrong CRCs (assertion
// abort). Valid DAE, GLB, 3MF and X files still give the closed form of their solid, parts and all.
// The mechanism itself (child_process.hpp) is tested with work that crashes, hangs and allocates on
// purpose.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <new>
#include <thread>
#include <unistd.h>

#include "../support/run.hpp"
#include "mass/child_process.hpp"
#include "mesh_support.hpp"
#include "tumble/error.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/shapes.hpp"
#include "tumble/mass/tessellate.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define TUMBLE_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TUMBLE_TEST_ASAN 1
#endif
#endif
#ifndef TUMBLE_TEST_ASAN
#define TUMBLE_TEST_ASAN 0
#endif

namespace tumble {
namespace {

using test::TestDir;

#define EXPECT_HAS(text, part) EXPECT_NE((text).find(part), std::string::npos) << "  got: " << (text)

using test::load_error;
using test::write_bytes;

/// Sets an environment variable for the scope.
struct ScopedEnv {
  const char* name;
  ScopedEnv(const char* n, const char* value) : name(n) { ::setenv(name, value, 1); }
  ~ScopedEnv() { ::unsetenv(name); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;
};

// ---- the files ----

/// The unit cube [0,1]³ (corner i: x = bit 0, y = bit 1, z = bit 2), triangles counter-clockwise from
/// outside.
constexpr std::array<std::array<int, 3>, 12> kCubeTriangles = {{{0, 2, 3},
                                                                {0, 3, 1},
                                                                {4, 5, 7},
                                                                {4, 7, 6},
                                                                {0, 1, 5},
                                                                {0, 5, 4},
                                                                {2, 6, 7},
                                                                {2, 7, 3},
                                                                {0, 4, 6},
                                                                {0, 6, 2},
                                                                {1, 3, 7},
                                                                {1, 7, 5}}};
Vec3 corner(int i, double x0 = 0.0) { return Vec3(x0 + (i & 1), (i >> 1) & 1, (i >> 2) & 1); }

/// A Collada file of `cubes` unit cubes, each its own geometry, material and node, the k-th at x = 3k
/// (assimp's PreTransformVertices joins meshes of one material).
std::string cube_dae(int cubes = 1) {
  std::string geometries, nodes, effects, materials;
  for (int k = 0; k < cubes; ++k) {
    std::string positions, indices;
    for (int i = 0; i < 8; ++i) {
      const Vec3 c = corner(i, 3.0 * k);
      positions += fmt::format("{} {} {} ", c.x(), c.y(), c.z());
    }
    for (const auto& t : kCubeTriangles) indices += fmt::format("{} {} {} ", t[0], t[1], t[2]);
    geometries += fmt::format(
        "<geometry id=\"g{0}\" name=\"cube{0}\"><mesh>\n"
        "<source id=\"p{0}\"><float_array id=\"pa{0}\" count=\"24\">{1}</float_array>\n"
        "<technique_common><accessor source=\"#pa{0}\" count=\"8\" stride=\"3\"><param name=\"X\" "
        "type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor>"
        "</technique_common></source>\n"
        "<vertices id=\"v{0}\"><input semantic=\"POSITION\" source=\"#p{0}\"/></vertices>\n"
        "<triangles material=\"m{0}\" count=\"12\"><input semantic=\"VERTEX\" source=\"#v{0}\" "
        "offset=\"0\"/><p>{2}</p>"
        "</triangles>\n</mesh></geometry>\n",
        k, positions, indices);
    nodes += fmt::format(
        "<node id=\"n{0}\" name=\"cube{0}\"><instance_geometry "
        "url=\"#g{0}\"><bind_material><technique_common>"
        "<instance_material symbol=\"m{0}\" target=\"#mat{0}\"/></technique_common></bind_material>"
        "</instance_geometry></node>\n",
        k);
    effects += fmt::format(
        "<effect id=\"e{}\"><profile_COMMON><technique sid=\"t\"><lambert/></technique></profile_COMMON>"
        "</effect>\n",
        k);
    materials += fmt::format("<material id=\"mat{0}\"><instance_effect url=\"#e{0}\"/></material>\n", k);
  }
  return "<?xml version=\"1.0\"?>\n"
         "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
         "<library_effects>\n" +
         effects + "</library_effects>\n<library_materials>\n" + materials +
         "</library_materials>\n<library_geometries>\n" + geometries +
         "</library_geometries>\n<library_visual_scenes><visual_scene id=\"s\">\n" + nodes +
         "</visual_scene></library_visual_scenes>\n<scene><instance_visual_scene url=\"#s\"/></scene>\n"
         "</COLLADA>\n";
}

/// `text` with its first `from` replaced by `to` (the edit must apply).
std::string edited(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// A DirectX .x text file of the unit cube.
std::string cube_x() {
  std::string s = "xof 0303txt 0032\nMesh cube {\n 8;\n";
  for (int i = 0; i < 8; ++i) {
    const Vec3 c = corner(i);
    s += fmt::format(" {};{};{};{}\n", c.x(), c.y(), c.z(), i < 7 ? "," : ";");
  }
  s += " 12;\n";
  for (std::size_t t = 0; t < kCubeTriangles.size(); ++t) {
    const auto& f = kCubeTriangles[t];
    s += fmt::format(" 3;{},{},{};{}\n", f[0], f[1], f[2], t + 1 < kCubeTriangles.size() ? "," : ";");
  }
  return s + "}\n";
}

void put_u32(std::string& s, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) s += static_cast<char>((v >> (8 * k)) & 0xff);
}
void put_u16(std::string& s, std::uint32_t v) {
  for (int k = 0; k < 2; ++k) s += static_cast<char>((v >> (8 * k)) & 0xff);
}

/// A binary glTF 2.0 file of the unit cube: float32 positions, uint16 indices.
/// The unit cube's glTF buffer: 8 float32 corners, then 36 uint16 indices.
std::string cube_gltf_buffer() {
  std::string bin;
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < 3; ++k) {
      const float x = static_cast<float>(corner(i)[k]);
      std::uint32_t bits;
      std::memcpy(&bits, &x, 4);
      put_u32(bin, bits);
    }
  }
  for (const auto& t : kCubeTriangles) {
    for (int v : t) put_u16(bin, static_cast<std::uint32_t>(v));
  }
  while (bin.size() % 4 != 0) bin += '\0';
  return bin;
}

/// The unit cube's glTF document with these buffers (JSON objects), its vertices and indices in
/// buffer `cube`.
std::string cube_gltf_json(const std::string& buffers, int cube) {
  return fmt::format(
      R"({{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0,"name":"cube"}}],)"
      R"("meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],"buffers":[{}],)"
      R"("bufferViews":[{{"buffer":{},"byteOffset":0,"byteLength":96}},{{"buffer":{},"byteOffset":96,"byteLength":72}}],)"
      R"("accessors":[{{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}},)"
      R"({{"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}}]}})",
      buffers, cube, cube);
}

/// The JSON of a buffer of the cube's bytes, in the file (`uri` empty: a .glb's BIN chunk) or at `uri`.
std::string cube_buffer(const std::string& uri = "") {
  return fmt::format(R"({{"byteLength":{}{}}})", cube_gltf_buffer().size(),
                     uri.empty() ? "" : fmt::format(R"(,"uri":"{}")", uri));
}

/// A glTF text file of the unit cube whose buffer is the file at `uri`.
std::string cube_gltf(const std::string& uri) { return cube_gltf_json(cube_buffer(uri), 0); }

/// A binary glTF of the unit cube: its buffer in the file's BIN chunk, or (`uri` given) the file at
/// `uri`, beside a BIN chunk of 4 bytes that nothing uses (buffer 0 of a .glb is always its chunk).
std::string cube_glb(const std::string& uri = "") {
  const std::string bin = uri.empty() ? cube_gltf_buffer() : std::string(4, '\0');
  std::string json = uri.empty() ? cube_gltf_json(cube_buffer(), 0)
                                 : cube_gltf_json(R"({"byteLength":4},)" + cube_buffer(uri), 1);
  while (json.size() % 4 != 0) json += ' ';
  std::string glb;
  put_u32(glb, 0x46546C67);  // "glTF"
  put_u32(glb, 2);
  put_u32(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  put_u32(glb, static_cast<std::uint32_t>(json.size()));
  put_u32(glb, 0x4E4F534A);  // "JSON"
  glb += json;
  put_u32(glb, static_cast<std::uint32_t>(bin.size()));
  put_u32(glb, 0x004E4942);  // "BIN\0"
  return glb + bin;
}

std::uint32_t crc32(std::string_view data) {
  std::uint32_t crc = 0xffffffffu;
  for (char c : data) {
    crc ^= static_cast<unsigned char>(c);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

/// A zip archive of stored (uncompressed) entries; with `right_crcs` false every CRC is 0.
std::string zip(const std::vector<std::pair<std::string, std::string>>& entries, bool right_crcs) {
  std::string out, central;
  for (const auto& [name, data] : entries) {
    const std::uint32_t crc = right_crcs ? crc32(data) : 0;
    const auto offset = static_cast<std::uint32_t>(out.size());
    put_u32(out, 0x04034b50);
    for (std::uint32_t v : {20u, 0u, 0u, 0u, 0u}) put_u16(out, v);  // version, flags, method, time, date
    put_u32(out, crc);
    put_u32(out, static_cast<std::uint32_t>(data.size()));
    put_u32(out, static_cast<std::uint32_t>(data.size()));
    put_u16(out, static_cast<std::uint32_t>(name.size()));
    put_u16(out, 0);
    out += name + data;
    put_u32(central, 0x02014b50);
    for (std::uint32_t v : {20u, 20u, 0u, 0u, 0u, 0u}) put_u16(central, v);
    put_u32(central, crc);
    put_u32(central, static_cast<std::uint32_t>(data.size()));
    put_u32(central, static_cast<std::uint32_t>(data.size()));
    put_u16(central, static_cast<std::uint32_t>(name.size()));
    for (std::uint32_t v : {0u, 0u, 0u, 0u}) put_u16(central, v);  // extra, comment, disk, internal
    put_u32(central, 0);                                           // external attributes
    put_u32(central, offset);
    central += name;
  }
  const auto central_offset = static_cast<std::uint32_t>(out.size());
  out += central;
  put_u32(out, 0x06054b50);
  for (std::uint32_t v : {0u, 0u}) put_u16(out, v);
  put_u16(out, static_cast<std::uint32_t>(entries.size()));
  put_u16(out, static_cast<std::uint32_t>(entries.size()));
  put_u32(out, static_cast<std::uint32_t>(central.size()));
  put_u32(out, central_offset);
  put_u16(out, 0);
  return out;
}

/// A 3MF package (a zip) of the unit cube in metres... 3MF says millimetres; assimp ignores the unit.
std::string cube_3mf(bool right_crcs = true) {
  std::string model =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"millimeter\" xml:lang=\"en-US\" "
      "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\"><resources><object id=\"1\" "
      "type=\"model\"><mesh><vertices>";
  for (int i = 0; i < 8; ++i) {
    const Vec3 c = corner(i);
    model += fmt::format("<vertex x=\"{}\" y=\"{}\" z=\"{}\"/>", c.x(), c.y(), c.z());
  }
  model += "</vertices><triangles>";
  for (const auto& t : kCubeTriangles) {
    model += fmt::format("<triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>", t[0], t[1], t[2]);
  }
  model += "</triangles></mesh></object></resources><build><item objectid=\"1\"/></build></model>";
  const std::string rels =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships "
      "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"><Relationship "
      "Target=\"/3D/3dmodel.model\" Id=\"rel0\" "
      "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/></Relationships>";
  const std::string types =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Types "
      "xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"><Default Extension=\"rels\" "
      "ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/><Default "
      "Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/></Types>";
  return zip({{"[Content_Types].xml", types}, {"_rels/.rels", rels}, {"3D/3dmodel.model", model}},
             right_crcs);
}

const MassProperties kUnitCube{1.0, Vec3(0.5, 0.5, 0.5), Mat3::Identity() / 6.0, 1.0};

/// "FILE: the mesh loader (assimp) crashed on this file (" ... "): the file is malformed or unsupported;
/// convert it to OBJ, PLY or STL", one line.
void expect_crash_message(const std::string& msg, const std::filesystem::path& path) {
  EXPECT_EQ(msg.find(path.string() + ": the mesh loader (assimp) crashed on this file ("), 0U) << msg;
  EXPECT_HAS(msg, "): the file is malformed or unsupported; convert it to OBJ, PLY or STL");
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

// ---- through load_mesh ----

TEST(MeshIsolation, ValidDaeGlb3mfAndXGiveTheUnitCube) {
  TestDir dir;
  write_bytes(dir / "cube.dae", cube_dae());
  write_bytes(dir / "cube.glb", cube_glb());
  write_bytes(dir / "cube.3mf", cube_3mf());
  write_bytes(dir / "cube.x", cube_x());
  TriangleMesh cube;
  for (int i = 0; i < 8; ++i) cube.vertices.push_back(corner(i));
  for (const auto& t : kCubeTriangles) {
    cube.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                              static_cast<std::uint32_t>(t[2])});
  }
  write_binary_stl(cube, dir / "cube.stl");
  for (const char* name : {"cube.dae", "cube.glb", "cube.3mf", "cube.x", "cube.stl"}) {
    const LoadedMesh loaded = load_mesh(dir / name);
    EXPECT_EQ(loaded.parts, 1U) << name;
    EXPECT_EQ(loaded.mesh.vertices.size(), 8U) << name;  // welded
    EXPECT_EQ(loaded.mesh.triangles.size(), 12U) << name;
    const MeshMassResult r = solid_mass_properties(loaded.mesh, MassSpec::density(1.0), name);
    MassProperties want = kUnitCube;
    // assimp turns DirectX's left-handed axes right-handed by negating z (as it always did).
    if (std::string(name) == "cube.x") want.center_of_mass.z() = -0.5;
    test::expect_close(r.properties, want, 1e-15, 1.0, name);
  }
  // Scaled as before: every coordinate times the factor.
  const LoadedMesh mm = load_mesh(dir / "cube.glb", {.scale = 0.001});
  EXPECT_NEAR(solid_mass_properties(mm.mesh, MassSpec::density(1.0)).properties.volume, 1e-9, 1e-24);
}

TEST(MeshIsolation, AMeshReadsNoFileOutsideItsDirectory) {
  // A glTF's buffer is another file. Beside the mesh or below it, it is read; anywhere else ("../", a
  // symbolic link out, an absolute path) it is refused by name, though the file there holds a valid
  // buffer: its bytes would become vertices in reports and run files made to be shared.
  TestDir dir;
  std::filesystem::create_directories(dir / "model/data");
  write_bytes(dir / "model/data/cube.bin", cube_gltf_buffer());
  write_bytes(dir / "secret.bin", cube_gltf_buffer());
  std::filesystem::create_symlink(dir / "secret.bin", dir / "model/link.bin");
  write_bytes(dir / "model/inside.gltf", cube_gltf("data/cube.bin"));
  const LoadedMesh inside = load_mesh(dir / "model/inside.gltf");
  EXPECT_EQ(inside.mesh.triangles.size(), 12U);
  // The buffer is named as a file the mesh read: a run stamps it (resume refuses a changed one) and
  // never writes over it.
  const auto buffer = std::filesystem::weakly_canonical(dir / "model/data/cube.bin");
  EXPECT_EQ(inside.companions, std::vector<std::filesystem::path>{buffer});
  write_bytes(dir / "model/s.toml",
              "[simulation]\nduration = 1\n[[bodies]]\nname = \"c\"\nmesh = \"inside.gltf\"\ndensity = 1\n");
  const Scene scene = load_scene(dir / "model/s.toml");
  EXPECT_NE(std::find(scene.input_files.begin(), scene.input_files.end(), buffer), scene.input_files.end());
  // A link to a mesh elsewhere: the mesh is read, and its buffer beside the link.
  std::filesystem::create_directories(dir / "scene/data");
  std::filesystem::create_symlink(dir / "model/inside.gltf", dir / "scene/cube.gltf");
  write_bytes(dir / "scene/data/cube.bin", cube_gltf_buffer());
  EXPECT_EQ(load_mesh(dir / "scene/cube.gltf").mesh.triangles.size(), 12U);
  const std::string secret = (dir / "secret.bin").string();
  const std::string model = std::filesystem::weakly_canonical(dir / "model").string();
  for (const auto& [name, uri] : std::vector<std::pair<std::string, std::string>>{
           {"up.gltf", "../secret.bin"}, {"link.gltf", "link.bin"}}) {
    write_bytes(dir / "model" / name, cube_gltf(uri));
    const std::string msg = load_error(dir / "model" / name);
    EXPECT_HAS(msg, (dir / "model" / name).string() + ": the mesh refers to the file ");
    EXPECT_HAS(msg, ", outside its directory " + model + ": tumble reads only the files beside a mesh");
  }
  // assimp 5.2 puts the glTF's directory before an absolute name: nothing there, nothing read.
  write_bytes(dir / "model/absolute.gltf", cube_gltf(secret));
  EXPECT_HAS(load_error(dir / "model/absolute.gltf"), "could not open referenced file");
  // A .glb is read from memory, where an external buffer's name has no directory before it: an
  // absolute one is refused, a relative one is taken beside the mesh.
  write_bytes(dir / "model/outside.glb", cube_glb(secret));
  EXPECT_HAS(load_error(dir / "model/outside.glb"), "the mesh refers to the file " + secret + ", outside");
  write_bytes(dir / "model/beside.glb", cube_glb("data/cube.bin"));
  const LoadedMesh beside = load_mesh(dir / "model/beside.glb");
  EXPECT_EQ(beside.mesh.triangles.size(), 12U);
  EXPECT_EQ(beside.companions, std::vector<std::filesystem::path>{buffer});
}

TEST(MeshIsolation, PartsOfAnAssimpFileAreCountedNamedAndPicked) {
  TestDir dir;
  write_bytes(dir / "cubes.dae", cube_dae(2));
  const LoadedMesh merged = load_mesh(dir / "cubes.dae");
  EXPECT_EQ(merged.parts, 2U);
  ASSERT_EQ(merged.warnings.size(), 2U);  // float32, then the merge
  EXPECT_HAS(merged.warnings[0], "read through assimp, which rounds coordinates to float32");
  EXPECT_HAS(merged.warnings[1], "cubes.dae holds 2 meshes ('g0', 'g1'); they were merged into one body");
  EXPECT_NEAR(solid_mass_properties(merged.mesh, MassSpec::density(1.0)).properties.mass, 2.0, 1e-14);
  const LoadedMesh second = load_mesh(dir / "cubes.dae", {.part = 2});
  const MassProperties want{1.0, Vec3(3.5, 0.5, 0.5), Mat3::Identity() / 6.0, 1.0};
  test::expect_close(solid_mass_properties(second.mesh, MassSpec::density(1.0)).properties, want, 1e-15, 1.0);
  try {
    (void)load_mesh(dir / "cubes.dae", {.part = 3});
    ADD_FAILURE() << "part 3 of 2";
  } catch (const InvalidArgument& e) {
    EXPECT_HAS(std::string(e.what()), "part 3 does not exist: the file has 2 meshes ('g0', 'g1')");
  }
}

TEST(MeshIsolation, AssimpErrorsStillComeThroughWithTheFileName) {
  TestDir dir;
  write_bytes(dir / "broken.glb", "glTF but not really");
  const std::string msg = load_error(dir / "broken.glb");
  EXPECT_HAS(msg, (dir / "broken.glb").string() + ": cannot read the mesh: ");
  EXPECT_EQ(msg.find("$$$"), std::string::npos) << msg;  // assimp's name for a file read from memory
  write_bytes(dir / "empty.dae", "");
  EXPECT_HAS(load_error(dir / "empty.dae"), "empty.dae: the file is empty (0 bytes)");
}

TEST(MeshIsolation, ACrashOfAssimpIsOneLineAndTumbleGoesOn) {
  TestDir dir;
  // The count attribute of <float_array> misspelt: assimp 5.2.5 dereferences a null pointer.
  const auto segv = dir / "segv.dae";
  write_bytes(segv, edited(cube_dae(), "count=\"24\"", "coXnt=\"24\""));
  const std::string msg = load_error(segv);
  expect_crash_message(msg, segv);
  if (!TUMBLE_TEST_ASAN) {  // AddressSanitizer reports the segfault itself, then aborts or exits
    EXPECT_EQ(msg,
              segv.string() +
                  ": the mesh loader (assimp) crashed on this file (signal 11, segmentation fault): the file "
                  "is malformed or unsupported; convert it to OBJ, PLY or STL");
  }
  // A 3MF whose zip entries have wrong CRCs: an assertion in assimp's zip reader aborts; its text is
  // quoted.
  const auto abort_3mf = dir / "crc.3mf";
  write_bytes(abort_3mf, cube_3mf(false));
  const std::string aborted = load_error(abort_3mf);
  expect_crash_message(aborted, abort_3mf);
  EXPECT_HAS(aborted, "(signal 6, abort: ai_assert failure in ");
  EXPECT_HAS(aborted, "ZipArchiveIOSystem.cpp");
  // Still here, and the next file loads.
  write_bytes(dir / "cube.dae", cube_dae());
  EXPECT_EQ(load_mesh(dir / "cube.dae").mesh.triangles.size(), 12U);
}

TEST(MeshIsolation, AHangIsCutAtTheTimeout) {
  TestDir dir;
  // A letter among the indices of <p>: assimp 5.2.5 never advances past it.
  const auto hang = dir / "hang.dae";
  write_bytes(hang, edited(cube_dae(), "4 5 7 4 7 6", "4 5 x 4 7 6"));
  const ScopedEnv timeout(kLoaderTimeoutVariable, "0.5");
  const auto start = std::chrono::steady_clock::now();
  const std::string msg = load_error(hang);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(msg,
            hang.string() +
                ": the mesh loader (assimp) did not finish within 0.5 s (TUMBLE_LOADER_TIMEOUT_S raises the "
                "limit): the file is malformed (assimp loops forever on some) or very large; convert it to "
                "OBJ, PLY or STL");
  EXPECT_GE(took, 0.5);
  EXPECT_LT(took, 5.0);
}

TEST(MeshIsolation, AValidFileTimesOutUnderATinyLimit) {
  TestDir dir;
  write_bytes(dir / "cubes.dae", cube_dae(200));
  const ScopedEnv timeout(kLoaderTimeoutVariable, "0.001");
  EXPECT_HAS(load_error(dir / "cubes.dae"),
             "cubes.dae: the mesh loader (assimp) did not finish within 0.001 s");
}

TEST(MeshIsolation, RunningOutOfMemoryIsNamedWithTheLimit) {
  if (TUMBLE_TEST_ASAN) GTEST_SKIP() << "AddressSanitizer's allocator reports a failed allocation itself";
  TestDir dir;
  write_bytes(dir / "cubes.dae", cube_dae(400));  // large enough that parsing it needs more than 64 KiB
  const ScopedEnv memory(kLoaderMemoryVariable, "64k");
  EXPECT_EQ(
      load_error(dir / "cubes.dae"),
      (dir / "cubes.dae").string() +
          ": the mesh loader (assimp) ran out of memory on this file (limit 64 KiB; "
          "TUMBLE_LOADER_MEMORY_BYTES raises it): the file is malformed or too large for assimp; convert "
          "it to OBJ, PLY or STL");
}

TEST(MeshIsolation, LimitsDefaultWithTheFileSizeAndAreChecked) {
  EXPECT_EQ(loader_timeout_seconds(0), 30.0);
  EXPECT_EQ(loader_timeout_seconds(100u << 20), 130.0);
  EXPECT_EQ(loader_timeout_seconds((100u << 20) + 1), 131.0);
  EXPECT_EQ(loader_memory_bytes(1000), std::uint64_t{2} << 30);
  EXPECT_EQ(loader_memory_bytes(std::uint64_t{1} << 30), std::uint64_t{32} << 30);
  {
    const ScopedEnv timeout(kLoaderTimeoutVariable, "2.5");
    EXPECT_EQ(loader_timeout_seconds(1u << 30), 2.5);
  }
  for (const char* bad : {"0", "-1", "abc", "1s", "inf", "nan"}) {
    const ScopedEnv timeout(kLoaderTimeoutVariable, bad);
    EXPECT_THROW(loader_timeout_seconds(0), InvalidArgument) << bad;
  }
  const ScopedEnv memory(kLoaderMemoryVariable, "8G");
  EXPECT_EQ(loader_memory_bytes(0), std::uint64_t{8} << 30);
}

TEST(MeshIsolation, TheCommandLineSaysOneLineAndExitsWithOne) {
  TestDir dir;
  const auto segv = dir / "segv.dae";
  write_bytes(segv, edited(cube_dae(), "count=\"24\"", "coXnt=\"24\""));
  const test::CommandResult r = test::run_tumble("inertia '" + segv.string() + "'");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(r.output.find("tumble: error: " + segv.string() +
                          ": the mesh loader (assimp) crashed on this file"),
            0U)
      << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

// ---- the mechanism ----

using child_process::End;

child_process::Outcome run_child(const std::function<void(int)>& work, double timeout = 10.0,
                                 std::uint64_t memory = 0) {
  return child_process::run(work, {timeout, memory});
}

/// The child is gone, not a zombie: kill(pid, 0) fails only once it is reaped.
void expect_reaped(const std::string& answer) {
  ASSERT_EQ(answer.size(), sizeof(pid_t));
  pid_t pid;
  std::memcpy(&pid, answer.data(), sizeof pid);
  errno = 0;
  EXPECT_EQ(::kill(pid, 0), -1);
  EXPECT_EQ(errno, ESRCH);
}

void send_pid(int fd) {
  const pid_t pid = ::getpid();
  child_process::write_all(fd, &pid, sizeof pid);
}

TEST(ChildProcess, AnAnswerLargerThanAPipeArrivesWhole) {
  std::string big(10 << 20, '\0');
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 2654435761u >> 24);
  const auto out = run_child([&](int fd) { child_process::write_all(fd, big.data(), big.size()); });
  EXPECT_EQ(out.end, End::finished);
  EXPECT_TRUE(out.answer == big);
}

TEST(ChildProcess, CrashesAreReportedWithTheSignalAndTheLastWords) {
  const auto out = run_child([](int fd) {
    send_pid(fd);
    std::fputs("noise\nai_assert failure in x.cpp(7): p != nullptr\nmore noise\n", stderr);
    std::fflush(stderr);
    std::abort();
  });
  EXPECT_EQ(out.end, End::crashed);
  EXPECT_EQ(out.signal, SIGABRT);
  EXPECT_EQ(child_process::telling_line(out.diagnostics), "ai_assert failure in x.cpp(7): p != nullptr");
  expect_reaped(out.answer);

  const auto segv = run_child([](int fd) {
    send_pid(fd);
    ::raise(SIGSEGV);
  });
  EXPECT_EQ(segv.end, End::crashed);
  if (!TUMBLE_TEST_ASAN) {
    EXPECT_EQ(segv.signal, SIGSEGV);
  }
  expect_reaped(segv.answer);

  const auto thrown = run_child([](int) { throw std::runtime_error("out of the work"); });
  EXPECT_EQ(thrown.end, End::crashed);
  EXPECT_EQ(thrown.exit_status, 1);
}

TEST(ChildProcess, AnEndlessLoopIsKilledAtTheTimeout) {
  const auto start = std::chrono::steady_clock::now();
  const auto out = run_child(
      [](int fd) {
        send_pid(fd);
        volatile unsigned spin = 0;
        for (;;) {
          spin = spin + 1u;
        }
      },
      0.3);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(out.end, End::timed_out);
  EXPECT_GE(took, 0.3);
  EXPECT_LT(took, 3.0);
  expect_reaped(out.answer);
  // A child that closed its output but does not exit is timed out too.
  const auto silent = run_child(
      [](int fd) {
        send_pid(fd);
        ::close(fd);
        ::close(STDOUT_FILENO);
        ::close(STDERR_FILENO);
        ::pause();
      },
      0.3);
  EXPECT_EQ(silent.end, End::timed_out);
  expect_reaped(silent.answer);
}

TEST(ChildProcess, AnAllocationBeyondTheLimitEndsTheChildAsOutOfMemory) {
  if (TUMBLE_TEST_ASAN) GTEST_SKIP() << "AddressSanitizer's allocator reports a failed allocation itself";
  const auto out = run_child(
      [](int fd) {
        send_pid(fd);
        std::vector<char> huge(std::size_t{1} << 30, 'x');  // 1 GiB against a 64 MiB limit
        child_process::write_all(fd, huge.data(), 1);
      },
      10.0, 64u << 20);
  EXPECT_EQ(out.end, End::out_of_memory)
      << "signal " << out.signal << ", exit status " << out.exit_status << ": " << out.diagnostics;
  EXPECT_EQ(out.answer.size(), sizeof(pid_t));
  // Within the limit, the same work finishes.
  const auto fine = run_child(
      [](int fd) {
        std::vector<char> some(std::size_t{16} << 20, 'x');
        child_process::write_all(fd, some.data(), 1);
      },
      10.0, 64u << 20);
  EXPECT_EQ(fine.end, End::finished);
}

TEST(ChildProcess, ASignalFromOutsideIsAnInterruptionNotACrash) {
  const auto out = run_child([](int) { ::raise(SIGTERM); });
  EXPECT_EQ(out.end, End::interrupted);
  EXPECT_EQ(out.signal, SIGTERM);
}

TEST(ChildProcess, ThreadsInTheParentDoNotHinderTheChild) {
  // OpenMP-like: other threads busy (allocating) while the child is forked and runs.
  std::atomic<bool> stop{false};
  std::atomic<double> sink{0.0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 3; ++t) {
    threads.emplace_back([&] {
      while (!stop) {
        const std::vector<double> v(1000, 1.0);
        sink = sink + v[7];
      }
    });
  }
  for (int k = 0; k < 20; ++k) {
    const auto out = run_child([](int fd) {
      std::vector<std::string> lots(1000, std::string(100, 'a'));
      child_process::write_all(fd, lots[999].data(), 100);
    });
    EXPECT_EQ(out.end, End::finished);
    EXPECT_EQ(out.answer, std::string(100, 'a'));
  }
  stop = true;
  for (auto& t : threads) t.join();
}

}  // namespace
}  // namespace tumble
