// A controller's least supply voltage (vdc_min_v, issue 51: eVTOL controllers lock out below it):
// the evaluator holds the pack's cut-off to it, and R1 (docs/search.md#r1) drops the controller
// for a pack whose cut-off is below it, as exhaustive evaluation would.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "catalog/catalog.h"
#include "optimization/mission_eval.h"
#include "optimization/search_stages.h"

namespace dynosize {
namespace {

TEST(ControllerVoltage, APackBelowTheControllersLeastVoltageIsRefused) {
  const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  // The 150 kg cargo octocopter's 24S LiPo (cut-off 24 x 3.3 V under load; 100.8 V full) on the
  // Sevcon Gen4 size 8 (128-400 V): rated for the full charge, locked out long before the cut-off.
  const Mission m = ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/cargo_octocopter_150kg.json");
  const EscEntry& sevcon = cat.esc("hv_e_borgwarner_sevcon_gen4_size_8");
  ASSERT_DOUBLE_EQ(sevcon.params.vdc_min_v, 128.0);
  const EscEntry& apd = cat.esc("hv_e_advanced_power_drives_uhv_28s");  // 15-120 V
  const Combination c{&cat.motor("hl_m_t_motor_u15ii_kv80"), &sevcon, &cat.prop("kde_p_35.5x12.1x2"),
                      &cat.battery("pc_b_tattuplus25c22000mah12s1p"), 24, {}};
  const MissionResult r = MissionEvaluator(m, c).Solve();
  EXPECT_FALSE(r.feasible);
  const bool named = std::any_of(r.violations.begin(), r.violations.end(), [](const Violation& v) {
    return v.constraint == "esc_min_voltage" && v.limit == 128.0 && v.value < 100.0;
  });
  EXPECT_TRUE(named);
  Combination ok = c;
  ok.esc = &apd;
  const MissionResult a = MissionEvaluator(m, ok).Solve();
  EXPECT_TRUE(std::none_of(a.violations.begin(), a.violations.end(),
                           [](const Violation& v) { return v.constraint == "esc_min_voltage"; }));
  // R1: the search never offers the Sevcon for a 24S option, offers the APD.
  const auto options = search_internal::BatteryOptions(m, cat);
  const search_internal::EscTable table = search_internal::BuildEscTable(cat, options);
  const int sevcon_i = static_cast<int>(&sevcon - cat.escs().data());
  const int apd_i = static_cast<int>(&apd - cat.escs().data());
  for (std::size_t o = 0; o < options.size(); ++o) {
    bool has_sevcon = false, has_apd = false;
    for (const auto& members : table.per_option[o]) {
      has_sevcon = has_sevcon || std::count(members.begin(), members.end(), sevcon_i) > 0;
      has_apd = has_apd || std::count(members.begin(), members.end(), apd_i) > 0;
    }
    EXPECT_FALSE(has_sevcon) << o;
    EXPECT_TRUE(has_apd) << o;
  }
  // Dominance keeps to it: an otherwise better controller that locks out higher does not dominate.
  EscEntry better = apd;
  better.params.vdc_min_v = 128.0;
  better.params.resc_ohm = 0.0;
  EXPECT_FALSE(search_internal::EscDominates(better, apd));
}

}  // namespace
}  // namespace dynosize
