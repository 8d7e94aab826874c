#include "optimization/search.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cmath>
#include <limits>
#include <memory>
#include <thread>

#include "common/error.h"
#include "common/units.h"
#include "mission/flight.h"

namespace dynosize {

// Pruning rules and why they are safe.
//
// Monotonicity assumed of the model (true of eqs 42-59 and of the propeller data checked here):
//  (M1) a rotor's static thrust and torque rise with its speed (checked per propeller on the
//       grid below; a propeller whose grid is not monotone gets no thrust-based pruning);
//  (M2) at a fixed operating point (torque, speed) the drive's throttle, Irms, PAC and IDC rise
//       with the load and do not depend on the ESC except through RESC >= 0, which only adds
//       to them (eq 48: U = (Rm + RESC)*I + KE*omega); the throttle falls with the voltage;
//  (M3) more mass means more thrust in every segment (flight.h), hence (M1, M2) more speed,
//       torque, current and power.
// Bounds on one (motor, propeller, battery option) pair use the lightest the vehicle can be
// with them: the lightest ESC that can take the cell count and the smallest battery capacity.
//
// R0 (frame): a propeller larger than the vehicle's max_prop_diameter_m fails prop_diameter
//    whatever else is chosen; so does a folding propeller for lift (prop_folding), a motor
//    without a source rating when the mission excludes such motors (motor_unrated),
//    credibility.h, and an entry the catalog excludes ("exclude", catalog_exclude).
// Data scenario (credibility.h): the evaluator flies the mission's ranking scenario (the
//    credible value by default); the grids below use the same adjusted propeller torque (it
//    only rises, pointwise, and keeps rising with speed: M1 holds) and the same motor ratings,
//    so every rule bounds the score that is ranked.
// R1 (ratings, ESC voltage): an ESC whose vdc_max_v is below the full-charge OCV of the cells
//    fails the esc_voltage constraint whatever else is chosen; so does a motor whose cells_max
//    (4.2 V per cell) is below it (motor_voltage).
// R2 (thrust / prop speed): in every hover segment each rotor gives at least T_lb, the thrust
//    at the lightest mass. By (M1) its speed is at least omega_lb, the largest grid speed whose
//    thrust is <= T_lb, and its torque at least the smallest grid torque at or above omega_lb.
//    A propeller with max_rpm below omega_lb fails prop_max_rpm.
// R3 (motor): with (omega_lb, Q_lb) and an ESC of zero resistance at the highest voltage the
//    pack can have (its full-charge OCV), Drive::Inverse gives lower bounds of the throttle,
//    Irms and PAC of every real choice (M2). If that throttle is above the mission's limit
//    (or the ESC's saturation knee when saturation is not allowed), or Irms above the motor's
//    margin-reduced rating, or PAC above its power rating, no ESC and no capacity can fix it.
//    An ESC whose margin-reduced rating is below that Irms lower bound is left out for the pair.
// R4 (objective bound, branch and bound): with the same bounds the power drawn in a hover
//    segment is at least N*PDC_lb + P_avionics, PDC_lb the smaller of the zero-resistance
//    drive's PDC at the full-charge and the cut-off voltage (PDC = C1*U*I/kv + C0*VDC*I is
//    linear in VDC, eqs 57, 59). So is the power of a climb or fixed-airspeed cruise segment
//    whose per-rotor thrust is at least the hover bound's, when the propeller has static-only
//    data (read at J = 0 in any inflow: the same speed-thrust curve). Every segment draws at
//    least P_avionics. min_energy: the energy is at least the sum over segments of that power
//    times their shortest duration (and of the momentum bound below). max_endurance with a
//    hover segment stretched: the terminal energy of the whole mission is at most
//    Q_max*integral of OCV(s) ds over [reserve, 1] (Q_max the largest capacity); the other
//    segments take at least their energy bounds, the stretch gets the rest at no less than its
//    power bound; the fixed segments add at most their longest durations. Pairs are evaluated best bound
//    first and the search stops when the next bound cannot beat the N-th best found (every
//    later pair has a worse bound). max_efficiency has no such bound (it is not pruned by R4).
// R5 (ESC dominance): within one pair, an ESC with the same C1, C0, tr_sat, sat_slope as an
//    ESC already evaluated but no lighter, no lower in resistance and no higher in current
//    rating scores no better (M2, M3) and is infeasible if the other is; so when the other is
//    infeasible or not in the top N, it is skipped. A virtual ESC of zero resistance, the
//    lightest mass and no current limit dominates all ESCs of a class: when it cannot enter
//    the top N the whole class is skipped for the pair. min_hover_throttle is the one
//    constraint that more resistance or mass helps: the virtual ESC is evaluated without it,
//    and an ESC that fails it does not rule out the ESCs it dominates.
// R6 (propeller data credibility): see the comment at the rule; the hover point's figure of
//    merit must not exceed the mission's max_figure_of_merit.
// R7 (static-only propeller data in fast axial flow): see the comment at the rule.
// Everything not pruned is evaluated exactly (MissionEvaluator::Solve): the answer is the
// true top N over the catalog under (M1)-(M3).

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kGrid = 256;
constexpr double kGridMinRadS = 30.0, kGridMaxRadS = 6000.0;

struct PropGrid {
  bool monotone = true;
  double omega[kGrid], thrust[kGrid], torque_suffix_min[kGrid];
  double fom[kGrid];  // static figure of merit T^1.5/(sqrt(2*rho*A)*P) (R6)
  double mass_kg = 0;
};

struct BatteryOption {
  const BatteryEntry* entry;
  int cells;
  double v_full, v_cut, capacity_lo_ah, capacity_hi_ah, mass_lo_kg, mass_hi_kg, max_current_hi_a;
  double ocv_integral_v = 0;  // upper bound of the integral of OCV(s) ds over [reserve, 1]
};

struct EscClass {
  double c1, c0, tr_sat, sat_slope;
  std::vector<int> members;
};

double EscMassKg(const EscEntry& e) {
  if (e.mass_kg) return *e.mass_kg;
  const double rating = std::isfinite(e.params.max_current_a) ? e.params.max_current_a : 30.0;
  return 0.005 + 0.001 * rating;  // as MissionEvaluator assumes
}

struct Candidate {
  double bound;  // lower bound of the score (smaller is better)
  int motor, prop, option;
  double irms_lb;
};

// Counts per pruning rule without building a string per pruned pair (rule names are literals).
class RuleCounts {
 public:
  void Add(const char* rule, long long n) {
    for (auto& [name, count] : counts_) {
      if (std::strcmp(name, rule) == 0) {
        count += n;
        return;
      }
    }
    counts_.emplace_back(rule, n);
  }
  void MergeInto(std::map<std::string, long long>* out) const {
    for (const auto& [name, count] : counts_) (*out)[name] += count;
  }

