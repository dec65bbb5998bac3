#include "body_sections.hpp"

#include <algorithm>

namespace tumble::scene {
namespace {

bool is_bare_key_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
}

/// A table header: [a.b] or [[a.b]], its first key and how many keys it has.
struct Header {
  bool array;
  std::string_view first;
  int keys;
};

/// Reads the text of a scene a character at a time, as far as finding its header lines needs.
class Lexer {
 public:
  explicit Lexer(std::string_view text) : t_(text) {}
  bool done() const { return i_ >= t_.size(); }
  size_t at() const { return i_; }
  std::uint32_t line() const { return line_; }

  /// At a line's start outside any value: the header that begins the line, if one does; the line is
  /// then consumed. False when the line is a plain header that could not be read (decline).
  bool header(std::optional<Header>& h) {
    h.reset();
    size_t i = i_;
    while (i < t_.size() && (t_[i] == ' ' || t_[i] == '\t')) ++i;
    if (i == t_.size() || t_[i] != '[') return true;
    Header r{};
    r.array = i + 1 < t_.size() && t_[i + 1] == '[';
    i += r.array ? 2 : 1;
    while (true) {
      while (i < t_.size() && (t_[i] == ' ' || t_[i] == '\t')) ++i;
      const size_t start = i;
      while (i < t_.size() && is_bare_key_char(t_[i])) ++i;
      if (i == start) return false;  // a quoted or empty key
      if (r.keys++ == 0) r.first = t_.substr(start, i - start);
      while (i < t_.size() && (t_[i] == ' ' || t_[i] == '\t')) ++i;
      if (i < t_.size() && t_[i] == '.') {
        ++i;
        continue;
      }
      break;
    }
    for (int k = 0; k < (r.array ? 2 : 1); ++k) {
      if (i == t_.size() || t_[i] != ']') return false;
      ++i;
    }
    while (i < t_.size() && (t_[i] == ' ' || t_[i] == '\t')) ++i;
    if (i < t_.size() && t_[i] == '#') i = std::min(t_.find('\n', i), t_.size());
    if (i < t_.size() && t_[i] == '\r') ++i;
    if (i < t_.size() && t_[i] != '\n') return false;
    i_ = i;
    next_line();
    h = r;
    return true;
  }

  /// Consumes the rest of a line that is not a header: strings, comments and the brackets of values
  /// (an array may go on over the next lines). False where the text is not plain (decline).
  bool rest_of_line() {
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '\n') {
        next_line();
        return true;
      }
      if (c == '#') {
        i_ = std::min(t_.find('\n', i_), t_.size());
        continue;
      }
      if (c == '"' || c == '\'') {
        if (t_.substr(i_, 3) == (c == '"' ? "\"\"\"" : "'''")) return false;  // a multi-line string
        for (++i_; i_ < t_.size() && t_[i_] != c; ++i_) {
          if (t_[i_] == '\n') return false;  // unterminated: toml++ says where
          if (c == '"' && t_[i_] == '\\' && i_ + 1 < t_.size() && t_[i_ + 1] != '\n') ++i_;  // an escape
        }
        if (i_ >= t_.size()) return false;
        ++i_;
        continue;
      }
      if (c == '[' || c == '{') ++depth_;
      if (c == ']' || c == '}') {
        if (depth_ == 0) return false;
        --depth_;
      }
      ++i_;
    }
    return true;
  }

  /// Whether the next line starts outside every value (a header may only begin there).
  bool outside_values() const { return depth_ == 0; }

 private:
  void next_line() {
    if (i_ < t_.size()) ++i_;  // the '\n'
    ++line_;
  }
  std::string_view t_;
  size_t i_ = 0;
  std::uint32_t line_ = 1;
  int depth_ = 0;
};

}  // namespace

std::optional<BodySections> split_body_sections(std::string_view text) {
  BodySections out;
  Lexer lex(text);
  // The open section: where it starts (a byte and a line), or none.
  std::optional<size_t> open;
  std::uint32_t open_line = 0;
  size_t kept = 0;  // the text before `kept` is in `out.rest` or a section already
  const auto close = [&](size_t end) {
    const std::string_view section = text.substr(*open, end - *open);
    out.sections.push_back({section, open_line});
    out.rest.append(static_cast<size_t>(std::count(section.begin(), section.end(), '\n')), '\n');
    open.reset();
    kept = end;
  };
  while (!lex.done()) {
    const size_t line_start = lex.at();
    const std::uint32_t line = lex.line();
    if (lex.outside_values()) {
      std::optional<Header> h;
      if (!lex.header(h)) return std::nullopt;
      if (h) {
        const bool body = h->array && h->keys == 1 && h->first == "bodies";
        if (h->first == "bodies" && !body && !open) return std::nullopt;  // [bodies.x] outside a section
        if (body && open && line_start - *open >= kBodySectionBytes) close(line_start);
        if (h->first != "bodies" && open) close(line_start);
        if (body) {
          ++out.bodies;
          if (!open) {
            // The text between the previous section and this one stays in the rest, as it is.
            out.rest.append(text.substr(kept, line_start - kept));
            open = line_start;
            open_line = line;
          }
        }
        continue;
      }
    }
    if (!lex.rest_of_line()) return std::nullopt;
  }
  if (!lex.outside_values()) return std::nullopt;  // an array left open: toml++ says where
  if (open) close(text.size());
  if (out.bodies == 0) return std::nullopt;
  out.rest.append(text.substr(kept));
  return out;
}

}  // namespace tumble::scene
