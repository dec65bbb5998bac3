#pragma once
// Tumble's own readers of the text mesh formats (OBJ, OFF, ASCII PLY, ASCII STL): every coordinate is
// converted from its decimal digits straight to the nearest double (std::from_chars), so a file that
// says 0.1 gives the double nearest 0.1, not a float32 widened. Binary PLY, whose header is text, is
// read here too (mesh_read_ply_binary.cpp), its values as the file stores them. docs/ARCHITECTURE.md ("Text meshes are
// read by tumble") says why no library does this here: assimp, OpenMesh 9 and tinyobjloader all round.
//
// Every error is a FileError "PATH:LINE:COLUMN: what is wrong; how to fix it". Counts in headers (OFF,
// PLY) are checked against the bytes that follow before anything is reserved, and storage grows only
// with what the file really holds, so memory stays proportional to the file's size.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/math/types.hpp"

namespace tumble::mesh_text {

/// What a reader found, before part selection and welding.
struct RawMesh {
  std::vector<Vec3> vertices;  ///< scaled
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> part_of;   ///< each triangle's part (index into part_names)
  std::vector<std::string> part_names;  ///< one per part that has triangles, in file order
  std::string part_word = "part";       ///< what the format calls a part: "object", "group", "solid"
  std::size_t ignored_elements = 0;     ///< lines and points (OBJ l/p) that carry no surface
  std::vector<std::string> warnings;
  std::vector<std::filesystem::path> companions;  ///< other files the loader read (a glTF's buffers)
  bool every_vertex_used = false;  ///< known by the reader (binary STL: corners only), saving a pass
  bool welded = false;             ///< the reader welded as it read (binary STL): no second pass
};

/// A file's text and where a byte offset is in it, for messages. A UTF-8 byte-order mark is dropped.
class Text {
 public:
  Text(std::filesystem::path path, std::string bytes, double scale);

  std::string_view view() const { return bytes_; }
  const std::filesystem::path& path() const { return path_; }

  /// "PATH:LINE:COLUMN" of a byte offset (lines and columns from 1, columns in bytes).
  std::string where(std::size_t pos) const;
  /// Throws FileError "PATH:LINE:COLUMN: message".
  [[noreturn]] void fail(std::size_t pos, std::string_view message) const;

  double scale() const { return scale_; }

  /// A vertex from three parsed coordinates: scaled, checked to be finite (pos: where it starts).
  Vec3 point(double x, double y, double z, std::size_t pos) const;

 private:
  std::filesystem::path path_;
  std::string bytes_;
  double scale_;
};

/// A word of the text and where it starts.
struct Token {
  std::string_view text;
  std::size_t pos = 0;
  bool empty() const { return text.empty(); }
};

/// Walks a Text word by word. Line-based formats (OBJ, OFF) read words within the current line and
/// then move to the next; `hash_comments` makes '#' start a comment to the end of the line, and
/// `continuation` joins a line ending in a backslash with the next (OBJ).
class Scanner {
 public:
  Scanner(const Text& text, bool hash_comments, bool continuation, std::size_t start = 0)
      : s_(text.view()), pos_(start), hash_(hash_comments), continuation_(continuation) {}

  std::size_t pos() const { return pos_; }
  bool at_end() const { return pos_ >= s_.size(); }

  /// The next word on this line (empty at the end of the line or at a comment).
  Token word();
  /// The next word, crossing line ends (empty only at the end of the file).
  Token any_word();
  /// The rest of this line without leading and trailing blanks (a name after OBJ o/g, STL solid).
  std::string_view rest_of_line();
  /// True when only blanks (or a comment) are left on this line.
  bool at_line_end();
  /// Moves past the end of this line.
  void next_line();
  /// Skips blank lines and comment lines; true if a line with content follows.
  bool skip_blank_lines();

 private:
  void skip_blanks();  // spaces, tabs, \r, \f, \v and (with `continuation`) backslash-newline

  std::string_view s_;
  std::size_t pos_;
  bool hash_;
  bool continuation_;
};

/// A word of the file as it may be quoted in a message: at most 40 bytes (then "..."), control bytes
/// as \xNN, so that a message stays one short readable line whatever the file holds.
std::string excerpt(std::string_view token);

/// A coordinate: the nearest double to the decimal text (correctly rounded); a leading '+' is allowed.
/// Throws with the location and, for "0,1", a hint about decimal commas. `what` names the value.
double to_double(const Text& text, const Token& token, std::string_view what);
/// Checks that a word is a number (any, nan included) without keeping it: a value tumble does not use.
void check_number(const Text& text, const Token& token, std::string_view what);
/// A whole number (an index or a count).
std::int64_t to_integer(const Text& text, const Token& token, std::string_view what);
/// The next word on the line as a coordinate, or an error saying it is missing.
double next_double(const Text& text, Scanner& s, std::string_view what);

/// Appends a polygon's triangles, fanned from its first corner. For a planar polygon, convex or not,
/// the signed triangles integrate every polynomial exactly as the polygon does (their signed areas
/// add up to the polygon's, point by point), so mass properties are exact.
void add_polygon(RawMesh& mesh, const std::vector<std::uint32_t>& corners, std::uint32_t part);

/// Largest vertex count (indices are 32-bit and one value is kept free).
constexpr std::uint64_t kMaxVertices = 0xfffffffeULL;

RawMesh read_obj(const Text& text);
RawMesh read_off(const Text& text);
RawMesh read_ascii_stl(const Text& text);
/// A binary STL's `triangles` records (its size already checked: 84 + 50 n bytes), scaled. Throws
/// FileError naming the triangle and its bytes for a corner that is not finite.
RawMesh read_binary_stl(const std::filesystem::path& path, std::string_view bytes, std::uint64_t triangles,
                        double scale);

/// The header of a PLY file, ASCII or binary.
struct PlyProperty {
  std::string name;
  std::string type;        ///< scalar type, or the item type of a list
  std::string count_type;  ///< empty for a scalar
  std::size_t line_pos = 0;
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  std::size_t line_pos = 0;
};
struct PlyHeader {
  enum class Format { ascii, binary_little_endian, binary_big_endian } format = Format::ascii;
  std::vector<PlyElement> elements;
  std::size_t data_pos = 0;  ///< first byte after "end_header\n"
  const PlyElement* find(std::string_view name) const;
};

/// Bytes of a binary value of a PLY type (char ... double, int8 ... float64); 0 for an unknown type.
std::size_t ply_type_size(std::string_view type);
/// True for the face element's list of vertex indices ("vertex_indices" or "vertex_index").
bool is_ply_face_list(const PlyProperty& p);

/// Parses and checks a PLY header: the element counts must fit in the bytes that follow (each ASCII
/// value takes at least two bytes, each binary one its size), the vertex element must have x, y, z.
/// `file_size` is the whole file's size (the text may hold only the header of a binary file).
PlyHeader read_ply_header(const Text& text, std::uint64_t file_size);
RawMesh read_ascii_ply(const Text& text, const PlyHeader& header);
/// The data of a binary PLY (either byte order): `text` holds the whole file. The vertex's x, y, z may
/// have any scalar type and are kept exactly (a double stays a double); the face list gives polygons
/// (any integer count and index types); other elements and properties are skipped by their sizes.
/// Every list count is checked against the bytes left before it is read, every index against the
/// vertex count; errors name the element, its index and the byte offset.
RawMesh read_binary_ply(const Text& text, const PlyHeader& header);

}  // namespace tumble::mesh_text
