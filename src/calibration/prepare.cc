#include "calibration/prepare.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "calibration/starting_values.h"
#include "common/error.h"
#include "fit/statistics.h"

namespace dynosize::calibration::internal {

using fit::Median;
using logs::Column;
using logs::SteadyTable;

namespace {

void AddDropLocal(std::vector<logs::DropCount>* v, const std::string& reason) {
  for (auto& d : *v) {
    if (d.reason == reason) {
      ++d.count;
      return;
    }
  }
  v->push_back({reason, 1});
}


// Prepare, stage 1: the required columns, then the rows used (the others are dropped with the
// reason) and their inputs. Fills pr->data's row vectors and pr->has_throttle.
LogColumns SelectFitRows(const SteadyTable& t, const CalibrationOptions& o, const std::vector<char>* excluded,
                      Prepared* pr) {
  const std::string file = FileTag(t);
  if (!t.Has(Column::kOmegaRadS)) {
    throw DataError(file + ": column omega_rad_s (shaft speed) is absent: calibration needs the speed "
                    "to find the back-EMF constant");
  }
  const bool has_v = t.Has(Column::kVdcV);
  LogColumns c;
  c.ac = t.Has(Column::kVllRmsV) && t.Has(Column::kIrmsA);
  if (!has_v) {
    throw DataError(file + ": column vdc_v (supply voltage) is absent: calibration needs the voltage "
                    "at the ESC (eq 48)");
  }
  pr->has_throttle = t.Has(Column::kThrottle);
  c.has_q = t.Has(Column::kTorqueNm);
  c.has_nl = t.Has(Column::kNoLoad);
  const auto& w_all = t.Get(Column::kOmegaRadS);
  const auto& idc_all = t.Get(Column::kIdcA);
  double wmax = 0.0;
  for (double w : w_all) wmax = std::max(wmax, w);
  bool any_idc = false;
  for (double v : idc_all) any_idc = any_idc || v != 0.0;
  if (!any_idc) throw DataError(file + ": column idc_a is zero in every row: nothing to fit");

  FitData& d = pr->data;
  for (int m = 0; m < kMeasCount; ++m) d.measured[m] = t.Has(kMeasColumn[m]);
  // Speed readings the circuit cannot produce (fit_rows.h) are left out, each with its value (on
  // the first pass; a refit with `excluded` keeps the first pass's rows and list).
  std::vector<char> spurious(t.rows(), 0);
  if (excluded == nullptr) {
    std::string listed;
    for (const auto& sp : SpuriousSpeedRows(t, o, excluded)) {
      spurious[sp.row] = 1;
      const std::string what = identification::SpuriousSpeedText(t, sp);
      AddDropLocal(&pr->dropped, "spurious speed reading (inconsistent with VDC, throttle and current)");
      pr->dropped_rows.push_back({sp.row, sp.row < t.source_line.size() ? t.source_line[sp.row] : 0,
                                  "spurious speed reading: " + what});
      listed += (listed.empty() ? "" : "; ") + what;
    }
    if (!listed.empty()) {
      pr->warnings.push_back("speed readings inconsistent with VDC, throttle and current left out (fit_rows.h "
                             "FindSpuriousSpeeds): " + listed);
    }
  }
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (excluded != nullptr && (*excluded)[i]) continue;
    if (spurious[i]) continue;
    const double w = w_all[i];
    const double tr = pr->has_throttle ? t.Get(Column::kThrottle)[i] : o.assumed_throttle;
    const bool nl = c.has_nl && t.Get(Column::kNoLoad)[i] != 0.0;
    // A no-load row without a speed reading (DriveCalc n = 0) still measures Io: at Q = 0 the
    // model's current I = Io does not depend on the speed (eq 42). Only its current is compared.
    const bool speed_unknown = nl && w == 0.0;
    if (const char* why = identification::RowRejection(w, wmax, o.min_speed_fraction, pr->has_throttle, tr,
                                                       o.min_throttle, t.Get(Column::kVdcV)[i], speed_unknown)) {
      DropRow(pr, t, i, why);
      continue;
    }
    d.table_row.push_back(i);
    d.vdc.push_back(t.Get(Column::kVdcV)[i]);
    d.tr.push_back(tr);
    d.omega.push_back(w);
    d.q.push_back(c.has_q ? t.Get(Column::kTorqueNm)[i] : 0.0);
    d.torque_known.push_back(c.has_q || nl ? 1 : 0);
    d.speed_known.push_back(speed_unknown ? 0 : 1);
    const bool current_input = pr->has_throttle && !c.has_q && !c.ac && !nl && !speed_unknown && idc_all[i] > 0.0;
    d.idc_in.push_back(current_input ? idc_all[i] : kNaN);
  }
  std::size_t with_speed = 0;
  for (char k : d.speed_known) with_speed += k != 0 ? 1 : 0;
  if (with_speed < 2) {
    throw DataError(file + ": only " + std::to_string(with_speed) +
                    " row(s) with the motor turning: calibration needs at least 2");
  }
  return c;
}

// Prepare, stage 2: the residual terms of every row, in percent of the column's median magnitude
// over the rows used; the row's inputs (speed or current) are not terms.
void BuildTerms(const SteadyTable& t, FitData* fd) {
  FitData& d = *fd;
  const std::array<double, kMeasCount> inv_scale = identification::MedianPercentScales(t, d.table_row, &d.measured);
  d.term_begin.push_back(0);
  for (std::size_t k = 0; k < d.rows(); ++k) {
    for (int m = 0; m < kMeasCount; ++m) {
      if (!d.measured[m]) continue;
      const bool current_input = d.idc_in[k] == d.idc_in[k];
      if (m == kMOmega && !d.torque_known[k] && !current_input) continue;  // speed is the input
      if (m == kMOmega && !d.speed_known[k]) continue;   // speed not measured on this row
      if (m == kMIdc && current_input) continue;         // the current is the input
      d.terms.push_back({m, t.Get(kMeasColumn[m])[d.table_row[k]], inv_scale[m]});
    }
    d.term_begin.push_back(static_cast<int>(d.terms.size()));
  }
}

// Prepare, stage 3: which parameters are free, with a note for each one the log cannot identify.
void ChooseFree(const CalibrationOptions& o, const LogColumns& c, Prepared* pr) {
  const FitData& d = pr->data;
  Layout& lay = pr->layout;
  auto& fr = lay.free;
  auto idx = [](Param p) { return static_cast<int>(p); };
  pr->levels = identification::ThrottleLevels(d.tr);
  if (!pr->levels.empty()) pr->offset_upper = std::min(0.5, 0.9 * pr->levels.front());
  bool any_torque_known = false;
  for (char k : d.torque_known) any_torque_known = any_torque_known || k;
  pr->mode = c.ac ? "ac" : (pr->has_throttle ? "dc" : "dc_no_throttle");
  identification::LogContent content;
  content.ac = c.ac;
  content.has_torque = c.has_q;
  content.has_throttle = pr->has_throttle;
  content.has_idc = d.measured[kMIdc];
  content.any_torque_known = any_torque_known;
  content.throttle_levels = pr->levels.size();
  lay.tie_kt = identification::TieKt(content);
  const auto base_free = identification::FreeBaseParams(content);
  std::copy(base_free.begin(), base_free.begin() + kBaseParamCount, fr.begin());
  const bool esc_ratio = fr[kC1I];
  fr[idx(Param::kTrSat)] = false;  // profiled
  fr[idx(Param::kSatSlope)] = false;  // freed per knee candidate
  fr[kDbI] = false;                   // freed when the offset is tested (FitWithOffset)
  auto& nt = pr->notes;
  nt[kDbI] = !pr->has_throttle ? "no throttle column: held at prior"
             : pr->levels.size() < 3 ? "fewer than 3 throttle levels: held at prior"
                                     : "";
  if (lay.tie_kt) {
    nt[idx(Param::kKt)] = c.has_q ? "tied: KT = sqrt(27/10)*KE (no AC columns to separate KT from the ESC ratio)"
                                  : "tied: KT = sqrt(27/10)*KE (no torque column)";
  }
  if (!fr[idx(Param::kIo)]) nt[idx(Param::kIo)] = "no torque column and no no-load rows: Io does not enter the predictions";
  if (!fr[idx(Param::kResc)]) {
    nt[idx(Param::kResc)] = "held at prior: without vll_rms_v/irms_a only Rm + RESC is determined (eq 48)";
    nt[idx(Param::kRm)] = "Rm + RESC determined, the split is not (held RESC at its prior)";
  }
  if (!esc_ratio) {
    nt[idx(Param::kC1)] = nt[idx(Param::kC0)] =
        !pr->has_throttle ? "no throttle column: held at prior (rows taken as full throttle)"
        : !d.measured[kMIdc] ? "no idc_a: held at prior"
        : !(c.ac || c.has_q) ? "no torque and no AC columns: only C1/R, C0/R are determined; held at prior"
                             : "one throttle level: C1*TR + C0 not separable; held at prior";
  }
  if (!pr->has_throttle) {
    pr->warnings.push_back("no throttle column: every row taken as throttle " +
                           std::to_string(o.assumed_throttle) +
                           "; KE and R are conditional on that and on the assumed ESC (ideal unless --esc prior)");
  }
}

}  // namespace

