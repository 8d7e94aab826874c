#include "optimization/credibility.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "catalog/esc_prior.h"
#include "common/units.h"
#include "model/physics.h"
#include "optimization/mission_eval.h"

namespace dynosize {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Relative band of Rm and Io per tier of the value (pessimistic x(1 + b), optimistic /(1 + b)):
//   measured   0.10  a 25 K winding temperature rise at +0.393 %/K (copper, model.md section 9)
//   computed,  0.25  datasheets measure R and Io differently from the rms circuit (ohmmeter, Io
//   stated         at a stated voltage; model.md section 8): an allowance
//   user       0.60  DriveCalc's data-base Rm is about 1.6x below a fit of DriveCalc's own
//                    measurements (catalog/README.md)
//   assumed    1.00  a factor of 2 either way
double ValueBand(SourceTier tier) {
  switch (tier) {
    case SourceTier::kMeasured: return 0.10;
    case SourceTier::kManufacturerComputed:
    case SourceTier::kManufacturerStated: return 0.25;
    case SourceTier::kUserContributed: return 0.60;
    case SourceTier::kAssumed: return 1.00;
  }
  return 1.0;
}

bool Contains(const std::string& s, const char* what) { return s.find(what) != std::string::npos; }

std::string Lower(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

const Json* SourceValues(const EntryBase& e) {
  if (!e.json.is_object() || !e.json.contains("source")) return nullptr;
  const Json& s = e.json.at("source");
  if (!s.is_object() || !s.contains("values") || !s.at("values").is_object()) return nullptr;
  return &s.at("values");
}

// The provenance text LabelTier reads: source.dataset and the catalog file's name (the
// manufacturer tables of sjkim-snu live in sjkim_mfr_tables.json).
std::string Dataset(const EntryBase& e) {
  std::string d;
  if (e.json.is_object() && e.json.contains("source") && e.json.at("source").is_object() &&
      e.json.at("source").contains("dataset") && e.json.at("source").at("dataset").is_string()) {
    d = e.json.at("source").at("dataset").get<std::string>();
  }
  const std::size_t slash = e.file.find_last_of('/');
  return d + " " + (slash == std::string::npos ? e.file : e.file.substr(slash + 1));
}

// The tier of one key of the entry: its own label, else (unlabelled or derived) the entry's.
SourceTier KeyTier(const EntryBase& e, ComponentKind kind, const char* key) {
  const Json* values = SourceValues(e);
  SourceTier t;
  if (values && values->contains(key) && values->at(key).is_string() &&
      LabelTier(values->at(key).get<std::string>(), Dataset(e), &t)) {
    return t;
  }
  return EntryTier(e, kind);
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double x = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(x);
  if (i + 1 >= v.size()) return v.back();
  const double f = x - static_cast<double>(i);
  return v[i] * (1.0 - f) + v[i + 1] * f;
}

std::string Fixed(double x, int digits) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(digits);
  o << x;
  return o.str();
}

}  // namespace

const char* SourceTierName(SourceTier tier) {
  switch (tier) {
    case SourceTier::kMeasured: return "measured";
    case SourceTier::kManufacturerComputed: return "manufacturer_computed";
    case SourceTier::kManufacturerStated: return "manufacturer_stated";
    case SourceTier::kUserContributed: return "user_contributed";
    case SourceTier::kAssumed: return "assumed";
  }
  return "assumed";
}

bool LabelTier(const std::string& label, const std::string& dataset, SourceTier* tier) {
  const std::string d = Lower(dataset);
  if (label == "measured") {
    *tier = SourceTier::kMeasured;
  } else if (label == "fitted") {
    // Fitted to a stand's measurements (DriveCalc MData, CTU tests, a user's log), or to a
    // manufacturer's published table (sjkim, dronebuildcalc): then it is what they state.
    *tier = Contains(d, "manufacturer") || Contains(d, "mfr") ? SourceTier::kManufacturerStated
                                                                : SourceTier::kMeasured;
  } else if (label == "computed") {
    *tier = SourceTier::kManufacturerComputed;
  } else if (label == "datasheet") {
    // DriveCalc's data base is contributed by its users (motor data, propeller power laws).
    *tier = Contains(d, "drivecalc") ? SourceTier::kUserContributed : SourceTier::kManufacturerStated;
  } else if (label == "assumed") {
    *tier = SourceTier::kAssumed;
  } else {
    return false;  // "derived": inherits
  }
  return true;
}

