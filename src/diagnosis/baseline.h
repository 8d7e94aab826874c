// The first-order model of `diagnose` fitted and cross-validated (stage 7), and what its held-out
// errors show (stage 8): the worst points and the residual trends against each logged variable.
// Internal to src/diagnosis.
#pragma once

#include <cstddef>
#include <map>
#include <vector>

#include "diagnosis/diagnosis_types.h"
#include "diagnosis/model_fit.h"

namespace dynosize::diagnosis::internal {

// Held-out predictions of cv as full table columns (NaN on rows not used).
void CvTable(const Data& d, std::size_t table_rows, const std::vector<std::size_t>& used, const CvOut& cv,
             std::map<logs::Column, std::vector<double>>* out);
// Stage 7: the first-order model fitted and cross-validated.
Step FitBaseline(const logs::SteadyTable& t, const Data& d, const std::vector<std::size_t>& used, const Folds& folds,
                 const Model& base, const std::vector<double>& knees, DiagnoseResult* res);
// Stage 8a: the 5 worst held-out points of the baseline.
std::vector<WorstPoint> WorstPoints(const logs::SteadyTable& t, const Data& d, const std::vector<std::size_t>& used,
                                    const CvOut& cv);
// Stage 8b: residual structure of the baseline: the held-out percent error of every predicted
// column against each logged variable.
std::vector<ResidualTrend> ResidualTrends(const logs::SteadyTable& t, const Prepared& p,
                                          const std::vector<std::size_t>& used, const CvOut& cv, double alpha);
// Stage 10b: what the extended model's held-out residual of each predicted column still follows
// (speed, accumulated heat, command; identification/trend_attribution.h): the structured ones.
std::vector<RemainingTrend> RemainingTrends(const logs::SteadyTable& t, const Prepared& p,
                                            const std::vector<std::size_t>& used, const CvOut& cv, double alpha);

}  // namespace dynosize::diagnosis::internal
