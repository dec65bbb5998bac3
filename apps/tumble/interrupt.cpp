#include "interrupt.hpp"

#include <csignal>

namespace tumble::cli {
namespace {

volatile std::sig_atomic_t g_requested = 0;
struct sigaction g_previous_int, g_previous_term;

extern "C" void on_signal(int) { g_requested = 1; }  // async-signal-safe: only sets the flag

}  // namespace

InterruptGuard::InterruptGuard() {
  g_requested = 0;
  struct sigaction action = {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // the second signal gets the default action: terminate
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

bool InterruptGuard::requested() const { return g_requested != 0; }

}  // namespace tumble::cli