SourceTier EntryTier(const EntryBase& e, ComponentKind kind, std::string* why) {
  static const char* const kMotor[] = {"kv_rpm_per_v", "ke_v_s_per_rad", "rm_ohm", "io_a"};
  static const char* const kEsc[] = {"resc_ohm", "c1", "c0"};
  static const char* const kProp[] = {"static_table", "j_tables", "ct_static", "cp_static",
                                      "thrust_law_n", "thrust_law_exp", "power_law_w", "power_law_exp"};
  static const char* const kBattery[] = {"capacity_ah", "voltage_nominal_v", "ri_ohm"};
  const char* const* keys = kMotor;
  std::size_t n = 4;
  switch (kind) {
    case ComponentKind::kMotor: keys = kMotor; n = 4; break;
    case ComponentKind::kEsc: keys = kEsc; n = 3; break;
    case ComponentKind::kProp: keys = kProp; n = 8; break;
    case ComponentKind::kBattery: keys = kBattery; n = 3; break;
  }
  const std::string dataset = Dataset(e);
  const Json* values = SourceValues(e);
  bool any = false;
  SourceTier worst = SourceTier::kMeasured;
  std::string worst_key;
  for (std::size_t i = 0; values && i < n; ++i) {
    if (!values->contains(keys[i]) || !values->at(keys[i]).is_string()) continue;
    SourceTier t;
    if (!LabelTier(values->at(keys[i]).get<std::string>(), dataset, &t)) continue;
    if (!any || t > worst) {
      worst = t;
      worst_key = keys[i];
    }
    any = true;
  }
  if (!any) {
    // No labelled performance value: the data set decides; unknown provenance is assumed.
    const std::string d = Lower(dataset);
    if (Contains(d, "uiuc")) worst = SourceTier::kMeasured;
    else if (Contains(d, "apc per3")) worst = SourceTier::kManufacturerComputed;
    else if (Contains(d, "drivecalc")) worst = SourceTier::kUserContributed;
    else worst = SourceTier::kAssumed;
    worst_key = "source.dataset";
  }
  if (why) *why = worst_key;
  return worst;
}

const std::vector<FmClass>& PropFmClasses() {
  // Recomputed from catalog/uiuc_propdb.json by ComputePropFmClasses (tested).
  static const std::vector<FmClass> kClasses = {
      {0.0, 0.127, 0.4243, 0.5284, 0.6076, 18, "under 5 in"},
      {0.127, 0.2032, 0.3133, 0.4542, 0.5711, 29, "5-8 in"},
      {0.2032, 0.254, 0.3541, 0.5454, 0.6306, 82, "8-10 in"},
      {0.254, 0.3048, 0.4315, 0.5922, 0.6834, 84, "10-12 in"},
      {0.3048, kInf, 0.3763, 0.6654, 0.7345, 26, "12 in and over"},
  };
  return kClasses;
}

const FmClass& PropFmClassOf(double diameter_m) {
  const auto& c = PropFmClasses();
  for (const FmClass& k : c) {
    if (diameter_m < k.d_hi_m) return k;
  }
  return c.back();
}

double MedianStaticFigureOfMerit(const PropEntry& prop) {
  const PropStaticTable& t = prop.static_table;
  std::vector<double> fm;
  for (std::size_t i = 0; i < t.rpm.size() && i < t.ct.size() && i < t.cp.size(); ++i) {
    if (t.ct[i] > 0 && t.cp[i] > 0) fm.push_back(std::pow(t.ct[i], 1.5) / (t.cp[i] * std::sqrt(kPi / 2.0)));
  }
  return fm.empty() ? 0.0 : Percentile(std::move(fm), 0.5);
}

std::vector<FmClass> ComputePropFmClasses(const std::vector<PropEntry>& props) {
  std::vector<FmClass> out = PropFmClasses();
  for (FmClass& k : out) {
    std::vector<double> fm;
    for (const PropEntry& p : props) {
      if (p.static_table.rpm.empty() || p.diameter_m < k.d_lo_m || !(p.diameter_m < k.d_hi_m)) continue;
      if (EntryTier(p, ComponentKind::kProp) != SourceTier::kMeasured) continue;
      fm.push_back(MedianStaticFigureOfMerit(p));
    }
    k.n = static_cast<int>(fm.size());
    k.p10 = Percentile(fm, 0.10);
    k.p50 = Percentile(fm, 0.50);
    k.p90 = Percentile(fm, 0.90);
  }
  return out;
}