 private:
  std::vector<std::pair<const char*, long long>> counts_;
};

// A result that breaks min_hover_throttle (possibly among others) says nothing about a
// dominated ESC, whose higher throttle may meet it (R5).
bool FailsMinHoverThrottle(const MissionResult& r) {
  for (const Violation& v : r.violations) {
    if (v.constraint == "min_hover_throttle") return true;
  }
  return false;
}

bool Dominates(const EscEntry& a, const EscEntry& b) {
  return EscMassKg(a) <= EscMassKg(b) && a.params.resc_ohm <= b.params.resc_ohm &&
         a.params.max_current_a >= b.params.max_current_a && a.params.vdc_max_v >= b.params.vdc_max_v;
}

}  // namespace

double OcvIntegralUpperBound(const BatteryPack& pack, double reserve_soc) {
  // OCV rises with SOC, so the right-endpoint sum over-estimates the integral.
  constexpr int kPieces = 400;
  double sum = 0;
  for (int i = 1; i <= kPieces; ++i) {
    sum += pack.OcvV(reserve_soc + (1.0 - reserve_soc) * i / kPieces);
  }
  return sum * (1.0 - reserve_soc) / kPieces;
}

SearchResult SearchCatalog(const Mission& m, const Catalog& cat, const SearchOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  if (opt.top_n < 1) throw UsageError("--top " + std::to_string(opt.top_n) + ": must be >= 1");
  SearchResult out;
  const auto& motors = cat.motors();
  const auto& escs = cat.escs();
  const auto& props = cat.props();
  const MissionConstraints& k = m.constraints;
  const double margin = 1.0 - k.current_margin;

  // Battery options (entry, cells in series).
  std::vector<BatteryOption> options;
  for (const std::string& id : m.battery.ids) {
    const BatteryEntry& b = cat.battery(id);
    if (!b.mass_kg) throw DataError("battery '" + id + "' has no mass_kg: the mission needs it");
    for (int s = m.battery.cells_min; s <= m.battery.cells_max; ++s) {
      if (s % b.cells_series != 0) continue;
      BatteryPackParams p = PackFromEntry(b, s / b.cells_series, 1);
      const BatteryPack pack(p);
      DischargeOptions d;
      if (m.battery.cutoff_cell_v) d.cutoff_cell_v = *m.battery.cutoff_cell_v;
      BatteryOption o{&b, s, pack.OcvV(1.0), pack.cutoff_v(d), pack.capacity_ah(), pack.capacity_ah(),
                      pack.mass_kg(), pack.mass_kg(), pack.max_current_a()};
      o.ocv_integral_v = OcvIntegralUpperBound(pack, m.battery.reserve_soc);
      if (m.battery.capacity_ah) {
        const double k_lo = m.battery.capacity_ah->lo / pack.capacity_ah();
        const double k_hi = m.battery.capacity_ah->hi / pack.capacity_ah();
        o.capacity_lo_ah = m.battery.capacity_ah->lo;
        o.capacity_hi_ah = m.battery.capacity_ah->hi;
        o.mass_lo_kg = pack.mass_kg() * k_lo;
        o.mass_hi_kg = pack.mass_kg() * k_hi;
        o.max_current_hi_a = pack.max_current_a() * k_hi;
      }
      options.push_back(o);
    }
  }
  if (options.empty()) {
    throw UsageError("mission battery: no cell count in [" + std::to_string(m.battery.cells_min) + ", " +
                     std::to_string(m.battery.cells_max) + "] is a multiple of the entries' cells in series");
  }
  out.combinations = static_cast<long long>(motors.size()) * static_cast<long long>(escs.size()) *
                     static_cast<long long>(props.size()) * static_cast<long long>(options.size());
  const long long per_pair = static_cast<long long>(escs.size());
  auto prune = [&](const std::string& rule, long long n) { out.pruned_by[rule] += n; };

  // ESC classes (same C1, C0, tr_sat, sat_slope).
  std::vector<EscClass> classes;
  for (std::size_t i = 0; i < escs.size(); ++i) {
    const EscParams& e = escs[i].params;
    auto it = std::find_if(classes.begin(), classes.end(), [&](const EscClass& c) {
      return c.c1 == e.c1 && c.c0 == e.c0 && c.tr_sat == e.tr_sat && c.sat_slope == e.sat_slope;
    });
    if (it == classes.end()) {
      classes.push_back({e.c1, e.c0, e.tr_sat, e.sat_slope, {}});
      it = classes.end() - 1;
    }
    it->members.push_back(static_cast<int>(i));
  }
  // Per option: the ESCs that pass R1, per class sorted by (mass, resistance); the lightest.
  std::vector<std::vector<std::vector<int>>> option_escs(options.size());
  std::vector<double> option_min_esc_mass(options.size(), kInf);
  std::vector<double> option_max_esc_mass(options.size(), 0.0);
  for (std::size_t o = 0; o < options.size(); ++o) {
    long long n_excluded = 0;
    for (const EscClass& c : classes) {
      std::vector<int> ok;
      for (int i : c.members) {
        if (!escs[i].exclude_reason.empty()) {  // R0: the catalog excludes it
          ++n_excluded;
          continue;
        }
        if (escs[i].params.vdc_max_v >= options[o].v_full) {
          ok.push_back(i);
          option_min_esc_mass[o] = std::min(option_min_esc_mass[o], EscMassKg(escs[i]));
          option_max_esc_mass[o] = std::max(option_max_esc_mass[o], EscMassKg(escs[i]));
        }
      }
      std::sort(ok.begin(), ok.end(), [&](int a, int b) {
        const double ma = EscMassKg(escs[a]), mb = EscMassKg(escs[b]);
        if (ma != mb) return ma < mb;
        if (escs[a].params.resc_ohm != escs[b].params.resc_ohm) return escs[a].params.resc_ohm < escs[b].params.resc_ohm;
        return escs[a].params.max_current_a > escs[b].params.max_current_a;
      });
      option_escs[o].push_back(std::move(ok));
    }
    long long n_ok = 0;
    for (const auto& v : option_escs[o]) n_ok += static_cast<long long>(v.size());
    prune("esc_voltage", (per_pair - n_ok - n_excluded) * static_cast<long long>(motors.size() * props.size()));
    if (n_excluded > 0) prune("catalog_exclude", n_excluded * static_cast<long long>(motors.size() * props.size()));
  }

  // Propeller grids (static, at the mission's density): thrust and torque vs speed.
  std::vector<PropGrid> grids(props.size());
  std::vector<std::unique_ptr<PropModel>> models(props.size());
  for (std::size_t p = 0; p < props.size(); ++p) {
    models[p] = std::make_unique<PropModel>(props[p]);
    const PropModel& model = *models[p];
    const PropAdjustment prop_adj = PropAdjustmentFor(props[p], m.objective.ranking);
    PropGrid& g = grids[p];
    g.mass_kg = props[p].mass_kg ? *props[p].mass_kg : AssumedPropMassKg(props[p].diameter_m);
    double torque[kGrid];
    for (int i = 0; i < kGrid; ++i) {
      g.omega[i] = kGridMinRadS * std::pow(kGridMaxRadS / kGridMinRadS, i / double(kGrid - 1));
      PropEvaluation ev = model.Evaluate(g.omega[i], m.rho_kg_m3, 0.0);
      g.thrust[i] = ev.thrust_n;
      const double area = 0.25 * kPi * props[p].diameter_m * props[p].diameter_m;
      g.fom[i] = ev.power_w > 0 ? std::pow(ev.thrust_n, 1.5) / (std::sqrt(2.0 * m.rho_kg_m3 * area) * ev.power_w)
                                : kInf;
      // The FM limit (R6) judges the data; the load is the scenario's (credibility.h), as in
      // the evaluator. The adjustment only raises the torque, and keeps it rising with speed.
      AdjustPropEvaluation(prop_adj, props[p].diameter_m, &ev);
      torque[i] = ev.torque_nm;
      if (i > 0 && !(g.thrust[i] > g.thrust[i - 1])) g.monotone = false;
    }
    g.torque_suffix_min[kGrid - 1] = torque[kGrid - 1];
    for (int i = kGrid - 2; i >= 0; --i) g.torque_suffix_min[i] = std::min(torque[i], g.torque_suffix_min[i + 1]);
  }

  // R0 per propeller: excluded by the catalog, or folding for lift (credibility.h); nullptr: usable.
  std::vector<const char*> prop_refused(props.size(), nullptr);
  for (std::size_t p = 0; p < props.size(); ++p) {
    if (!props[p].exclude_reason.empty()) prop_refused[p] = "catalog_exclude";
    else if (FoldingPropRefused(props[p], m)) prop_refused[p] = "prop_folding";
  }

  // Hover segments (R2-R4) and the fixed durations (R4).
  std::vector<int> hover;
  for (std::size_t i = 0; i < m.segments.size(); ++i) {
    if (m.segments[i].type == SegmentType::kHover) hover.push_back(static_cast<int>(i));
  }
  const double t_fixed_max = LongestFixedDurationS(m);
  const bool stretch_is_hover = m.objective.type == ObjectiveType::kMaxEndurance &&
                                m.segments[m.objective.segment_index].type == SegmentType::kHover;
  const double tr_limit = std::min(k.max_throttle, 1.0);

  // Candidate pairs, on two threads (motors interleaved); each thread has its own lists,
  // merged below and sorted with a full tie-break, so the result does not depend on timing.
  constexpr int kThreads = 2;
  std::vector<std::vector<Candidate>> thread_cands(kThreads);
  std::vector<RuleCounts> thread_pruned(kThreads);
  std::vector<long long> thread_skipped(kThreads, 0);
  auto work = [&](int tid) {
  std::vector<Candidate>& cands = thread_cands[tid];
  auto prune_pair = [&](const char* rule, long long n) { thread_pruned[tid].Add(rule, n); };
  for (std::size_t mi = static_cast<std::size_t>(tid); mi < motors.size(); mi += kThreads) {
    const MotorEntry& mo = motors[mi];
    if (!mo.exclude_reason.empty()) {  // R0: the catalog excludes it (catalog.h, "exclude")
      prune_pair("catalog_exclude", per_pair * static_cast<long long>(props.size() * options.size()));
      continue;
    }
    if (!mo.mass_kg) {
      ++thread_skipped[tid];
      prune_pair("motor_without_mass", per_pair * static_cast<long long>(props.size() * options.size()));
      continue;
    }
    bool unrated_excluded = false;  // credibility.h: the rating (estimated from mass) or exclusion
    const MotorParams mp = ScenarioMotorParams(mo, m, nullptr, &unrated_excluded);
    if (unrated_excluded) {
      prune_pair("motor_unrated", per_pair * static_cast<long long>(props.size() * options.size()));
      continue;
    }
    const double motor_max_v = MotorMaxVoltageV(mo);
    for (std::size_t o = 0; o < options.size(); ++o) {
      const BatteryOption& bo = options[o];
      if (bo.v_full > motor_max_v) {  // R1 for the motor's cells_max (credibility.h)
        prune_pair("motor_voltage", per_pair * static_cast<long long>(props.size()));
        continue;
      }
      // Zero-resistance drives, one per ESC class (R3, R4).
      std::vector<Drive> ideal;
      for (const EscClass& c : classes) {
        EscParams e;
        e.c1 = c.c1; e.c0 = c.c0; e.tr_sat = c.tr_sat; e.sat_slope = c.sat_slope; e.resc_ohm = 0.0;
        ideal.emplace_back(mp, e);
      }
      for (std::size_t pi = 0; pi < props.size(); ++pi) {
        const PropGrid& g = grids[pi];
        if (m.vehicle.max_prop_diameter_m && props[pi].diameter_m > *m.vehicle.max_prop_diameter_m) {
          prune_pair("prop_diameter", per_pair);  // R0
          continue;
        }
        if (prop_refused[pi]) {
          prune_pair(prop_refused[pi], per_pair);  // R0
          continue;
        }
        const double mass_lb = m.vehicle.mass_kg + bo.mass_lo_kg +
                               m.vehicle.rotors * (*mo.mass_kg + g.mass_kg + option_min_esc_mass[o]);
        double omega_lb = 0, q_lb = 0;
        int lb_idx = 0;  // grid index of omega_lb
        Candidate cand{0.0, static_cast<int>(mi), static_cast<int>(pi), static_cast<int>(o), 0.0};
        if (!hover.empty() && g.monotone) {
          const RotorLoad load = SegmentRotorLoad(m, m.segments[hover[0]], mass_lb, 0.0);
          const double* it = std::upper_bound(g.thrust, g.thrust + kGrid, load.thrust_per_rotor_n);
          const int idx = static_cast<int>(it - g.thrust) - 1;  // last grid thrust <= T_lb
          if (idx >= 0) {
            lb_idx = idx;
            omega_lb = g.omega[idx];
            q_lb = g.torque_suffix_min[idx];
          }
        }
        if (!hover.empty() && g.monotone) {
          // R6: the hover speed lies between omega_lb and the first grid speed whose thrust
          // reaches T_ub (the heaviest the vehicle can be); if the data break momentum theory
          // (figure of merit > the mission's limit) on that whole bracket, every hover point fails
          // prop_figure_of_merit (mission_eval.cc). The 2 % allowance covers the variation between grid points.
          const double mass_ub = m.vehicle.mass_kg + bo.mass_hi_kg +
                                 m.vehicle.rotors * (*mo.mass_kg + g.mass_kg + option_max_esc_mass[o]);
          const RotorLoad load = SegmentRotorLoad(m, m.segments[hover[0]], mass_ub, 0.0);
          const double* it = std::lower_bound(g.thrust, g.thrust + kGrid, load.thrust_per_rotor_n);
          const int hi_idx = std::min(static_cast<int>(it - g.thrust), kGrid - 1);
          double fom_min = kInf;
          for (int i = lb_idx; i <= hi_idx; ++i) fom_min = std::min(fom_min, g.fom[i]);
          if (it != g.thrust + kGrid && fom_min > 1.02 * k.max_figure_of_merit) {
            prune_pair("prop_figure_of_merit", per_pair);
            continue;
          }
        }
        if (models[pi]->data_kind() != PropDataKind::kTables || props[pi].j_tables.empty()) {
          // R7: static-only data. The shaft cannot turn faster than the motor's no-load speed
          // at full throttle and the full-charge voltage with no ESC resistance, so the advance
          // ratio in a segment with axial airspeed >= V_ax is at least V_ax/(n_max*D); above
          // the mission's max_static_advance_ratio the segment fails
          // prop_no_forward_flight_data whatever else is chosen.
          double w_nl = 0;
          for (const Drive& d : ideal) w_nl = std::max(w_nl, d.NoLoadSpeed(bo.v_full, 1.0));
          const double n_max = w_nl / (2.0 * kPi);
          bool fails = false;
          for (const Segment& sg : m.segments) {
            double v_ax = 0;
            if (sg.type == SegmentType::kClimb && sg.climb_rate_m_s > 0) v_ax = sg.climb_rate_m_s;
            if (sg.type == SegmentType::kCruise && sg.lift_to_drag > 0) v_ax = sg.airspeed_m_s.lo;
            if (n_max > 0 && v_ax / (n_max * props[pi].diameter_m) > k.max_static_advance_ratio) fails = true;
          }
          if (fails) {
            prune_pair("prop_no_forward_flight_data", per_pair);
            continue;
          }
        }
        if (props[pi].max_rpm && RadPerSecToRpm(omega_lb) > *props[pi].max_rpm) {
          prune_pair("prop_max_rpm", per_pair);  // R2
          continue;
        }
        // R3 and R4 over the ESC classes: the pair survives if any class can.
        bool any = false;
        double best_bound = kInf, irms_lb = kInf;
        const char* why = "throttle";
        for (std::size_t ci = 0; ci < classes.size(); ++ci) {
          if (option_escs[o][ci].empty()) continue;
          const OperatingPoint hi_v = ideal[ci].Inverse(bo.v_full, q_lb, omega_lb);
          const double t_max = k.allow_esc_saturation ? tr_limit : std::min(tr_limit, classes[ci].tr_sat);
          if (hi_v.throttle > t_max) { why = "throttle"; continue; }
          if (hi_v.irms_a > mp.max_current_a * margin) { why = "motor_current"; continue; }
          if (k.enforce_motor_power && hi_v.pac_w > mp.max_power_w) { why = "motor_power"; continue; }
          const OperatingPoint lo_v = ideal[ci].Inverse(bo.v_cut, q_lb, omega_lb);
          const double pdc_lb = std::max(0.0, std::min(hi_v.pdc_w, lo_v.pdc_w));
          double bound = -kInf;
          if (!hover.empty()) {
            // The terminal power of a segment is at least N*PDC_lb + P_avionics when each of
            // its N rotors must give at least T_lb (hover[0]'s per-rotor thrust at the lightest
            // mass, which defines omega_lb and Q_lb) from the same speed-thrust curve: hover
            // segments, and climb or fixed-airspeed cruise segments of a propeller with static-
            // only data (the evaluator reads them at J = 0 in any inflow, so speed and torque
            // are at least omega_lb and Q_lb there too, M1, M2). Any other segment draws at
            // least P_avionics.
            const double t_lb = SegmentRotorLoad(m, m.segments[hover[0]], mass_lb, 0.0).thrust_per_rotor_n;
            const bool static_only = models[pi]->data_kind() != PropDataKind::kTables || props[pi].j_tables.empty();
            auto p_lb_of = [&](std::size_t si) {
              const Segment& sg = m.segments[si];
              const bool fixed_v = sg.type != SegmentType::kCruise || !sg.airspeed_m_s.free();
              if (sg.type == SegmentType::kHover ||
                  (static_only && fixed_v && (sg.type == SegmentType::kClimb || sg.type == SegmentType::kCruise))) {
                const RotorLoad ld = SegmentRotorLoad(m, sg, mass_lb, sg.type == SegmentType::kCruise ? sg.airspeed_m_s.lo : 0.0);
                if (ld.thrust_per_rotor_n >= t_lb) return ld.rotors * pdc_lb + m.vehicle.avionics_power_w;
              }
              return m.vehicle.avionics_power_w;
            };
            // The shortest a segment can last (free airspeed: at its top speed).
            auto t_min_of = [&](const Segment& sg) { return SegmentDurationS(sg, sg.airspeed_m_s.hi); };
            if (m.objective.type == ObjectiveType::kMinEnergy) {
              // Per segment the larger of: the hover bound above, and momentum theory. A
              // feasible point has prop power >= P_ideal/max_figure_of_merit (the evaluator's
              // prop_figure_of_merit constraint), P_ideal = T*(V/2 + sqrt(V^2/4 + T/(2*rho*A)))
              // per rotor, and PDC >= Pmech when the motor has KT <= sqrt(27/10)*KE and the
              // ESC C1 >= (3/pi)*sqrt(27/20), C0 >= 0 (then eta_motor, eta_esc <= 1, eqs
              // 41-59). V is the axial inflow (0 for static-only data: P_ideal rises with V).
              const bool lossy = mp.kt_nm_per_a <= kPacPerVllIrms * mp.ke_v_s_per_rad &&
                                 classes[ci].c1 >= kIdealIdcPerIrmsPerThrottle && classes[ci].c0 >= 0.0;
              const bool axial_data = !props[pi].j_tables.empty();
              const double area = 0.25 * kPi * props[pi].diameter_m * props[pi].diameter_m;
              double e = 0;
              for (std::size_t si = 0; si < m.segments.size(); ++si) {
                const Segment& sg = m.segments[si];
                double e_seg = p_lb_of(si) * t_min_of(sg);
                const bool fixed_v = sg.type != SegmentType::kCruise || !sg.airspeed_m_s.free() || sg.lift_to_drag > 0;
                if (lossy && sg.type != SegmentType::kShaft && fixed_v) {
                  const double v = sg.type == SegmentType::kCruise ? sg.airspeed_m_s.hi : 0.0;
                  const RotorLoad ld = SegmentRotorLoad(m, sg, mass_lb, v);
                  if (sg.type != SegmentType::kCruise || sg.lift_to_drag > 0) {
                    const double t = SegmentDurationS(sg, v);
                    const double va = axial_data ? 0.5 * ld.axial_airspeed_m_s : 0.0;
                    const double tr = ld.thrust_per_rotor_n;
                    const double p_ideal = tr * (va + std::sqrt(va * va + tr / (2.0 * m.rho_kg_m3 * area)));
                    e_seg = std::max(e_seg, (ld.rotors * p_ideal / k.max_figure_of_merit + m.vehicle.avionics_power_w) * t);
                  }
                }
                e += e_seg;
              }
              bound = e / 3600.0;
            } else if (stretch_is_hover) {
              // Terminal energy = integral of V*I dt <= integral of OCV*I dt = Q*integral of
              // OCV(s) ds over [reserve, 1] (coulomb counting): the energy budget.
              double e_other = 0;
              for (std::size_t si = 0; si < m.segments.size(); ++si) {
                if (static_cast<int>(si) != m.objective.segment_index) e_other += p_lb_of(si) * t_min_of(m.segments[si]);
              }
              const double p_stretch = p_lb_of(static_cast<std::size_t>(m.objective.segment_index));
              const double e_max = bo.ocv_integral_v * AhToCoulomb(bo.capacity_hi_ah);
              bound = p_stretch > 0 ? -(t_fixed_max + std::max(0.0, e_max - e_other) / p_stretch) : -kInf;
            }
          }
          any = true;
          best_bound = std::min(best_bound, bound);
          irms_lb = std::min(irms_lb, hi_v.irms_a);
        }
        if (!any) {
          prune_pair(why, per_pair);
          continue;
        }
        cand.bound = best_bound;
        cand.irms_lb = irms_lb;
        cands.push_back(cand);
      }
    }
  }
  };
  {
    std::vector<std::thread> pool;
    for (int t = 1; t < kThreads; ++t) pool.emplace_back(work, t);
    work(0);
    for (auto& th : pool) th.join();
  }
  std::vector<Candidate> cands;
  for (int t = 0; t < kThreads; ++t) {
    cands.insert(cands.end(), thread_cands[t].begin(), thread_cands[t].end());
    std::vector<Candidate>().swap(thread_cands[t]);
    thread_pruned[t].MergeInto(&out.pruned_by);
    out.skipped_without_mass += thread_skipped[t];
  }
  const double t_cands = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  long long virtual_evals = 0;
  // Candidates best bound first, with a full tie-break (a strict total order, so the order is
  // unique). The search usually stops after a small fraction of them, so they are drawn from a
  // heap on demand instead of sorted whole.
  auto after = [](const Candidate& a, const Candidate& b) {
    if (a.bound != b.bound) return a.bound > b.bound;
    if (a.option != b.option) return a.option > b.option;
    if (a.motor != b.motor) return a.motor > b.motor;
    return a.prop > b.prop;
  };
  std::make_heap(cands.begin(), cands.end(), after);
  std::size_t heap_size = cands.size();
  std::vector<Candidate> ordered;
  auto candidate_at = [&](std::size_t i) -> const Candidate* {  // the i-th best, or null
    while (ordered.size() <= i && heap_size > 0) {
      std::pop_heap(cands.begin(), cands.begin() + static_cast<std::ptrdiff_t>(heap_size), after);
      ordered.push_back(cands[--heap_size]);
    }
    return i < ordered.size() ? &ordered[i] : nullptr;
  };
  const std::size_t n_cands = cands.size();

  // Branch and bound over the surviving pairs.
  auto nth_best = [&]() {
    return static_cast<int>(out.best.size()) < opt.top_n ? kInf : out.best.back().result.score;
  };
  auto insert = [&](const Combination& c, MissionResult&& r) {
    if (!r.feasible) return;
    out.evaluated_mass_objective.emplace_back(r.propulsion_mass_kg, r.objective);
    if (!(r.score < nth_best())) return;
    auto pos = std::upper_bound(out.best.begin(), out.best.end(), r.score,
                                [](double s, const RankedCombination& x) { return s < x.result.score; });
    out.best.insert(pos, RankedCombination{c, std::move(r)});
    if (static_cast<int>(out.best.size()) > opt.top_n) out.best.pop_back();
  };
  // One candidate pair against a threshold (the N-th best score when its chunk started):
  // virtual ESC per class first (R5), then the real ESCs, lightest first, skipping dominated
  // ones. Pruning against a threshold at least the final N-th best is safe.
  struct Outcome {
    std::vector<std::pair<Combination, MissionResult>> results;
    std::map<std::string, long long> pruned;
    long long searched = 0, virtual_evals = 0;
  };
  // The virtual ESC (and so the class check) uses the mission without min_hover_throttle: a
  // real ESC's resistance and mass raise the throttle, so that lower limit is the one
  // constraint the virtual ESC may fail when a real one passes (R5). Relaxing it keeps the
  // check a bound.
  Mission relaxed = m;
  relaxed.constraints.min_hover_throttle = 0.0;
  auto process = [&](const Candidate& cand, std::vector<double> top, Outcome* o) {
    // `top`: the N best scores when the chunk started, updated with this pair's own results, so
    // that the threshold tightens within the pair exactly as it would in a sequential search.
    auto threshold_now = [&]() { return static_cast<int>(top.size()) < opt.top_n ? kInf : top[opt.top_n - 1]; };
    auto local_prune = [&](const std::string& rule, long long n) { o->pruned[rule] += n; };
    const BatteryOption& bo = options[cand.option];
    Combination c{&motors[cand.motor], nullptr, &props[cand.prop], bo.entry, bo.cells};
    for (std::size_t cl = 0; cl < classes.size(); ++cl) {
      const std::vector<int>& list = option_escs[cand.option][cl];
      if (list.empty()) continue;
      // R3: ESCs rated below the Irms lower bound.
      std::vector<int> rated;
      for (int e : list) {
        if (escs[e].params.max_current_a * margin >= cand.irms_lb) rated.push_back(e);
      }
      local_prune("esc_current", static_cast<long long>(list.size() - rated.size()));
      if (rated.empty()) continue;
      // R5: the virtual ESC of the class.
      EscEntry virt;  // only what the evaluator reads (no copy of the entry's JSON)
      virt.id = "virtual";
      virt.params = escs[rated.front()].params;
      virt.params.resc_ohm = 0.0;
      virt.params.max_current_a = kInf;
      virt.mass_kg = EscMassKg(escs[rated.front()]);
      for (int e : rated) virt.mass_kg = std::min(*virt.mass_kg, EscMassKg(escs[e]));
      {
        Combination vc = c;
        vc.esc = &virt;
        const double threshold = threshold_now();
        const MissionResult vr = MissionEvaluator(relaxed, vc, models[cand.prop].get()).Solve(threshold, false);
        ++o->virtual_evals;
        if (vr.bounded_out) {
          local_prune("objective_bound", static_cast<long long>(rated.size()));
          continue;
        }
        if (!vr.feasible || !(vr.score < threshold)) {
          local_prune(vr.feasible ? "objective_bound" : "infeasible_bound", static_cast<long long>(rated.size()));
          continue;
        }
      }
      std::vector<std::pair<int, bool>> done;  // ESC, "cannot enter the top N"
      for (int e : rated) {
        bool skip = false;
        for (const auto& d : done) {
          if (d.second && Dominates(escs[d.first], escs[e])) { skip = true; break; }
        }
        if (skip) {
          local_prune("esc_dominated", 1);
          continue;
        }
        c.esc = &escs[e];
        const double threshold = threshold_now();
        MissionResult r = MissionEvaluator(m, c, models[cand.prop].get()).Solve(threshold);
        if (r.bounded_out) {
          local_prune("objective_bound", 1);
          done.emplace_back(e, true);
          continue;
        }
        ++o->searched;
        done.emplace_back(e, r.feasible ? !(r.score < threshold) : !FailsMinHoverThrottle(r));
        if (r.feasible) {
          top.insert(std::upper_bound(top.begin(), top.end(), r.score), r.score);
          o->results.emplace_back(c, std::move(r));
        }
      }
    }
  };
  // Chunks of candidates evaluated on two threads against the threshold at the chunk's start,
  // merged in candidate order: the answer and the counts do not depend on timing. Ipopt (the
  // shaft segments' solver, MUMPS) is not thread-safe: missions with a free shaft speed run on
  // one thread.
  bool free_shaft = false;
  for (const Segment& sg : m.segments) free_shaft |= sg.type == SegmentType::kShaft && sg.shaft_omega_rad_s.free();
  const char* threads_env = std::getenv("DYNOSIZE_THREADS");
  const int workers = free_shaft ? 1 : (threads_env && std::atoi(threads_env) == 1 ? 1 : kThreads);
  constexpr std::size_t kMaxChunk = 64;
  std::size_t chunk = 2;  // grows while the threshold settles
  std::size_t ci = 0;
  while (ci < n_cands) {
    if (opt.progress) opt.progress(static_cast<double>(ci) / static_cast<double>(n_cands));
    const double threshold = nth_best();
    std::vector<double> top;
    for (const auto& b : out.best) top.push_back(b.result.score);
    std::size_t end = ci;
    while (end - ci < chunk && candidate_at(end) && candidate_at(end)->bound < threshold) ++end;
    chunk = std::min(kMaxChunk, 2 * chunk);
    if (end == ci) {  // R4: every later candidate has a bound at least as bad
      prune("objective_bound", per_pair * static_cast<long long>(n_cands - ci));
      break;
    }
    std::vector<Outcome> outs(end - ci);
    auto run = [&](int tid) {
      for (std::size_t i = ci + static_cast<std::size_t>(tid); i < end; i += static_cast<std::size_t>(workers)) {
        process(ordered[i], top, &outs[i - ci]);
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < workers; ++t) pool.emplace_back(run, t);
    run(0);
    for (auto& th : pool) th.join();
    for (Outcome& o : outs) {
      for (const auto& [rule, n] : o.pruned) out.pruned_by[rule] += n;
      out.searched += o.searched;
      virtual_evals += o.virtual_evals;
      for (auto& [c, r] : o.results) insert(c, std::move(r));
    }
    ci = end;
  }
  for (RankedCombination& b : out.best) AddObjectiveRange(m, b.combination, &b.result);  // credibility.h
  if (opt.progress) opt.progress(1.0);
  out.pruned = out.combinations - out.searched;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (std::getenv("DYNOSIZE_SEARCH_DEBUG")) {
    std::fprintf(stderr, "search: %zu candidate pairs in %.3f s; %lld virtual-ESC and %lld exact evaluations; total %.3f s\n",
                 n_cands, t_cands, virtual_evals, out.searched, out.seconds);
  }
  return out;
}

}  // namespace dynosize
