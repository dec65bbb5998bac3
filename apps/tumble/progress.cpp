#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace tumble::cli {
namespace {

/// Seconds shown as "4.2 s", "3 min 12 s" or "1 h 05 min".
std::string duration_text(double s) {
  if (s < 60) return fmt::format("{:.1f} s", s);
  const long total = static_cast<long>(s);
  if (total < 3600) return fmt::format("{} min {:02d} s", total / 60, static_cast<int>(total % 60));
  return fmt::format("{} h {:02d} min", total / 3600, static_cast<int>(total % 3600 / 60));
}

// Below this a run is over before a bar would help; above it the user is waiting.
constexpr double kShowAfterSeconds = 1.0;
constexpr double kRedrawSeconds = 0.1;

}  // namespace

Progress::Progress(ProgressMode mode, double t_begin, double t_end, const char* unit)
    : mode_(mode),
      terminal_(::isatty(::fileno(stderr)) != 0),
      t_begin_(t_begin),
      t_end_(t_end),
      last_t_(t_begin),
      unit_(unit),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

double Progress::seconds_since_start() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(double t) {
  last_t_ = t;
  if (mode_ == ProgressMode::never) return;
  if (mode_ == ProgressMode::automatic && (!terminal_ || seconds_since_start() < kShowAfterSeconds)) return;
  const auto now = std::chrono::steady_clock::now();
  if (shown_ && std::chrono::duration<double>(now - last_draw_).count() < kRedrawSeconds) return;
  last_draw_ = now;
  draw(t);
}

void Progress::draw(double t) {
  const double span = t_end_ - t_begin_;
  const double fraction = span > 0 ? std::clamp((t - t_begin_) / span, 0.0, 1.0) : 1.0;
  const double elapsed = seconds_since_start();
  constexpr int width = 30;
  const int filled = static_cast<int>(fraction * width);
  const std::string remaining =
      fraction > 0 && fraction < 1
          ? fmt::format("  ~{} left", duration_text(elapsed * (1 - fraction) / fraction))
          : std::string();
  // "\r" and the clear-to-end-of-line code redraw in place on a terminal; when forced onto a file or
  // pipe the updates are separate lines instead.
  const char* begin = terminal_ ? "\r\x1b[K" : "";
  const char* end = terminal_ ? "" : "\n";
  const std::string where = unit_ != nullptr ? fmt::format("{:.0f} / {:.0f} {}", t, t_end_, unit_)
                                             : fmt::format("t = {:.4g} / {:.4g} s", t, t_end_);
  std::fputs(fmt::format("{}[{}{}] {:3.0f}%  {}  elapsed {}{}{}", begin, std::string(filled, '#'),
                         std::string(width - filled, '.'), 100 * fraction, where, duration_text(elapsed),
                         remaining, end)
                 .c_str(),
             stderr);
  std::fflush(stderr);
  shown_ = true;
}

void Progress::message(const std::string& line) {
  if (shown_ && terminal_) std::fputs("\r\x1b[K", stderr);
  std::fputs(fmt::format("{}\n", line).c_str(), stderr);
  if (shown_ && terminal_) draw(last_t_);
}

void Progress::finish() {
  if (!shown_ && mode_ != ProgressMode::always) return;
  draw(last_t_);
  if (terminal_) std::fputs("\n", stderr);
}

}  // namespace tumble::cli
