#include "model/operating_point.h"

namespace dynosize {

std::vector<std::string> LimitNames(std::uint32_t limits) {
  static const char* const kNames[] = {"throttle_above_one", "throttle_below_zero",
                                       "motor_current",      "esc_current",
                                       "motor_power",        "esc_voltage",
                                       "stalled",            "overrunning",
                                       "thermal_runaway",    "creates_energy"};
  std::vector<std::string> names;
  for (std::uint32_t bit = 0; bit < sizeof(kNames) / sizeof(kNames[0]); ++bit) {
    if (limits & (1u << bit)) names.emplace_back(kNames[bit]);
  }
  return names;
}

}  // namespace dynosize