PropAdjustment PropAdjustmentFor(const PropEntry& prop, DataScenario scenario) {
  PropAdjustment a;
  if (scenario == DataScenario::kAsGiven) return a;
  const SourceTier tier = EntryTier(prop, ComponentKind::kProp);
  const FmClass& k = PropFmClassOf(prop.diameter_m);
  if (tier == SourceTier::kMeasured) {
    if (scenario == DataScenario::kPessimistic) a.power_factor = 1.0 + kMeasuredPowerBand;
    if (scenario == DataScenario::kOptimistic) {
      a.power_factor = 1.0 - kMeasuredPowerBand;
      a.fm_cap = 1.0;  // never beyond momentum theory
    }
    return a;
  }
  if (tier == SourceTier::kManufacturerComputed) {
    switch (scenario) {
      case DataScenario::kPessimistic: a.power_factor = 1.0 / kComputedFmRatio.min; break;
      case DataScenario::kOptimistic: a.power_factor = 1.0 / kComputedFmRatio.max; a.fm_cap = k.p90; break;
      default: a.power_factor = 1.0 / kComputedFmRatio.median; a.fm_cap = k.p90; break;
    }
    return a;
  }
  switch (scenario) {
    case DataScenario::kPessimistic: a.fm_cap = k.p10; break;
    case DataScenario::kOptimistic: a.fm_cap = k.p90; break;
    default: a.fm_cap = k.p50; break;
  }
  return a;
}

void AdjustPropEvaluation(const PropAdjustment& adj, double diameter_m, PropEvaluation* ev) {
  if (adj.identity() || !(ev->omega_rad_s > 0.0) || !(ev->power_w > 0.0)) return;
  if (ev->airspeed_m_s > 0.0 && !ev->no_forward_flight_data) return;  // forward-flight tables
  double p = adj.power_factor * ev->power_w;
  if (adj.fm_cap < 1e300) p = std::max(p, IdealRotorPowerW(ev->thrust_n, diameter_m, ev->rho_kg_m3) / adj.fm_cap);
  const double k = p / ev->power_w;
  ev->power_w = p;
  ev->torque_nm *= k;
  ev->cp *= k;
}

bool IsFoldingProp(const PropEntry& prop) {
  // Words and UIUC codes that name folding blades: "folding"/"folder"/"klapp" in any name;
  // Aeronaut CAM (AeroCAM, AeroCarbon, Aero-Cam, UIUC ancf/ance), Graupner CAM folding
  // ("Graupner CAM", UIUC grcp/grcsp) and Kavan folding (UIUC kavfk). "GrpCamSpeed" (Graupner
  // CAM Speed, a fixed pylon propeller) is one word and does not match.
  static const char* const kTokens[] = {"cam", "aerocam", "aerocarbon", "ancf", "ance", "grcp", "grcsp", "kavfk"};
  const std::string name = Lower(prop.name);
  if (Contains(name, "fold") || Contains(name, "klapp")) return true;
  std::string token;
  for (std::size_t i = 0; i <= name.size(); ++i) {
    const char ch = i < name.size() ? name[i] : ' ';
    if (std::isalnum(static_cast<unsigned char>(ch))) {
      token += ch;
      continue;
    }
    for (const char* t : kTokens) {
      if (token == t) return true;
    }
    token.clear();
  }
  return false;
}

bool MissionUsesRotorLift(const Mission& m) {
  for (const Segment& s : m.segments) {
    if (s.type == SegmentType::kHover || s.type == SegmentType::kClimb) return true;
    if (s.type == SegmentType::kCruise && !(s.lift_to_drag > 0)) return true;
  }
  return false;
}

bool FoldingPropRefused(const PropEntry& prop, const Mission& m) {
  return !m.constraints.allow_folding_props_for_lift && MissionUsesRotorLift(m) && IsFoldingProp(prop);
}

double MotorMaxVoltageV(const MotorEntry& motor) {
  if (!motor.json.is_object() || !motor.json.contains("cells_max") || !motor.json.at("cells_max").is_number()) {
    return kInf;
  }
  // 1e-9 relative: a full pack's OCV is 4.2 V per cell up to the rounding of its table.
  return 4.2 * motor.json.at("cells_max").get<double>() * (1.0 + 1e-9);
}

double EstimatedMotorPowerW(double mass_kg) { return 4319.0 * std::pow(mass_kg, 0.953); }

double EstimatedMotorCurrentA(double mass_kg, double kv_rpm_per_v) {
  return 0.5956 * std::pow(mass_kg, 1.2816) * std::pow(kv_rpm_per_v, 0.9629);
}

