// Scene files: parsing (toml++), [simulation], and the order in which the sections are read.
#include "tumble/io/scene.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "scene_sections.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/mass/input_file.hpp"
#include "tumble/sim/output_fields.hpp"
#include "tumble/sim/run_settings.hpp"

namespace tumble {
namespace scene {
namespace {

/// [simulation]: every setting of sim/run_settings.hpp that a scene may give, checked as the table says.
void read_simulation(const TableReader& root, Scene& scene) {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k;
    for (const RunSetting& s : run_settings()) {
      if (s.in_scene) k.push_back(s.key);
    }
    return k;
  }();
  const auto sim = root.table("simulation", "[simulation]", Keys(keys));
  if (!sim) root.fail_here("missing [simulation]: give at least duration = T (s)");
  RunSettings& s = scene.settings;
  for (const RunSetting& setting : run_settings()) {
    if (!setting.in_scene) continue;
    const std::string key(setting.key);
    if (setting.kind == RunSetting::Kind::name) {
      const auto name = sim->string(key);
      if (!name) continue;
      const auto choices = setting.choices();
      if (std::find(choices.begin(), choices.end(), *name) == choices.end()) {
        const auto close = closest(std::string(*name), choices);
        sim->fail_at(key, fmt::format("unknown {} \"{}\"; {}choose one of: {}", key, *name,
                                      close ? fmt::format("did you mean \"{}\"? ", *close) : "",
                                      fmt::join(choices, ", ")));
      }
      setting.set(s, std::string(*name));
      continue;
    }
    const Domain domain = setting.range == RunSetting::Range::positive       ? Domain::positive
                          : setting.range == RunSetting::Range::non_negative ? Domain::non_negative
                                                                             : Domain::finite;
    const std::string unit(setting.unit);
    const double value =
        setting.scene_default == "required"
            ? sim->required_number(key, unit.c_str(), domain)
            : sim->number(key, std::stod(std::string(setting.scene_default)), unit.c_str(), domain);
    setting.set(s, value);
  }
}

/// [output] fields = ["position", ...]: what `tumble run` writes for each body unless --fields says;
/// unwrap_angles = true: Euler angles continuous from sample to sample.
void read_output(const TableReader& root, Scene& scene) {
  const auto out = root.table("output", "[output]", {"fields", "unwrap_angles"});
  if (!out) return;
  scene.unwrap_angles = out->boolean("unwrap_angles").value_or(false);
  if (!out->has("fields")) return;
  const toml::array* a = out->node("fields")->as_array();
  if (!a) out->fail_at("fields", "fields must be a list of field names, e.g. [\"position\", \"euler_zyx\"]");
  std::vector<std::string> names;
  for (const toml::node& n : *a) {
    const auto name = n.value<std::string>();
    if (!name) out->fail_at("fields", "fields must be a list of strings, e.g. [\"position\", \"euler_zyx\"]");
    names.push_back(*name);
  }
  try {
    body_fields(names);  // unknown or repeated names, with the list of fields
  } catch (const InvalidArgument& e) {
    out->fail_at("fields", e.what());
  }
  scene.output_fields = std::move(names);
}

/// The [output] fields that need the forces: those relative to the orbit frame need one central body.
void check_output_against_forces(const TableReader& root, const Scene& scene) {
  if (scene.output_fields.empty()) return;
  try {
    body_fields(scene.output_fields, scene.model);
  } catch (const InvalidArgument& e) {
    root.table("output", "[output]", {"fields", "unwrap_angles"})->fail_at("fields", e.what());
  }
}

}  // namespace

namespace {
/// A scene through a pipe (`tumble check <(generate)`, a named pipe being written): read to its end as a
/// stream, up to the input limit, waiting for the writer as `cat` would. A pipe that nobody writes (a
/// named pipe without a writer: the first read finds its end at once) is refused at once, never waited
/// on; devices stay refused (they may never end: read_input_file).
std::string read_pipe(const std::filesystem::path& path, const char* what) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    throw FileError(fmt::format("cannot read {} {}: {}", what, path.string(), std::strerror(errno)));
  const auto fail = [&](const std::string& why) {
    ::close(fd);
    throw FileError(fmt::format("cannot read {} {}: {}", what, path.string(), why));
  };
  const std::uint64_t limit = max_input_bytes();
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) {  // the writer is there and has not written yet
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, -1) < 0 && errno != EINTR) fail(std::strerror(errno));
      continue;
    }
    if (n < 0) fail(std::strerror(errno));
    if (n == 0) {
      if (text.empty()) {
        fail(
            "a FIFO (named pipe) with nothing written into it, which may never end, not a regular file; give "
            "a scene file, or write the scene into the pipe as tumble reads it (e.g. tumble check "
            "<(cat s.toml))");
      }
      break;
    }
    if (text.size() + static_cast<std::size_t>(n) > limit) {
      fail(
          fmt::format("the pipe gave more than tumble reads from one input ({} bytes); raise the limit with "
                      "{}, or save the stream to a file",
                      limit, kMaxInputBytesVariable));
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return text;
}
}  // namespace

