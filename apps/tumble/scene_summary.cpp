#include "scene_summary.hpp"
#include "plural.hpp"

#include <fmt/format.h>

#include "tumble/error.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/sim/diagnostics.hpp"

namespace tumble::cli {
namespace {

// + 0.0 turns −0 into +0: a negative zero is rounding's sign, not a fact to print.
std::string vec(const Vec3& v) {
  return fmt::format("({:.6g}, {:.6g}, {:.6g})", v.x() + 0.0, v.y() + 0.0, v.z() + 0.0);
}

std::string conserved_list(const Conservation& c) {
  std::vector<std::string> names;
  if (c.energy) names.emplace_back("energy");
  if (c.linear_momentum) names.emplace_back("linear momentum");
  if (c.angular_momentum) names.emplace_back("angular momentum about the origin");
  return names.empty() ? "nothing (the forces exchange energy and momentum with the outside)"
                       : fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace

void print_scene_summary(std::FILE* out, const Scene& scene) {
  const RunSettings& s = scene.settings;
  const Model& m = scene.model;
  fmt::print(out, "scene {}\n", scene.path.string());
  fmt::print(out, "  simulation   {:g} s, integrator {}, {} formulation, {}, output every {}\n", s.duration,
             s.integrator, formulation_name(s.formulation),
             is_adaptive(s.integrator)
                 ? fmt::format("rtol {:g}, atol {:g}", s.tolerances.relative, s.tolerances.absolute)
                 : fmt::format("timestep {:g} s", s.timestep),
             s.output_interval > 0 ? fmt::format("{:g} s", s.output_interval) : std::string("step"));
  if (s.integrator == "exact") {
    fmt::print(out,
               "               samples are analytic: the Euler–Poinsot motion and the centre of mass's "
               "parabola, evaluated from t = {:g} s; the timestep only sets where a run may stop\n",
               scene.initial.t);
  }
  fmt::print(out, "  contents     {}, {}, {}\n", count(m.bodies.size(), "body", "bodies"),
             count(m.particles.size(), "particle", "particles"),
             count(m.forces.size(), "force model", "force models"));
  for (size_t i = 0; i < m.bodies.size(); ++i) {
    const RigidBody& b = m.bodies[i];
    fmt::print(out, "  body '{}': {}\n", b.name(), *scene.body_info[i].source);
    fmt::print(out, "    mass               {:.10g} kg\n", b.mass());
    fmt::print(out, "    centre of mass     {} m (body reference frame)\n", vec(b.center_of_mass()));
    fmt::print(out, "    principal moments  {:.10g}  {:.10g}  {:.10g} kg*m^2 (ascending)\n", b.Lambda()(0),
               b.Lambda()(1), b.Lambda()(2));
    const Mat3& U = b.U();
    fmt::print(out, "    principal axes     {}  {}  {} (columns of U, reference frame)\n", vec(U.col(0)),
               vec(U.col(1)), vec(U.col(2)));
    fmt::print(out, "    initial velocity   {} m/s of the centre of mass (world)\n",
               vec(scene.initial.bodies[i].v));
  }
  for (const Particle& p : m.particles) fmt::print(out, "  particle '{}': mass {:.10g} kg\n", p.name, p.mass);
  for (const auto& f : m.forces) fmt::print(out, "  force        {}\n", f->describe(m.bodies));
  const Invariants inv = invariants(m, scene.initial);
  fmt::print(out, "  initial      kinetic energy {:.10g} J", inv.kinetic_energy);
  if (inv.potential_energy) {
    fmt::print(out, ", potential energy {:.10g} J, total {:.10g} J", *inv.potential_energy,
               *inv.total_energy());
  }
  fmt::print(out, "\n               linear momentum {} kg*m/s (world)\n", vec(inv.linear_momentum));
  fmt::print(out, "               angular momentum {} kg*m^2/s (world, about the origin)\n",
             vec(inv.angular_momentum));
  fmt::print(out, "  conserved    {}{}\n", conserved_list(scene.conserved),
             scene.settings.drift_threshold > 0
                 ? fmt::format(" (warns past a relative drift of {:g})", scene.settings.drift_threshold)
                 : std::string(" (drift warning off)"));
}

void print_scene_warnings(const Scene& scene, bool strict) {
  for (const auto& w : scene.warnings) fmt::print(stderr, "tumble: warning: {}\n", w);
  if (strict && !scene.warnings.empty()) {
    throw InvalidArgument(fmt::format(
        "{} warning{} about the scene, and --strict makes them errors: fix the scene (each warning says how) "
        "or drop --strict",
        scene.warnings.size(), scene.warnings.size() == 1 ? "" : "s"));
  }
}

}  // namespace tumble::cli