double MotorKvRpmPerV(const MotorEntry& motor) {
  if (motor.kv_rpm_per_v) return *motor.kv_rpm_per_v;
  const double k = motor.params.type == MotorType::kBldc ? 3.0 / (std::sqrt(2.0) * kPi) : 1.0;
  return k / (motor.params.ke_v_s_per_rad * kPi / 30.0);
}

MotorParams ScenarioMotorParams(const MotorEntry& motor, const Mission& m, bool* rating_estimated,
                                bool* excluded) {
  MotorParams p = motor.params;
  const bool unrated = !std::isfinite(p.max_current_a) && !std::isfinite(p.max_power_w);
  if (rating_estimated) *rating_estimated = false;
  if (excluded) *excluded = unrated && !m.constraints.estimate_unrated_motors;
  if (unrated && m.constraints.estimate_unrated_motors && motor.mass_kg) {
    p.max_power_w = EstimatedMotorPowerW(*motor.mass_kg);
    const double kv = MotorKvRpmPerV(motor);
    if (kv > 0 && std::isfinite(kv)) p.max_current_a = EstimatedMotorCurrentA(*motor.mass_kg, kv);
    if (rating_estimated) *rating_estimated = true;
  }
  const DataScenario s = m.objective.ranking;
  if (s == DataScenario::kPessimistic || s == DataScenario::kOptimistic) {
    const double br = 1.0 + ValueBand(KeyTier(motor, ComponentKind::kMotor, "rm_ohm"));
    const double bi = 1.0 + ValueBand(KeyTier(motor, ComponentKind::kMotor, "io_a"));
    const bool up = s == DataScenario::kPessimistic;
    p.rm_ohm = up ? p.rm_ohm * br : p.rm_ohm / br;
    p.io_a = up ? p.io_a * bi : p.io_a / bi;
  }
  return p;
}

EscParams ScenarioEscParams(const EscEntry& esc, DataScenario s) {
  EscParams p = esc.params;
  if (s != DataScenario::kPessimistic && s != DataScenario::kOptimistic) return p;
  const bool up = s == DataScenario::kPessimistic;
  const SourceTier tr = KeyTier(esc, ComponentKind::kEsc, "resc_ohm");
  // An assumed RESC is the prior's law (esc_prior.h): its scatter is a factor exp(sd) either way.
  const double kr = tr == SourceTier::kAssumed ? std::exp(DefaultEscPrior().resistance_log_sd) : 1.0 + ValueBand(tr);
  p.resc_ohm = up ? p.resc_ohm * kr : p.resc_ohm / kr;
  if (up && KeyTier(esc, ComponentKind::kEsc, "c0") == SourceTier::kAssumed) {
    p.c0 = std::max(p.c0, kAssumedEscC0Pessimistic);
  }
  return p;
}

