// Reading a log, step 4: the steady table built from the rows read (one point per row, or per
// plateau of a time series), and its checks.
#include "logs/log_read_steps.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "logs/log_reader.h"
#include "logs/plateau.h"

namespace dynosize::logs::read_internal {

namespace {

bool AllNaN(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isnan(x); });
}
bool AllZeroOrNaN(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isnan(x) || x == 0.0; });
}

}  // namespace

// Decides which slots make columns; fills info.
std::vector<Slot*> ResolveColumns(Plan* plan, SteadyTable* t) {
  std::vector<Slot*> chosen(kColumnCount, nullptr);
  for (Slot& s : plan->slots) {
    if (!s.active) continue;
    ColumnInfo& ci = t->info[static_cast<int>(s.target)];
    if (AllNaN(s.values)) {
      if (chosen[static_cast<int>(s.target)] == nullptr) {
        ci.note = "\"" + s.header + "\" is empty in every row";
      }
      continue;
    }
    if (s.target == Column::kOmegaRadS && AllZeroOrNaN(s.values)) {
      if (chosen[static_cast<int>(s.target)] == nullptr) {
        ci.note += std::string(ci.note.empty() ? "" : "; ") + "\"" + s.header +
                   "\" is zero in every row (no speed sensor)";
      }
      continue;
    }
    if (chosen[static_cast<int>(s.target)] != nullptr) {
      ci.note += std::string(ci.note.empty() ? "" : "; ") + "\"" + s.header + "\" not used";
      continue;
    }
    chosen[static_cast<int>(s.target)] = &s;
    if (s.target == Column::kThrottle && s.pulse_us) {
      t->throttle_pulse_min_us = s.pulse_min;
      t->throttle_pulse_max_us = s.pulse_max;
    }
    ci.present = true;
    ci.source_header = s.header;
    ci.source_unit = s.unit;
  }
  return chosen;
}

namespace {

void AppendRow(SteadyTable* t, const std::vector<Slot*>& chosen, std::size_t line,
               std::size_t samples, const double* values) {
  for (int c = 0; c < kColumnCount; ++c) {
    if (chosen[c] != nullptr) t->columns[c].push_back(values[c]);
  }
  t->source_line.push_back(line);
  t->samples.push_back(samples);
}

}  // namespace

void BuildPerRow(SteadyTable* t, const std::vector<Slot*>& chosen, const RawRows& rows,
                 bool zero_is_dropout) {
  double vals[kColumnCount];
  const std::size_t n = rows.line.size();
  // At most n rows: no growth by doubling on the way (peak memory of a million-row log).
  for (int c = 0; c < kColumnCount; ++c) {
    if (chosen[c] != nullptr) t->columns[c].reserve(n);
  }
  t->source_line.reserve(n);
  t->samples.reserve(n);
  for (std::size_t r = 0; r < n; ++r) {
    if (rows.esc_outside[r]) {
      AddDrop(t, rows.esc_reason);
      continue;
    }
    bool ok = true;
    for (int c = 0; c < kColumnCount && ok; ++c) {
      if (chosen[c] == nullptr) continue;
      vals[c] = chosen[c]->values[r];
      if (std::isnan(vals[c])) {
        AddDrop(t, "rows with an empty " +
                       std::string(zero_is_dropout && c == static_cast<int>(Column::kOmegaRadS)
                                       ? "or zero (probe dropout / motor not started) "
                                       : "") +
                       "\"" + chosen[c]->header + "\" cell");
        ok = false;
      }
    }
    if (ok) AppendRow(t, chosen, rows.line[r], 1, vals);
  }
}

