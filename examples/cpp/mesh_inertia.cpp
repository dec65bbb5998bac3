// Mass properties of a part from its mesh file (OBJ, STL, PLY, OFF, glTF and what else assimp reads):
// load_mesh, then the exact integrals of the solid it bounds at a density, then the body a run steps.
//   mesh_inertia MESH [DENSITY kg/m^3] [SCALE]      e.g. mesh_inertia part.stl 2700 0.001 (a file in mm)
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tumble/dynamics/rigid_body.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"

int main(int argc, char** argv) {
  using namespace tumble;
  if (argc < 2 || argc > 4) {
    std::fprintf(stderr, "usage: %s MESH [DENSITY kg/m^3, default 1000] [SCALE, default 1]\n", argv[0]);
    return 2;
  }
  try {
    const double density = argc > 2 ? std::stod(argv[2]) : 1000.0;
    MeshLoadOptions options;
    options.scale = argc > 3 ? std::stod(argv[3]) : 1.0;
    const LoadedMesh loaded = load_mesh(argv[1], options);  // throws FileError with file:line:column
    for (const std::string& w : loaded.warnings) std::printf("warning: %s\n", w.c_str());
    // Throws MeshError naming the defect (holes, non-manifold edges, ...) if the mesh bounds no solid.
    const MeshMassResult solid = solid_mass_properties(loaded.mesh, MassSpec::density(density), argv[1]);
    const MassProperties& mp = solid.properties;
    std::printf("%s: %zu triangles (%s)\n", argv[1], loaded.mesh.triangles.size(), loaded.format.c_str());
    std::printf("mass %.9g kg, volume %.9g m^3\n", mp.mass, mp.volume);
    std::printf("centre of mass (%.9g, %.9g, %.9g) m\n", mp.center_of_mass.x(), mp.center_of_mass.y(),
                mp.center_of_mass.z());
    const RigidBody body = RigidBody::from_mass_properties(mp, "part");
    std::printf("principal moments %.9g %.9g %.9g kg m^2\n", body.Lambda()(0), body.Lambda()(1),
                body.Lambda()(2));
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {  // std::stod on a word
    std::fprintf(stderr, "error: DENSITY and SCALE must be numbers (%s)\n", e.what());
    return 2;
  }
}
