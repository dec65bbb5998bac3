#pragma once
// The sections of a scene file, each read by its own source file (scene.cpp, scene_bodies.cpp,
// scene_forces.cpp) into the Scene under construction.
#include <filesystem>
#include <map>
#include <string>

#include "scene_reader.hpp"

namespace tumble::scene {

/// The TOML of a scene file; a syntax error is a SceneError at its file:line:column.
toml::table parse_toml(const std::string& text, const std::string& file);
/// The Scene of a parsed scene file `text` read from `path`: parse_scene() is parse_toml() then this.
/// Apart so that bench/scene_setup can time the two stages.
Scene read_scene(const toml::table& root, const std::string& text, const std::filesystem::path& path);

/// Names of bodies and particles seen so far → where they were defined ("line:column"), so that a
/// duplicate can say where the first one is. Bodies and particles share one namespace: both are rows
/// of the same trajectory.
using NameTable = std::map<std::string, std::string>;

/// The mass properties of one [[bodies]] table (shape, mesh, explicit inertia or parts) in its
/// reference frame, and a description of where they came from. Mesh warnings go to scene.warnings.
struct BodyMass {
  MassProperties properties;
  std::string source;
};
BodyMass read_body_mass(const TableReader& body, const std::filesystem::path& directory, Scene& scene);

/// [[bodies]]: mass properties, the rigid bodies and their initial states. Mesh paths are relative to
/// `directory`.
void read_bodies(const TableReader& root, const std::filesystem::path& directory, NameTable& names,
                 Scene& scene);
/// [[particles]].
void read_particles(const TableReader& root, NameTable& names, Scene& scene);
/// [world] gravity and [[forces]]; sets scene.conserved from the force models present.
void read_forces(const TableReader& root, Scene& scene);

/// Checks a body or particle name (non-empty, letters, digits, '_', '-', '.', unique) and records it.
void register_name(const TableReader& table, const std::string& name, NameTable& names);

}  // namespace tumble::scene
