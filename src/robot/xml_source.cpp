#include "xml_source.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "tumble/error.hpp"

namespace tumble::robot {

const char* format_name(Format format) {
  switch (format) {
    case Format::urdf:
      return "urdf";
    case Format::mjcf:
      return "mjcf";
    case Format::sdf:
      return "sdf";
  }
  return "?";
}

namespace {

/// Where the element that starts at `begin` (its '<') ends: past its '/>' or its closing tag. A scan
/// of the bytes, not of the DOM: the rewrite must know the exact bytes, comments and all.
std::size_t element_end(const std::string& s, std::size_t begin) {
  int depth = 0;
  std::size_t i = begin;
  while (i < s.size()) {
    if (s.compare(i, 4, "<!--") == 0) {
      const std::size_t e = s.find("-->", i + 4);
      i = e == std::string::npos ? s.size() : e + 3;
      continue;
    }
    if (s.compare(i, 9, "<![CDATA[") == 0) {
      const std::size_t e = s.find("]]>", i + 9);
      i = e == std::string::npos ? s.size() : e + 3;
      continue;
    }
    if (s.compare(i, 2, "<?") == 0) {
      const std::size_t e = s.find("?>", i + 2);
      i = e == std::string::npos ? s.size() : e + 2;
      continue;
    }
    if (s[i] != '<') {
      ++i;
      continue;
    }
    const bool closing = i + 1 < s.size() && s[i + 1] == '/';
    // To the tag's '>', over quoted attribute values (which may hold '>').
    char quote = 0;
    std::size_t j = i + 1;
    for (; j < s.size(); ++j) {
      if (quote) {
        if (s[j] == quote) quote = 0;
      } else if (s[j] == '"' || s[j] == '\'') {
        quote = s[j];
      } else if (s[j] == '>') {
        break;
      }
    }
    if (j >= s.size()) return s.size();
    const bool empty = !closing && s[j - 1] == '/';
    if (closing) --depth;
    if (!closing && !empty) ++depth;
    i = j + 1;
    if (depth == 0) return i;
  }
  return s.size();
}

}  // namespace

XmlSource::XmlSource(std::filesystem::path path, std::string text)
    : path_(std::move(path)), text_(std::move(text)) {
  line_starts_.push_back(0);
  for (std::size_t i = 0; i < text_.size(); ++i)
    if (text_[i] == '\n') line_starts_.push_back(i + 1);
  // parse_doctype keeps a DTD as a node, so that it can be refused; pugixml never expands entities
  // other than the five predefined ones and character references.
  const pugi::xml_parse_result r = doc_.load_buffer(
      text_.data(), text_.size(), pugi::parse_default | pugi::parse_doctype, pugi::encoding_utf8);
  const auto position = [&](std::ptrdiff_t offset) {
    const auto at = static_cast<std::size_t>(std::max<std::ptrdiff_t>(offset, 0));
    const auto line = std::upper_bound(line_starts_.begin(), line_starts_.end(), at) - line_starts_.begin();
    return fmt::format("{}:{}:{}", path_.string(), line,
                       at - line_starts_[static_cast<std::size_t>(line - 1)] + 1);
  };
  if (!r)
    throw InvalidArgument(fmt::format("{}: not well-formed XML: {}", position(r.offset), r.description()));
  for (const pugi::xml_node& n : doc_.children()) {
    if (n.type() == pugi::node_doctype) {
      throw InvalidArgument(fmt::format(
          "{}: a document type declaration (<!DOCTYPE ...>) is refused: its entities could expand without "
          "bound; remove it (robot descriptions need none)",
          position(static_cast<std::ptrdiff_t>(
              text_.rfind('<', static_cast<std::size_t>(std::max<std::ptrdiff_t>(n.offset_debug(), 0)))))));
    }
  }
}

int XmlSource::line_of(const pugi::xml_node& element) const {
  const auto at = static_cast<std::size_t>(std::max<std::ptrdiff_t>(element.offset_debug(), 0));
  return static_cast<int>(std::upper_bound(line_starts_.begin(), line_starts_.end(), at) -
                          line_starts_.begin());
}

SourceSpan XmlSource::span_of(const pugi::xml_node& element) const {
  // offset_debug is the offset of the element's name, just after its '<'.
  std::size_t begin = static_cast<std::size_t>(std::max<std::ptrdiff_t>(element.offset_debug(), 1)) - 1;
  while (begin > 0 && text_[begin] != '<') --begin;
  return {begin, element_end(text_, begin), line_of(element)};
}

std::string XmlSource::where(const pugi::xml_node& element) const {
  return fmt::format("{}:{}", path_.string(), line_of(element));
}

void XmlSource::fail(const pugi::xml_node& element, std::string_view message) const {
  throw InvalidArgument(fmt::format("{}: <{}>: {}", where(element), element.name(), message));
}

std::vector<double> XmlSource::parse_numbers(const pugi::xml_node& element, std::string_view what,
                                             std::string_view text) const {
  std::vector<double> out;
  std::size_t i = 0;
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ','; };
  while (true) {
    while (i < text.size() && space(text[i])) ++i;
    if (i == text.size()) break;
    std::size_t j = i;
    while (j < text.size() && !space(text[j])) ++j;
    double x = 0.0;
    std::string_view token = text.substr(i, j - i);
    if (!token.empty() && token[0] == '+') token.remove_prefix(1);
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), x);
    if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(x)) {
      fail(element,
           fmt::format("{} \"{}\": \"{}\" is not a finite number", what, text, text.substr(i, j - i)));
    }
    out.push_back(x);
    i = j;
  }
  return out;
}

std::vector<double> XmlSource::numbers(const pugi::xml_node& element, const char* attribute,
                                       std::size_t count, std::vector<double> fallback) const {
  const pugi::xml_attribute a = element.attribute(attribute);
  if (!a) {
    if (fallback.empty()) fail(element, fmt::format("needs {}=\"...\" ({} numbers)", attribute, count));
    return fallback;
  }
  std::vector<double> v = parse_numbers(element, attribute, a.value());
  if (v.size() != count) {
    fail(element,
         fmt::format("{}=\"{}\" has {} numbers; it needs {}", attribute, a.value(), v.size(), count));
  }
  return v;
}

double XmlSource::number(const pugi::xml_node& element, const char* attribute) const {
  return numbers(element, attribute, 1)[0];
}

double XmlSource::number(const pugi::xml_node& element, const char* attribute, double fallback) const {
  return numbers(element, attribute, 1, {fallback})[0];
}

std::vector<double> XmlSource::text_numbers(const pugi::xml_node& element, std::size_t count) const {
  std::vector<double> v = parse_numbers(element, "text", element.child_value());
  if (v.size() != count) {
    fail(element, fmt::format("\"{}\" has {} numbers; it needs {}", element.child_value(), v.size(), count));
  }
  return v;
}

std::vector<double> XmlSource::all_numbers(const pugi::xml_node& element, const char* attribute) const {
  return parse_numbers(element, attribute, element.attribute(attribute).value());
}

Mat3 rotation_rpy(const Vec3& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

Mat3 rotation_wxyz(double w, double x, double y, double z) {
  return Quat(w, x, y, z).normalized().toRotationMatrix();
}

std::string number_text(double x) {
  return fmt::format("{}", x + 0.0);  // shortest round trip; + 0.0 turns -0 into 0
}

}  // namespace tumble::robot
