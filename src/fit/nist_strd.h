// Reader for NIST StRD nonlinear regression files (.dat, www.itl.nist.gov/div898/strd/nls).
//
// The format: a free-text header that states where things are ("Starting Values (lines 41 to
// 44)", "Data (lines 61 to 71)"); one line per parameter "b1 = start1 start2 certified sd";
// a line "Residual Sum of Squares: value"; data lines "y x1 [x2 ...]". Line numbers are 1-based
// and are taken from the header, not assumed, so the reader also works for the linear sets.
#pragma once

#include <Eigen/Core>
#include <string>

namespace dynosize {

struct NistDataset {
  std::string name;                   // file stem, "MGH09"
  std::string path;
  Eigen::VectorXd start1, start2;     // NIST's two starting points (far, near)
  Eigen::VectorXd certified_values;   // b1..bp
  Eigen::VectorXd certified_std_devs;
  double certified_residual_sum_of_squares = 0.0;
  Eigen::VectorXd y;                  // response
  Eigen::MatrixXd x;                  // predictors, one column each
};

// Throws NoInputError when the file cannot be read and DataError (naming file, line and what
// was expected) when it does not follow the format.
NistDataset ReadNistDataset(const std::string& path);

// Log relative error, the StRD accuracy measure: -log10(|estimate - certified| / |certified|),
// or -log10|estimate| when certified is 0; capped at 15 (exact agreement) and floored at 0.
double LogRelativeError(double estimate, double certified);

}  // namespace dynosize
