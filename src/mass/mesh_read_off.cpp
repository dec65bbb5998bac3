// Object File Format (Geomview): an optional keyword [ST][C][N]OFF, the counts "vertices faces
// [edges]", then one vertex per line (x y z, then the normal, colour or texture coordinates the
// keyword announces, ignored) and one face per line ("n i1 ... in", 0-based, then an optional colour,
// ignored). '#' starts a comment. 4OFF, nOFF and binary OFF are refused with a message.
#include <cctype>
#include <fmt/format.h>

#include "mesh_text.hpp"

namespace tumble::mesh_text {
namespace {

/// The header keyword is optional: a first word that does not end in "OFF" is the vertex count.
bool is_keyword(std::string_view t) { return t.ends_with("OFF") || t.ends_with("BINARY"); }

std::uint64_t count(const Text& text, Scanner& s, std::string_view what) {
  const Token t = s.word();
  if (t.empty()) text.fail(t.pos, fmt::format("the header line ends where the {} should be", what));
  const std::int64_t n = to_integer(text, t, what);
  if (n < 0) text.fail(t.pos, fmt::format("the {} is negative ({})", what, n));
  return static_cast<std::uint64_t>(n);
}

}  // namespace

RawMesh read_off(const Text& text) {
  RawMesh mesh;
  Scanner s(text, /*hash_comments=*/true, /*continuation=*/false);
  if (!s.skip_blank_lines()) text.fail(s.pos(), "the file is empty: no OFF header, vertices or faces");

  // The keyword, if there is one: [ST][C][N][4][n]OFF.
  const std::size_t key_pos = s.pos();
  Scanner peek = s;
  const Token first = peek.word();
  if (is_keyword(first.text) || first.text.empty() ||
      !std::isdigit(static_cast<unsigned char>(first.text[0]))) {
    std::string_view k = first.text;
    for (std::string_view prefix : {"ST", "C", "N"}) {
      if (k.starts_with(prefix)) k.remove_prefix(prefix.size());
    }
    if (k == "4OFF" || k == "nOFF" || k == "4nOFF") {
      text.fail(key_pos, fmt::format("'{}' is a 4-dimensional or n-dimensional OFF file; tumble reads "
                                     "3-dimensional OFF only",
                                     excerpt(first.text)));
    }
    if (k != "OFF") {
      text.fail(key_pos, fmt::format("'{}' is not an OFF header: expected OFF (or COFF, NOFF, STOFF...) "
                                     "followed by the vertex and face counts",
                                     excerpt(first.text)));
    }
    s = peek;
    const Token next = s.word();
    if (next.text == "BINARY") {
      text.fail(next.pos, "binary OFF is not supported; write the file as text OFF (or as binary STL/PLY)");
    }
    if (next.empty()) {
      s.next_line();
      if (!s.skip_blank_lines()) text.fail(s.pos(), "the file ends before the vertex and face counts");
    } else {
      s = Scanner(text, true, false, next.pos);
    }
  }
  const std::size_t counts_pos = s.pos();
  const std::uint64_t nv = count(text, s, "vertex count");
  const std::uint64_t nf = count(text, s, "face count");
  if (!s.at_line_end()) count(text, s, "edge count");  // optional, unused
  if (!s.at_line_end()) {
    text.fail(s.pos(), "unexpected text after the counts 'vertices faces edges' on the header line");
  }
  s.next_line();

  // Each vertex line holds at least "0 0 0\n" (6 bytes), each face line "3 0 1 2\n" (8): counts that
  // cannot fit are wrong before anything is stored.
  const std::uint64_t left = text.view().size() - s.pos() + 1;  // the last line may lack its newline
  if (nv > kMaxVertices || nv > left / 6 || nf > left / 8 || 6 * nv + 8 * nf > left) {
    text.fail(counts_pos,
              fmt::format("the header declares {} vertices and {} faces, which need at least "
                          "{:.0f} bytes (6 a vertex, 8 a face), but only {} follow: the counts "
                          "are wrong or the file is truncated",
                          nv, nf, 6.0 * static_cast<double>(nv) + 8.0 * static_cast<double>(nf), left - 1));
  }

  mesh.vertices.reserve(nv);
  for (std::uint64_t i = 0; i < nv; ++i) {
    if (!s.skip_blank_lines()) {
      text.fail(s.pos(), fmt::format("the file ends after {} of the {} vertices the header declares", i, nv));
    }
    const std::size_t pos = s.pos();
    const double x = next_double(text, s, "x coordinate");
    const double y = next_double(text, s, "y coordinate");
    const double z = next_double(text, s, "z coordinate");
    mesh.vertices.push_back(text.point(x, y, z, pos));
    s.next_line();  // normals, colours, texture coordinates
  }
  std::vector<std::uint32_t> corners;
  for (std::uint64_t f = 0; f < nf; ++f) {
    if (!s.skip_blank_lines()) {
      text.fail(s.pos(), fmt::format("the file ends after {} of the {} faces the header declares", f, nf));
    }
    const Token n_token = s.word();
    const std::int64_t n = to_integer(text, n_token, "corner count");
    if (n < 3) {
      text.fail(n_token.pos, fmt::format("face {} has {} corners; a face needs at least 3", f, n));
    }
    corners.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      const Token t = s.word();
      if (t.empty()) {
        text.fail(t.pos, fmt::format("face {} declares {} corners but the line ends after {}", f, n, k));
      }
      const std::int64_t i = to_integer(text, t, "vertex index");
      if (i < 0 || static_cast<std::uint64_t>(i) >= nv) {
        text.fail(t.pos, fmt::format("vertex index {} is out of range: the file has {} vertices, numbered "
                                     "from 0",
                                     i, nv));
      }
      corners.push_back(static_cast<std::uint32_t>(i));
    }
    add_polygon(mesh, corners, 0);
    s.next_line();  // a colour
  }
  if (s.skip_blank_lines()) {
    text.fail(s.pos(), fmt::format("unexpected text after the {} vertices and {} faces the header "
                                   "declares: the counts are wrong",
                                   nv, nf));
  }
  mesh.part_names = {""};
  return mesh;
}

}  // namespace tumble::mesh_text
