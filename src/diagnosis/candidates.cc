#include "diagnosis/candidates.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "fit/statistics.h"

namespace dynosize::diagnosis {

const char* CauseId(Cause c) {
  switch (c) {
    case Cause::kEscSaturation: return "esc_saturation";
    case Cause::kSpeedDependentNoLoadCurrent: return "speed_dependent_no_load_current";
    case Cause::kWindingTemperatureRise: return "winding_temperature_rise";
    case Cause::kTorqueConstantDroop: return "torque_constant_droop";
    case Cause::kThrottleDeadband: return "throttle_deadband";
    case Cause::kSupplyResistance: return "supply_resistance";
  }
  return "?";
}

const char* CauseDescription(Cause c) {
  switch (c) {
    case Cause::kEscSaturation:
      return "ESC saturation: above tr_sat the ESC delivers only sat_slope of the nominal "
             "voltage slope (model.md section 7)";
    case Cause::kSpeedDependentNoLoadCurrent:
      return "no-load current grows with speed (iron, eddy-current, bearing and windage losses): "
             "Io = io_a + io1*omega (model.md section 9)";
    case Cause::kWindingTemperatureRise:
      return "winding resistance rises with copper temperature heated by I^2*R: Rm = Rm0*(1 + "
             "0.00393*rth*P_cu) (model.md section 9)";
    case Cause::kTorqueConstantDroop:
      return "torque constant falls at high current (magnetic saturation, armature reaction): "
             "KT = KT0/(1 + kt_droop*I) (model.md section 9)";
    case Cause::kThrottleDeadband:
      return "ESC throttle dead band or offset: TR_eff = (TR - deadband)/(1 - deadband); positive: "
             "the first part of the command range produces no voltage, negative: voltage already "
             "at zero command (model.md section 9)";
    case Cause::kSupplyResistance:
      return "supply sag: VDC is not measured at the ESC; wires and connectors drop "
             "rsupply*IDC before it (model.md section 9)";
  }
  return "?";
}

namespace internal {

using fit::Aicc;
using fit::FDistributionUpperTail;

namespace {

// Which slots each cause adds.
std::vector<int> CauseSlots(Cause c) {
  switch (c) {
    case Cause::kEscSaturation: return {kSatSlope};  // + the profiled tr_sat
    case Cause::kSpeedDependentNoLoadCurrent: return {kIo1};
    case Cause::kWindingTemperatureRise: return {kRth};
    case Cause::kTorqueConstantDroop: return {kDroop};
    case Cause::kThrottleDeadband: return {kDeadband};
    case Cause::kSupplyResistance: return {kRsupply};
  }
  return {};
}

// Fits model `m` (the current model plus candidate `c`) from several starts and keeps the best:
// the current fit's values, and - for the offset-like dead band and supply resistance, or when
// a base parameter of the current fit sits on a bound (the first-order model could not follow
// the data) - the linear starting values of the base model with the candidate's own starts
// (dead band: +0.05, -0.1, -0.3, i.e. a dead band or a throttle offset).
FitOut FitCandidate(const Data& d, const std::vector<std::size_t>& rows, const Model& m, Cause c,
                    const Values& fresh, bool base_at_bound, const std::vector<double>& knees) {
  std::vector<Model> starts = {m};
  const bool offset_like = c == Cause::kThrottleDeadband || c == Cause::kSupplyResistance;
  if (offset_like || base_at_bound) {
    Model f = m;
    for (int s = 0; s < kSlotCount; ++s) {
      if (id::IsFirstOrderParam(s)) f.values[s] = fresh[s];
    }
    starts.push_back(f);
  }
  if (c == Cause::kThrottleDeadband) {
    const std::size_t k = starts.size();
    for (std::size_t j = 0; j < k; ++j) {
      for (double db : {-0.1, -0.3}) {
        Model v = starts[j];
        v.values[kDeadband] = std::clamp(db, v.lower[kDeadband], v.upper[kDeadband]);
        starts.push_back(v);
      }
    }
  }
  FitOut best;
  for (const Model& st : starts) {
    FitOut f = FitProfiled(d, rows, st, knees, LossType::kTrivial, 1.0);
    if (f.ok && (!best.ok || f.sse < best.sse)) best = f;
  }
  return best;
}

std::string Separation(Cause a, Cause b) {
  auto is = [&](Cause x, Cause y) { return (a == x && b == y) || (a == y && b == x); };
  if (is(Cause::kWindingTemperatureRise, Cause::kTorqueConstantDroop)) {
    return "log the winding temperature (temp_c), or repeat a high-current point after a "
           "cool-down: a thermal effect drifts with time and temperature, magnetic droop does not";
  }
  if (is(Cause::kWindingTemperatureRise, Cause::kSupplyResistance)) {
    return "measure VDC at the ESC input terminals (supply sag vanishes) or log the winding "
           "temperature (heating does not)";
  }
  if (is(Cause::kEscSaturation, Cause::kThrottleDeadband)) {
    return "add throttle levels at both ends of the range (below 20 % and between 85 % and 100 %)";
  }
  if (is(Cause::kSpeedDependentNoLoadCurrent, Cause::kTorqueConstantDroop)) {
    return "no-load runs at several speeds (torque = 0) isolate Io(omega); high-torque points at "
           "low speed isolate KT(I)";
  }
  if (is(Cause::kSpeedDependentNoLoadCurrent, Cause::kWindingTemperatureRise)) {
    return "no-load runs at several speeds (low current, high speed) and locked-rotor-like "
           "high-torque points at low speed (high current) separate speed from current effects";
  }
  if (is(Cause::kSupplyResistance, Cause::kEscSaturation) ||
      is(Cause::kSupplyResistance, Cause::kThrottleDeadband)) {
    return "measure VDC at the ESC input terminals, and run the same throttle levels at two "
           "loads (props): supply sag follows the current, the ESC law follows the throttle";
  }
  return "more throttle levels and voltages, a torque column, or the AC-side columns "
         "(vll_rms_v, irms_a) to see the motor and the ESC separately";
}

// Stage 9a: candidate c added to the current model: fitted from several starts, tested (F test,
// AICc, its own parameter determined and not clipped) and, when it passes, cross-validated.
Scored ScoreCandidate(const SearchContext& x, const Step& cur, bool base_at_bound, double aicc0, Cause c,
                      std::size_t tested) {
  Scored sc;
  Model& m = sc.model;
  m = cur.model;
  AddCause(&m, c);
  const FitOut f = FitCandidate(x.d, x.used, m, c, x.base_values, base_at_bound, x.knees);
  CandidateScore& cs = sc.cs;
  cs.cause = c;
  cs.testable = true;
  sc.fit = f;
  if (!f.ok) return sc;
  m.values = f.values;
  for (int s : CauseSlots(c)) {
    cs.parameters[SlotName(s)] = f.values[s];
    cs.stderrs[SlotName(s)] = f.stderr_[s];
  }
  if (c == Cause::kEscSaturation) {
    cs.parameters["tr_sat"] = f.values[kTrSat];
    double step = 0.02;
    for (std::size_t j = 0; j + 1 < x.knees.size(); ++j) {
      if (x.knees[j] <= f.values[kTrSat]) step = x.knees[j + 1] - x.knees[j];
    }
    // The refined knee's own standard error (FitProfiled), else the grid resolution.
    cs.stderrs["tr_sat"] = std::isfinite(f.stderr_[kTrSat]) ? f.stderr_[kTrSat] : step / std::sqrt(12.0);
  }
  cs.sse = f.sse;
  cs.aicc = Aicc(f.sse, f.n_terms, f.n_free);
  cs.delta_aicc = cs.aicc - aicc0;
  const int q = CauseExtraParams(c);
  const double df2 = static_cast<double>(f.n_terms - f.n_free);
  if (df2 > 0.0 && f.sse < cur.fit.sse) {
    cs.f_statistic = ((cur.fit.sse - f.sse) / q) / (f.sse / df2);
    cs.p_value = FDistributionUpperTail(cs.f_statistic, q, df2);
    if (c == Cause::kEscSaturation) cs.p_value = std::min(1.0, cs.p_value * static_cast<double>(x.knees.size()));
    // Every candidate of the step is a test of "the current model is enough": alpha holds for the
    // step (Bonferroni over the `tested` candidates), not for each candidate. Per candidate, a
    // clean campaign's noise passed p < alpha as a second cause now and then (in the hidden-effect
    // suite: rth at p = 0.00094 beside a hidden io1, 5 candidates tested).
    cs.p_value = std::min(1.0, cs.p_value * static_cast<double>(std::max<std::size_t>(tested, 1)));
  }
  // The extension's own parameter must be determined: at least 2 standard errors from
  // its "no effect" value (0; 1 for sat_slope). A parameter the data cannot separate from
  // the base parameters (|corr| -> 1, huge error) is not a finding, whatever the F test.
  bool determined = true;
  for (int sl : CauseSlots(c)) {
    const double null_value = sl == kSatSlope ? 1.0 : 0.0;
    const double se = f.stderr_[sl];
    if (std::isfinite(se) && std::fabs(f.values[sl] - null_value) < 2.0 * se) determined = false;
    // On a bound of its physical range the parameter is not estimated but clipped: the
    // misfit is bigger than, or different from, what this mechanism can produce. (A knee
    // slope of 0 - no voltage gain above the knee - is a physical value, not a clip.)
    const double tol = 1e-6 * (m.upper[sl] - m.lower[sl]);
    const bool at_lower = f.values[sl] - m.lower[sl] <= tol && sl != kSatSlope;
    const bool at_upper = m.upper[sl] - f.values[sl] <= tol && sl != kSatSlope;
    if (at_lower || at_upper) {
      determined = false;
      cs.note = std::string(SlotName(sl)) + " clipped at the bound of its physical range";
    }
  }
  if (!determined && cs.note.empty()) cs.note = "parameter within 2 standard errors of no effect";
  const bool pre = cs.p_value < x.o.alpha && cs.delta_aicc < 0.0 && determined;
  if (pre) {
    sc.cv = CrossValidate(x.d, x.used, x.folds.fold_of, x.folds.count, m, f, x.knees);
    cs.cv_rms_percent = sc.cv.rms_percent;
    cs.gain_percent = 100.0 * (1.0 - sc.cv.rms_percent / cur.cv.rms_percent);
    cs.significant = cs.gain_percent >= x.o.min_gain_percent;
  }
  return sc;
}

// Stage 9b: the rivals of the winner bs (significant and within ambiguity_aicc of it, or close
// in gain) that are no longer significant once the winner is in the model (cur) explain the same
// thing: the data cannot tell the two apart. Each becomes an ambiguity and leaves `remaining`.
void ResolveRivals(const SearchContext& x, const Step& cur, bool base_at_bound, const std::vector<Scored>& scored,
                   int best, std::vector<Cause>* remaining, DiagnoseResult* res) {
  const CandidateScore& bs = scored[best].cs;
  std::vector<Cause> rivals;
  for (std::size_t j = 0; j < scored.size(); ++j) {
    if (static_cast<int>(j) == best || !scored[j].cs.significant) continue;
    if (scored[j].cs.aicc - bs.aicc < x.o.ambiguity_aicc ||
        scored[j].cs.gain_percent >= x.o.ambiguity_gain_ratio * bs.gain_percent) {
      rivals.push_back(scored[j].cs.cause);
    }
  }
  for (Cause rc : rivals) {
    Model m = cur.model;
    AddCause(&m, rc);
    const FitOut f = FitCandidate(x.d, x.used, m, rc, x.base_values, base_at_bound, x.knees);
    bool still = false;
    if (f.ok && f.sse < cur.fit.sse) {
      const int q = CauseExtraParams(rc);
      const double df2 = static_cast<double>(f.n_terms - f.n_free);
      const double fs = ((cur.fit.sse - f.sse) / q) / (f.sse / df2);
      still = FDistributionUpperTail(fs, q, df2) < x.o.alpha;
    }
    if (still) continue;
    Ambiguity a;
    a.causes = {bs.cause, rc};
    std::ostringstream s;
    const auto it = std::find_if(scored.begin(), scored.end(), [&](const Scored& y) { return y.cs.cause == rc; });
    s << std::setprecision(3) << CauseId(bs.cause) << " (gain " << bs.gain_percent << " %, AICc "
      << bs.aicc << ") and " << CauseId(rc) << " (gain " << it->cs.gain_percent << " %, AICc "
      << it->cs.aicc << ") both explain the misfit and the second adds nothing once the first is "
      << "in the model: the data cannot tell them apart";
    a.reason = s.str();
    a.measurement = Separation(bs.cause, rc);
    res->ambiguous.push_back(a);
    remaining->erase(std::remove(remaining->begin(), remaining->end(), rc), remaining->end());
  }
}

// Stage 9c: without AC columns C1, C0 are seen only through the tied KT (section 5). Where the
// extended model leaves them on a bound of docs/model.md section 10 (the data alone ask for an ESC
// that creates energy), the slot on the bound is held at the ESC prior (--esc, else ideal) and
// the extended model refitted; if the other ESC slot is then on a bound or undetermined
// (relative standard error above 50 %), it is held too. c0 = 0 on its bound thus leaves a c1 the
// log does determine free (held both, xNova-SR-steps-up predicted its held-out rows at 9.6 %
// instead of 3.3 %). The findings keep their scores; the written model and its status are the
// held one.
bool EscSlotWeak(const Model& m, const FitOut& f, int s) {
  if (!m.free[s]) return false;
  if (SlotAtBound(m, f.values, s)) return true;
  const double se = f.stderr_[s];
  return !std::isfinite(se) ||
         std::fabs(se) > 0.01 * identification::kMaxRelStdErrorPercent * std::fabs(f.values[s]);
}

}  // namespace

int CauseExtraParams(Cause c) { return c == Cause::kEscSaturation ? 2 : 1; }

void AddCause(Model* m, Cause c) {
  for (int s : CauseSlots(c)) m->free[s] = true;
  if (c == Cause::kEscSaturation) {
    m->profile_knee = true;
    if (m->values[kSatSlope] >= 1.0) m->values[kSatSlope] = 0.8;
  } else {
    const int s = CauseSlots(c)[0];
    if (m->values[s] == 0.0) m->values[s] = 0.05 * m->scale[s];
  }
}

// True when free slot s of values v sits on a bound of its coordinate (ToCoordinate).
bool SlotAtBound(const Model& m, const Values& v, int s) {
  const double tol = 1e-6 * std::max(std::fabs(m.upper[s] - m.lower[s]), 1e-12);
  const double c = ToCoordinate(s, v);
  return c - m.lower[s] <= tol || m.upper[s] - c <= tol;
}

bool BaseAtBound(const Model& m, const Values& v) {
  for (int s = 0; s < kSlotCount; ++s) {
    if (id::IsFirstOrderParam(s) && m.free[s] && SlotAtBound(m, v, s)) return true;
  }
  return false;
}

// Knee candidates: midpoints between throttle levels from 0.5 up (or a 0.02 grid when the
// throttle is continuous), each with at least one level above. Not calibrate's regular grid
// (calibration/joint_fit.cc): the F test's p value is multiplied by the number of knees tried
// (diagnose.h step 5), so diagnose tries few knees, one per gap between two levels (which rows
// lie above the knee is all a grid point decides), and FitProfiled then frees the knee between
// the best one's neighbours.
std::vector<double> KneeGrid(const std::vector<double>& levels) {
  std::vector<double> knees;
  if (levels.size() >= 3) {
    if (levels.size() <= 40) {
      for (std::size_t j = 0; j + 1 < levels.size(); ++j) {
        const double mid = 0.5 * (levels[j] + levels[j + 1]);
        if (mid >= 0.5) knees.push_back(mid);
      }
    } else {
      for (double k = 0.5; k < levels.back() - 1e-9; k += 0.02) knees.push_back(k);
    }
  }
  return knees;
}

// Stage 3: the candidates this log can test; the others go to res->not_testable with the reason.
std::vector<Cause> TestableCandidates(const DiagnoseOptions& o, const Prepared& p,
                                      const std::vector<double>& knees, DiagnoseResult* res) {
  std::vector<Cause> candidates;
  for (Cause c : o.candidates) {
    CandidateScore cs;
    cs.cause = c;
    std::string reason;
    switch (c) {
      case Cause::kEscSaturation:
        if (!p.has_tr) reason = "no throttle column";
        else if (knees.empty()) reason = "fewer than 3 throttle levels or none above 50 %";
        break;
      case Cause::kSpeedDependentNoLoadCurrent:
        if (!p.any_tk) reason = "no torque column and no no-load rows: with the speed as input the no-load current does not enter the predicted columns";
        break;
      case Cause::kTorqueConstantDroop:
        if (!p.has_q) reason = "no torque column: the torque constant does not enter the predicted columns";
        break;
      case Cause::kThrottleDeadband:
        if (!p.has_tr) reason = "no throttle column";
        else if (p.levels.size() < 3) reason = "fewer than 3 throttle levels";
        break;
      case Cause::kSupplyResistance:
        if (!p.has_tr) reason = "no throttle column: at one throttle a supply resistance is indistinguishable from Rm";
        else if (!p.d.measured[kMIdc]) reason = "no idc_a column";
        else if (p.levels.size() < 3) reason = "fewer than 3 throttle levels";
        break;
      case Cause::kWindingTemperatureRise:
        break;
    }
    if (reason.empty()) {
      candidates.push_back(c);
    } else {
      cs.not_testable_reason = reason;
      res->not_testable.push_back(cs);
    }
  }
  return candidates;
}

// Stage 9: greedy forward selection from the baseline cur: at each step every remaining
// candidate is scored and the significant one with the largest CV gain joins the model.
// Returns the final (extended) model.
Step SearchCandidates(const SearchContext& x, bool has_tr, std::vector<Cause> remaining, Step cur,
                      DiagnoseResult* res) {
  const DiagnoseOptions& o = x.o;
  if (!has_tr && res->baseline_cv_rms_percent > o.no_throttle_max_percent) {
    // Without a throttle column every row is taken at assumed_throttle; when the model misses
    // by this much the rows are not such points and any "cause" would explain the wrong
    // throttle, not the drive.
    std::ostringstream w;
    w << std::setprecision(3) << "no throttle column and the first-order model misses by "
      << res->baseline_cv_rms_percent << " % rms: the rows are not full-throttle points, so no "
      << "cause is named; diagnose a log that records the throttle";
    res->warnings.push_back(w.str());
    remaining.clear();
  }
  while (static_cast<int>(res->findings.size()) < o.max_findings && !remaining.empty()) {
    const double aicc0 = Aicc(cur.fit.sse, cur.fit.n_terms, cur.fit.n_free);
    const bool base_at_bound = BaseAtBound(cur.model, cur.fit.values);
    std::vector<Scored> scored;
    std::vector<CandidateScore> scores;
    for (Cause c : remaining) {
      scored.push_back(ScoreCandidate(x, cur, base_at_bound, aicc0, c, remaining.size()));
      scores.push_back(scored.back().cs);
    }
    int best = -1;
    for (std::size_t j = 0; j < scores.size(); ++j) {
      if (scores[j].significant && (best < 0 || scores[j].gain_percent > scores[best].gain_percent)) {
        best = static_cast<int>(j);
      }
    }
    if (best < 0) {
      res->last_step_scores = scores;
      break;
    }
    Scored& win = scored[best];
    const CandidateScore& bs = win.cs;
    Finding fd;
    fd.cause = bs.cause;
    fd.description = CauseDescription(bs.cause);
    fd.parameters = bs.parameters;
    fd.stderrs = bs.stderrs;
    fd.gain_percent = bs.gain_percent;
    fd.f_statistic = bs.f_statistic;
    fd.p_value = bs.p_value;
    fd.delta_aicc = bs.delta_aicc;
    fd.max_abs_correlation = win.fit.max_corr_ext_base;
    fd.most_correlated_with = win.fit.corr_with;
    fd.cv_after = ColumnErrors(x.d, x.used, win.cv);
    fd.step_scores = scores;
    cur.model = win.model;
    cur.model.values = win.fit.values;
    // Extensions added are fitted from now on (the knee stays profiled).
    cur.fit = win.fit;
    cur.cv = std::move(win.cv);
    res->findings.push_back(fd);
    remaining.erase(std::find(remaining.begin(), remaining.end(), bs.cause));
    ResolveRivals(x, cur, base_at_bound, scored, best, &remaining, res);
  }
  return cur;
}

Step HoldEscOnBound(const SearchContext& x, bool ac, Step cur, DiagnoseResult* res) {
  if (ac) return cur;
  std::vector<int> held_slots;
  for (int s : {kC1, kC0}) {
    if (cur.model.free[s] && SlotAtBound(cur.model, cur.fit.values, s)) held_slots.push_back(s);
  }
  if (held_slots.empty()) return cur;
  const EscParams e0 = x.o.esc ? *x.o.esc : EscParams{};
  // The extended model refitted from its own values with the held slots at the prior.
  const auto refit = [&](const std::vector<int>& slots, Step* out) {
    *out = cur;
    for (int s : slots) {
      out->model.free[s] = false;
      out->model.values[s] = s == kC0 ? e0.c0 : e0.c1;  // values hold c1 itself (ToCoordinate)
    }
    if (!out->model.free[kC1] && out->model.free[kC0]) {
      // c1 held, c0 free: c1 + c0 >= K*kp (docs/model.md section 10) becomes a floor on c0 when the
      // prior's c1 is below the ideal ratio.
      const double floor = IdealIdcPerIrmsPerThrottle(x.d.motor_type) - out->model.values[kC1];
      out->model.lower[kC0] = std::max(out->model.lower[kC0], floor);
      out->model.values[kC0] = std::max(out->model.values[kC0], out->model.lower[kC0]);
    }
    out->fit = FitProfiled(x.d, x.used, out->model, x.knees, LossType::kTrivial, 1.0);
    out->model.values = out->fit.values;
    return out->fit.ok;
  };
  Step held;
  if (!refit(held_slots, &held)) return cur;
  const int other = held_slots.size() == 1 ? (held_slots[0] == kC0 ? kC1 : kC0) : -1;
  if (other >= 0 && EscSlotWeak(held.model, held.fit, other)) {
    held_slots.push_back(other);
    if (!refit(held_slots, &held)) return cur;
  }
  held.cv = CrossValidate(x.d, x.used, x.folds.fold_of, x.folds.count, held.model, held.fit, x.knees);
  const std::string names = held_slots.size() == 2 ? "c1, c0" : (held_slots[0] == kC0 ? "c0" : "c1");
  res->warnings.push_back(names + " held at the " + (x.o.esc ? "ESC entry's" : "ideal ESC's") +
                          " value in the extended model: fitted freely the ESC sits on a bound of model.md "
                          "section 10 (log torque and the AC columns to identify it)");
  return held;
}

}  // namespace internal
}  // namespace dynosize::diagnosis
