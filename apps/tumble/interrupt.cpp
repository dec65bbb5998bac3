#include "interrupt.hpp"

#include <atomic>
#include <csignal>
#include <exception>
#include <iterator>

namespace tumble::cli {
namespace {

// Lock-free atomics: safe to touch from a handler, and from whichever thread the kernel picks to run
// it (OpenMP's threads too).
std::atomic<int> g_count{0};           // signals received since the guard was installed
std::atomic<int> g_first{0};           // the first one's number
std::atomic<bool> g_deferring{false};  // a Deferral exists
std::atomic<int> g_deferred{0};        // the second signal, held by a Deferral
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free);

// SIGXCPU: a batch system's warning that the CPU-time limit is near (before SIGKILL), answered as
// SIGTERM is (a checkpoint, a valid file).
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGXCPU};
constexpr size_t kSignalCount = std::size(kSignals);
struct sigaction g_previous[kSignalCount];

/// Ends the process as the signal's default action does (the shell sees "killed by SIGINT").
void terminate_by(int sig) {
  struct sigaction action = {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  sigaction(sig, &action, nullptr);
  raise(sig);  // inside the handler the signal is blocked: delivered, fatally, as the handler returns
}

extern "C" void on_signal(int sig) {  // async-signal-safe: atomics, sigaction and raise only
  const int n = g_count.fetch_add(1) + 1;
  if (n == 1) {
    g_first.store(sig);
    return;
  }
  if (n == 2 && g_deferring.load()) {
    g_deferred.store(sig);
    return;
  }
  terminate_by(sig);
}

}  // namespace

InterruptGuard::InterruptGuard() {
  g_count = 0;
  g_first = 0;
  g_deferred = 0;
  struct sigaction action = {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  for (int s : kSignals) sigaddset(&action.sa_mask, s);  // one handler at a time per thread
  action.sa_flags = SA_RESTART;
  for (size_t i = 0; i < kSignalCount; ++i) sigaction(kSignals[i], &action, &g_previous[i]);
}

InterruptGuard::~InterruptGuard() {
  for (size_t i = 0; i < kSignalCount; ++i) sigaction(kSignals[i], &g_previous[i], nullptr);
}

bool InterruptGuard::requested() const { return g_count.load() != 0; }

int InterruptGuard::signal() const { return g_first.load(); }

InterruptGuard::Deferral::Deferral() { g_deferring = true; }

InterruptGuard::Deferral::~Deferral() {
  g_deferring = false;
  const int sig = g_deferred.exchange(0);
  if (sig != 0 && std::uncaught_exceptions() == 0) terminate_by(sig);
}

}  // namespace tumble::cli
