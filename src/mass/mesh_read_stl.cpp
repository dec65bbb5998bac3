// ASCII STL: one or more `solid NAME ... endsolid NAME`, each a list of
//   facet normal nx ny nz / outer loop / vertex x y z (three or more) / endloop / endfacet.
// Keywords in any case. Each solid with facets is a part. The normal is not used (the winding says
// which side is out) and may be anything, even nan. Corners are stored per facet and welded later.
#include <algorithm>
#include <fmt/format.h>

#include "mesh_text.hpp"

namespace tumble::mesh_text {
namespace {

bool is(std::string_view word, std::string_view keyword) {
  return word.size() == keyword.size() &&
         std::equal(word.begin(), word.end(), keyword.begin(),
                    [](char a, char b) { return (a >= 'A' && a <= 'Z' ? a - 'A' + 'a' : a) == b; });
}

void expect(const Text& text, Scanner& s, std::string_view keyword, std::string_view after) {
  const Token t = s.any_word();
  if (!is(t.text, keyword)) {
    text.fail(t.pos,
              t.empty() ? fmt::format("the file ends where '{}' should follow {}", keyword, after)
                        : fmt::format("expected '{}' after {}, found '{}'", keyword, after, excerpt(t.text)));
  }
}

double coordinate(const Text& text, Scanner& s, std::string_view what) {
  const Token t = s.any_word();
  if (t.empty()) text.fail(t.pos, fmt::format("the file ends where the {} should be", what));
  return to_double(text, t, what);
}

}  // namespace

RawMesh read_ascii_stl(const Text& text) {
  RawMesh mesh;
  mesh.part_word = "solid";
  Scanner s(text, /*hash_comments=*/false, /*continuation=*/false);
  std::vector<std::uint32_t> corners;
  std::vector<std::string> names;
  for (Token t = s.any_word(); !t.empty(); t = s.any_word()) {
    if (!is(t.text, "solid")) {
      text.fail(t.pos, fmt::format("expected 'solid' to start a solid, found '{}'", excerpt(t.text)));
    }
    const std::size_t solid_pos = t.pos;
    const std::string name(s.rest_of_line());
    const auto part = static_cast<std::uint32_t>(names.size());
    names.push_back(name);
    std::size_t facets = 0;
    while (true) {
      const Token k = s.any_word();
      if (k.empty()) {
        mesh.warnings.push_back(
            fmt::format("{}: the solid '{}' has no 'endsolid' (a truncated file?); its {} "
                        "complete facets were read",
                        text.where(solid_pos), excerpt(name), facets));
        break;
      }
      if (is(k.text, "endsolid")) {
        s.rest_of_line();
        break;
      }
      if (!is(k.text, "facet")) {
        text.fail(k.pos, fmt::format("expected 'facet' or 'endsolid', found '{}'", excerpt(k.text)));
      }
      Token n = s.any_word();
      if (is(n.text, "normal")) {
        for (int i = 0; i < 3; ++i) s.any_word();  // unused; "nan" occurs in the wild
        n = s.any_word();
      }
      if (!is(n.text, "outer")) {
        text.fail(n.pos, fmt::format("expected 'outer loop' after 'facet normal nx ny nz', found '{}'",
                                     excerpt(n.text)));
      }
      expect(text, s, "loop", "'outer'");
      corners.clear();
      while (true) {
        const Token v = s.any_word();
        if (is(v.text, "endloop")) break;
        if (!is(v.text, "vertex")) {
          text.fail(v.pos, v.empty() ? std::string("the file ends inside a facet")
                                     : fmt::format("expected 'vertex x y z' or 'endloop', found '{}'",
                                                   excerpt(v.text)));
        }
        const double x = coordinate(text, s, "x coordinate");
        const double y = coordinate(text, s, "y coordinate");
        const double z = coordinate(text, s, "z coordinate");
        if (mesh.vertices.size() >= kMaxVertices) text.fail(v.pos, "more than 4294967294 vertices");
        corners.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
        mesh.vertices.push_back(text.point(x, y, z, v.pos));
      }
      if (corners.size() < 3) {
        text.fail(k.pos, fmt::format("this facet has {} vertices; a facet needs 3", corners.size()));
      }
      expect(text, s, "endfacet", "'endloop'");
      add_polygon(mesh, corners, part);
      ++facets;
    }
  }
  // Parts: the solids that have facets, in file order.
  std::vector<std::uint32_t> renumber(names.size(), 0xffffffffu);
  for (std::uint32_t& p : mesh.part_of) {
    if (renumber[p] == 0xffffffffu) {
      renumber[p] = static_cast<std::uint32_t>(mesh.part_names.size());
      mesh.part_names.push_back(names[p].empty() ? "(unnamed)" : names[p]);
    }
    p = renumber[p];
  }
  return mesh;
}

}  // namespace tumble::mesh_text