void BuildPlateaus(SteadyTable* t, const std::vector<Slot*>& chosen, const RawRows& rows,
                   const PlateauOptions& po) {
  const std::size_t n = rows.line.size();
  const Slot* time = chosen[static_cast<int>(Column::kTimeS)];
  const Slot* cmd = chosen[static_cast<int>(Column::kThrottle)];
  const Slot* sig = chosen[static_cast<int>(Column::kOmegaRadS)];
  if (sig == nullptr) sig = chosen[static_cast<int>(Column::kIdcA)];
  // Rows without time or command cannot be placed in a step.
  std::vector<std::size_t> keep;
  keep.reserve(n);
  for (std::size_t r = 0; r < n; ++r) {
    if (rows.esc_outside[r]) {
      AddDrop(t, rows.esc_reason);
      continue;
    }
    if (time != nullptr && std::isnan(time->values[r])) {
      AddDrop(t, "samples with an empty \"" + time->header + "\" cell");
      continue;
    }
    if (cmd != nullptr && std::isnan(cmd->values[r])) {
      AddDrop(t, "samples with an empty \"" + cmd->header + "\" cell");
      continue;
    }
    keep.push_back(r);
  }
  // Gather compact copies (contiguous arrays for the search).
  std::vector<std::vector<double>> col(kColumnCount);
  for (int c = 0; c < kColumnCount; ++c) {
    if (chosen[c] == nullptr) continue;
    col[c].reserve(keep.size());
    for (const std::size_t r : keep) col[c].push_back(chosen[c]->values[r]);
  }
  const int sig_col = sig == nullptr ? -1 : static_cast<int>(sig->target);
  std::vector<const double*> measured;
  for (int c = 0; c < kColumnCount; ++c) {
    if (chosen[c] == nullptr || c == static_cast<int>(Column::kTimeS) ||
        c == static_cast<int>(Column::kThrottle)) {
      continue;
    }
    measured.push_back(col[c].data());
  }
  // Independent runs where time goes backwards (appended recordings, out-of-order rows).
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  std::size_t run_start = 0;
  const std::size_t m = keep.size();
  // Asynchronous sampling makes time jitter backwards by a few ms; only a jump back by more
  // than summary_min_interval_s is a new recording appended to the file.
  for (std::size_t i = 1; i <= m; ++i) {
    if (i == m || (time != nullptr && col[0][i] < col[0][i - 1] - po.summary_min_interval_s)) {
      runs.emplace_back(run_start, i);
      run_start = i;
    }
  }
  if (runs.size() > 1) {
    t->notes.push_back("time goes backwards " + std::to_string(runs.size() - 1) +
                       " time(s): the log was searched as " + std::to_string(runs.size()) +
                       " separate runs");
  }
  std::vector<char> mask;
  std::size_t short_plateaus = 0, short_samples = 0, unsteady = 0;
  std::vector<std::size_t> by_method(4, 0);
  double vals[kColumnCount];
  for (const auto& [rb, re] : runs) {
    const std::size_t len = re - rb;
    const double* tp = time != nullptr ? col[0].data() + rb : nullptr;
    const double* cp = cmd != nullptr ? col[static_cast<int>(Column::kThrottle)].data() + rb : nullptr;
    const double* sp = sig_col >= 0 ? col[sig_col].data() + rb : nullptr;
    const PlateauSearch ps = FindPlateaus(tp, cp, sp, len, po);
    by_method[static_cast<std::size_t>(ps.method)] += 1;
    t->transient_samples += ps.transient_samples;
    short_plateaus += ps.short_plateaus;
    short_samples += ps.short_plateau_samples;
    unsteady += ps.unsteady_samples;
    for (const Plateau& pl : ps.plateaus) {
      std::vector<const double*> cols;
      for (const double* x : measured) cols.push_back(x + rb);
      t->outlier_samples += MarkOutliers(cols, pl.begin, pl.end, po, &mask);
      bool ok = true;
      std::size_t used_max = 0;
      std::size_t first_line = 0;
      for (int c = 0; c < kColumnCount && ok; ++c) {
        if (chosen[c] == nullptr) continue;
        const double* x = col[c].data() + rb;
        double sum = 0.0;
        std::size_t cnt = 0;
        for (std::size_t i = pl.begin; i < pl.end; ++i) {
          if (mask[i - pl.begin] || std::isnan(x[i])) continue;
          if (first_line == 0) first_line = rows.line[keep[rb + i]];
          sum += x[i];
          ++cnt;
        }
        if (cnt == 0) {
          AddDrop(t, "plateaus without a \"" + chosen[c]->header + "\" sample");
          ok = false;
          break;
        }
        vals[c] = sum / static_cast<double>(cnt);
        used_max = std::max(used_max, cnt);
      }
      if (ok) {
        AppendRow(t, chosen, first_line, used_max, vals);
        ++t->plateaus_found;
      }
    }
  }
  AddDrop(t, "samples in steps too short to average after the transient (plateau minimum sample count)", short_samples);
  AddDrop(t, "samples not steady (signal search)", unsteady);
  if (short_plateaus > 0) {
    t->notes.push_back(std::to_string(short_plateaus) + " steps/runs too short to be plateaus");
  }
  std::string how;
  for (std::size_t k = 0; k < by_method.size(); ++k) {
    if (by_method[k] == 0) continue;
    how += std::string(how.empty() ? "" : ", ") + PlateauMethodName(static_cast<PlateauMethod>(k));
    if (runs.size() > 1) how += " (" + std::to_string(by_method[k]) + " runs)";
  }
  t->notes.push_back("plateaus found by " + how);
}

double MedianInterval(const std::vector<double>& t) {
  std::vector<double> d;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (!std::isnan(t[i]) && !std::isnan(t[i - 1])) d.push_back(std::fabs(t[i] - t[i - 1]));
  }
  return MedianOf(d.data(), 0, d.size());
}

