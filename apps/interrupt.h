// SIGINT during a long command (optimize): the handler only sets a flag, which the search reads
// (SearchOptions::stop) to stop between chunks and return the best found so far.
#pragma once

#include <atomic>
#include <chrono>
#include <string>

namespace dynosize::cli {

// While one lives, SIGINT sets Flag() instead of ending the process (the previous handler is
// restored when it goes): the command finishes its output, nothing is half-written.
class SigintToFlag {
 public:
  SigintToFlag();
  ~SigintToFlag();
  SigintToFlag(const SigintToFlag&) = delete;
  SigintToFlag& operator=(const SigintToFlag&) = delete;
  static const std::atomic<bool>& Flag();
  static bool Received() { return Flag().load(); }
};

// "12.3 s" / "1 min 05 s": the elapsed time of a progress line (optimize, sweep).
std::string ElapsedText(double s);

}  // namespace dynosize::cli
