#pragma once
// A progress bar on stderr: simulated time, elapsed wall time and an estimate of the time remaining.
#include <chrono>
#include <string>

namespace tumble::cli {

enum class ProgressMode {
  automatic,  ///< only when stderr is a terminal, and only once the run has taken about a second
  always,     ///< from the start, terminal or not (--progress)
  never,      ///< --quiet
};

class Progress {
 public:
  /// Counts simulated time from t_begin to t_end, or, with `unit` (e.g. "runs"), items of that unit.
  Progress(ProgressMode mode, double t_begin, double t_end, const char* unit = nullptr);
  /// The run has reached simulated time t. Redraws at most ten times a second.
  void update(double t);
  /// Prints a line on stderr without leaving a broken bar behind (the bar is redrawn on the next update).
  void message(const std::string& line);
  /// Draws the last state and ends the line, if the bar was shown.
  void finish();

 private:
  void draw(double t);
  double seconds_since_start() const;
  ProgressMode mode_;
  bool terminal_;
  double t_begin_, t_end_;
  double last_t_;
  const char* unit_ = nullptr;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool shown_ = false;
};

}  // namespace tumble::cli
