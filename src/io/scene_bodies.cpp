// [[bodies]] and [[particles]]: names, mass properties (scene_mass.cpp) and initial states.
#include <fmt/format.h>

#include <algorithm>

#include "scene_sections.hpp"
#include "tumble/dynamics/rigid_body.hpp"

namespace tumble::scene {

namespace {

std::vector<std::string> keys_of(const toml::table& table) {
  std::vector<std::string> keys;
  for (auto&& [k, v] : table) keys.emplace_back(k.str());
  return keys;
}

}  // namespace

void register_name(const TableReader& table, const std::string& name, NameTable& names) {
  // Names become CSV fields and HDF5 strings; keeping them to these characters means no quoting or
  // escaping anywhere a trajectory is read.
  const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
  });
  if (!ok) {
    table.fail_at(
        "name", fmt::format("name \"{}\" is not allowed: use letters, digits, '_', '-' and '.' only", name));
  }
  const toml::source_region& where = table.where("name");
  const auto [it, inserted] =
      names.emplace(name, fmt::format("line {}, column {}", where.begin.line, where.begin.column));
  if (!inserted) {
    table.fail_at("name", fmt::format("duplicate name \"{}\" (first defined at {}): give every body and "
                                      "particle its own name",
                                      name, it->second));
  }
}

void read_bodies(const TableReader& root, const std::filesystem::path& directory, NameTable& names,
                 Scene& scene) {
  const auto bodies = root.tables("bodies");
  for (size_t i = 0; i < bodies.size(); ++i) {
    const std::vector<std::string> keys = {"name",
                                           "shape",
                                           "mesh",
                                           "scale",
                                           "thickness",
                                           "parts",
                                           "inertia",
                                           "center_of_mass",
                                           "density",
                                           "mass",
                                           "position",
                                           "orientation",
                                           "velocity",
                                           "angular_velocity",
                                           "angular_velocity_frame"};
    // The name first (any keys allowed), so that every other message can name the body.
    const TableReader untitled(*bodies[i], fmt::format("[[bodies]] #{}", i + 1), root.file(),
                               keys_of(*bodies[i]));
    const std::string name = untitled.required_string("name", "the body a name, e.g. name = \"handle\"");
    register_name(untitled, name, names);
    const TableReader named(*bodies[i], fmt::format("body '{}'", name), root.file(),
                            keys);  // messages name it
    const BodyMass mass = read_body_mass(named, directory, scene);
    RigidBody rigid = [&] {
      try {
        return RigidBody::from_mass_properties(mass.properties, name);
      } catch (const InvalidMassProperties& e) {
        named.fail_at(named.has("inertia") ? "inertia" : "name", e.what());
      }
    }();
    const Vec3 position = named.vec3("position", Vec3::Zero(), "m");
    const Quat orientation = named.quaternion("orientation").value_or(Quat::Identity());
    const Vec3 velocity = named.vec3("velocity", Vec3::Zero(), "m/s");
    const Vec3 omega = named.vec3("angular_velocity", Vec3::Zero(), "rad/s");
    const Frame omega_frame = named.frame("angular_velocity_frame", Frame::world);
    scene.initial.bodies.push_back(
        state_from_reference(rigid, position, orientation, velocity, omega, omega_frame));
    scene.model.add_body(std::move(rigid));
    scene.body_info.push_back({mass.source, mass.properties});
  }
}

void read_particles(const TableReader& root, NameTable& names, Scene& scene) {
  const auto particles = root.tables("particles");
  for (size_t i = 0; i < particles.size(); ++i) {
    const std::vector<std::string> keys = {"name", "mass", "position", "velocity"};
    const TableReader untitled(*particles[i], fmt::format("[[particles]] #{}", i + 1), root.file(),
                               keys_of(*particles[i]));
    const std::string name = untitled.required_string("name", "the particle a name, e.g. name = \"p1\"");
    register_name(untitled, name, names);
    const TableReader p(*particles[i], fmt::format("particle '{}'", name), root.file(), keys);
    scene.model.add_particle(Particle{name, p.required_number("mass", "kg", Domain::positive)});
    scene.initial.particles.push_back(
        ParticleState{p.vec3("position", Vec3::Zero(), "m"), p.vec3("velocity", Vec3::Zero(), "m/s")});
  }
}

}  // namespace tumble::scene