std::string read_file(const std::filesystem::path& path, const char* what) {
  // A regular file within the input limit, or a pipe read as a stream: never a device that could be
  // read forever.
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISFIFO(st.st_mode)) return read_pipe(path, what);
  try {
    return read_input_file(path, what);
  } catch (const FileError& e) {
    throw FileError(fmt::format("cannot read {} {}", what, e.what()));
  }
}

/// Arrays and inline tables nested deeper than a scene ever needs are refused before toml++ parses
/// them: its parser recurses once per level (to its own limit of 256), and so does code that walks the
/// tree, and 256 levels overflow a small stack (ulimit -s 256, a Python thread's) — a crash. Strings and
/// comments are skipped, so brackets inside them do not count. Table headers ([a], [[a]]) open and close
/// on their line.
void check_nesting(std::string_view text, const TomlFile& file) {
  constexpr int kMaxNesting = 32;
  int depth = 0;
  toml::source_position at{1, 1};
  auto starts = [&](size_t i, std::string_view what) { return text.substr(i, what.size()) == what; };
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    // Skips to just past `close` (escapes honoured in basic strings), counting lines.
    auto skip_to = [&](std::string_view close, bool escapes) {
      for (++i; i < text.size() && !starts(i, close); ++i) {
        if (escapes && text[i] == '\\') ++i;
        if (i < text.size() && text[i] == '\n') at = {at.line + 1, 0};
      }
      i += close.size() - 1;
    };
    if (c == '#') {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
    } else if (starts(i, "\"\"\"")) {
      i += 2, skip_to("\"\"\"", true);
    } else if (starts(i, "'''")) {
      i += 2, skip_to("'''", false);
    } else if (c == '"') {
      skip_to("\"", true);
    } else if (c == '\'') {
      skip_to("'", false);
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxNesting) {
        fail(file, toml::source_region{at, at, nullptr},
             fmt::format("arrays and inline tables nested more than {} deep: a scene needs a few levels; "
                         "flatten the value",
                         kMaxNesting));
      }
    } else if (c == ']' || c == '}') {
      depth = std::max(0, depth - 1);
    }
    if (i < text.size() && text[i] == '\n') {
      at = {at.line + 1, 1};
    } else {
      ++at.column;
    }
  }
}

toml::table parse_toml(std::string_view text, const TomlFile& file) {
  check_nesting(text, file);
  try {
    return toml::parse(text);  // positions in the text; messages name `file`
  } catch (const toml::parse_error& e) {
    fail(file, e.source(), fmt::format("TOML syntax error: {}", e.description()));
  }
}

ParsedScene parse_scene_text(std::string_view text, const TomlFile& file) {
  if (auto split = split_body_sections(text)) {
    toml::table rest = parse_toml(split->rest, file);
    // A `bodies` the rest still defines (bodies = [...], [bodies] or a dotted key) is no TOML together
    // with [[bodies]] tables: parsed whole, the text gets toml++'s own message.
    if (!rest.contains("bodies")) return {std::move(rest), std::move(split)};
  }
  return {parse_toml(text, file), std::nullopt};
}

Scene read_scene(const toml::table& root, const BodySections* sections, std::string&& text,
                 const std::filesystem::path& path) {
  Scene scene;
  scene.path = path;
  scene.input_files.push_back(path);   // then every mesh, as it is read
  const TomlFile file{path.string()};  // for messages; outlives every reader
  const TableReader r(root, "scene", file,
                      {"simulation", "output", "world", "bodies", "body_tables", "particles", "forces",
                       "rotors", "events", "ensemble"});
  read_simulation(r, scene);
  read_output(r, scene);
  NameTable names(scene.model, file.name);
  read_bodies(r, sections, path.parent_path(), names, scene, central_bodies(r));
  read_body_tables(r, path.parent_path(), names, scene);
  read_particles(r, names, scene);
  names.seal();
  if (scene.model.bodies.empty() && scene.model.particles.empty()) {
    r.fail_here("the scene has nothing to simulate: add [[bodies]], [[body_tables]] or [[particles]]");
  }
  read_forces(r, names, scene);
  read_rotors(r, names, scene);
  check_output_against_forces(r, scene);
  scene.events = read_events(r, names, scene);
  scene.text = std::move(text);  // last: the sections are views into it
  return scene;
}

}  // namespace scene

Scene parse_scene(const std::string& text, const std::filesystem::path& path) {
  const scene::ParsedScene parsed = scene::parse_scene_text(text, scene::TomlFile{path.string()});
  return scene::read_scene(parsed.root, parsed.sections ? &*parsed.sections : nullptr, std::string(text),
                           path);
}

Scene load_scene(const std::filesystem::path& path) {
  std::string text = scene::read_file(path);
  const scene::ParsedScene parsed = scene::parse_scene_text(text, scene::TomlFile{path.string()});
  const scene::BodySections* sections = parsed.sections ? &*parsed.sections : nullptr;
  return scene::read_scene(parsed.root, sections, std::move(text), path);
}

}  // namespace tumble
