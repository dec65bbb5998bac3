// The pieces the text mesh readers share: locations for messages, a word scanner, exact number
// parsing and polygon fans.
#include "mesh_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <system_error>

#include "tumble/error.hpp"

namespace tumble::mesh_text {

Text::Text(std::filesystem::path path, std::string bytes, double scale)
    : path_(std::move(path)), bytes_(std::move(bytes)), scale_(scale) {
  if (bytes_.starts_with("\xEF\xBB\xBF")) bytes_.erase(0, 3);  // UTF-8 byte-order mark
}

std::string Text::where(std::size_t pos) const {
  pos = std::min(pos, bytes_.size());
  const auto begin = bytes_.begin();
  const auto line = 1 + std::count(begin, begin + static_cast<std::ptrdiff_t>(pos), '\n');
  const std::size_t line_start = pos == 0 ? 0 : bytes_.rfind('\n', pos - 1);
  const std::size_t column = line_start == std::string::npos || pos == 0 ? pos + 1 : pos - line_start;
  return fmt::format("{}:{}:{}", path_.string(), line, column);
}

void Text::fail(std::size_t pos, std::string_view message) const {
  throw FileError(fmt::format("{}: {}", where(pos), message));
}

Vec3 Text::point(double x, double y, double z, std::size_t pos) const {
  const Vec3 v = scale_ * Vec3(x, y, z);
  if (!v.allFinite()) {
    fail(pos, fmt::format("the vertex ({}, {}, {}) scaled by {} overflows to infinity; give a smaller scale",
                          x, y, z, scale_));
  }
  return v;
}

namespace {
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
bool is_space(char c) { return is_blank(c) || c == '\n'; }
}  // namespace

void Scanner::skip_blanks() {
  while (pos_ < s_.size()) {
    const char c = s_[pos_];
    if (is_blank(c)) {
      ++pos_;
    } else if (c == '\\' && continuation_) {
      // A backslash at the end of a line joins the next one to it.
      std::size_t k = pos_ + 1;
      while (k < s_.size() && s_[k] == '\r') ++k;
      if (k < s_.size() && s_[k] == '\n') {
        pos_ = k + 1;
      } else {
        return;
      }
    } else {
      return;
    }
  }
}

bool Scanner::at_line_end() {
  skip_blanks();
  return pos_ >= s_.size() || s_[pos_] == '\n' || (hash_ && s_[pos_] == '#');
}

Token Scanner::word() {
  if (at_line_end()) return {{}, pos_};
  const std::size_t start = pos_;
  while (pos_ < s_.size() && !is_space(s_[pos_])) ++pos_;
  return {s_.substr(start, pos_ - start), start};
}

Token Scanner::any_word() {
  while (true) {
    if (!at_line_end()) return word();
    if (at_end()) return {{}, pos_};
    next_line();
  }
}

std::string_view Scanner::rest_of_line() {
  skip_blanks();
  const std::size_t start = pos_;
  std::size_t end = s_.find('\n', start);
  if (end == std::string_view::npos) end = s_.size();
  pos_ = end;
  std::size_t last = end;
  while (last > start && is_blank(s_[last - 1])) --last;
  return s_.substr(start, last - start);
}

void Scanner::next_line() {
  std::size_t i = pos_;
  while (true) {
    i = s_.find('\n', i);
    if (i == std::string_view::npos) {
      pos_ = s_.size();
      return;
    }
    std::size_t k = i;
    while (k > pos_ && s_[k - 1] == '\r') --k;
    // A continued line (backslash before the newline) is still this line, unless inside a comment.
    const bool continued = continuation_ && k > pos_ && s_[k - 1] == '\\';
    if (!continued || s_.substr(pos_, k - pos_).find('#') != std::string_view::npos) {
      pos_ = i + 1;
      return;
    }
    i = i + 1;
  }
}

bool Scanner::skip_blank_lines() {
  while (at_line_end()) {
    if (at_end()) return false;
    next_line();
  }
  return true;
}

std::string excerpt(std::string_view token) {
  // Long or binary garbage is cut so that a message stays one readable line; the cut does not split
  // a UTF-8 character.
  constexpr std::size_t kMax = 40;
  std::size_t n = std::min(token.size(), kMax);
  if (n < token.size()) {
    while (n > 0 && (static_cast<unsigned char>(token[n]) & 0xC0) == 0x80) --n;
  }
  std::string out;
  for (char c : token.substr(0, n)) {
    const auto u = static_cast<unsigned char>(c);
    out += u < 0x20 || u == 0x7f ? fmt::format("\\x{:02x}", u) : std::string(1, c);
  }
  return n < token.size() ? out + "..." : out;
}

namespace {
std::string_view unsigned_part(std::string_view t) {
  return t.size() > 1 && t[0] == '+' && t[1] != '-' ? t.substr(1) : t;  // from_chars takes no '+'
}
}  // namespace

double to_double(const Text& text, const Token& token, std::string_view what) {
  const std::string_view t = unsigned_part(token.text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  const bool whole = !t.empty() && end == t.data() + t.size();
  if (whole && ec == std::errc::result_out_of_range) {
    text.fail(token.pos, fmt::format("{} '{}' is out of the range of a double", what, excerpt(token.text)));
  }
  if (ec != std::errc{} || !whole) {
    const bool comma = token.text.find(',') != std::string_view::npos;
    text.fail(token.pos, fmt::format("{} '{}' is not a number{}", what, excerpt(token.text),
                                     comma ? "; write the decimal separator as '.', not ','" : ""));
  }
  if (!std::isfinite(value)) {
    text.fail(token.pos, fmt::format("{} '{}' is not finite; fix the file", what, excerpt(token.text)));
  }
  return value;
}

void check_number(const Text& text, const Token& token, std::string_view what) {
  const std::string_view t = unsigned_part(token.text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if ((ec != std::errc{} && ec != std::errc::result_out_of_range) || end != t.data() + t.size() ||
      t.empty()) {
    text.fail(token.pos, fmt::format("{} '{}' is not a number", what, excerpt(token.text)));
  }
}

std::int64_t to_integer(const Text& text, const Token& token, std::string_view what) {
  const std::string_view t = unsigned_part(token.text);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  const bool whole = !t.empty() && end == t.data() + t.size();
  if (whole && ec == std::errc::result_out_of_range) {
    text.fail(token.pos, fmt::format("{} '{}' is too large", what, excerpt(token.text)));
  }
  if (ec != std::errc{} || !whole) {
    text.fail(token.pos, fmt::format("{} '{}' is not a whole number", what, excerpt(token.text)));
  }
  return value;
}

double next_double(const Text& text, Scanner& s, std::string_view what) {
  const Token t = s.word();
  if (t.empty()) text.fail(t.pos, fmt::format("the line ends where the {} should be", what));
  return to_double(text, t, what);
}

void add_polygon(RawMesh& mesh, const std::vector<std::uint32_t>& corners, std::uint32_t part) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
    mesh.part_of.push_back(part);
  }
}

}  // namespace tumble::mesh_text
