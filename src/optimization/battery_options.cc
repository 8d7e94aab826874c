// Stage 1 of the catalog search (search_stages.h): the (battery entry, cells in series) options.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "battery/battery.h"
#include "common/error.h"
#include "optimization/components.h"
#include "optimization/search_stages.h"

namespace dynosize::search_internal {

std::vector<BatteryOption> BatteryOptions(const Mission& m, const Catalog& cat) {
  std::vector<BatteryOption> options;
  for (const std::string& id : m.battery.ids) {
    const BatteryEntry& b = cat.battery(id);
    if (!b.mass_kg) throw DataError("battery '" + id + "' has no mass_kg: the mission needs it");
    for (int s = m.battery.cells_min; s <= m.battery.cells_max; ++s) {
      if (s % b.cells_series != 0) continue;
      const BatteryPack pack(MissionPackParams(m.battery, b, s));
      DischargeOptions d;
      if (m.battery.cutoff_cell_v) d.cutoff_cell_v = *m.battery.cutoff_cell_v;
      BatteryOption o{&b, s, pack.OcvV(1.0), pack.cutoff_v(d), pack.capacity_ah(), pack.capacity_ah(),
                      pack.mass_kg(), pack.mass_kg(), pack.max_current_a()};
      o.ocv_integral_v = OcvIntegralUpperBound(pack, m.battery.reserve_soc);
      o.chemistry = pack.params().chemistry;
      o.ri_at_hi_ohm = pack.ri_ohm();
      if (m.battery.capacity_ah) {
        const double k_lo = m.battery.capacity_ah->lo / pack.capacity_ah();
        const double k_hi = m.battery.capacity_ah->hi / pack.capacity_ah();
        o.capacity_lo_ah = m.battery.capacity_ah->lo;
        o.capacity_hi_ah = m.battery.capacity_ah->hi;
        o.mass_lo_kg = pack.mass_kg() * k_lo;
        o.mass_hi_kg = pack.mass_kg() * k_hi;
        o.max_current_hi_a = pack.max_current_a() * k_hi;
        o.ri_at_hi_ohm = pack.ri_ohm() / k_hi;
      }
      options.push_back(o);
    }
  }
  if (options.empty()) {
    throw UsageError("mission battery: no cell count in [" + std::to_string(m.battery.cells_min) + ", " +
                     std::to_string(m.battery.cells_max) + "] is a multiple of the entries' cells in series");
  }
  return options;
}

}  // namespace dynosize::search_internal
