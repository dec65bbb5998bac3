// Binary PLY data (binary_little_endian, binary_big_endian), after the text header that
// mesh_read_ply.cpp parses. tumble reads it itself rather than through assimp, whose binary PLY reader
// and triangulation crash (segfaults, assertion aborts, endless loops) on small corrupt files
// (docs/ARCHITECTURE.md, "Binary PLY is read by tumble"). Nothing here trusts the file: every value is
// read only after checking that its bytes are there, every list count before the list is read, every
// vertex index against the vertex count; storage grows only with what was read.
#include <bit>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

#include "mesh_text.hpp"
#include "tumble/error.hpp"

namespace tumble::mesh_text {
namespace {

enum class Scalar { i8, u8, i16, u16, i32, u32, f32, f64 };

Scalar scalar_of(std::string_view t) {
  if (t == "char" || t == "int8") return Scalar::i8;
  if (t == "uchar" || t == "uint8") return Scalar::u8;
  if (t == "short" || t == "int16") return Scalar::i16;
  if (t == "ushort" || t == "uint16") return Scalar::u16;
  if (t == "int" || t == "int32") return Scalar::i32;
  if (t == "uint" || t == "uint32") return Scalar::u32;
  if (t == "float" || t == "float32") return Scalar::f32;
  return Scalar::f64;  // "double", "float64": the header admits no other type
}

bool is_integer(Scalar s) { return s != Scalar::f32 && s != Scalar::f64; }

/// A property with its types resolved.
struct Field {
  const PlyProperty* property;
  Scalar type;   ///< the scalar's type, or a list's item type
  Scalar count;  ///< a list's count type
  bool list;
  int axis;    ///< 0, 1, 2 for the vertex's x, y, z; -1 otherwise
  bool faces;  ///< the face element's vertex index list
};

class BinaryReader {
 public:
  BinaryReader(std::string_view bytes, std::size_t start, bool big_endian)
      : bytes_(bytes), pos_(start), swap_(big_endian != (std::endian::native == std::endian::big)) {}

  std::size_t pos() const { return pos_; }
  std::size_t left() const { return bytes_.size() - pos_; }

  /// One value of type s (the caller has checked that its bytes are there).
  double value(Scalar s) {
    switch (s) {
      case Scalar::i8:
        return take<std::int8_t>();
      case Scalar::u8:
        return take<std::uint8_t>();
      case Scalar::i16:
        return take<std::int16_t>();
      case Scalar::u16:
        return take<std::uint16_t>();
      case Scalar::i32:
        return take<std::int32_t>();
      case Scalar::u32:
        return take<std::uint32_t>();
      case Scalar::f32:
        return static_cast<double>(take<float>());
      case Scalar::f64:
        return take<double>();
    }
    return 0.0;
  }

  void skip(std::size_t n) { pos_ += n; }

 private:
  template <class T>
  T take() {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    if (swap_) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    T v;
    std::memcpy(&v, raw, sizeof(T));
    return v;
  }

