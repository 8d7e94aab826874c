// Small statistics helpers shared by calibration and diagnosis (one implementation each).
#pragma once

#include <vector>

namespace dynosize::fit {

// Median of the values (mean of the two middle ones for an even count); NaN when empty.
double Median(std::vector<double> v);
// Median of |v|; NaN when empty.
double MedianAbs(std::vector<double> v);

// Corrected Akaike information criterion of a least-squares fit with sum of squares sse, n
// residuals and p parameters (Hurvich & Tsai 1989): n*ln(sse/n) + 2p + 2p(p+1)/(n-p-1);
// +infinity when n - p - 1 <= 0.
double Aicc(double sse, int n, int p);

// Upper tail P(F > f) of the F(d1, d2) distribution, by the regularized incomplete beta
// function I_x(d2/2, d1/2), x = d2/(d2 + d1*f) (Numerical Recipes 6.4, Lentz's continued fraction).
double FDistributionUpperTail(double f, double d1, double d2);

}  // namespace dynosize::fit

namespace dynosize::fit {

// The q-quantile (0 <= q <= 1) of the values by linear interpolation between order statistics
// (Hyndman & Fan type 7: position q*(n-1)); NaN when empty.
double Quantile(std::vector<double> v, double q);
// The same of values already sorted ascending (no copy).
double SortedQuantile(const std::vector<double>& sorted, double q);

}  // namespace dynosize::fit