void NormalizeSigns(SteadyTable* t) {
  for (const Column c : {Column::kTorqueNm, Column::kThrustN}) {
    if (!t->Has(c)) continue;
    std::vector<double>& v = t->Mutable(c);
    const double med = MedianOf(v.data(), 0, v.size());
    if (med < 0.0) {
      for (double& x : v) x = -x;
      ColumnInfo& ci = t->info[static_cast<int>(c)];
      ci.note += std::string(ci.note.empty() ? "" : "; ") +
                 "sign flipped (negative median: mounting direction)";
    }
  }
}

void CheckCanonicalRanges(const SteadyTable& t, const std::string& path) {
  const std::size_t n = t.rows();
  auto check = [&](Column c, bool (*ok)(double), const char* rule) {
    if (!t.Has(c)) return;
    const auto& v = t.Get(c);
    for (std::size_t r = 0; r < n; ++r) {
      if (!ok(v[r])) {
        std::ostringstream val;
        val.precision(17);
        val << v[r];
        CellError(path, t.source_line[r], ColumnName(c), val.str(), rule);
      }
    }
  };
  check(Column::kVdcV, [](double x) { return x > 0.0; }, "vdc_v must be > 0");
  check(Column::kVllRmsV, [](double x) { return x >= 0.0; }, "vll_rms_v must be >= 0");
  check(Column::kIrmsA, [](double x) { return x >= 0.0; }, "irms_a must be >= 0");
}

void CheckTable(const SteadyTable& t, const std::string& path) {
  const std::size_t n = t.rows();
  std::string why = t.DroppedTotal() > 0 ? " after dropping " + std::to_string(t.DroppedTotal()) +
                                               " rows/samples"
                                         : std::string();
  if (n < 2) {
    throw DataError(path + ": " + std::to_string(n) + " steady operating point" +
                    (n == 1 ? "" : "s") + why + " (" + std::to_string(t.data_rows_read) +
                    " data rows read): a calibration needs at least 2");
  }
  if (!t.Has(Column::kIdcA)) {
    throw DataError(path + ": no usable current column (" +
                    t.info[static_cast<int>(Column::kIdcA)].note +
                    "): every calibration needs the DC current");
  }
  bool all_same = true;
  for (int c = 0; c < kColumnCount && all_same; ++c) {
    if (!t.info[c].present || c == static_cast<int>(Column::kTimeS)) continue;
    const auto& v = t.columns[c];
    for (std::size_t r = 1; r < n && all_same; ++r) all_same = v[r] == v[0];
  }
  if (all_same) {
    throw DataError(path + ": all " + std::to_string(n) +
                    " operating points are identical (time aside): nothing to fit");
  }
  const auto& idc = t.Get(Column::kIdcA);
  if (std::all_of(idc.begin(), idc.end(), [](double x) { return x == 0.0; })) {
    throw DataError(path + ": column \"" + t.info[static_cast<int>(Column::kIdcA)].source_header +
                    "\" (idc_a) is zero in every point: current sensor not connected?");
  }
}

// DriveCalc: points whose speed was not measured (n = 0) are not operating points (see
// LogReadOptions::drivecalc_keep_no_load_without_speed for the no-load exception).
void DropDriveCalcWithoutSpeed(SteadyTable* t, const LogReadOptions& options) {
  std::size_t w = 0;
  const std::size_t n = t->rows();
  auto& om = t->columns[static_cast<int>(Column::kOmegaRadS)];
  std::vector<char> keep(n);
  const bool keep_nl = options.drivecalc_keep_no_load_without_speed && t->Has(Column::kNoLoad);
  std::size_t kept_without_speed = 0;
  for (std::size_t r = 0; r < n; ++r) {
    keep[r] = om[r] != 0.0;
    if (!keep[r] && keep_nl && t->columns[static_cast<int>(Column::kNoLoad)][r] != 0.0) {
      keep[r] = 1;
      ++kept_without_speed;
    }
  }
  if (kept_without_speed > 0) {
    t->notes.push_back(std::to_string(kept_without_speed) +
                      " no-load points without a speed reading (n = 0) kept: they give Io only");
  }
  for (int c = 0; c < kColumnCount; ++c) {
    if (!t->info[c].present) continue;
    auto& v = t->columns[c];
    w = 0;
    for (std::size_t r = 0; r < n; ++r) {
      if (keep[r]) v[w++] = v[r];
    }
    v.resize(w);
  }
  w = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (keep[r]) {
      t->source_line[w] = t->source_line[r];
      t->samples[w] = t->samples[r];
      ++w;
    }
  }
  AddDrop(t, keep_nl ? "loaded points with n = 0 (speed not measured)" : "points with n = 0 (speed not measured)",
          n - w);
  t->source_line.resize(w);
  t->samples.resize(w);
}

}  // namespace dynosize::logs::read_internal