void AddObjectiveRange(const Mission& m, const Combination& c, MissionResult* r) {
  ObjectiveRange& g = r->range;
  g = ObjectiveRange{};
  std::string why;
  g.tiers.push_back({"motor", c.motor->id, EntryTier(*c.motor, ComponentKind::kMotor, &why), why});
  g.tiers.push_back({"ESC", c.esc->id, EntryTier(*c.esc, ComponentKind::kEsc, &why), why});
  g.tiers.push_back({"propeller", c.prop->id, EntryTier(*c.prop, ComponentKind::kProp, &why), why});
  g.tiers.push_back({"battery", c.battery->id, EntryTier(*c.battery, ComponentKind::kBattery, &why), why});
  bool estimated = false, excluded = false;
  ScenarioMotorParams(*c.motor, m, &estimated, &excluded);
  g.motor_rating = estimated ? "none in the catalog: " + Fixed(EstimatedMotorPowerW(*c.motor->mass_kg), 0) + " W, " +
                                   Fixed(EstimatedMotorCurrentA(*c.motor->mass_kg, MotorKvRpmPerV(*c.motor)), 1) +
                                   " A estimated from the mass and Kv (assumed; credibility.h)"
                   : excluded ? "none in the catalog: excluded (constraints.unrated_motors = exclude)"
                              : "catalog";
  // One scenario: its objective with the mission's limits relaxed to physics (*flies: that
  // run is feasible) and what it breaks under the mission's own limits.
  MotorEntry motor_free = *c.motor;
  EscEntry esc_free = *c.esc;
  BatteryEntry battery_free = *c.battery;
  constexpr double kNoRating = 1e300;  // finite: the motor counts as rated (no estimate)
  motor_free.params.max_current_a = motor_free.params.max_power_w = kNoRating;
  esc_free.params.max_current_a = kNoRating;
  battery_free.max_current_a = kNoRating;
  battery_free.peak_current_a = kNoRating;
  const Combination c_free{&motor_free, &esc_free, c.prop, &battery_free, c.cells};
  auto solve = [&](DataScenario s, bool* flies, std::string* breaks) {
    Mission ms = m;
    ms.objective.ranking = s;
    const MissionResult x = MissionEvaluator(ms, c).Solve(std::numeric_limits<double>::infinity(), false);
    for (const Violation& v : x.violations) *breaks += (breaks->empty() ? "" : ", ") + v.constraint;
    *flies = x.feasible;
    if (x.feasible) return x.objective;
    ms.constraints.max_throttle = 1.0;
    ms.constraints.min_hover_throttle = 0.0;
    ms.constraints.allow_esc_saturation = true;
    ms.constraints.enforce_motor_power = false;
    ms.constraints.current_margin = 0.0;
    const MissionResult y = MissionEvaluator(ms, c_free).Solve(std::numeric_limits<double>::infinity(), false);
    *flies = y.feasible;
    return y.objective;
  };
  bool pess_flies = false, opt_flies = false;
  std::string pess_breaks, opt_breaks;
  const double pess = solve(DataScenario::kPessimistic, &pess_flies, &pess_breaks);
  const double opt = solve(DataScenario::kOptimistic, &opt_flies, &opt_breaks);
  if (m.objective.ranking == DataScenario::kAsGiven) {
    g.as_given = r->objective;
    g.as_given_feasible = r->feasible;
  } else {
    Mission ms = m;
    ms.objective.ranking = DataScenario::kAsGiven;
    const MissionResult x = MissionEvaluator(ms, c).Solve(std::numeric_limits<double>::infinity(), false);
    g.as_given = x.objective;
    g.as_given_feasible = x.feasible;
    for (const Violation& v : x.violations) g.as_given_breaks += (g.as_given_breaks.empty() ? "" : ", ") + v.constraint;
  }
  // Larger is better for max_*: the pessimistic data give the low end; min_energy the high end.
  const bool larger_better = m.objective.type != ObjectiveType::kMinEnergy;
  const double lo_v = larger_better ? pess : opt, hi_v = larger_better ? opt : pess;
  const bool lo_ok = larger_better ? pess_flies : opt_flies, hi_ok = larger_better ? opt_flies : pess_flies;
  g.low_breaks = larger_better ? pess_breaks : opt_breaks;
  g.high_breaks = larger_better ? opt_breaks : pess_breaks;
  // A feasible result lies inside its range (the solver's tolerance could put it a hair
  // outside); an infeasible one's objective is not a value to bracket.
  const double mid = r->feasible ? r->objective : (lo_ok ? lo_v : hi_v);
  g.low = lo_ok ? std::min(lo_v, mid) : mid;
  g.high = hi_ok ? std::max(hi_v, mid) : mid;
  g.complete = lo_ok && hi_ok;
  const FmClass& k = PropFmClassOf(c.prop->diameter_m);
  const SourceTier pt = g.tiers[2].tier;
  std::ostringstream b;
  if (pt == SourceTier::kMeasured) {
    b << "propeller measured: shaft power +-" << Fixed(100 * kMeasuredPowerBand, 0) << " %";
  } else if (pt == SourceTier::kManufacturerComputed) {
    b << "propeller manufacturer_computed: static FM x " << Fixed(kComputedFmRatio.min, 2) << "-"
      << Fixed(kComputedFmRatio.max, 2) << " (credible " << Fixed(kComputedFmRatio.median, 2) << "), measured/computed of "
      << kComputedFmRatio.pairs << " APC products, at most the p90 " << Fixed(k.p90, 2) << " of " << k.n
      << " measured props of " << k.label;
  } else {
    b << "propeller " << SourceTierName(pt) << ": static FM held to the p10-p90 (" << Fixed(k.p10, 2) << "-"
      << Fixed(k.p90, 2) << ") of " << k.n << " measured props of " << k.label << " (credible: p50 "
      << Fixed(k.p50, 2) << ")";
  }
  b << "; motor Rm, Io by their tier (" << SourceTierName(g.tiers[0].tier) << "); ESC RESC";
  if (KeyTier(*c.esc, ComponentKind::kEsc, "c0") == SourceTier::kAssumed) b << " and C0 0-" << kAssumedEscC0Pessimistic;
  b << " within the prior's band";
  g.basis = b.str();
  g.computed = true;
}

}  // namespace dynosize
