// PLY: the header (ASCII and binary files alike) and the data of ASCII files. The vertex element's x,
// y, z may have any declared type: in an ASCII file they are decimal text, read to the nearest double
// whatever the type says (binary data: mesh_read_ply_binary.cpp). The face element's list "vertex_indices" (or "vertex_index") gives polygons,
// 0-based. Other elements and properties are read past. The data is a stream of words (line breaks
// are not significant), as the format defines it.
#include <array>
#include <fmt/format.h>

#include "mesh_text.hpp"

namespace tumble::mesh_text {

std::size_t ply_type_size(std::string_view t) {
  static constexpr std::array<std::pair<std::string_view, std::size_t>, 16> sizes{{
      {"char", 1},
      {"uchar", 1},
      {"int8", 1},
      {"uint8", 1},
      {"short", 2},
      {"ushort", 2},
      {"int16", 2},
      {"uint16", 2},
      {"int", 4},
      {"uint", 4},
      {"int32", 4},
      {"uint32", 4},
      {"float", 4},
      {"float32", 4},
      {"double", 8},
      {"float64", 8},
  }};
  for (const auto& [name, size] : sizes) {
    if (t == name) return size;
  }
  return 0;
}

bool is_ply_face_list(const PlyProperty& p) {
  return !p.count_type.empty() && (p.name == "vertex_indices" || p.name == "vertex_index");
}

const PlyElement* PlyHeader::find(std::string_view name) const {
  for (const PlyElement& e : elements) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

PlyHeader read_ply_header(const Text& text, std::uint64_t file_size) {
  PlyHeader h;
  Scanner s(text, /*hash_comments=*/false, /*continuation=*/false);
  const Token magic = s.word();
  if (magic.text != "ply" || !s.at_line_end()) text.fail(magic.pos, "a PLY file starts with the line 'ply'");
  s.next_line();
  bool have_format = false, ended = false;
  while (!ended && !s.at_end()) {
    const std::size_t line_pos = s.pos();
    const Token key = s.word();
    if (key.text == "format") {
      const Token f = s.word();
      const Token version = s.word();
      if (f.text == "ascii") {
        h.format = PlyHeader::Format::ascii;
      } else if (f.text == "binary_little_endian") {
        h.format = PlyHeader::Format::binary_little_endian;
      } else if (f.text == "binary_big_endian") {
        h.format = PlyHeader::Format::binary_big_endian;
      } else {
        text.fail(f.pos, fmt::format("unknown PLY format '{}': expected ascii, binary_little_endian or "
                                     "binary_big_endian",
                                     excerpt(f.text)));
      }
      if (version.text != "1.0") {
        text.fail(version.pos,
                  fmt::format("PLY version '{}': tumble reads version 1.0", excerpt(version.text)));
      }
      have_format = true;
    } else if (key.text == "element") {
      const Token name = s.word();
      const Token n = s.word();
      if (name.empty() || n.empty()) text.fail(key.pos, "expected 'element NAME COUNT'");
      const std::int64_t count = to_integer(text, n, "element count");
      if (count < 0) text.fail(n.pos, "the element count is negative");
      h.elements.push_back({std::string(name.text), static_cast<std::uint64_t>(count), {}, line_pos});
    } else if (key.text == "property") {
      if (h.elements.empty()) text.fail(key.pos, "a property before any 'element' line");
      PlyProperty p;
      p.line_pos = line_pos;
      Token type = s.word();
      if (type.text == "list") {
        const Token count_type = s.word();
        if (ply_type_size(count_type.text) == 0) {
          text.fail(count_type.pos, fmt::format("unknown list count type '{}'", excerpt(count_type.text)));
        }
        p.count_type = count_type.text;
        type = s.word();
      }
      if (ply_type_size(type.text) == 0) {
        text.fail(type.pos,
                  fmt::format("unknown property type '{}': expected char, uchar, short, ushort, int, "
                              "uint, float, double (or int8 ... float64)",
                              excerpt(type.text)));
      }
      p.type = type.text;
      const Token name = s.word();
      if (name.empty()) text.fail(s.pos(), "the property has no name");
      p.name = name.text;
      h.elements.back().properties.push_back(p);
    } else if (key.text == "end_header") {
      ended = true;
    } else if (key.text != "comment" && key.text != "obj_info" && !key.empty()) {
      text.fail(key.pos, fmt::format("unexpected '{}' in the PLY header (expected format, element, "
                                     "property, comment or end_header)",
                                     excerpt(key.text)));
    }
    s.next_line();
  }
  if (!ended) text.fail(s.pos(), "the PLY header has no 'end_header' line");
  if (!have_format) text.fail(0, "the PLY header has no 'format' line");
  h.data_pos = s.pos();

  const PlyElement* vertex = h.find("vertex");
  if (vertex == nullptr) text.fail(0, "the PLY header declares no 'element vertex'");
  for (const char* axis : {"x", "y", "z"}) {
    bool found = false;
    for (const PlyProperty& p : vertex->properties) found = found || (p.name == axis && p.count_type.empty());
    if (!found)
      text.fail(vertex->line_pos, fmt::format("the vertex element has no scalar property '{}'", axis));
  }
  if (vertex->count > kMaxVertices) text.fail(vertex->line_pos, "more than 4294967294 vertices");
  if (const PlyElement* face = h.find("face"); face != nullptr) {
    bool found = false;
    for (const PlyProperty& p : face->properties) found = found || is_ply_face_list(p);
    if (!found) {
      text.fail(face->line_pos, "the face element has no list property 'vertex_indices' (or 'vertex_index')");
    }
  }

  // The counts must fit in the bytes after the header: an ASCII value takes at least two bytes (a
  // digit and a separator), a binary one its size (a list at least its count). Checked one element at
  // a time with divisions, so that no product overflows.
  const bool ascii = h.format == PlyHeader::Format::ascii;
  std::uint64_t left = file_size > h.data_pos ? file_size - h.data_pos + (ascii ? 1 : 0) : 0;
  for (const PlyElement& e : h.elements) {
    std::uint64_t per_item = 0;
    for (const PlyProperty& p : e.properties) {
      per_item += ascii ? 2 : ply_type_size(p.count_type.empty() ? p.type : p.count_type);
    }
    if (per_item == 0) continue;  // no properties: nothing to read, whatever the count
    if (e.count > left / per_item) {
      text.fail(e.line_pos,
                fmt::format("'element {} {}' needs at least {} bytes ({} per {}), but only {} "
                            "follow the header: the count is wrong or the file is truncated",
                            e.name, e.count, fmt::format("{:.0f}", static_cast<double>(e.count) * per_item),
                            per_item, e.name, file_size - std::min(file_size, h.data_pos)));
    }
    left -= e.count * per_item;
  }
  return h;
}

RawMesh read_ascii_ply(const Text& text, const PlyHeader& header) {
  RawMesh mesh;
  Scanner s(text, /*hash_comments=*/false, /*continuation=*/false, header.data_pos);
  const std::uint64_t nv = header.find("vertex")->count;
  std::vector<std::uint32_t> corners;
  for (const PlyElement& e : header.elements) {
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face";
    if (e.properties.empty()) continue;
    if (is_vertex) mesh.vertices.reserve(e.count);  // the count was checked against the file's size
    for (std::uint64_t i = 0; i < e.count; ++i) {
      double xyz[3] = {0, 0, 0};
      std::size_t item_pos = 0;
      for (const PlyProperty& p : e.properties) {
        const Token t = s.any_word();
        if (&p == &e.properties.front()) item_pos = t.pos;
        if (t.empty()) {
          text.fail(t.pos, fmt::format("the file ends in {} {} of the {} the header declares: the header's "
                                       "counts are wrong or the file is truncated",
                                       e.name, i, e.count));
        }
        if (p.count_type.empty()) {
          const int axis = !is_vertex ? -1 : p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
          if (axis >= 0) {
            xyz[axis] = to_double(text, t, fmt::format("{} coordinate", p.name));
          } else {
            // Another value (a normal, a colour): checked to be a number (a misplaced word shows a wrong
            // header), not used.
            check_number(text, t, fmt::format("property '{}'", p.name));
          }
          continue;
        }
        const std::int64_t n = to_integer(text, t, fmt::format("the count of list '{}'", p.name));
        if (n < 0) text.fail(t.pos, fmt::format("the count of list '{}' is negative", p.name));
        const bool polygon = is_face && is_ply_face_list(p);
        if (polygon && n < 3) {
          text.fail(t.pos, fmt::format("face {} has {} corners; a face needs at least 3 (or the header's "
                                       "counts are wrong)",
                                       i, n));
        }
        corners.clear();
        for (std::int64_t k = 0; k < n; ++k) {
          const Token v = s.any_word();
          if (v.empty()) {
            text.fail(v.pos, fmt::format("the file ends inside list '{}' of {} {} ({} of {} values): the "
                                         "header's counts are wrong or the file is truncated",
                                         p.name, e.name, i, k, n));
          }
          if (!polygon) {
            check_number(text, v, fmt::format("a value of list '{}'", p.name));
            continue;
          }
          const std::int64_t index = to_integer(text, v, "vertex index");
          if (index < 0 || static_cast<std::uint64_t>(index) >= nv) {
            text.fail(v.pos, fmt::format("vertex index {} is out of range: the file has {} vertices, "
                                         "numbered from 0 (or the header's counts are wrong)",
                                         index, nv));
          }
          corners.push_back(static_cast<std::uint32_t>(index));
        }
        if (polygon) add_polygon(mesh, corners, 0);
      }
      if (is_vertex) mesh.vertices.push_back(text.point(xyz[0], xyz[1], xyz[2], item_pos));
    }
  }
  if (const Token t = s.any_word(); !t.empty()) {
    text.fail(t.pos, "unexpected text after the elements the header declares: the counts are wrong");
  }
  mesh.part_names = {""};
  return mesh;
}

}  // namespace tumble::mesh_text
