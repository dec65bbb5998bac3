#pragma once
// Ctrl-C (SIGINT), SIGTERM, SIGHUP (the terminal closed) and SIGXCPU (a batch system's warning that the
// CPU-time limit is near) during a run: the first one asks the run to stop after its current step,
// writing the state reached, so the files written so far are completed and kept valid; a second one
// terminates at once, leaving only temporaries behind (removed by the next run that writes the same
// file), never a half-written final file. While the files are being moved into place (a Deferral
// exists) a second signal waits until they are; a third one ends the process even then.
namespace tumble::cli {

class InterruptGuard {
 public:
  InterruptGuard();   // installs the handlers
  ~InterruptGuard();  // restores the previous ones
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  /// True once a signal arrived.
  bool requested() const;
  /// The first signal that arrived (SIGINT, SIGTERM, SIGHUP or SIGXCPU), 0 if none.
  int signal() const;

  /// While it exists, a second signal is held until it goes; then the process ends by that signal
  /// (unless an exception is on its way out: the run is ending with an error message anyway).
  class Deferral {
   public:
    Deferral();
    ~Deferral();
    Deferral(const Deferral&) = delete;
    Deferral& operator=(const Deferral&) = delete;
  };
};

}  // namespace tumble::cli