  std::string_view bytes_;
  std::size_t pos_;
  bool swap_;
};

/// "face 12" and the byte where it starts, for messages.
struct Item {
  const PlyElement* element;
  std::uint64_t index;
  std::size_t pos;
};

[[noreturn]] void fail(const Text& text, const Item& item, std::string_view message) {
  throw FileError(fmt::format("{}: {} {} (byte {}): {}", text.path().string(), item.element->name, item.index,
                              item.pos, message));
}

/// The file ends inside an item: the header promised more than the file holds.
[[noreturn]] void fail_truncated(const Text& text, const Item& item) {
  fail(text, item,
       fmt::format("the file ends inside this {} (the header declares {}): the file is truncated, or the "
                   "header's counts or types are wrong",
                   item.element->name, item.element->count));
}

std::vector<Field> fields_of(const Text& text, const PlyElement& e) {
  std::vector<Field> fields;
  for (const PlyProperty& p : e.properties) {
    Field f{&p, scalar_of(p.type), Scalar::u8, !p.count_type.empty(), -1, false};
    if (f.list) {
      f.count = scalar_of(p.count_type);
      if (!is_integer(f.count)) {
        text.fail(p.line_pos, fmt::format("list '{}' has the count type '{}'; a list count must be an "
                                          "integer type (uchar, ushort, uint, ...)",
                                          p.name, p.count_type));
      }
    }
    if (e.name == "vertex" && !f.list)
      f.axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
    f.faces = e.name == "face" && is_ply_face_list(p);
    if (f.faces && !is_integer(f.type)) {
      text.fail(p.line_pos, fmt::format("the face list '{}' holds values of type '{}'; vertex indices "
                                        "must be an integer type (int, uint, ...)",
                                        p.name, p.type));
    }
    fields.push_back(f);
  }
  return fields;
}

}  // namespace

RawMesh read_binary_ply(const Text& text, const PlyHeader& header) {
  RawMesh mesh;
  BinaryReader in(text.view(), header.data_pos, header.format == PlyHeader::Format::binary_big_endian);
  const std::uint64_t nv = header.find("vertex")->count;
  std::vector<std::uint32_t> corners;
  for (const PlyElement& e : header.elements) {
    const std::vector<Field> fields = fields_of(text, e);
    if (fields.empty()) continue;  // no properties: no bytes, whatever the count
    // The header's check (read_ply_header) already bounded count × minimum size by the file's size.
    if (e.name == "vertex") mesh.vertices.reserve(e.count);
    for (std::uint64_t i = 0; i < e.count; ++i) {
      const Item item{&e, i, in.pos()};
      double xyz[3] = {0, 0, 0};
      for (const Field& f : fields) {
        const std::size_t size = ply_type_size(f.list ? f.property->count_type : f.property->type);
        if (in.left() < size) fail_truncated(text, item);
        if (!f.list) {
          const double v = in.value(f.type);
          if (f.axis >= 0) xyz[f.axis] = v;
          continue;
        }
        const double n = in.value(f.count);
        const std::size_t item_size = ply_type_size(f.property->type);
        if (n < 0) fail(text, item, fmt::format("list '{}' has a negative count ({})", f.property->name, n));
        if (n > static_cast<double>(in.left() / item_size)) {
          fail(
              text, item,
              fmt::format("list '{}' declares {} values ({} bytes each), but only {} bytes are left in the "
                          "file: the file is corrupt or truncated, or the header's counts or types are wrong",
                          f.property->name, n, item_size, in.left()));
        }
        const auto count = static_cast<std::size_t>(n);
        if (!f.faces) {
          in.skip(count * item_size);
          continue;
        }
        if (count < 3) {
          fail(text, item,
               fmt::format("the face has {} corners; a face needs at least 3 (or the header's counts or "
                           "types are wrong)",
                           count));
        }
        corners.clear();
        for (std::size_t k = 0; k < count; ++k) {
          const double index = in.value(f.type);
          if (index < 0 || index >= static_cast<double>(nv)) {
            fail(
                text, item,
                fmt::format("vertex index {} (corner {}) is out of range: the file has {} vertices, numbered "
                            "from 0",
                            index, k, nv));
          }
          corners.push_back(static_cast<std::uint32_t>(index));
        }
        add_polygon(mesh, corners, 0);
      }
      if (e.name != "vertex") continue;
      const Vec3 p = text.scale() * Vec3(xyz[0], xyz[1], xyz[2]);
      if (!p.allFinite()) {
        fail(text, item,
             fmt::format("the vertex ({}, {}, {}) {}", xyz[0], xyz[1], xyz[2],
                         Vec3(xyz[0], xyz[1], xyz[2]).allFinite()
                             ? fmt::format("scaled by {} overflows to infinity; give a smaller scale",
                                           text.scale())
                             : std::string("has non-finite coordinates; fix the file")));
      }
      mesh.vertices.push_back(p);
    }
  }
  if (in.left() > 0) {
    throw FileError(
        fmt::format("{}: {} bytes follow the elements the header declares (which end at byte {} "
                    "of {}): the header's counts are wrong",
                    text.path().string(), in.left(), in.pos(), text.view().size()));
  }
  mesh.part_names = {""};
  return mesh;
}

}  // namespace tumble::mesh_text
