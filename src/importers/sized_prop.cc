#include "importers/sized_prop.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"
#include "fit/statistics.h"
#include "catalog/catalog.h"
#include "importers/blade_geometry.h"
#include "importers/csv.h"
#include "importers/import_common.h"
#include "rotor/bemt.h"
#include "rotor/family.h"
#include "prop/prop_model.h"
#include "rotor/uiuc_polar.h"

namespace dynosize {

using fit::Quantile;
namespace {

constexpr int kStaticSpeeds = 12;
constexpr int kSweepPoints = 14;
constexpr double kSweepTipSpeeds[] = {100.0, 160.0, 220.0};


}  // namespace

Json SizedPropJson(const PropSize& size) {
  const std::string family_id = FamilyIdOf(size);
  const RotorFamily* family = FindFamily(family_id);
  if (family == nullptr) {
    throw UsageError("propeller family '" + family_id + "' is not bundled: known are " + KnownFamilyIds());
  }
  return SizedPropJson(size, *family);
}

Json BemtPropJson(const BladeGeometry& blade, const std::string& id, const std::string& name, double pitch_m) {
  const Bemt bemt(blade, kUiucFittedPolar);
  const double d = 2.0 * blade.radius_m;
  Json stat = {{"rpm", Json::array()}, {"ct", Json::array()}, {"cp", Json::array()}};
  for (int i = 0; i < kStaticSpeeds; ++i) {
    const double tip = kSizedTipSpeedMin * std::pow(kSizedTipSpeedMax / kSizedTipSpeedMin, i / (kStaticSpeeds - 1.0));
    const double omega = tip / (0.5 * d);
    const BemtPoint p = bemt.Evaluate(omega, 0.0, kIsaSeaLevelRhoKgM3);
    stat["rpm"].push_back(RoundSig(RadPerSecToRpm(omega), 6));
    stat["ct"].push_back(RoundSig(p.ct, 5));
    stat["cp"].push_back(RoundSig(p.cp, 5));
  }
  Json sweeps = Json::array();
  // J up to past zero thrust: the geometric pitch ratio at 0.75 R, with margin.
  const double j_max = 1.3 * GeometricPitchM(blade, 0.75) / d + 0.1;
  for (const double tip : kSweepTipSpeeds) {
    const double omega = tip / (0.5 * d);
    Json sw = {{"rpm", RoundSig(RadPerSecToRpm(omega), 6)}, {"j", Json::array()}, {"ct", Json::array()}, {"cp", Json::array()}};
    for (int k = 1; k <= kSweepPoints; ++k) {
      const double j = j_max * k / kSweepPoints;
      const BemtPoint p = bemt.EvaluateAtAdvanceRatio(omega, j, kIsaSeaLevelRhoKgM3);
      if (!(p.ct > 0.0) || !(p.cp > 0.0)) break;
      sw["j"].push_back(RoundSig(j, 5));
      sw["ct"].push_back(RoundSig(p.ct, 5));
      sw["cp"].push_back(RoundSig(p.cp, 5));
    }
    if (!sw["j"].empty()) sweeps.push_back(sw);
  }
  Json e;
  e["id"] = id;
  e["name"] = name;
  e["diameter_m"] = RoundSig(d, 6);
  e["pitch_m"] = RoundSig(pitch_m, 6);
  e["blades"] = blade.blades;
  e["static_table"] = stat;
  if (!sweeps.empty()) e["j_tables"] = sweeps;
  return e;
}

Json SizedPropJson(const PropSize& size, const RotorFamily& family) {
  const std::string& family_id = family.id;
  BladeGeometry blade = SizedBlade(family, size.diameter_m, size.pitch_m, size.blades);
  const std::string dims = SizeText(size);
  blade.name = family_id + " " + dims;
  // "sized_<family>_<D>x<P>x<B>": SizedPropId(size) when family_id is size.family's.
  Json e = BemtPropJson(blade, "sized_" + family_id + "_" + dims,
                        "sized " + dims + " in, " + family.description + " (blade-element model)", size.pitch_m);
  e["source"] = {{"dataset", "dynosize blade-element model (src/rotor, docs/model.md section 13)"},
                 {"reference", "family " + family_id + ": " + family.source},
                 {"values", {{"diameter_m", "datasheet"}, {"pitch_m", "datasheet"}, {"blades", "datasheet"},
                             {"static_table", "estimated"}, {"j_tables", "estimated"}}},
                 {"note", "geometry of the family scaled to the size (eq B12), polar fitted on UIUC's measured propellers "
                          "(rotor/uiuc_polar.h); the family's blades span " + SignificantText(family.d_min_in, 3) + "-" +
                          SignificantText(family.d_max_in, 3) + " in and pitch ratios " +
                          SignificantText(family.pd_min, 2) + "-" + SignificantText(family.pd_max, 2) +
                          "; measured/predicted p10-p90 of propellers of 12 in and more left out (docs/validation.md): "
                          "thrust " + FixedText(kSizedThrustRatioP10, 2) + "-" + FixedText(kSizedThrustRatioP90, 2) +
                          ", torque " + FixedText(kSizedTorqueRatioP10, 2) + "-" + FixedText(kSizedTorqueRatioP90, 2)},
                 {"tier", "estimated"}};
  return e;
}

Json GeometryPropJson(const BladeGeometry& blade, const std::string& id, const std::string& geometry_file) {
  const double pitch_m = GeometricPitchM(blade, 0.75);
  Json e = BemtPropJson(blade, id, blade.name + " (blade-element model from its geometry)", pitch_m);
  e["source"] = {{"dataset", "dynosize blade-element model (src/rotor, docs/model.md section 13)"},
                 {"reference", geometry_file},
                 {"values", {{"diameter_m", "datasheet"}, {"pitch_m", "derived"}, {"blades", "datasheet"},
                             {"static_table", "estimated"}, {"j_tables", "estimated"}}},
                 {"note", "the blade's own chord and twist (eqs B5-B10), polar fitted on UIUC's measured propellers "
                          "(rotor/uiuc_polar.h); pitch: the geometric pitch at 0.75 R"},
                 {"tier", "estimated"}};
  return e;
}

SizeOnlyCheck CheckSizeOnly(const std::vector<PropEntry>& measured, const std::string& data, double min_diameter_m) {
  SizeOnlyCheck out;
  std::vector<int> prop_of_point;
  const FamilyBlades blades = ReadFamilyBlades(data);  // read once; each propeller left out of its copy
  for (const PropEntry& p : measured) {
    if (p.tier != DataTier::kMeasured || p.static_table.rpm.empty() || p.diameter_m < min_diameter_m || !p.pitch_m ||
        !p.exclude_reason.empty()) {
      continue;
    }
    PropSize size{p.diameter_m, *p.pitch_m, p.blades.value_or(2), ""};
    const std::string family_id = DefaultFamilyId(size.diameter_m, size.pitch_m);
    RotorFamily family;
    for (const RotorFamily& f : DeriveBundledFamilies(blades, UiucBladeNameOfId(p.id))) {
      if (f.id == family_id) family = f;
    }
    const PropEntry sized = PropEntryFromJson(SizedPropJson(size, family));
    const PropModel model(sized);
    for (std::size_t i = 0; i < p.static_table.rpm.size(); ++i) {
      const PropEvaluation e = model.Evaluate(RpmToRadPerSec(p.static_table.rpm[i]), kIsaSeaLevelRhoKgM3);
      out.points.push_back({p.id, family_id, p.diameter_m / 0.0254, p.static_table.rpm[i],
                            p.static_table.ct[i] / e.ct, p.static_table.cp[i] / e.cp});
      prop_of_point.push_back(out.props);
    }
    ++out.props;
  }
  if (out.points.empty()) return out;
  std::vector<double> t_all, q_all, t_med, q_med;
  for (const SizeOnlyPoint& s : out.points) {
    t_all.push_back(s.thrust_ratio);
    q_all.push_back(s.torque_ratio);
  }
  out.thrust_p10 = Quantile(t_all, 0.1);
  out.thrust_p90 = Quantile(t_all, 0.9);
  out.torque_p10 = Quantile(q_all, 0.1);
  out.torque_p90 = Quantile(q_all, 0.9);
  int t_in = 0, q_in = 0;
  for (int k = 0; k < out.props; ++k) {
    std::vector<double> t_other, q_other, t_own, q_own;
    for (std::size_t i = 0; i < out.points.size(); ++i) {
      (prop_of_point[i] == k ? t_own : t_other).push_back(out.points[i].thrust_ratio);
      (prop_of_point[i] == k ? q_own : q_other).push_back(out.points[i].torque_ratio);
    }
    std::vector<double> te, qe;
    for (double r : t_own) te.push_back(std::fabs(1.0 / r - 1.0));
    for (double r : q_own) qe.push_back(std::fabs(1.0 / r - 1.0));
    t_med.push_back(Quantile(te, 0.5));
    q_med.push_back(Quantile(qe, 0.5));
    if (t_other.empty()) continue;
    const double t10 = Quantile(t_other, 0.1), t90 = Quantile(t_other, 0.9);
    const double q10 = Quantile(q_other, 0.1), q90 = Quantile(q_other, 0.9);
    for (double r : t_own) t_in += (r >= t10 && r <= t90) ? 1 : 0;
    for (double r : q_own) q_in += (r >= q10 && r <= q90) ? 1 : 0;
  }
  out.thrust_median = Quantile(t_med, 0.5);
  out.torque_median = Quantile(q_med, 0.5);
  out.thrust_coverage = static_cast<double>(t_in) / static_cast<double>(out.points.size());
  out.torque_coverage = static_cast<double>(q_in) / static_cast<double>(out.points.size());
  return out;
}

}  // namespace dynosize
