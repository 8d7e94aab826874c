// The fit of one diagnosis model, used by every stage of `diagnose`: the parameter slots (the
// table of identification/parameters.h), the log's rows and residual terms, the model's
// predictions (Drive::AtTorque / Drive::AtSpeed, so the extensions act exactly as in simulate),
// the bounded least-squares fit with its profiled saturation knee, and the k-fold
// cross-validation. Internal to src/diagnosis (namespace internal).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "common/numbers.h"
#include "diagnosis/diagnosis_types.h"
#include "fit/nonlinear_least_squares.h"
#include "identification/fit_rows.h"
#include "identification/parameters.h"
#include "logs/steady_table.h"
#include "model/drive.h"

namespace dynosize::diagnosis::internal {

// Parameters: the slots of identification/parameters.h (kParamTable). Every model is a subset of
// them made free; the rest are held.
namespace id = identification;
inline constexpr int kKe = id::ParamIndex(id::Param::kKe), kKt = id::ParamIndex(id::Param::kKt),
                     kRm = id::ParamIndex(id::Param::kRm), kIo = id::ParamIndex(id::Param::kIo),
                     kResc = id::ParamIndex(id::Param::kResc), kC1 = id::ParamIndex(id::Param::kC1),
                     kC0 = id::ParamIndex(id::Param::kC0), kTrSat = id::ParamIndex(id::Param::kTrSat),
                     kSatSlope = id::ParamIndex(id::Param::kSatSlope),
                     kDeadband = id::ParamIndex(id::Param::kDeadband), kIo1 = id::ParamIndex(id::Param::kIo1),
                     kRth = id::ParamIndex(id::Param::kRth), kDroop = id::ParamIndex(id::Param::kDroop),
                     kRsupply = id::ParamIndex(id::Param::kRsupply), kSlotCount = id::kParamCount;
inline const char* SlotName(int s) { return id::kParamTable[s].name; }

using Values = std::array<double, kSlotCount>;
using FreeSet = std::array<bool, kSlotCount>;

// Measured columns the model predicts and the residual terms (identification/fit_rows.h);
// diagnose's term scale is 100 / max(|value|, 5 % of the column median): a residual in percent
// of the measured value (then the effective-variance weights, ApplyEffectiveVarianceWeights).
using identification::kMeasColumn;
using identification::kMeasCount;
using identification::kMIdc;
using identification::kMIrms;
using identification::kMOmega;
using identification::kMPac;
using identification::kMVll;
using Term = identification::ResidualTerm;
using identification::TermResidual;

struct Data : identification::FitRows {
  bool tie_kt = true;
  MotorType motor_type = MotorType::kBldc;
  // Effective-variance weights that follow the model being fitted (ApplyEffectiveVarianceWeights
  // switches them on): each residual of a fit is divided by the spread the relative noise of its
  // row's inputs gives it under the parameters being tried, not under a preliminary fit's
  // (prepare.cc, stage 5). spread_floor: the smallest spread of each measured column, in its units.
  bool weights_follow_model = false;
  std::array<double, kMeasCount> spread_floor{};
};

struct Model {
  FreeSet free{};
  Values values{};  // starts for free slots, held values otherwise
  Values scale{};   // optimisation unit of each slot (x = value/scale)
  Values lower{}, upper{};
  bool profile_knee = false;  // tr_sat chosen on a grid
};

struct FitOut {
  bool ok = false;
  Values values{};
  double sse = 0.0;  // sum of squared percent residuals (trivial loss)
  int n_terms = 0;
  int n_free = 0;    // incl. a profiled knee
  Values stderr_{};
  double max_corr_ext_base = 0.0;
  std::string corr_with;
};

// Cross-validation.
struct CvOut {
  double rms_percent = kNaN;  // all terms, percent residuals
  std::array<std::vector<double>, kMeasCount> pred;  // per data row
  int failed_folds = 0;
};

// The stages' shared state (the stages of Diagnose(), in the order it runs them: prepare.h,
// baseline.h, candidates.h, diagnose.cc).
// Stage 1: what the log offers, and the rows and terms of the fit.
struct Prepared {
  Data d;
  bool has_tr = false;  // throttle column
  bool has_q = false;   // torque column
  bool has_nl = false;  // no-load flag column
  bool ac = false;      // AC-side columns (vll_rms_v and irms_a)
  bool any_tk = false;  // some row has a known torque (torque column or a no-load row)
  double wmax = 0.0;    // largest logged speed, rad/s
  std::vector<double> levels;                  // distinct throttle levels (none without throttle)
  std::array<double, kMeasCount> inv_scale{};  // 100 / column median: percent of a typical value
};

// Stage 4: cross-validation folds, seeded. Leave-one-out below kLooRows rows (small tables:
// "fewer than about 15" rows; from 12 rows on, o.folds folds hold out at least 2 rows each
// and keep 9 or more to fit).
struct Folds {
  int count = 0;
  std::vector<int> fold_of;  // per data row
};

// A model, its fit on the used rows and its cross-validation: the state of the forward selection.
struct Step {
  Model model;
  FitOut fit;
  CvOut cv;
};

void ToParams(const Data& d, const Values& v, MotorParams* m, EscParams* e);
// Predictions of row k (every measured column) by the model with these values.
bool PredictRow(const Data& d, const Drive& drive, std::size_t k, double* pred);
// The effective-variance scale of each term of row k (100 / spread, the spread of its value under
// relative noise on the value and on the row's inputs, VDC and the speed or torque) into inv_scale,
// with the derivatives of `drive`; pred: the row's predictions (PredictRow). False where a
// perturbed prediction fails.
bool EffectiveVarianceScales(const Data& d, const Drive& drive, std::size_t k, const double* pred, double* inv_scale);
// The residual terms of `rows` into r; false outside the model's domain.
bool Residuals(const Data& d, const std::vector<std::size_t>& rows, const Values& v, double* r);
int TermCount(const Data& d, const std::vector<std::size_t>& rows);
// The optimised coordinate of slot s (see model_fit.cc).
double ToCoordinate(int s, const Values& v);
// Fits the model's free slots on `rows` (bounded Levenberg-Marquardt of src/fit).
FitOut FitModel(const Data& d, const std::vector<std::size_t>& rows, const Model& model,
                LossType loss, double loss_scale);
// Fits the model, profiling tr_sat over `knees` when the model asks for it.
FitOut FitProfiled(const Data& d, const std::vector<std::size_t>& rows, const Model& model,
                   const std::vector<double>& knees, LossType loss, double loss_scale);
// k-fold cross-validation of the model (warm-started at `full`, the knee re-profiled per fold).
CvOut CrossValidate(const Data& d, const std::vector<std::size_t>& used,
                    const std::vector<int>& fold_of, int folds, const Model& model,
                    const FitOut& full, const std::vector<double>& knees);
std::vector<ColumnError> ColumnErrors(const Data& d, const std::vector<std::size_t>& used, const CvOut& cv);

}  // namespace dynosize::diagnosis::internal
