#pragma once
// A robot description's XML, parsed by pugixml and kept with its bytes: where each element is (its byte
// span and line, for messages and for rewriting one element in place), and the readers' common chores —
// numbers and vectors from attributes or text, rotations from roll-pitch-yaw and quaternions — each
// failing with file:line and what was expected.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

#include "tumble/robot/robot_model.hpp"

namespace tumble::robot {

class XmlSource {
 public:
  /// Parses `text` (the bytes of `path`). Throws InvalidArgument with path:line:column for malformed
  /// XML, and for a document type declaration (DTD): its entities could expand without bound.
  XmlSource(std::filesystem::path path, std::string text);
  XmlSource(const XmlSource&) = delete;
  XmlSource& operator=(const XmlSource&) = delete;

  const pugi::xml_document& document() const { return doc_; }
  const std::filesystem::path& path() const { return path_; }
  const std::string& text() const { return text_; }

  /// The line (1-based) of an element's start tag.
  int line_of(const pugi::xml_node& element) const;
  /// The bytes of the whole element: from its '<' to the end of its closing tag or of its '/>'.
  SourceSpan span_of(const pugi::xml_node& element) const;
  /// "path:line" of an element, for messages.
  std::string where(const pugi::xml_node& element) const;
  /// Throws InvalidArgument "path:line: <element>: message".
  [[noreturn]] void fail(const pugi::xml_node& element, std::string_view message) const;

  /// The numbers of an attribute ("0.1 0.2 0.3"), exactly `count` of them; `fallback` when the attribute
  /// is absent (empty fallback: it is required).
  std::vector<double> numbers(const pugi::xml_node& element, const char* attribute, std::size_t count,
                              std::vector<double> fallback = {}) const;
  /// One number of an attribute; required unless a fallback is given.
  double number(const pugi::xml_node& element, const char* attribute) const;
  double number(const pugi::xml_node& element, const char* attribute, double fallback) const;
  /// The numbers of an element's text (SDF: <size>1 2 3</size>), exactly `count`.
  std::vector<double> text_numbers(const pugi::xml_node& element, std::size_t count) const;
  /// The numbers of an attribute, however many (MJCF: size="0.1" or size="0.1 0.2").
  std::vector<double> all_numbers(const pugi::xml_node& element, const char* attribute) const;

 private:
  std::vector<double> parse_numbers(const pugi::xml_node& element, std::string_view what,
                                    std::string_view text) const;
  std::filesystem::path path_;
  std::string text_;
  pugi::xml_document doc_;
  std::vector<std::size_t> line_starts_;
};

/// URDF's and SDF's roll, pitch, yaw (fixed axes x, y, z): R = Rz(yaw) Ry(pitch) Rx(roll).
Mat3 rotation_rpy(const Vec3& rpy);
/// A quaternion given w first, normalised.
Mat3 rotation_wxyz(double w, double x, double y, double z);
/// Numbers written as a file would want them back: the shortest text that reads back as the same double.
std::string number_text(double x);

}  // namespace tumble::robot
