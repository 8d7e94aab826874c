#include "interrupt.h"

#include <csignal>

namespace dynosize::cli {

namespace {

// Lock-free (checked below), so setting it is safe in a signal handler.
std::atomic<bool> g_sigint{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the SIGINT flag must be lock-free");

struct sigaction g_previous;

extern "C" void OnSigint(int) { g_sigint.store(true); }

}  // namespace

SigintToFlag::SigintToFlag() {
  g_sigint.store(false);
  struct sigaction sa = {};
  sa.sa_handler = OnSigint;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // writes to stdout are not cut short by the signal
  sigaction(SIGINT, &sa, &g_previous);
}

SigintToFlag::~SigintToFlag() { sigaction(SIGINT, &g_previous, nullptr); }

const std::atomic<bool>& SigintToFlag::Flag() { return g_sigint; }

}  // namespace dynosize::cli
