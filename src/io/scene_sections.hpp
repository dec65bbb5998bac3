#pragma once
// The sections of a scene file, each read by its own source file (scene.cpp, scene_bodies.cpp,
// scene_forces.cpp) into the Scene under construction.
#include <filesystem>
#include <string>
#include <string_view>

#include "body_sections.hpp"
#include "name_table.hpp"
#include "scene_reader.hpp"

namespace tumble::scene {

/// The contents of a scene file (or another input it names: `what` says which, for messages); FileError
/// if it cannot be read.
std::string read_file(const std::filesystem::path& path, const char* what = "scene file");
/// The TOML of a scene file (or a part of one); a syntax error is a SceneError at its file:line:column.
toml::table parse_toml(std::string_view text, const TomlFile& file);

/// A scene's text parsed for read_scene(): the tree of all but its [[bodies]] sections, which are parsed
/// one at a time as the bodies are read (body_sections.hpp); or the tree of the whole text, where it is
/// not split (`sections` empty). The sections are views into the text.
struct ParsedScene {
  toml::table root;
  std::optional<BodySections> sections;
};
ParsedScene parse_scene_text(std::string_view text, const TomlFile& file);

/// The Scene of the scene file `text` from `path`: `root` and its [[bodies]] `sections` (views into
/// `text`, or null when `root` holds the bodies). load_scene() is read_file(), parse_scene_text() and
/// this, kept apart so that bench/scene_setup can time each stage.
Scene read_scene(const toml::table& root, const BodySections* sections, std::string&& text,
                 const std::filesystem::path& path);
/// The same for a tree of the whole text (an ensemble's runs).
inline Scene read_scene(const toml::table& root, std::string text, const std::filesystem::path& path) {
  return read_scene(root, nullptr, std::move(text), path);
}

/// The mass properties of one [[bodies]] table (shape, mesh, explicit inertia or parts) in its
/// reference frame, and a description of where they came from. Mesh warnings go to scene.warnings.
struct BodyMass {
  MassProperties properties;
  std::string source;
  /// Its surface for pictures (reference frame); null for given mass and inertia.
  std::shared_ptr<const TriangleMesh> display;
};
BodyMass read_body_mass(const TableReader& body, const std::filesystem::path& directory, Scene& scene);

/// [[bodies]]: mass properties, the rigid bodies and their initial states, from root's `bodies` or from
/// `sections` when there are. Mesh paths are relative to `directory`.
void read_bodies(const TableReader& root, const BodySections* sections,
                 const std::filesystem::path& directory, NameTable& names, Scene& scene,
                 const std::vector<CentralBody>& central);
/// [[body_tables]]: bodies from CSV files, a row each (scene_body_table.cpp).
void read_body_tables(const TableReader& root, const std::filesystem::path& directory, NameTable& names,
                      Scene& scene);
/// [[particles]].
void read_particles(const TableReader& root, NameTable& names, Scene& scene);
/// [world] gravity and [[forces]], which name bodies and particles by `names`; sets scene.conserved
/// from the force models present.
void read_forces(const TableReader& root, const NameTable& names, Scene& scene);
/// [[rotors]]: spinning rotors on the bodies, as one Rotors model after the forces.
void read_rotors(const TableReader& root, const NameTable& names, Scene& scene);
/// The central bodies of the [[forces]] of type gravity_gradient, read ahead of the bodies (whose
/// `orbit` is about one), in file order.
std::vector<CentralBody> central_bodies(const TableReader& root);

/// [[events]], which name bodies and particles by `names`.
std::vector<EventSpec> read_events(const TableReader& root, const NameTable& names, const Scene& scene);

/// Whether a body or particle name is non-empty and only letters, digits, '_', '-' and '.'.
bool valid_name(std::string_view name);
/// Checks a body or particle name of a TOML table (non-empty, letters, digits, '_', '-', '.') and records
/// it with its index and place; NameTable::seal() checks that it is unique.
void register_name(const TableReader& table, std::string_view name, bool is_particle, size_t index,
                   NameTable& names);

}  // namespace tumble::scene
