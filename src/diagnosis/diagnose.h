// Diagnosis: what the first-order motor + ESC model (docs/model.md, src/model/drive.h)
// gets wrong in a measured log, which physical mechanism explains it, and how much better the
// model predicts held-out data once that mechanism is part of it.
//
// Method
//  1. Rows: the steady rows of the log with the motor turning (as in src/calibration). Known
//     inputs per row are VDC, the throttle TR and either the shaft torque Q (torque column or a
//     no-load row: Q = 0) or the measured speed omega; every other measured column among
//     omega_rad_s, idc_a, irms_a, vll_rms_v, pac_w is predicted by the model (Drive::AtTorque or
//     Drive::AtSpeed, so the extensions act exactly as in simulate). Each residual is in percent
//     of its effective spread (errors in variables): sqrt(y^2 + (dy/dVDC*VDC)^2 + (dy/dx*x)^2),
//     x the speed or torque input, derivatives from a preliminary first-order fit, floored at 5 %
//     of the column's median. With sensors of equal relative noise the residuals are then
//     homoscedastic, as the F test needs (at low throttle I = (U - KE*omega)/R is a small
//     difference, and plain percent errors there would call input noise an effect), and columns
//     in different units weigh alike.
//  2. Base parameters free in every model (as src/calibration/calibrate.h explains what each
//     column set identifies): KE; R = Rm (+ RESC with AC columns); Io with a known torque; KT with
//     torque + AC columns (else KT = sqrt(27/10)*KE, section 5); C1, C0 with idc_a, several
//     throttle levels and torque or AC columns (else held at the ideal ESC of eq 56 or --esc).
//  3. Candidate extensions (docs/model.md section 9), each adding its own parameters:
//       esc_saturation                  tr_sat, sat_slope          (section 7; tr_sat profiled)
//       speed_dependent_no_load_current io1_a_s_per_rad            (needs a known torque)
//       winding_temperature_rise        rth_k_per_w
//       torque_constant_droop           kt_droop_per_a             (needs torque + current)
//       throttle_deadband               deadband
//       supply_resistance               rsupply_ohm                (VDC not measured at the ESC)
//     A candidate the data cannot test (no column that it changes) is listed as not testable.
//  4. Outliers: a Huber fit of the base model with every testable extension at once (which can
//     follow any of the effects, so effect rows are not mistaken for outliers) flags rows whose
//     residual exceeds outlier_sigmas robust standard deviations (1.4826*MAD); they are left out
//     of every later fit and score, and reported.
//  5. Greedy forward selection. For the current model M and each candidate c: least-squares fit
//     of M+c, F test of the nested pair (F = (SSE_M - SSE_M+c)/q / (SSE_M+c/(N - p)), q extra
//     parameters; the profiled knee counts as 2 and its p value is multiplied by the number of
//     knees tried, Bonferroni, and by the number of candidates tested at the step, so that alpha
//     is the step's false-alarm rate), AICc, and k-fold cross-validated rms error (folds of rows,
//     seeded; every score is on rows the fit did not see). A candidate is significant when
//     p < alpha, AICc falls, its own parameter is at least 2 standard errors from "no effect"
//     and not clipped at a bound of its physical range, and the CV error falls by at least
//     min_gain_percent. In the folds the knee is re-profiled among the full-data knee's grid
//     neighbours (a small leak of the knee choice, documented rather than hidden). The best
//     significant one (largest CV gain) is added and the search repeats; it stops when nothing
//     significant is left or after max_findings.
//  6. Ambiguity: when another significant candidate comes within ambiguity_aicc of the winner's
//     AICc or reaches ambiguity_gain_ratio of its CV gain, and is no longer significant once the
//     winner is in the model, the data cannot tell the two apart: both are reported, with the
//     measurement that would separate them.
//
// Files of src/diagnosis (the parameter table and the row rules shared with calibrate are in
// src/identification):
//   diagnosis_types.h    the causes, the options and the result (below every stage)
//   diagnose.h/.cc       this interface and Diagnose(): the stages in order, the verdict, the
//                        calibration entry
//   model_fit.h/.cc      one model's fit: parameter slots, predictions, the bounded fit with its
//                        profiled knee, the k-fold cross-validation
//   prepare.h/.cc        stages 1-6: rows and terms, the first-order model (free parameters,
//                        starts, scales, bounds), folds, effective-variance weights, outliers
//   baseline.h/.cc       stages 7-8: the first-order model cross-validated, worst points, trends
//   candidates.h/.cc     the hidden-effect extensions (steps 3, 5, 6 above): their slots, their
//                        fits and scores, the forward selection, ambiguities
//   diagnose_report.cc   FullReport
#pragma once

#include "diagnosis/diagnosis_types.h"
#include "fit/statistics.h"
#include "logs/steady_table.h"

namespace dynosize::diagnosis {

// Runs the diagnosis. Throws DataError when the log lacks what any fit needs (speed, VDC, a
// predicted column, enough rows), UsageError for invalid options.
DiagnoseResult Diagnose(const logs::SteadyTable& table, const DiagnoseOptions& options = {});

// Upper tail of the F(d1, d2) distribution (p value of an F statistic): fit/statistics.h.
using fit::FDistributionUpperTail;

}  // namespace dynosize::diagnosis
