#include "optimization/search_options.h"

#include <string>

#include "mission/mission.h"

namespace dynosize {

bool SearchOptions::IsValid(std::string* error) const {
  std::string why;
  if (top_n < 1) why = "--top " + std::to_string(top_n) + ": must be >= 1";
  if (error) *error = why;
  return why.empty();
}

bool StopRequested(const SearchOptions& opt) {
  if (opt.stop && opt.stop->load(std::memory_order_relaxed)) return true;
  return opt.deadline != std::chrono::steady_clock::time_point::max() && std::chrono::steady_clock::now() >= opt.deadline;
}

bool NeedsOneThread(const Mission& mission) {
  for (const Segment& sg : mission.segments) {
    if (sg.type == SegmentType::kShaft && sg.shaft_omega_rad_s.free()) return true;
  }
  return false;
}

}  // namespace dynosize
