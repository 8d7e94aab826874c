// Peak ratings (issue 51): a part's peak current and power hold for its stated duration only; a
// segment longer than that is held to the continuous rating (model/params.h SegmentRating,
// ApplyPeakRatings), and the search's lists read the peak (EscReachCurrentA) so that no bound
// drops what a short segment may fly.
#include <gtest/gtest.h>

#include <string>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "optimization/credibility.h"
#include "optimization/mission_eval.h"

namespace dynosize {
namespace {

TEST(PeakRatings, ASegmentLongerThanThePeakDurationIsHeldToTheContinuousRating) {
  MotorParams p;
  p.max_current_a = 100.0;
  p.max_power_w = 27000.0;
  p.peak_current_a = 190.0;
  p.peak_power_w = 60000.0;
  p.peak_duration_s = 120.0;
  ApplyPeakRatings(&p);
  EXPECT_EQ(p.max_current_a, 190.0);
  EXPECT_EQ(p.continuous_current_a, 100.0);
  EXPECT_EQ(SegmentRating(p.max_power_w, p.continuous_power_w, p.peak_duration_s, 120.0), 60000.0);
  EXPECT_EQ(SegmentRating(p.max_power_w, p.continuous_power_w, p.peak_duration_s, 121.0), 27000.0);
  // No duration stated: the peak is never used.
  MotorParams q;
  q.max_current_a = 100.0;
  q.peak_current_a = 190.0;
  ApplyPeakRatings(&q);
  EXPECT_EQ(q.max_current_a, 100.0);
  EXPECT_EQ(SegmentRating(q.max_current_a, q.continuous_current_a, q.peak_duration_s, 1.0), 100.0);
}

// The one-seat air taxi made heavier (350 kg) so that its Joby JM1S lift motors (8.2 kW
// continuous, 12.6 kW for 15 s) hover above their continuous power: a 10 s hover may, a 60 s
// one may not.
TEST(PeakRatings, TheEvaluatorAllowsThePeakInAShortSegmentOnly) {
  const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/air_taxi_one_seat.json");
  j["vehicle"]["mass_kg"] = 250.0;
  j["segments"] = Json::array({{{"name", "short"}, {"type", "hover"}, {"duration_s", 10}, {"group", "lift"}},
                               {{"name", "long"}, {"type", "hover"}, {"duration_s", 60}, {"group", "lift"}},
                               {{"name", "cruise"}, {"type", "cruise"}, {"airspeed_m_s", 25}, {"lift_to_drag", 8},
                                {"distance_m", 1000}, {"group", "cruise"}}});
  j["battery"]["capacity_ah"] = 40;
  const Mission m = ParseMission(j, "heavy taxi");
  const int lift = m.segments[0].group, cruise = m.segments[2].group;
  Combination c;
  c.battery = &cat.battery("pc_b_molicel_inr21700_p45b");
  c.cells = 96;
  c.groups.resize(2);
  c.groups[static_cast<std::size_t>(lift)] = {&cat.motor("ev_m_jm1s_inrunner"), &cat.esc("hv_e_embention_veronte_mc110_v2.0"),
                                              &cat.prop("kde_p_35.5x12.1x2")};
  c.groups[static_cast<std::size_t>(cruise)] = {&cat.motor("ev_m_emrax_188_hv_ac"),
                                                &cat.esc("hv_e_embention_veronte_mc110_v2.0"), &cat.prop("apc_per3_28x20_4")};
  c.motor = c.groups[static_cast<std::size_t>(lift)].motor;
  c.esc = c.groups[static_cast<std::size_t>(lift)].esc;
  c.prop = c.groups[static_cast<std::size_t>(lift)].prop;
  const MissionResult r = MissionEvaluator(m, c).Solve();
  ASSERT_EQ(r.segments.size(), 3u);
  const double pac_short = r.segments[0].point.pac_w, pac_long = r.segments[1].point.pac_w;
  ASSERT_GT(pac_short, 8200.0) << "the test needs a hover above the continuous power";
  ASSERT_LT(pac_long, 12600.0) << "the test needs a hover below the peak power";
  bool long_held = false, short_held = false;
  for (const Violation& v : r.violations) {
    if (v.constraint != "motor_power") continue;
    if (v.segment == "long") long_held = v.limit == 8200.0;
    if (v.segment == "short") short_held = true;
  }
  EXPECT_TRUE(long_held);
  EXPECT_FALSE(short_held);
}

}  // namespace
}  // namespace dynosize
