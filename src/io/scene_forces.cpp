// [world] gravity and [[forces]]: the force models of forces.hpp, and which invariants they conserve.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string_view>

#include "scene_sections.hpp"
#include "tumble/dynamics/quantities.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/forces/rotors.hpp"

namespace tumble::scene {
namespace {

/// The index of the body named by `key` in t.
size_t body_index(const TableReader& t, std::string_view key, const NameTable& names, const Scene& scene) {
  const std::string_view name = *t.string(key);
  if (const auto* found = names.find(name)) {
    if (!found->is_particle) return found->index;
    t.fail_at(key, fmt::format("\"{}\" is a particle; this force acts on rigid bodies only", name));
  }
  std::vector<std::string> bodies;
  for (const RigidBody& b : scene.model.bodies) bodies.push_back(b.name());
  const auto s = closest(std::string(name), bodies);
  t.fail_at(key, fmt::format("no body named \"{}\"; {}", name,
                             s                ? fmt::format("did you mean \"{}\"?", *s)
                             : bodies.empty() ? std::string("the scene has no [[bodies]]")
                                              : fmt::format("the bodies are: {}", fmt::join(bodies, ", "))));
}

/// The index of the particle named by `key` in t.
size_t particle_index(const TableReader& t, std::string_view key, const NameTable& names,
                      const Scene& scene) {
  const std::string_view name = *t.string(key);
  if (const auto* found = names.find(name); found && found->is_particle) return found->index;
  std::vector<std::string> particles;
  for (const Particle& p : scene.model.particles) particles.push_back(p.name);
  const auto s = closest(std::string(name), particles);
  t.fail_at(key, fmt::format("no particle named \"{}\"; {}", name,
                             s ? fmt::format("did you mean \"{}\"?", *s)
                             : particles.empty()
                                 ? std::string("the scene has no [[particles]]")
                                 : fmt::format("the particles are: {}", fmt::join(particles, ", "))));
}

size_t required_body(const TableReader& t, const NameTable& names, const Scene& scene) {
  if (!t.has("body")) t.fail_here("missing 'body': name the body this force acts on");
  return body_index(t, "body", names, scene);
}

Vec3 required_vec3(const TableReader& t, std::string_view key, const char* unit) {
  const auto v = t.vec3(key, unit);
  if (!v) t.fail_here(fmt::format("missing '{}': give [x, y, z] ({})", key, unit));
  return *v;
}

Spring::End spring_end(const TableReader& spring, std::string_view key, const NameTable& names,
                       const Scene& scene, bool& anchored) {
  const auto end =
      spring.table(key, spring.context().child(" end ", key), {"body", "point", "anchor", "particle"});
  if (!end) {
    spring.fail_here(
        fmt::format("missing '{}': give {} = {{ body = \"NAME\", point = [x, y, z] }}, "
                    "{} = {{ particle = \"NAME\" }} or {} = {{ anchor = [x, y, z] }}",
                    key, key, key, key));
  }
  end->at_most_one_of({"body", "anchor", "particle"});
  if (end->has("particle")) {
    if (end->has("point")) end->fail_at("point", "point goes with body; a particle is a point by itself");
    return Spring::End{all_bodies, Vec3::Zero(), particle_index(*end, "particle", names, scene)};
  }
  if (end->has("anchor")) {
    if (end->has("point"))
      end->fail_at("point", "point goes with body; an anchor is a world point by itself");
    anchored = true;
    return Spring::End{all_bodies, *end->vec3("anchor", "m")};
  }
  if (!end->has("body")) {
    end->fail_here("give body = \"NAME\" (with point), particle = \"NAME\" or anchor = [x, y, z] (world, m)");
  }
  const size_t i = body_index(*end, "body", names, scene);
  // Default: the body's centre of mass (in its reference frame), where a spring exerts no torque.
  return Spring::End{i, end->vec3("point", scene.model.bodies[i].center_of_mass(), "m")};
}

}  // namespace

namespace {
/// A gravity_gradient table's central body: μ and the centre.
CentralBody read_central_body(const TableReader& t) {
  const double mu = t.required_number("mu", "m^3/s^2", Domain::positive);
  return {t.vec3("center", Vec3::Zero(), "m"), mu};
}
}  // namespace

std::vector<CentralBody> central_bodies(const TableReader& root) {
  std::vector<CentralBody> out;
  const auto forces = root.tables("forces");
  for (size_t i = 0; i < forces.size(); ++i) {
    if ((*forces[i])["type"].value<std::string>() != "gravity_gradient") continue;
    const TableReader t(*forces[i],
                        Context::numbered("[[forces]] #", i + 1).child(" (", "gravity_gradient", ")"),
                        root.file(), {"mu", "center", "torque_only", "type"});
    out.push_back(read_central_body(t));
  }
  return out;
}

void read_forces(const TableReader& root, const NameTable& names, Scene& scene) {
  Conservation& c = scene.conserved;
  c = Conservation{};
  auto external = [&c] {  // a force from outside the system: momenta change
    c.linear_momentum = false;
    c.angular_momentum = false;
  };
  if (const auto world = root.table("world", "[world]", {"gravity"})) {
    const Vec3 g = world->vec3("gravity", Vec3::Zero(), "m/s^2");
    if (g != Vec3::Zero()) {
      scene.model.add_force<UniformGravity>(g);
      external();  // conservative: the energy includes −m g·x
    }
  }

  constexpr std::array<std::string_view, 6> types = {"force", "torque", "damping",
                                                     "drag",  "spring", "gravity_gradient"};
  const auto forces = root.tables("forces");
  for (size_t i = 0; i < forces.size(); ++i) {
    const TableReader any(*forces[i], Context::numbered("[[forces]] #", i + 1), root.file(),
                          {"type", "body", "force", "frame", "point", "point_frame", "torque", "linear",
                           "angular", "a", "b", "stiffness", "rest_length", "damping", "mu", "center",
                           "torque_only"});
    if (!any.has("type")) {
      any.fail_here(fmt::format("missing 'type': give the kind: type = \"{}\"", fmt::join(types, "\" | \"")));
    }
    const std::string_view type = *any.string("type");
    // The keys of this type, then "type".
    auto reader = [&](Keys keys) {
      return TableReader(*forces[i], any.context().child(" (", type, ")"), root.file(), keys);
    };
    if (type == "force") {
      const auto t = reader({"body", "force", "frame", "point", "point_frame", "type"});
      const size_t b = required_body(t, names, scene);
      const Vec3 f = required_vec3(t, "force", "N");
      const Frame frame = t.frame("frame", Frame::world);
      const Frame point_frame = t.frame("point_frame", Frame::reference);
      if (point_frame == Frame::world && !t.has("point")) {
        t.fail_here("point_frame = \"world\" needs point = [x, y, z] (world, m)");
      }
      const Vec3 point = t.vec3("point", scene.model.bodies[b].center_of_mass(), "m");
      scene.model.add_force<PointForce>(b, f, frame, point, point_frame);
      c = Conservation{false, false, false};
    } else if (type == "torque") {
      const auto t = reader({"body", "torque", "frame", "type"});
      const size_t b = required_body(t, names, scene);
      scene.model.add_force<PureTorque>(b, required_vec3(t, "torque", "N*m"), t.frame("frame", Frame::world));
      c = Conservation{false, false, false};
    } else if (type == "damping" || type == "drag") {
      const auto t = reader({"body", "linear", "angular", "type"});
      const size_t b = t.has("body") ? body_index(t, "body", names, scene) : all_bodies;
      const bool damping = type == "damping";
      const double linear = t.number("linear", 0.0, damping ? "N*s/m" : "kg/m", Domain::non_negative);
      const double angular = t.number("angular", 0.0, damping ? "N*m*s" : "kg*m^2", Domain::non_negative);
      if (linear == 0 && angular == 0) t.fail_here("give linear and/or angular coefficients (> 0)");
      if (damping) {
        scene.model.add_force<ViscousDamping>(b, linear, angular);
      } else {
        scene.model.add_force<QuadraticDrag>(b, linear, angular);
      }
      c = Conservation{false, false, false};
    } else if (type == "spring") {
      const auto t = reader({"a", "b", "stiffness", "rest_length", "damping", "type"});
      bool anchored = false;
      const Spring::End a = spring_end(t, "a", names, scene, anchored);
      const Spring::End b = spring_end(t, "b", names, scene, anchored);
      const auto is_anchor = [](const Spring::End& e) {
        return e.body == all_bodies && e.particle == all_bodies;
      };
      if (is_anchor(a) && is_anchor(b))
        t.fail_here("both ends are anchors: attach one to a body or a particle");
      // Within one rigid body the pair of forces cancels: a spring that does nothing is a mistake.
      if (a.body != all_bodies && a.body == b.body) {
        t.fail_at("b", fmt::format("both ends are on body '{}': within one rigid body the spring's forces "
                                   "cancel and it does nothing; attach b to another body, a particle or "
                                   "an anchor",
                                   scene.model.bodies[a.body].name()));
      }
      if (a.particle != all_bodies && a.particle == b.particle)
        t.fail_at("b", "both ends are the same particle: attach b to another particle, a body or an anchor");
      const double k = t.required_number("stiffness", "N/m", Domain::positive);
      const double rest = t.number("rest_length", 0.0, "m", Domain::non_negative);
      // Ends that coincide give the spring no direction to push in: at rest length 0 that is its rest,
      // at any other it would be a compressed spring exerting nothing (Spring::accumulate).
      const auto start = [&](const Spring::End& e) -> Vec3 {
        if (e.particle != all_bodies) return scene.initial.particles[e.particle].x;
        if (e.body == all_bodies) return e.point;
        return point_position(scene.model.bodies[e.body], scene.initial.bodies[e.body], e.point);
      };
      if (rest > 0 && start(a) == start(b)) {
        const Vec3 x = start(a);
        t.fail_at("rest_length",
                  fmt::format("the ends coincide at the start (both at ({:g}, {:g}, {:g}) m) while the rest "
                              "length is {:g} m: the spring has no direction to push in; move an end apart "
                              "or give rest_length = 0",
                              x.x(), x.y(), x.z(), rest));
      }
      const double damping = t.number("damping", 0.0, "N*s/m", Domain::non_negative);
      scene.model.add_force<Spring>(a, b, k, rest, damping);
      if (damping > 0) c.energy = false;
      if (anchored) external();  // between two bodies the pair of forces is internal and central
    } else if (type == "gravity_gradient") {
      const auto t = reader({"mu", "center", "torque_only", "type"});
      const CentralBody central = read_central_body(t);
      const bool torque_only = t.boolean("torque_only").value_or(false);
      scene.model.add_force<GravityGradient>(central.mu, central.center, torque_only);
      c.linear_momentum = false;
      // The potential is invariant under rotations about `center`, so angular momentum about it is
      // conserved; the monitor measures about the world origin.
      if (central.center != Vec3::Zero()) c.angular_momentum = false;
      // The torque without its force is not the gradient of the potential: nothing is conserved.
      if (torque_only) c = Conservation{false, false, false};
    } else {
      const auto s = closest(std::string(type), {types.begin(), types.end()});
      any.fail_at("type", fmt::format("unknown force type \"{}\"; {}", type,
                                      s ? fmt::format("did you mean \"{}\"?", *s)
                                        : fmt::format("choose \"{}\"", fmt::join(types, "\", \""))));
    }
  }
}

/// [[rotors]]: spinning rotors on bodies (forces/rotors.hpp), one Rotors model for all of them.
void read_rotors(const TableReader& root, const NameTable& names, Scene& scene) {
  const auto tables = root.tables("rotors");
  if (tables.empty()) return;
  std::vector<Rotor> rotors;
  std::vector<std::string> seen;
  for (size_t i = 0; i < tables.size(); ++i) {
    const auto untitled =
        TableReader::any_keys(*tables[i], Context::numbered("[[rotors]] #", i + 1), root.file());
    const std::string_view name =
        untitled.required_string("name", "the rotor a name, e.g. name = \"wheel_x\"");
    const TableReader t(*tables[i], Context::named("rotor", name), root.file(),
                        {"name", "body", "axis", "moment", "speed", "torque", "max_speed", "max_torque"});
    // The name heads CSV columns (rotor_speed_<name>): nothing a column name must not hold.
    if (name.empty() || std::any_of(name.begin(), name.end(), [](char c) {
          return !(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.');
        })) {
      t.fail_at("name", fmt::format("rotor name \"{}\": use letters, digits, '_', '-' and '.' only (it "
                                    "names output columns, e.g. rotor_speed_wheel_x)",
                                    name));
    }
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
      t.fail_at("name", fmt::format("a second rotor named \"{}\": give each rotor its own name", name));
    }
    seen.emplace_back(name);
    Rotor r;
    r.name = std::string(name);
    r.body = required_body(t, names, scene);
    r.axis = required_vec3(t, "axis", "");
    if (!(std::abs(r.axis.norm() - 1.0) <= 1e-6)) {
      t.fail_at("axis",
                fmt::format("axis must be a unit vector (the spin axis in the body's reference frame); "
                            "its length is {:.6g}{}",
                            r.axis.norm(),
                            r.axis.norm() > 0
                                ? fmt::format(": normalised it would be [{:.6g}, {:.6g}, {:.6g}]",
                                              r.axis.x() / r.axis.norm(), r.axis.y() / r.axis.norm(),
                                              r.axis.z() / r.axis.norm())
                                : std::string()));
    }
    r.moment = t.required_number("moment", "kg*m^2", Domain::positive);
    r.speed = t.number("speed", 0.0, "rad/s");
    if (const toml::node* table = t.node("torque"); table && table->is_array()) {
      // [[t, u], ...]: u (N m) linear between the times t (s), held before the first and after the last.
      const toml::array& rows = *table->as_array();
      for (size_t k = 0; k < rows.size(); ++k) {
        const toml::array* row = rows.get(k)->as_array();
        if (!row || row->size() != 2) {
          t.fail_at("torque",
                    fmt::format("torque row {} must be [t, u] (s, N*m): a table is [[t0, u0], [t1, u1], "
                                "...], u linear between the times",
                                k));
        }
        const double at =
            number_value(t, *row->get(0), {"torque", static_cast<int>(k), 0}, "s", Domain::finite);
        const double u =
            number_value(t, *row->get(1), {"torque", static_cast<int>(k), 1}, "N*m", Domain::finite);
        if (k > 0 && !(at > r.torque_table.back().first)) {
          t.fail_at("torque",
                    fmt::format("torque row {}: t = {} s does not follow {} s: give the times increasing", k,
                                at, r.torque_table.back().first));
        }
        r.torque_table.emplace_back(at, u);
      }
    } else {
      r.torque = t.number("torque", 0.0, "N*m");
    }
    r.max_speed = t.number("max_speed", 0.0, "rad/s", Domain::non_negative);
    if (r.max_speed > 0.0 && !r.torque_table.empty()) {
      t.fail_at("max_speed", "max_speed goes with a constant torque; a torque table sets the speeds itself");
    }
    if (r.max_speed > 0.0 && std::abs(r.speed) > r.max_speed) {
      t.fail_at("speed",
                fmt::format("speed = {} rad/s is beyond max_speed = {} rad/s", r.speed, r.max_speed));
    }
    r.max_torque = t.number("max_torque", 0.0, "N*m", Domain::non_negative);
    if (r.max_torque > 0.0 && std::abs(r.torque) > r.max_torque) {
      t.fail_at("torque",
                fmt::format("torque = {} N*m is beyond max_torque = {} N*m", r.torque, r.max_torque));
    }
    for (size_t k = 0; k < r.torque_table.size(); ++k) {
      if (r.max_torque > 0.0 && std::abs(r.torque_table[k].second) > r.max_torque) {
        t.fail_at("torque", fmt::format("torque row {} asks {} N*m, beyond max_torque = {} N*m", k,
                                        r.torque_table[k].second, r.max_torque));
      }
    }
    rotors.push_back(std::move(r));
  }
  auto model = std::make_shared<const Rotors>(std::move(rotors), scene.model.bodies);
  // Internal: momenta stay conserved; the bodies' kinetic energy only while no motor works.
  if (model->motors_work()) scene.conserved.energy = false;
  scene.model.forces.push_back(std::move(model));
}

}  // namespace tumble::scene
