#pragma once
// Numbers in text files (CSV trajectories, tables, run.json): the fewest digits that read back as the
// same double (std::to_chars' shortest round trip, Ryu). Exact like %.17g, several times faster (fmt's
// {:.17g} took a fifth of a 10⁵-body run) and shorter: 0.1, not 0.10000000000000001. Private to tumble_io.
#include <charconv>
#include <string>
#include <string_view>

namespace tumble::io {

/// The shortest text of x that reads back as x; "nan", "inf" or "-inf" for those.
class NumberText {
 public:
  // x + 0.0 is x, but for −0, which becomes +0: a negative zero is rounding's sign, not a fact to print.
  explicit NumberText(double x) : end_(std::to_chars(digits_, digits_ + sizeof digits_, x + 0.0).ptr) {}
  std::string_view view() const { return {digits_, static_cast<size_t>(end_ - digits_)}; }
  operator std::string_view() const { return view(); }

 private:
  char digits_[32];
  char* end_;
};

/// Appends x's shortest text to `out` (a std::string or fmt::memory_buffer).
template <class Buffer>
void append_number(Buffer& out, double x) {
  const NumberText t(x);
  out.append(t.view().data(), t.view().data() + t.view().size());
}

}  // namespace tumble::io