// The speed readings of the rows a fit may use (not excluded, not no-load, passing RowRejection)
// that the circuit cannot produce (identification::FindSpuriousSpeeds).
std::vector<identification::SpuriousSpeed> SpuriousSpeedRows(const SteadyTable& t, const CalibrationOptions& o,
                                                             const std::vector<char>* excluded) {
  if (!t.Has(Column::kOmegaRadS) || !t.Has(Column::kVdcV)) return {};
  const bool thr = t.Has(Column::kThrottle);
  const bool has_nl = t.Has(Column::kNoLoad);
  const auto& w_all = t.Get(Column::kOmegaRadS);
  double wmax = 0.0;
  for (double w : w_all) wmax = std::max(wmax, w);
  std::vector<std::size_t> cand;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (excluded != nullptr && (*excluded)[i]) continue;
    if (has_nl && t.Get(Column::kNoLoad)[i] != 0.0) continue;
    const double tr = thr ? t.Get(Column::kThrottle)[i] : o.assumed_throttle;
    if (identification::RowRejection(w_all[i], wmax, o.min_speed_fraction, thr, tr, o.min_throttle,
                                     t.Get(Column::kVdcV)[i]) == nullptr) {
      cand.push_back(i);
    }
  }
  return identification::FindSpuriousSpeeds(t, cand, o.assumed_throttle);
}

std::string FileTag(const SteadyTable& t) { return t.file.empty() ? std::string("log") : t.file; }

void DropRow(Prepared* pr, const SteadyTable& t, std::size_t i, const std::string& reason) {
  AddDropLocal(&pr->dropped, reason);
  pr->dropped_rows.push_back({i, i < t.source_line.size() ? t.source_line[i] : 0, reason});
}

// Selects the rows, decides what is free, and finds starting values by linear least squares.
Prepared Prepare(const SteadyTable& t, const CalibrationOptions& o, const std::vector<char>* excluded) {
  Prepared pr;
  const LogColumns c = SelectFitRows(t, o, excluded, &pr);
  BuildTerms(t, &pr.data);
  ChooseFree(o, c, &pr);
  StartingValues(t, o, c, &pr);
  return pr;
}
}  // namespace dynosize::calibration::internal
