// What a residual trend left by a fitted model follows, where a log can tell (docs/model.md
// section 9: the effects a discrepancy analysis should look for). A current residual that drifts
// over a sweep has three usual physical causes, each with its own signature in a log with time:
//   speed     a loss that grows with speed beyond the model's (iron, eddy-current, windage):
//             follows the shaft speed;
//   heating   the winding warming over the run (Rm = Rm0*(1 + 0.00393*dT), section 9): follows
//             the copper loss the winding has accumulated, I^2 low-pass filtered with the motor's
//             thermal time constant (unknown; tried on a grid);
//   command   the ESC (its DC/AC current ratio or voltage gain drifting with the command):
//             follows the throttle.
// Each is tested as a linear trend of the residual (F test, Bonferroni over every signature and
// time constant tried). The strongest is named only where the log separates it from the others:
// where it still explains the residual beyond any smooth (quadratic) function of each other
// signature (partial F test, p < alpha).
// In a sweep that runs one way, time, speed, command and accumulated heat all rise (or fall)
// together and no fit can tell them apart; then the rival and the measurement that separates
// them are given instead.
#pragma once

#include <string>
#include <vector>

namespace dynosize::identification {

struct TrendRows {
  // One column: the model's prediction and the measured value of each row. The residual is in
  // percent of the measured value, floored at 5 % of the column's median (a near-zero reading
  // would otherwise dominate, as in the fits: diagnosis/prepare.cc).
  std::vector<double> predicted, measured;
  std::vector<double> time_s;            // empty when the log has no time
  std::vector<double> omega_rad_s;
  std::vector<double> current_a;         // the motor (or DC) current, for the copper loss
  std::vector<double> throttle;          // empty when the log has no throttle
};

struct TrendSignature {
  std::string mechanism;  // "speed", "heating", "command"
  double r2 = 0.0;
  double p_value = 1.0;          // after the Bonferroni correction
  double change_percent = 0.0;   // the residual's linear change over the signature's range
  double tau_s = 0.0;            // heating: the time constant of the best fit
};

// A trend smaller than this over its range is not reported, however significant: below the
// 0.3-1 % noise of stand sensors, and below the 1 % a diagnosis finding must gain.
inline constexpr double kMinTrendChangePercent = 1.0;

struct TrendAttribution {
  // The strongest signature has p < alpha, R^2 >= 0.2 and a change of kMinTrendChangePercent or more.
  bool structured = false;
  std::vector<TrendSignature> signatures;  // every signature tested, strongest first
  // The strongest signature, named when it explains the residual beyond every other one.
  bool separable = false;
  std::string rival;               // the signature that leaves the least to the strongest
  double rival_correlation = 0.0;  // |corr| of the two signatures over the rows
  std::string text;                // one sentence: what the trend follows, or why it cannot say
  std::string measurement;         // what would separate the rivals (empty when separable)
};

// The attribution of one column's residual; rows with a non-finite value in a used column are
// skipped. alpha: the test level (the diagnosis's).
TrendAttribution AttributeTrend(const TrendRows& rows, double alpha);

}  // namespace dynosize::identification
