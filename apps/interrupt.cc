#include "interrupt.h"

#include <csignal>
#include <iomanip>
#include <sstream>

#include "common/error.h"
#include "common/text_format.h"

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

std::string ElapsedText(double s) {
  if (s < 60) return FixedText(s, 1) + " s";
  std::ostringstream o;
  o << static_cast<long long>(s / 60) << " min " << std::setw(2) << std::setfill('0') << static_cast<long long>(s) % 60
    << " s";
  return o.str();
}

}  // namespace dynosize::cli
