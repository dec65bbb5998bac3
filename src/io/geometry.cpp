#include "tumble/io/geometry.hpp"

#include "tumble/forces/forces.hpp"
#include "tumble/math/huge_pages.hpp"

namespace tumble {

SceneGeometry scene_geometry(const Scene& scene) {
  SceneGeometry g;
  const Model& model = scene.model;
  g.bodies.reserve(model.bodies.size());
  prefer_huge_pages(g.bodies);  // 144 bytes a body
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const RigidBody& b = model.bodies[i];
    BodyGeometry& out = g.bodies.emplace_back();
    if (i < scene.body_info.size()) out.mesh = scene.body_info[i].display;  // shared, not copied
    out.mass = b.mass();
    out.com = b.center_of_mass();
    out.U = b.U();
    out.Lambda = b.Lambda();
  }
  const auto row = [&](const Spring::End& e) {
    if (e.body != all_bodies) return static_cast<long>(e.body);
    if (e.particle != all_bodies) return static_cast<long>(model.bodies.size() + e.particle);
    return -1L;
  };
  for (const auto& f : model.forces) {
    if (const auto* s = dynamic_cast<const Spring*>(f.get())) {
      g.springs.push_back({row(s->a()), row(s->b()), s->a().point, s->b().point});
    }
  }
  return g;
}

}  // namespace tumble
