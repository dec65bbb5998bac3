// [[bodies]] and [[particles]]: names, mass properties (scene_mass.cpp) and initial states.
#include <fmt/format.h>

#include <algorithm>

#include "scene_sections.hpp"
#include "tumble/dynamics/rigid_body.hpp"
#include "tumble/math/huge_pages.hpp"

namespace tumble::scene {

bool valid_name(std::string_view name) {
  // Names become CSV fields and HDF5 strings; keeping them to these characters means no quoting or
  // escaping anywhere a trajectory is read.
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
  });
}

void register_name(const TableReader& table, std::string_view name, bool is_particle, size_t index,
                   NameTable& names) {
  if (!valid_name(name)) {
    table.fail_at(
        "name", fmt::format("name \"{}\" is not allowed: use letters, digits, '_', '-' and '.' only", name));
  }
  const toml::source_position at = table.file().in_file(table.where("name").begin);
  names.add(name, is_particle, index, 0, at.line, at.column);
}

namespace {

/// The [[bodies]] table `body`, the `number`-th (from 1), of the text `file` describes.
void read_body(const toml::table& body, size_t number, const TomlFile& file,
               const std::filesystem::path& directory, NameTable& names, Scene& scene) {
  // The name first (any keys allowed), so that every other message can name the body.
  const auto untitled = TableReader::any_keys(body, Context::numbered("[[bodies]] #", number), file);
  const std::string_view name = untitled.required_string("name", "the body a name, e.g. name = \"handle\"");
  register_name(untitled, name, false, scene.model.bodies.size(), names);
  const TableReader named(body, Context::named("body", name), file,
                          {"name", "shape", "mesh", "scale", "thickness", "parts", "inertia",
                           "center_of_mass", "density", "mass", "position", "orientation", "velocity",
                           "velocity_of", "angular_velocity", "angular_velocity_frame"});
  BodyMass mass = read_body_mass(named, directory, scene);
  RigidBody rigid = [&] {
    try {
      return RigidBody::from_mass_properties(mass.properties, std::string(name));
    } catch (const InvalidMassProperties& e) {
      named.fail_at(named.has("inertia") ? "inertia" : "name", e.what());
    }
  }();
  const Vec3 position = named.vec3("position", Vec3::Zero(), "m");
  const Quat orientation = named.rotation("orientation", &scene.warnings).value_or(Quat::Identity());
  const Vec3 velocity = named.vec3("velocity", Vec3::Zero(), "m/s");
  const Vec3 omega = named.vec3("angular_velocity", Vec3::Zero(), "rad/s");
  const Frame omega_frame = named.frame("angular_velocity_frame", Frame::world);
  BodyState state = state_from_reference(rigid, position, orientation, velocity, omega, omega_frame);
  // `velocity` is that of the reference origin unless velocity_of = "com" says it is the centre of
  // mass's (an off-centre part spun "at rest" then stays in place).
  const std::string_view velocity_of = named.string("velocity_of").value_or("origin");
  if (velocity_of == "com") {
    state.v = velocity;
  } else if (velocity_of != "origin") {
    named.fail_at("velocity_of",
                  fmt::format("velocity_of must be \"origin\" (the reference frame's origin, the default) "
                              "or \"com\" (the centre of mass), found \"{}\"",
                              velocity_of));
  }
  scene.initial.bodies.push_back(state);
  scene.model.add_body(std::move(rigid));
  scene.body_info.push_back(
      {std::make_shared<const std::string>(std::move(mass.source)), std::move(mass.display)});
}

}  // namespace

void read_bodies(const TableReader& root, const BodySections* sections,
                 const std::filesystem::path& directory, NameTable& names, Scene& scene) {
  const size_t count = sections ? sections->bodies : root.tables("bodies").size();
  names.reserve(count);
  scene.model.bodies.reserve(count);
  scene.initial.bodies.reserve(count);
  scene.body_info.reserve(count);
  prefer_huge_pages(scene.model.bodies);
  prefer_huge_pages(scene.initial.bodies);
  prefer_huge_pages(scene.body_info);
  if (!sections) {
    const auto bodies = root.tables("bodies");
    for (size_t i = 0; i < bodies.size(); ++i)
      read_body(*bodies[i], i + 1, root.file(), directory, names, scene);
    return;
  }
  // A section at a time: its tree is freed before the next one is parsed (body_sections.hpp).
  size_t number = 0;
  for (const BodySections::Section& section : sections->sections) {
    const TomlFile file{root.file().name, section.first_line};
    const toml::table tree = parse_toml(section.text, file);
    for (const toml::table* body : TableReader::any_keys(tree, "scene", file).tables("bodies")) {
      read_body(*body, ++number, file, directory, names, scene);
    }
  }
}

void read_particles(const TableReader& root, NameTable& names, Scene& scene) {
  const auto particles = root.tables("particles");
  names.reserve(particles.size());
  for (size_t i = 0; i < particles.size(); ++i) {
    const auto untitled =
        TableReader::any_keys(*particles[i], Context::numbered("[[particles]] #", i + 1), root.file());
    const std::string_view name = untitled.required_string("name", "the particle a name, e.g. name = \"p1\"");
    register_name(untitled, name, true, scene.model.particles.size(), names);
    const TableReader p(*particles[i], Context::named("particle", name), root.file(),
                        {"name", "mass", "position", "velocity"});
    scene.model.add_particle(Particle{std::string(name), p.required_number("mass", "kg", Domain::positive)});
    scene.initial.particles.push_back(
        ParticleState{p.vec3("position", Vec3::Zero(), "m"), p.vec3("velocity", Vec3::Zero(), "m/s")});
  }
}

}  // namespace tumble::scene
