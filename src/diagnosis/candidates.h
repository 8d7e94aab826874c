// The hidden-effect candidates of `diagnose` (docs/model.md section 9; the list in diagnose.h): which
// parameter slots each adds, which a log can test, how each is fitted on top of the current
// model and scored (F test, AICc, cross-validated gain), and the greedy forward selection that
// adds the significant ones. Internal to src/diagnosis.
#pragma once

#include <string>
#include <vector>

#include "diagnosis/diagnosis_types.h"
#include "diagnosis/model_fit.h"

namespace dynosize::diagnosis::internal {

// What the forward selection shares between its steps (fixed for the whole search).
struct SearchContext {
  const Data& d;
  const std::vector<std::size_t>& used;
  const Folds& folds;
  const std::vector<double>& knees;
  const Values& base_values;  // the base model's starts, a second start for candidates
  const DiagnoseOptions& o;
};

// One candidate fitted on top of the current model and scored.
struct Scored {
  CandidateScore cs;
  FitOut fit;
  CvOut cv;
  Model model;
};

// Extra parameters of cause c in the F test and AICc (the profiled knee counts as 2).
int CauseExtraParams(Cause c);
// Frees cause c's slots in *m with their starting values.
void AddCause(Model* m, Cause c);
// True when free slot s of values v sits on a bound of its coordinate (ToCoordinate).
bool SlotAtBound(const Model& m, const Values& v, int s);
// True when a free first-order slot sits on a bound.
bool BaseAtBound(const Model& m, const Values& v);
// Knee candidates: midpoints between throttle levels from 0.5 up (or a 0.02 grid when the
// throttle is continuous), each with at least one level above.
std::vector<double> KneeGrid(const std::vector<double>& levels);
// Stage 3: the candidates this log can test; the others go to res->not_testable with the reason.
std::vector<Cause> TestableCandidates(const DiagnoseOptions& o, const Prepared& p,
                                      const std::vector<double>& knees, DiagnoseResult* res);
// Stage 9: greedy forward selection from the baseline cur; returns the extended model.
Step SearchCandidates(const SearchContext& x, bool has_tr, std::vector<Cause> remaining, Step cur,
                      DiagnoseResult* res);
// Stage 9c: ESC slots left on a bound without AC columns held at the ESC prior (candidates.cc).
Step HoldEscOnBound(const SearchContext& x, bool ac, Step cur, DiagnoseResult* res);

}  // namespace dynosize::diagnosis::internal
