#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a run: the first one asks the run to stop after its current step,
// writing the state reached, so the files written so far are completed and kept valid; a second one terminates at once
// (the handler resets itself), leaving only temporaries behind, never a half-written final file.
namespace tumble::cli {

class InterruptGuard {
 public:
  InterruptGuard();   // installs the handlers
  ~InterruptGuard();  // restores the previous ones
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  /// True once a signal arrived.
  bool requested() const;
};

}  // namespace tumble::cli
