// [[bodies]] and [[particles]]: names, mass properties (scene_mass.cpp) and initial states.
#include <fmt/format.h>

#include <algorithm>
#include <numbers>
#include <optional>

#include "scene_sections.hpp"
#include "tumble/dynamics/orbit_frame.hpp"
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
/// `orbit = { a, e, i, raan, argp, nu }` (m, rad): the centre of mass's orbit about the central body.
OrbitalElements read_orbit(const TableReader& body) {
  const auto t = body.table("orbit", body.context().child(" orbit"), {"a", "e", "i", "raan", "argp", "nu"});
  OrbitalElements k;
  k.a = t->required_number("a", "m", Domain::positive);
  k.e = t->number("e", 0.0, "");
  if (!(k.e >= 0.0 && k.e < 1.0)) {
    t->fail_at("e",
               fmt::format("e = {} is not an ellipse's eccentricity: give 0 <= e < 1 (open orbits are not "
                           "supported; give position and velocity instead)",
                           k.e));
  }
  k.i = t->number("i", 0.0, "rad");
  if (!(k.i >= 0.0 && k.i <= std::numbers::pi)) {
    t->fail_at("i", fmt::format("i = {} rad is not an inclination: give 0 <= i <= pi (rad)", k.i));
  }
  k.raan = t->number("raan", 0.0, "rad");
  k.argp = t->number("argp", 0.0, "rad");
  k.nu = t->number("nu", 0.0, "rad");
  return k;
}

/// A body placed on its orbit: the centre of mass at centre + r with velocity v (orbit_state), the
/// attitude and angular velocity given in world axes or relative to the orbit frame LVLH
/// (orientation_frame, angular_velocity_frame = "lvlh": R_ref = R_lvlh R_given, ω = Ω_lvlh + R_ref ω_given
/// — the inverse of the output fields euler_zyx_lvlh/mrp_lvlh and angular_velocity_lvlh).
BodyState on_orbit(const TableReader& named, const RigidBody& rigid, const CentralBody& central,
                   Quat orientation, bool orientation_lvlh, const Vec3& omega,
                   std::optional<Frame> omega_frame) {
  const auto [r, v] = orbit_state(central.mu, read_orbit(named));
  const std::optional<Quat> lvlh = lvlh_orientation(r, v);
  if (!lvlh) named.fail_at("orbit", "the orbit has no plane (r x v = 0): check a and e");
  if (orientation_lvlh) orientation = (*lvlh * orientation).normalized();
  BodyState s = state_from_reference(rigid, Vec3::Zero(), orientation, Vec3::Zero(), omega,
                                     omega_frame.value_or(Frame::reference));
  if (!omega_frame) s.omega_w = lvlh_angular_velocity(r, v) + orientation * omega;  // relative to LVLH
  s.o = central.center + r;
  s.v = v;
  return s;
}

void read_body(const toml::table& body, size_t number, const TomlFile& file,
               const std::filesystem::path& directory, NameTable& names, Scene& scene,
               const std::vector<CentralBody>& central) {
  // The name first (any keys allowed), so that every other message can name the body.
  const auto untitled = TableReader::any_keys(body, Context::numbered("[[bodies]] #", number), file);
  const std::string_view name = untitled.required_string("name", "the body a name, e.g. name = \"handle\"");
  register_name(untitled, name, false, scene.model.bodies.size(), names);
  const TableReader named(body, Context::named("body", name), file,
                          {"name", "shape", "mesh", "scale", "thickness", "parts", "inertia",
                           "center_of_mass", "density", "mass", "position", "orientation", "velocity",
                           "velocity_of", "angular_velocity", "angular_velocity_frame", "orbit",
                           "orientation_frame"});
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
  // Relative to the orbit frame ("lvlh") only for a body given its orbit: LVLH is that of the centre of
  // mass, which the orbit places.
  const std::string_view orientation_frame = named.string("orientation_frame").value_or("world");
  if (orientation_frame != "world" && orientation_frame != "lvlh") {
    named.fail_at(
        "orientation_frame",
        fmt::format("orientation_frame must be \"world\" (the default) or \"lvlh\" (relative to the "
                    "orbit frame: z to the central body, y opposite the orbit normal), found \"{}\"",
                    orientation_frame));
  }
  // (Each key looked up once: a scene of 10⁵ bodies reads these for every one.)
  const std::optional<std::string_view> omega_frame_name = named.string("angular_velocity_frame");
  const bool omega_lvlh = omega_frame_name == "lvlh";
  const Frame omega_frame =
      omega_frame_name && !omega_lvlh ? named.frame("angular_velocity_frame", Frame::world) : Frame::world;
  const bool has_orbit = named.has("orbit");
  const bool lvlh = orientation_frame == "lvlh" || omega_lvlh;
  if (lvlh && !has_orbit) {
    named.fail_at(orientation_frame == "lvlh" ? "orientation_frame" : "angular_velocity_frame",
                  "\"lvlh\" is relative to the orbit frame of the centre of mass: give the body its orbit, "
                  "orbit = { a = ..., e = ..., i = ..., raan = ..., argp = ..., nu = ... } (m, rad)");
  }
  if (has_orbit) {
    for (const char* key : {"position", "velocity", "velocity_of"}) {
      if (named.has(key)) {
        named.fail_at(key, fmt::format("{} and orbit both place the body: give one of them", key));
      }
    }
    if (central.empty()) {
      named.fail_at(
          "orbit",
          "an orbit is about a central body: add [[forces]] type = \"gravity_gradient\" with its mu "
          "(and center)");
    }
    for (const CentralBody& c : central) {
      if (c.center != central[0].center || c.mu != central[0].mu) {
        named.fail_at("orbit",
                      "the scene has two central bodies (gravity_gradient forces with different mu "
                      "or center): an orbit needs one");
      }
    }
    scene.initial.bodies.push_back(on_orbit(named, rigid, central[0], orientation,
                                            orientation_frame == "lvlh", omega,
                                            omega_lvlh ? std::nullopt : std::optional<Frame>(omega_frame)));
    scene.model.add_body(std::move(rigid));
    scene.body_info.push_back(
        {std::make_shared<const std::string>(std::move(mass.source)), std::move(mass.display)});
    return;
  }
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
                 const std::filesystem::path& directory, NameTable& names, Scene& scene,
                 const std::vector<CentralBody>& central) {
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
      read_body(*bodies[i], i + 1, root.file(), directory, names, scene, central);
    return;
  }
  // A section at a time: its tree is freed before the next one is parsed (body_sections.hpp).
  size_t number = 0;
  for (const BodySections::Section& section : sections->sections) {
    const TomlFile file{root.file().name, section.first_line};
    const toml::table tree = parse_toml(section.text, file);
    for (const toml::table* body : TableReader::any_keys(tree, "scene", file).tables("bodies")) {
      read_body(*body, ++number, file, directory, names, scene, central);
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
