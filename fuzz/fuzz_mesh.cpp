// libFuzzer target: bytes -> mesh through tumble's own reader of one format (TUMBLE_FUZZ_NAME names the
// file, its extension picks the reader: fuzz_obj, fuzz_off, fuzz_ply (ASCII and binary), fuzz_stl (ASCII
// by tumble; a binary STL of the exact size 84 + 50 n goes on to assimp, which is not instrumented)).
// The same entry point load_mesh() uses after reading a file: load_mesh_bytes().
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "tumble/mass/mesh_check.hpp"
#include "tumble/mass/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  tumble::fuzz::refused_or_ok([&] {
    const tumble::LoadedMesh loaded = tumble::load_mesh_bytes(TUMBLE_FUZZ_NAME, std::move(bytes));
    tumble::fuzz::check_mesh_contract(loaded.mesh);
    FUZZ_CHECK(loaded.parts >= 1);
    // The loaded mesh goes on to the checks every use of it starts with.
    const tumble::MeshReport report = tumble::check_mesh(loaded.mesh);
    FUZZ_CHECK(report.usable());
    FUZZ_CHECK(report.triangle_count == loaded.mesh.triangles.size());
  });
  return 0;
}
