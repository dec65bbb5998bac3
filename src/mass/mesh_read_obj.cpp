// Wavefront OBJ: `v x y z` (further numbers, a weight or a colour, are ignored), `f` with three or
// more corners written i, i/t, i//n or i/t/n (1-based; negative counts back from the last vertex so
// far), `o` objects and `g` groups as parts. Everything else (vt, vn, usemtl, s, curves...) carries no
// geometry for the mass and is skipped; `l` and `p` are counted for the point-cloud message.
#include <fmt/format.h>
#include <map>

#include "mesh_text.hpp"

namespace tumble::mesh_text {
namespace {

/// Distinct names in order of first use; index 0 is the unnamed part before any o/g statement.
struct Names {
  std::vector<std::string> names{""};
  std::map<std::string, std::uint32_t, std::less<>> index{{"", 0}};
  std::uint32_t intern(std::string_view name) {
    const auto it = index.find(name);
    if (it != index.end()) return it->second;
    const auto k = static_cast<std::uint32_t>(names.size());
    names.emplace_back(name);
    index.emplace(std::string(name), k);
    return k;
  }
};

}  // namespace

RawMesh read_obj(const Text& text) {
  RawMesh mesh;
  Scanner s(text, /*hash_comments=*/true, /*continuation=*/true);
  Names objects, groups;
  bool any_object = false;
  std::uint32_t object = 0, group = 0;
  std::vector<std::uint32_t> triangle_group;  // the group of each triangle; part_of holds the object
  std::vector<std::uint32_t> corners;
  // A face may name a vertex defined later (a forward reference); the largest one is checked at the end.
  std::uint64_t max_forward = 0;
  std::size_t max_forward_pos = 0;

  while (s.skip_blank_lines()) {
    const Token key = s.word();
    if (key.text == "v") {
      const double x = next_double(text, s, "x coordinate");
      const double y = next_double(text, s, "y coordinate");
      const double z = next_double(text, s, "z coordinate");
      if (mesh.vertices.size() >= kMaxVertices) text.fail(key.pos, "more than 4294967294 vertices");
      mesh.vertices.push_back(text.point(x, y, z, key.pos));
    } else if (key.text == "f" || key.text == "fo") {
      corners.clear();
      for (Token t = s.word(); !t.empty(); t = s.word()) {
        const Token index{t.text.substr(0, t.text.find('/')), t.pos};
        const std::int64_t i = to_integer(text, index, "vertex index");
        const auto defined = static_cast<std::int64_t>(mesh.vertices.size());
        if (i == 0) text.fail(t.pos, "vertex index 0: OBJ counts vertices from 1 (or from -1 backwards)");
        if (i < 0 && -i > defined) {
          text.fail(t.pos, fmt::format("vertex index {} reaches back before the first vertex ({} defined "
                                       "so far)",
                                       i, defined));
        }
        const std::int64_t v = i > 0 ? i - 1 : defined + i;
        if (v >= static_cast<std::int64_t>(kMaxVertices)) text.fail(t.pos, "vertex index too large");
        if (v >= defined && static_cast<std::uint64_t>(v) >= max_forward) {
          max_forward = static_cast<std::uint64_t>(v) + 1;
          max_forward_pos = t.pos;
        }
        corners.push_back(static_cast<std::uint32_t>(v));
      }
      if (corners.size() < 3) {
        text.fail(key.pos, fmt::format("a face needs at least 3 corners, this one has {}{}", corners.size(),
                                       corners.size() == 2 ? " (a line is written 'l')" : ""));
      }
      add_polygon(mesh, corners, object);
      triangle_group.resize(mesh.triangles.size(), group);
    } else if (key.text == "o") {
      object = objects.intern(s.rest_of_line());
      any_object = true;
    } else if (key.text == "g") {
      const std::string_view name = s.rest_of_line();
      group = groups.intern(name.empty() ? "default" : name);
    } else if (key.text == "l" || key.text == "p") {
      ++mesh.ignored_elements;
    }
    s.next_line();
  }
  if (max_forward > mesh.vertices.size()) {
    text.fail(max_forward_pos, fmt::format("vertex index {} is past the last vertex: the file has {}",
                                           max_forward, mesh.vertices.size()));
  }

  // Parts: the objects if the file names any, else the groups; only those with faces count.
  if (!any_object) mesh.part_of = std::move(triangle_group);
  const std::vector<std::string>& names = any_object ? objects.names : groups.names;
  std::vector<std::uint32_t> renumber(names.size(), 0xffffffffu);
  for (std::uint32_t& p : mesh.part_of) {
    if (renumber[p] == 0xffffffffu) {
      renumber[p] = static_cast<std::uint32_t>(mesh.part_names.size());
      mesh.part_names.push_back(names[p].empty() ? "(unnamed)" : names[p]);
    }
    p = renumber[p];
  }
  mesh.part_word = any_object ? "object" : "group";
  return mesh;
}

}  // namespace tumble::mesh_text
